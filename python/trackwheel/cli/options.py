"""The command line's parser and its shared option groups: argument types (numbers in exponent
notation, comma lists, seed ranges), and the excitation, track, simulation and mesh options
several commands take."""

from __future__ import annotations

import argparse
import math
import re

from ..run.defaults import default_settings
from ..run.simulate import FIDELITY_LEVELS, TIME_DOMAIN_LEVELS
from ..scene import Scene, Window

#: the paper's scene, whose derived defaults the help texts quote
PAPER = default_settings(Scene.kato2005())


#: what argparse takes for a negative number (its own pattern misses exponents such as -1e6,
#: which it would then read as an unknown option), or a comma list starting with one
#: (--joint -0.002,0.5,2 reaches the check of the depth)
_NUMBER = r"(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"
_NEGATIVE_NUMBER = re.compile(rf"^-{_NUMBER}(,\s*-?{_NUMBER})*$")


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors ("trackwheel run: error: ...", exit code 2), negative
    numbers in exponent notation read as values, and no abbreviated options (``--speed 300``
    is an error, not ``--speed-kmh 300``)."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message}\n")


def positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {n}")
    return n


def finite_float(text: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return x


def positive_float(text: str) -> float:
    x = finite_float(text)
    if x <= 0.0:
        raise argparse.ArgumentTypeError(f"expected a positive number, got {text!r}")
    return x


#: spectra by their command-line name
SPECTRA = {"fra": "fra:N (US FRA class N = 1..6)", "german": "german:low|high",
            "china": "china (TB/T 3352-2014)", "iso3095": "iso3095 (ISO 3095 roughness limit)",
            "sine": "sine:WAVELENGTH,AMPLITUDE [m]"}


def floats(text: str, n: int, what: str) -> list[float]:
    parts = text.split(",")
    if len(parts) != n:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
    return [finite_float(x.strip()) for x in parts]


def irregularity_spec(text: str) -> tuple[str, str]:
    """``KIND[:ARG]`` -> (kind, arg), checked against the known kinds."""
    kind, _, arg = text.partition(":")
    kind = kind.strip().lower()
    if kind not in SPECTRA:
        raise argparse.ArgumentTypeError(f"unknown irregularity {text!r}; use "
                                         + ", ".join(SPECTRA.values()))
    if kind in ("fra", "german", "sine") and not arg:
        raise argparse.ArgumentTypeError(f"{text!r} needs its argument: {SPECTRA[kind]}")
    if kind in ("china", "iso3095") and arg:
        raise argparse.ArgumentTypeError(f"{text!r}: {kind} takes no argument")
    return kind, arg.strip()


def joint(text: str) -> list[float]:
    return floats(text, 3, "DEPTH,LENGTH,AT in m, e.g. 0.002,0.5,2.0")


def seed_list(text: str) -> list[int]:
    """``0-19``, ``1,4,7`` or ``0-4,10`` -> the integers (ranges inclusive)."""
    out = []
    for item in text.split(","):
        lo, dash, hi = item.strip().partition("-")
        try:
            a = int(lo)
            b = int(hi) if dash else a
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected seeds such as 0-19 or 1,4,7 (integers "
                                             f">= 0), got {text!r}") from None
        if b < a:
            raise argparse.ArgumentTypeError(f"empty seed range {item!r} in {text!r}")
        out.extend(range(a, b + 1))
    return out


def excitation_options(p: argparse.ArgumentParser, seeds: bool = False) -> None:
    g = p.add_argument_group("excitation (docs: Model § Irregularities; lengths in m, default a smooth rail "
                             "and a round wheel)")
    g.add_argument("--irregularity", type=irregularity_spec, action="append", metavar="SPEC",
                   help="rail profile: " + ", ".join(SPECTRA.values()) + "; repeat to add "
                        "profiles")
    g.add_argument("--seed", type=int, metavar="N",
                   help="seed of the random profile (default 0)"
                        + ("; --seeds sweeps over several" if seeds else ""))
    if seeds:
        g.add_argument("--seeds", type=seed_list, nargs="+", metavar="SEEDS",
                       help="realisations of the random profile, e.g. 0-19 or 1,4,7: one case "
                            "per seed (summarised as percentiles per speed)")
    g.add_argument("--wavelengths", type=positive_float, nargs=2, metavar=("MIN", "MAX"),
                   help="wavelength band of the random profile [m] (default: the spectrum's "
                        "validity band)")
    g.add_argument("--joint", type=joint, metavar="DEPTH,LENGTH,AT",
                   help="dipped joint (Kabo form) of depth and length [m] starting at X = AT "
                        "[m]; turns the contact filter on")
    g.add_argument("--wheel-flat", type=finite_float, metavar="LENGTH",
                   help="new wheel flat of chord LENGTH [m], meeting the rail half a "
                        "revolution after the start")
    g.add_argument("--patch-filter", action="store_true",
                   help="average the profile over the Hertz contact patch")


#: rail length [m] of ``decay-rate --track ballasted``: the EN 15461 line (66 bays, 39.6 m)


#: --track: the scene presets by name
TRACKS = {"kato2005": Scene.kato2005, "ballasted": Scene.ballasted_track}


def track_option(p: argparse.ArgumentParser, length_default: str = "30",
                 fidelity: bool = True) -> None:
    """--track, --length, --beam and --shear-coefficient; ``fidelity``: the command has
    --fidelity (its --beam help says every level takes the beam theory)."""
    g = p.add_argument_group("track (docs: Model § Layered supports and section "
                             "\"Shear-deformable rail (Timoshenko)\")")
    g.add_argument("--track", choices=tuple(TRACKS), default="kato2005",
                   help="the scene: kato2005 (the paper's 5 m rail on single springs, default) "
                        "or ballasted (Scene.ballasted_track(): UIC60 on rail pads, "
                        "sleepers and ballast every 0.6 m, a high-speed wheel)")
    g.add_argument("--length", type=positive_float, metavar="L",
                   help=f"rail length [m] of --track ballasted, a multiple of 0.6 m (default "
                        f"{length_default})")
    g.add_argument("--beam", choices=("euler", "timoshenko"), default="euler",
                   help="rail beam theory (default euler: Euler-Bernoulli, the paper's); "
                        "timoshenko adds shear deformation and rotary inertia"
                        + (", at every --fidelity level" if fidelity else ""))
    g.add_argument("--shear-coefficient", type=positive_float, metavar="K",
                   help="shear coefficient kappa of the rail section, 0 < K <= 1 (default 0.4; "
                        "with --beam timoshenko)")
    g.add_argument("--shear-modulus", type=positive_float, metavar="G",
                   help="shear modulus G of the rail [Pa] (default E / (2 (1 + nu)); with "
                        "--beam timoshenko)")



def transition_spec(text: str) -> list[float]:
    """``K1,K2,AT[,RAMP]`` -> [K1, K2, AT, RAMP] (RAMP 0 if not given)."""
    parts = text.split(",")
    if len(parts) not in (3, 4):
        raise argparse.ArgumentTypeError(f"expected K1,K2,AT[,RAMP] (N/m, N/m, m, m), e.g. "
                                         f"50e6,200e6,15,3; got {text!r}")
    return [finite_float(x.strip()) for x in parts] + ([0.0] if len(parts) == 3 else [])


def void_spec(text: str) -> list[float]:
    return floats(text, 2, "AT,GAP in m, e.g. 15,1e-3")


def along_x_options(p: argparse.ArgumentParser) -> None:
    """--transition, --transition-shape, --scatter and --void: a track whose supports vary
    along X (docs: Model § Supports varying along the track)."""
    g = p.add_argument_group("track varying along X (the property: the ballast stiffness k_b "
                             "of --track ballasted, the support stiffness k_s of kato2005; "
                             "docs: Model § Supports varying along the track)")
    g.add_argument("--transition", type=transition_spec, metavar="K1,K2,AT[,RAMP]",
                   help="the property changes from K1 to K2 [N/m] at X = AT [m], over a ramp "
                        "of RAMP [m] centred on AT (default 0: a step)")
    g.add_argument("--transition-shape", choices=("linear", "cosine"),
                   help="the ramp's shape with RAMP > 0 (default linear)")
    g.add_argument("--scatter", type=positive_float, metavar="CV",
                   help="lognormal scatter of the property from sleeper to sleeper with "
                        "coefficient of variation CV (e.g. 0.2; its mean the preset's value or "
                        "the --transition), drawn with --seed (default 0); --seeds (sweep) "
                        "redraws it per seed")
    g.add_argument("--void", type=void_spec, action="append", metavar="AT,GAP",
                   help="a gap of GAP [m] between the sleeper nearest X = AT [m] and its "
                        "ballast (a hanging sleeper; --track ballasted; repeat for several)")


def damping_options(p: argparse.ArgumentParser, contact: bool = True) -> None:
    """--support-damping (and, with ``contact``, --contact-damping): viscous damping of the
    supports (the rail pads of --track ballasted) and of the wheel/rail contact [N s/m]."""
    g = p.add_argument_group("damping (default: the --track preset's; the paper's track is "
                             "undamped)")
    g.add_argument("--support-damping", type=finite_float, metavar="C",
                   help="viscous damping of each support [N s/m], >= 0 (default 0 on "
                        "kato2005; with --track ballasted the rail pad's, default 18e3); "
                        "rail pads have about 1e4-5e4")
    if contact:
        g.add_argument("--contact-damping", type=finite_float, metavar="C",
                       help="viscous damping of the wheel/rail contact [N s/m], >= 0 "
                            "(default 0)")


def simulate_options(p: argparse.ArgumentParser, auto: bool = False) -> None:
    """Options passed to trackwheel.simulate (left out: simulate's defaults); ``auto`` offers
    ``--fidelity auto`` (sweep only: the cheapest level adequate on the sweep's hardest case)."""
    g = p.add_argument_group("simulation settings (default: simulate's derived defaults, the "
                             "same at every --fidelity level)")
    g.add_argument("--integrator", choices=("generalized_alpha", "explicit"),
                   help="time integrator (default generalized_alpha)")
    g.add_argument("--dt", type=finite_float, metavar="S",
                   help=f"time step [s] (default: derived from the scene, {PAPER['dt']:.3g} s "
                        "for the paper's)")
    g.add_argument("--n-elements", type=positive_int, metavar="N",
                   help=f"rail elements (default, when --dt is not given: derived from the "
                        f"scene, whole elements per support bay, at least 8 and enough for the "
                        f"pinned-pinned wavelength (12 with --beam timoshenko), "
                        f"{PAPER['n_elements']} for the paper's scene; with --dt the scene's "
                        "own; fewer elements than support bays warn)")
    g.add_argument("--x-start", type=finite_float, metavar="X",
                   help="wheel start [m] (default: the middle of the first support bay clear "
                        "of the rail's end, 5.1 m on --track ballasted; the first bay's on a "
                        "rail too short for that, e.g. the paper's)")
    g.add_argument("--x-end", type=finite_float, metavar="X",
                   help="wheel end [m] (default: the middle of the last support bay clear of "
                        "the rail's end, or of the last bay)")
    g.add_argument("--fidelity", choices=(FIDELITY_LEVELS + ("auto",)) if auto
                   else TIME_DOMAIN_LEVELS,
                   help="model level (default full: the paper's model)"
                        + ("; periodic/linear: each case's steady state in the frequency "
                           "domain (trackwheel periodic), milliseconds a case; auto: the "
                           "cheapest level within --fidelity-tol of the full model on the "
                           "highest speed and softest supports of the sweep"
                           if auto else ""))
    if auto:
        g.add_argument("--fidelity-tol", type=positive_float, metavar="TOL",
                       help="with --fidelity auto: relative tolerance on amplitude, main "
                            "frequency and peak contact force (default 0.005)")


def simulate_kwargs(args: argparse.Namespace) -> dict:
    names = ("integrator", "dt", "n_elements", "x_start", "x_end", "fidelity")
    return {n: getattr(args, n) for n in names if getattr(args, n) is not None}



def window_spec(text: str) -> Window:
    try:
        behind, ahead = (int(t) for t in text.split(","))
        return Window(bays_behind=behind, bays_ahead=ahead)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"{text!r}: give two whole numbers of bays "
                                         f"BEHIND,AHEAD, each 1..1000 ({exc})") from None



def mesh_option(p: argparse.ArgumentParser) -> None:
    p.add_argument("--n-elements", type=positive_int, metavar="N",
                   help="rail elements (default: whole elements per support bay, enough per "
                        "bending wavelength of the --beam at the highest frequency to put the "
                        "track's resonances within 0.1 %%, and no fewer than the preset's)")

