"""The ``trackwheel`` command: argument parsing and printing (the paper pipeline is in
:mod:`trackwheel.reproduce`).

``trackwheel reproduce --out DIR [--quick] [--only STEP ...]``
    The main job: recompute the paper's Figs. 3-8 for ``Scene.kato2005()`` and write them (PNG +
    CSV) to DIR with a ``summary.txt`` that sets our numbers beside the paper's claims
    (:func:`trackwheel.reproduce.reproduce`). The sweeps keep every finished case in
    ``DIR/sweep-store``, so an interrupted run resumes.
``trackwheel run --speed-kmh V [--support-stiffness K] [--integrator ...] [--plot PNG]``
    One passage: print the amplitude and main frequency of the contact-point vibration, the
    contact-force statistics (range, dynamic factor, contact loss, band levels, P1/P2 after a
    joint) and the wall time; optionally save :func:`plots.dynamic`.
``trackwheel sweep --speeds-kmh V ... [--support-stiffness K ...] [--seeds 0-19] --store DIR``
    A speed x support-stiffness (x seed) sweep into a resumable store; prints the table.

Excitation (``run`` and ``sweep``, docs: Model § Irregularities; lengths in m):
``--irregularity fra:N | german:low | german:high | china | iso3095 | sine:WAVELENGTH,AMPLITUDE``
(repeatable: the profiles add), ``--seed N`` and ``--wavelengths MIN MAX`` for the random
spectra, ``--joint DEPTH,LENGTH,AT`` (a Kabo dipped joint; turns the contact filter on),
``--wheel-flat LENGTH`` (a new flat, half a revolution from the start), ``--patch-filter``;
``run --brake-torque T_B`` brakes the wheel [N m] (beyond adhesion it locks and slides).
``trackwheel eigen [--position X] [--n-modes N]``
    Print the lowest vertical natural frequencies with the wheel at X [m].
``trackwheel receptance [--at midspan|support|X] [--fmin F] [--fmax F] [--n N] [--out CSV]``
    The track's point receptance [m/N] (magnitude and phase) at a mid-span, above a support or
    at X [m], from --fmin to --fmax [Hz] (trackwheel.receptance); ``--plot`` adds both points.
``trackwheel decay-rate [--per-band N] [--out CSV] [--plot PNG]``
    The vertical track decay rate [dB/m] per one-third-octave band (EN 15461, trackwheel.
    decay_rate) beside the ISO 3095 lower limit.

Track (every command but reproduce; docs: Model § Layered supports and the section
"Shear-deformable rail (Timoshenko)"):
``--track kato2005|ballasted`` (``--length L`` [m] for the ballasted preset), ``--beam
euler|timoshenko`` and ``--shear-coefficient K``; every ``--fidelity`` level takes the beam
theory (the full and ancf/... levels the shear-deformable ANCF rail, the linear/... levels the
linear Timoshenko beam).

``main(argv)`` returns the exit code: 0 on success, 2 for bad arguments (argparse, or a value
the library rejects), 1 when a computation fails (a diverging run, failed sweep cases). Every
error is one line on stderr; every output path is checked before anything is computed.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import re
import sys
import tempfile
import warnings
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ._errors import DivergenceError
from ._version import __version__
from .analysis import analyse
from .defaults import MAX_SPEED, default_settings
from .eigen import eigen as _eigen
from .force_statistics import defect_position
from .irregularity import Irregularity, WheelFlat
from .reproduce import REPRODUCE_STEPS, STORE_NAME, X_REPORT, reproduce
from .scene import MAX_ELEMENTS, Scene, Window, kmh
from .simulate import FIDELITY_LEVELS, simulate
from .vehicle import Vehicle
from .sweep import sweep

#: the paper's scene, whose derived defaults the help texts quote
_PAPER = default_settings(Scene.kato2005())


# --------------------------------------------------------------------------------------------
# argument parsing
# --------------------------------------------------------------------------------------------
#: what argparse takes for a negative number (its own pattern misses exponents such as -1e6,
#: which it would then read as an unknown option), or a comma list starting with one
#: (--joint -0.002,0.5,2 reaches the check of the depth)
_NUMBER = r"(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?"
_NEGATIVE_NUMBER = re.compile(rf"^-{_NUMBER}(,\s*-?{_NUMBER})*$")


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors ("trackwheel run: error: ...", exit code 2) and negative
    numbers in exponent notation read as values."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message}\n")


def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {n}")
    return n


def _finite_float(text: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return x


def _positive_float(text: str) -> float:
    x = _finite_float(text)
    if x <= 0.0:
        raise argparse.ArgumentTypeError(f"expected a positive number, got {text!r}")
    return x


#: spectra by their command-line name
_SPECTRA = {"fra": "fra:N (US FRA class N = 1..6)", "german": "german:low|high",
            "china": "china (TB/T 3352-2014)", "iso3095": "iso3095 (ISO 3095 roughness limit)",
            "sine": "sine:WAVELENGTH,AMPLITUDE [m]"}


def _floats(text: str, n: int, what: str) -> list[float]:
    parts = text.split(",")
    if len(parts) != n:
        raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
    return [_finite_float(x.strip()) for x in parts]


def _irregularity_spec(text: str) -> tuple[str, str]:
    """``KIND[:ARG]`` -> (kind, arg), checked against the known kinds."""
    kind, _, arg = text.partition(":")
    kind = kind.strip().lower()
    if kind not in _SPECTRA:
        raise argparse.ArgumentTypeError(f"unknown irregularity {text!r}; use "
                                         + ", ".join(_SPECTRA.values()))
    if kind in ("fra", "german", "sine") and not arg:
        raise argparse.ArgumentTypeError(f"{text!r} needs its argument: {_SPECTRA[kind]}")
    if kind in ("china", "iso3095") and arg:
        raise argparse.ArgumentTypeError(f"{text!r}: {kind} takes no argument")
    return kind, arg.strip()


def _joint(text: str) -> list[float]:
    return _floats(text, 3, "DEPTH,LENGTH,AT in m, e.g. 0.002,0.5,2.0")


def _seed_list(text: str) -> list[int]:
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


def _excitation_options(p: argparse.ArgumentParser, seeds: bool = False) -> None:
    g = p.add_argument_group("excitation (docs: Model § Irregularities; lengths in m, default a smooth rail "
                             "and a round wheel)")
    g.add_argument("--irregularity", type=_irregularity_spec, action="append", metavar="SPEC",
                   help="rail profile: " + ", ".join(_SPECTRA.values()) + "; repeat to add "
                        "profiles")
    g.add_argument("--seed", type=int, metavar="N",
                   help="seed of the random profile (default 0)"
                        + ("; --seeds sweeps over several" if seeds else ""))
    if seeds:
        g.add_argument("--seeds", type=_seed_list, nargs="+", metavar="SEEDS",
                       help="realisations of the random profile, e.g. 0-19 or 1,4,7: one case "
                            "per seed (summarised as percentiles per speed)")
    g.add_argument("--wavelengths", type=_positive_float, nargs=2, metavar=("MIN", "MAX"),
                   help="wavelength band of the random profile [m] (default: the spectrum's "
                        "validity band)")
    g.add_argument("--joint", type=_joint, metavar="DEPTH,LENGTH,AT",
                   help="dipped joint (Kabo form) of depth and length [m] starting at X = AT "
                        "[m]; turns the contact filter on")
    g.add_argument("--wheel-flat", type=_finite_float, metavar="LENGTH",
                   help="new wheel flat of chord LENGTH [m], meeting the rail half a "
                        "revolution after the start")
    g.add_argument("--patch-filter", action="store_true",
                   help="average the profile over the Hertz contact patch")


#: rail length [m] of ``decay-rate --track ballasted``: the EN 15461 line (66 bays, 39.6 m)
#: with about ten metres of damped rail beyond it at each end
_DECAY_LENGTH = 60.0

#: sleeper spacing of Scene.ballasted_track [m]
_BALLASTED_SPACING = Scene.ballasted_track().supports.spacing

#: --track: the scene presets by name
_TRACKS = {"kato2005": Scene.kato2005, "ballasted": Scene.ballasted_track}


def _track_option(p: argparse.ArgumentParser, length_default: str = "30") -> None:
    g = p.add_argument_group("track (docs: Model § Layered supports and section "
                             "\"Shear-deformable rail (Timoshenko)\")")
    g.add_argument("--track", choices=tuple(_TRACKS), default="kato2005",
                   help="the scene: kato2005 (the paper's 5 m rail on single springs, default) "
                        "or ballasted (Scene.ballasted_track(): UIC60 on rail pads, "
                        "sleepers and ballast every 0.6 m, a high-speed wheel)")
    g.add_argument("--length", type=_positive_float, metavar="L",
                   help=f"rail length [m] of --track ballasted, a multiple of 0.6 m (default "
                        f"{length_default})")
    g.add_argument("--beam", choices=("euler", "timoshenko"), default="euler",
                   help="rail beam theory (default euler: Euler-Bernoulli, the paper's); "
                        "timoshenko adds shear deformation and rotary inertia, at every "
                        "--fidelity level")
    g.add_argument("--shear-coefficient", type=_positive_float, metavar="K",
                   help="shear coefficient kappa of the rail section, 0 < K <= 1 (default 0.4; "
                        "with --beam timoshenko)")


def _track_scene(args: argparse.Namespace, stiffness: float | None = None,
                 length: float | None = None) -> Scene:
    """The --track preset with --length (or ``length`` [m] if not given), the support (pad)
    stiffness ``stiffness`` [N/m] and the beam options applied. Raises _OptionError."""
    if args.shear_coefficient is not None and args.beam != "timoshenko":
        raise _OptionError("--shear-coefficient is only used with --beam timoshenko")
    if args.length is not None and args.track != "ballasted":
        raise _OptionError(f"--length is only for --track ballasted (--track {args.track} "
                           "has its fixed length)")
    try:
        scene = _preset(args.track, stiffness, args.length or length)
        rail = dataclasses.replace(scene.rail, beam=args.beam)
        if args.shear_coefficient is not None:
            rail = dataclasses.replace(rail, shear_coefficient=args.shear_coefficient)
    except ValueError as exc:
        raise _OptionError(_option_error(exc)) from None
    return dataclasses.replace(scene, rail=rail)


def _scene_name(scene: Scene, args: argparse.Namespace) -> str:
    """The preset's name, with the length and beam theory if not the defaults."""
    name = "Scene.kato2005()" if args.track == "kato2005" else (
        "Scene.ballasted_track()" if args.length is None
        else f"Scene.ballasted_track(length={args.length:g})")
    if scene.rail.beam == "timoshenko":
        name += f" with a Timoshenko rail (kappa = {scene.rail.shear_coefficient:g})"
    return name


def _simulate_options(p: argparse.ArgumentParser, auto: bool = False) -> None:
    """Options passed to trackwheel.simulate (left out: simulate's defaults); ``auto`` offers
    ``--fidelity auto`` (sweep only: the cheapest level adequate on the sweep's hardest case)."""
    g = p.add_argument_group("simulation settings (default: simulate's derived defaults, the "
                             "same at every --fidelity level)")
    g.add_argument("--integrator", choices=("generalized_alpha", "explicit"),
                   help="time integrator (default generalized_alpha)")
    g.add_argument("--dt", type=_finite_float, metavar="S",
                   help=f"time step [s] (default: derived from the scene, {_PAPER['dt']:.3g} s "
                        "for the paper's)")
    g.add_argument("--n-elements", type=_positive_int, metavar="N",
                   help=f"rail elements (default: 8 per support bay, {_PAPER['n_elements']} for "
                        "the paper's scene, when --dt is not given, else the scene's 20; fewer "
                        "elements than support bays warn)")
    g.add_argument("--x-start", type=_finite_float, metavar="X",
                   help="wheel start [m] (default: middle of the first support bay)")
    g.add_argument("--x-end", type=_finite_float, metavar="X",
                   help="wheel end [m] (default: middle of the last support bay)")
    g.add_argument("--fidelity", choices=FIDELITY_LEVELS + (("auto",) if auto else ()),
                   help="model level (default full: the paper's model)"
                        + ("; auto: the cheapest level within --fidelity-tol of the full model "
                           "on the highest speed and softest supports of the sweep"
                           if auto else ""))
    if auto:
        g.add_argument("--fidelity-tol", type=_positive_float, metavar="TOL",
                       help="with --fidelity auto: relative tolerance on amplitude, main "
                            "frequency and peak contact force (default 0.005)")


def _simulate_kwargs(args: argparse.Namespace) -> dict:
    names = ("integrator", "dt", "n_elements", "x_start", "x_end", "fidelity")
    return {n: getattr(args, n) for n in names if getattr(args, n) is not None}


def _add_reproduce(sub) -> None:
    p = sub.add_parser(
        "reproduce", help="recompute the paper's figures (Figs. 3-8) into a folder",
        description="Recompute the paper's figures for Scene.kato2005() and write PNG + CSV "
                    "files and summary.txt (our numbers beside the paper's claims) into --out. "
                    "Steps: " + "; ".join(f"{s.name} = {s.title}" for s in REPRODUCE_STEPS)
                    + f". The sweeps keep finished cases in OUT/{STORE_NAME}: a re-run "
                    "resumes. --only refreshes those steps' sections of summary.txt and keeps "
                    "the others. Each step prints its wall time; benchmarks/README.md records "
                    "measured ones.")
    p.add_argument("--out", required=True, type=Path, metavar="DIR",
                   help="output folder (created if missing)")
    p.add_argument("--quick", action="store_true",
                   help="coarse grids, 20 elements at 1e-5 s in the sweeps and short "
                        "convergence stretches, for a fast check")
    p.add_argument("--only", nargs="+", choices=[s.name for s in REPRODUCE_STEPS],
                   metavar="STEP", help="run only these steps (" + ", ".join(
                       s.name for s in REPRODUCE_STEPS) + ")")
    p.add_argument("--workers", type=_positive_int, metavar="N",
                   help="processes for the sweeps (default: one per core)")
    p.set_defaults(run=_cmd_reproduce, parser=p)


def _add_run(sub) -> None:
    p = sub.add_parser(
        "run", help="simulate one passage and print the headline outputs",
        description="Simulate the wheel passing over the rail of Scene.kato2005() at one speed "
                    "and print the amplitude max|d| of the contact-point vibration "
                    "(d = y_B - y_qs, docs: Model § Outputs), its main frequency and resolution, the "
                    "contact-force range, whether the wheel lost contact, and the wall time.")
    p.add_argument("--speed-kmh", type=_finite_float, required=True, metavar="V",
                   help=f"forward speed [km/h], 0 < V <= {MAX_SPEED * 3.6:.4g}")
    p.add_argument("--support-stiffness", type=_finite_float, metavar="K",
                   help="support stiffness k_s [N/m] (default 140e6; with --track ballasted "
                        "the rail pad's, default 180e6)")
    _track_option(p)
    p.add_argument("--vehicle", choices=VEHICLES, default="single",
                   help="single: the paper's wheel under its constant load; bogie: "
                        "Vehicle.bogie() on the --track rail; half-car: Vehicle.half_car() on "
                        "the --track rail lengthened to 25 m (docs: Model § The vehicle)")
    _excitation_options(p)
    p.add_argument("--brake-torque", type=_finite_float, metavar="T_B",
                   help="friction brake on the wheel's rotation [N m], >= 0: beyond adhesion "
                        "(mu P rho0, 1414 N m for the paper's wheel) it locks the wheel, which "
                        "then slides (docs: Model § Rolling and slip)")
    _simulate_options(p)
    g = p.add_argument_group(
        "long runs on a travelling window (docs: Model § The travelling window)")
    g.add_argument("--distance", type=_positive_float, metavar="M",
                   help="run this many metres on a travelling window of the --track (the rail "
                        "becomes --window bays that move with the wheel): any distance at the "
                        "same cost per metre; default --fidelity linear/hertz (the fastest; "
                        "--fidelity full runs the nonlinear model on the window); prints "
                        "contact-force statistics per 100 m")
    g.add_argument("--window", type=_window_spec, metavar="BEHIND,AHEAD",
                   help="with --distance: whole sleeper bays behind the rear wheel's bay and "
                        "ahead of the leading wheel's (default 20,20)")
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save y_B, y_qs, d(t) and the spectrum of d to this file (any format "
                        "matplotlib writes: .png, .pdf, .svg, ...)")
    p.set_defaults(run=_cmd_run, parser=p)


def _window_spec(text: str) -> Window:
    try:
        behind, ahead = (int(t) for t in text.split(","))
        return Window(bays_behind=behind, bays_ahead=ahead)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"{text!r}: give two whole numbers of bays "
                                         f"BEHIND,AHEAD, each 1..1000 ({exc})") from None


def _add_sweep(sub) -> None:
    p = sub.add_parser(
        "sweep", help="run a speed x support-stiffness sweep into a store",
        description="Run every (speed, support stiffness) case of Scene.kato2005() in parallel "
                    "(trackwheel.sweep), with --seeds one case per realisation of the random "
                    "--irregularity, keep each finished case in --store (a re-run skips them) "
                    "and print the table (with --seeds also the 5/50/95 % percentiles over "
                    "the seeds per speed). Exit code 1 if a case failed (it is recorded with "
                    "its error).")
    p.add_argument("--speeds-kmh", type=_finite_float, nargs="+", required=True, metavar="V",
                   help=f"forward speeds [km/h], 0 < V <= {MAX_SPEED * 3.6:.4g}")
    p.add_argument("--support-stiffness", type=_finite_float, nargs="+", metavar="K",
                   help="support stiffnesses k_s [N/m] (default 140e6; with --track ballasted "
                        "the rail pad's, default 180e6)")
    _track_option(p)
    p.add_argument("--store", type=Path, required=True, metavar="DIR",
                   help="folder keeping one record per finished case (created if missing)")
    p.add_argument("--out", type=Path, metavar="CSV", help="also write the table to this file")
    p.add_argument("--workers", type=_positive_int, metavar="N",
                   help="processes (default: one per core)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    _excitation_options(p, seeds=True)
    _simulate_options(p, auto=True)
    p.set_defaults(run=_cmd_sweep, parser=p)


def _add_eigen(sub) -> None:
    p = sub.add_parser(
        "eigen", help="print the natural frequencies with the wheel at one position",
        description="Lowest vertical natural frequencies [Hz] of the wheel/rail/support system "
                    "of Scene.kato2005() with the wheel at --position, and the rail's lowest "
                    "axial frequencies.")
    p.add_argument("--position", type=_finite_float, default=X_REPORT, metavar="X",
                   help=f"wheel position X [m], 0 <= X <= L (default {X_REPORT})")
    p.add_argument("--n-modes", type=_positive_int, default=6, metavar="N",
                   help="number of vertical modes (default 6)")
    _track_option(p)
    p.set_defaults(run=_cmd_eigen, parser=p)


def _mesh_option(p: argparse.ArgumentParser) -> None:
    p.add_argument("--n-elements", type=_positive_int, metavar="N",
                   help="rail elements (default: whole elements per support bay, at least ten "
                        "per Euler-Bernoulli bending wavelength at the highest frequency, and "
                        "no fewer than the preset's)")


def _add_receptance(sub) -> None:
    p = sub.add_parser(
        "receptance", help="print the track's point receptance over frequency",
        description="Point receptance alpha = y / F [m/N] of the linear track (the rail on its "
                    "supports with their damping, no wheel) at one point, from --fmin to "
                    "--fmax [Hz] (trackwheel.receptance; "
                    "docs: Model § Receptance and decay rate): its largest magnitude, a table "
                    "of magnitude and phase, and the pinned-pinned frequencies of one support "
                    "bay by both beam theories.")
    p.add_argument("--at", default="midspan", metavar="midspan|support|X",
                   help="excitation and response point: the mid-span or the support nearest "
                        "the rail's middle (default midspan), or X [m]")
    p.add_argument("--fmin", type=_finite_float, default=20.0, metavar="F",
                   help="lowest frequency [Hz], >= 0 (default 20)")
    p.add_argument("--fmax", type=_finite_float, default=5000.0, metavar="F",
                   help="highest frequency [Hz] (default 5000)")
    p.add_argument("--n", type=_positive_int, default=400, metavar="N",
                   help="frequencies, log-spaced (linear from 0 Hz; default 400)")
    _mesh_option(p)
    _track_option(p)
    p.add_argument("--out", type=Path, metavar="CSV",
                   help="write f_hz, re_m_per_n, im_m_per_n, abs_m_per_n, phase_deg to this file")
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save magnitude and phase at the mid-span and above the support "
                        "(plots.receptance) to this file")
    p.set_defaults(run=_cmd_receptance, parser=p)


def _add_decay_rate(sub) -> None:
    p = sub.add_parser(
        "decay-rate", help="print the track decay rate per one-third-octave band",
        description="Vertical track decay rate [dB/m] of the linear track by the EN 15461 method "
                    "(trackwheel.decay_rate) in the one-third-octave bands 250 Hz - 5 kHz, each "
                    "from the band average of the squared magnitude of the transfer receptances over --per-band "
                    "frequencies, beside the ISO 3095:2013 lower limit for a test track. "
                    "The rail must be longer than 66 support spacings: --track ballasted, "
                    f"whose length here defaults to {_DECAY_LENGTH:g} m.")
    p.add_argument("--per-band", type=_positive_int, default=8, metavar="N",
                   help="frequencies per band, log-spaced inside it (default 8)")
    _mesh_option(p)
    _track_option(p, length_default=f"{_DECAY_LENGTH:g} here")
    p.add_argument("--out", type=Path, metavar="CSV",
                   help="write band_hz, decay_rate_db_per_m, iso3095_limit_db_per_m to this file")
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save the decay rate over the bands against the ISO 3095 limit "
                        "(plots.decay_rate) to this file")
    p.set_defaults(run=_cmd_decay_rate, parser=p)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="trackwheel",
        description="A railway wheel rolling at high speed over a flexible rail on elastic "
                    "supports (Kato et al. 2005). SI units throughout, speeds in km/h on the "
                    "command line.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for add in (_add_reproduce, _add_run, _add_sweep, _add_eigen, _add_receptance,
                _add_decay_rate):
        add(sub)
    return parser


# --------------------------------------------------------------------------------------------
# checks made before anything is computed
# --------------------------------------------------------------------------------------------
def _writable_folder(path: Path, option: str, parser: argparse.ArgumentParser,
                     create: bool) -> None:
    """Error unless ``path`` is (or, with ``create``, can be made) a folder we can write in."""
    if path.exists() and not path.is_dir():
        parser.error(f"{option} {path}: exists and is not a folder")
    if not path.exists():
        if not create:
            parser.error(f"{option}: the folder {path} does not exist")
        try:
            path.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            parser.error(f"{option} {path}: cannot create the folder ({exc.strerror or exc})")
    try:  # as root, os.access says yes to read-only file systems such as /proc: try it
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        parser.error(f"{option} {path}: cannot write in this folder ({exc.strerror or exc})")


def _output_file(path: Path, option: str, parser: argparse.ArgumentParser,
                 formats: Sequence[str] | None = None) -> None:
    """Error unless ``path`` can be written: an existing, writable folder, not a folder itself,
    and (if ``formats`` is given) one of those extensions."""
    if path.is_dir():
        parser.error(f"{option} {path}: is a folder, expected a file name")
    if formats is not None:
        ext = path.suffix.lstrip(".").lower()
        if ext not in formats:
            parser.error(f"{option} {path}: unknown file format {ext or '(none)'!r}; "
                         f"use one of {', '.join(sorted(formats))}")
    _writable_folder(path.parent if str(path.parent) else Path("."), option, parser,
                     create=False)
    if path.exists() and not os.access(path, os.W_OK):
        parser.error(f"{option} {path}: the file is not writable")


def _figure_formats() -> list[str]:
    """File extensions matplotlib can save figures to."""
    from matplotlib.backend_bases import FigureCanvasBase

    return list(FigureCanvasBase.get_supported_filetypes())


def _speeds_kmh(values: Sequence[float], option: str, parser: argparse.ArgumentParser) -> None:
    """Error, in km/h, for a speed outside (0, MAX_SPEED]."""
    top = MAX_SPEED * 3.6
    for v in values:
        if not 0.0 < v <= top:
            parser.error(f"{option}: speed {v:.4g} km/h is outside the allowed range "
                         f"0–{top:.4g} km/h (a passage needs a positive speed)")


def _option_error(exc: Exception) -> str:
    """A library message with its parameter names spelled as the command's options."""
    text = str(exc)
    text = text.replace("Supports.stiffness", "--support-stiffness")
    text = text.replace("Rail.shear_coefficient", "--shear-coefficient")
    text = text.replace("Wheel.brake_torque", "--brake-torque")
    if text.startswith("length = "):  # Scene.ballasted_track's length
        text = "--length " + text[len("length = "):]
    for name in ("n_elements", "x_start", "x_end", "speed_kmh", "support_stiffness"):
        text = text.replace(name, "--" + name.replace("_", "-"))
    return text


def _print_warnings(caught, command: str) -> None:
    """The library's warnings (mesh, stability), one line each on stderr."""
    for w in caught:
        print(f"trackwheel {command}: warning: {_option_error(w.message)}", file=sys.stderr)


# --------------------------------------------------------------------------------------------
# commands
# --------------------------------------------------------------------------------------------
def _cmd_reproduce(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    _writable_folder(args.out, "--out", parser, create=True)
    try:
        reproduce(args.out, quick=args.quick, only=args.only, workers=args.workers)
    except (OSError, RuntimeError) as exc:  # e.g. the disk filled up, a run failed
        print(f"trackwheel reproduce: failed: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    return 0


#: --vehicle choices of ``trackwheel run``
VEHICLES = ("single", "bogie", "half-car")
#: rail length for --vehicle half-car [m]: the half car's 20 m of wheels plus the paper's 5 m
HALF_CAR_RAIL = 25.0


def _vehicle_scene(scene: Scene, vehicle: str) -> Scene:
    """``scene`` carrying the --vehicle choice (the rail lengthened for a half car, the
    paper's element length kept)."""
    if vehicle == "single":
        return scene
    if vehicle == "bogie":
        return dataclasses.replace(scene, vehicle=Vehicle.bogie())
    ne = round(scene.rail.n_elements * HALF_CAR_RAIL / scene.rail.length)
    rail = dataclasses.replace(scene.rail, length=HALF_CAR_RAIL, n_elements=ne)
    return dataclasses.replace(scene, rail=rail, vehicle=Vehicle.half_car())


def _print_vehicle_run(scene: Scene, speed_kmh: float, r, x_d) -> None:
    """Headline outputs of a vehicle run, one line per wheel (analyse(r, wheel=i))."""
    st = r.settings
    veh = scene.active_vehicle
    k_name = "k_p" if scene.supports.layered else "k_s"
    print(f"{veh.n_wheels} wheels, {len(veh.bogies)} bogie(s), car body: "
          f"{'yes' if veh.car else 'no'}; {k_name} = {scene.supports.stiffness / 1e6:g} MN/m, "
          f"v = {speed_kmh:g} km/h ({kmh(speed_kmh):.2f} m/s)")
    print(f"  settings : {st.integrator}, dt = {st.dt:.3g} s, {st.n_elements} elements, "
          f"fidelity {st.fidelity}, excitation: {_describe(scene)}")
    loads = veh.static_loads(scene.gravity)
    for i in range(veh.n_wheels):
        a = analyse(r, wheel=i, defect_at=x_d)
        print(f"  wheel {i} (x = {veh.positions[i]:g} m): max|d| = {a.amplitude * 1e6:.3f} µm, "
              f"N = {a.min_contact_force / 1e3:.2f} .. {a.max_contact_force / 1e3:.2f} kN "
              f"(static {loads[i] / 1e3:.2f} kN), dynamic factor {a.dynamic_factor:.4f}, "
              f"lost contact: {'yes' if a.lost_contact else 'no'}")
    print(f"  wall time: {r.wall_time:.3f} s ({r.steps} steps)")


def _preset(track: str, stiffness: float | None = None, length: float | None = None) -> Scene:
    """The --track preset, with the support (pad) stiffness [N/m] and the ballasted track's
    length [m] replaced if given."""
    if track == "kato2005":
        return _scene(stiffness)
    if length is None:
        scene = _TRACKS[track]()
    else:  # the preset's 4 elements per bay, fewer on a long rail (the CLI re-meshes anyway)
        n_bays = max(round(length / _BALLASTED_SPACING), 1)
        if n_bays > MAX_ELEMENTS:
            raise ValueError(f"length = {length:g} m is too long; allowed: at most "
                             f"{MAX_ELEMENTS * _BALLASTED_SPACING:g} m ({MAX_ELEMENTS} "
                             f"elements, one per {_BALLASTED_SPACING:g} m sleeper bay)")
        scene = _TRACKS[track](length, elements_per_bay=min(4, MAX_ELEMENTS // n_bays))
    if stiffness is not None:
        scene = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports,
                                                                        stiffness=stiffness))
    return scene


def _scene(stiffness: float | None = None) -> Scene:
    """Scene.kato2005(), with the support stiffness replaced if given [N/m]."""
    scene = Scene.kato2005()
    if stiffness is not None:
        scene = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports,
                                                                        stiffness=stiffness))
    return scene


class _OptionError(ValueError):
    """A bad excitation value, worded for the command line."""


def _spectrum(kind: str, arg: str):
    from . import spectra

    if kind == "fra":
        try:
            track_class = int(arg)
        except ValueError:
            raise _OptionError(f"--irregularity fra:{arg}: the FRA class must be an integer "
                               "1..6") from None
        return spectra.fra(track_class)
    if kind == "german":
        return spectra.german(arg)
    return spectra.china_hsr() if kind == "china" else spectra.iso3095()


def _profile(args: argparse.Namespace) -> Irregularity | None:
    """The rail profile of --irregularity/--joint (None: smooth). The random parts are drawn
    with --seed (first part) and seeds derived from it (Irregularity.reseeded)."""
    parts = []
    for kind, arg in args.irregularity or ():
        text = f"--irregularity {kind}{':' + arg if arg else ''}"
        try:
            if kind == "sine":
                lam, amp = _floats(arg, 2, "sine:WAVELENGTH,AMPLITUDE in m, e.g. sine:0.5,1e-5")
                parts.append(Irregularity.sine(lam, amp))
            else:
                parts.append(Irregularity.random(_spectrum(kind, arg), seed=0,
                                                 wavelengths=args.wavelengths))
        except _OptionError:
            raise
        except (ValueError, argparse.ArgumentTypeError) as exc:
            msg = str(exc).replace("wavelengths = ", "--wavelengths ")
            raise _OptionError(f"{text}: {msg}") from None
    irr = sum(parts) if parts else None
    n_random = 0 if irr is None else irr.n_random
    if n_random == 0 and (args.seed is not None or args.wavelengths is not None
                          or getattr(args, "seeds", None)):
        used = [o for o, val in (("--seed", args.seed), ("--wavelengths", args.wavelengths),
                                 ("--seeds", getattr(args, "seeds", None))) if val is not None]
        raise _OptionError(f"{' and '.join(used)} need(s) a random --irregularity "
                           "(fra:N, german:low|high, china or iso3095)")
    if n_random:
        if args.seed is not None and args.seed < 0:
            raise _OptionError(f"--seed {args.seed}: allowed range 0 .. 2^63 - 1")
        irr = irr.reseeded(args.seed or 0)
    if args.joint is not None:
        depth, length, at = args.joint
        try:
            joint = Irregularity.dipped_joint(depth, length, at)
        except ValueError as exc:
            raise _OptionError(f"--joint: {exc}") from None
        irr = joint if irr is None else irr + joint
    return irr


def _excited_scene(scene: Scene, args: argparse.Namespace) -> tuple[Scene, list[str]]:
    """``scene`` with the excitation options applied, and notes to print (stdout) or warn
    (lines starting "warning:"). Raises _OptionError for bad values."""
    notes = []
    irr = _profile(args)
    if irr is not None:
        length = scene.rail.length
        if args.joint is not None and not 0.0 <= args.joint[2] <= length - args.joint[1]:
            raise _OptionError(f"--joint: the joint from X = {args.joint[2]:g} m over "
                               f"{args.joint[1]:g} m leaves the rail; allowed AT range "
                               f"[0, {length - args.joint[1]:g}] m")
        scene = dataclasses.replace(scene, irregularity=irr)
    if args.wheel_flat is not None:
        if not args.wheel_flat > 0.0:
            raise _OptionError(f"--wheel-flat {args.wheel_flat:g}: the flat's length must be "
                               "> 0 m")
        try:
            flat = WheelFlat(args.wheel_flat, at_angle=math.pi)
            scene = dataclasses.replace(scene, wheel=dataclasses.replace(
                scene.wheel, defects=(*scene.wheel.defects, flat)))
        except ValueError as exc:
            raise _OptionError(f"--wheel-flat: {exc}") from None
    if args.patch_filter or args.joint is not None:
        scene = dataclasses.replace(scene, contact=dataclasses.replace(scene.contact,
                                                                       patch_filter=True))
        if not args.patch_filter:
            notes.append("--joint turns the contact filter on (Contact.patch_filter = True: "
                         "the dip's cusp curves more sharply than the wheel)")
    return scene, notes


def _describe(scene: Scene) -> str:
    """One line naming the excitation of ``scene``."""
    words = []
    for p in () if scene.irregularity is None else scene.irregularity.parts:
        if p.kind == "random":
            words.append(f"{p.spectrum.name} (seed {p.seed}, {p.wavelengths[0]:g}-"
                         f"{p.wavelengths[1]:g} m)")
        elif p.kind == "sine":
            words.append(f"sine {p.wavelength:g} m x {p.amplitude:g} m")
        elif p.kind == "dipped_joint":
            words.append(f"dipped joint {p.depth * 1e3:g} mm over {p.length:g} m at "
                         f"X = {p.at:g} m")
    for d in scene.wheel.defects:
        words.append(f"wheel flat {d.length * 1e3:g} mm" if d.kind == "wheel_flat"
                     else f"polygon order {d.order}")
    if scene.contact.patch_filter:
        words.append("contact filter on")
    return ", ".join(words) if words else "none (smooth rail, round wheel)"


def _print_forces(scene: Scene, a) -> None:
    f = a.forces
    print(f"  dynamic factor : {a.dynamic_factor:.4f}  (max N / static load)")
    if f.band_rms.size:
        top = np.argsort(f.band_rms)[::-1][:3]
        print("  force bands    : " + ", ".join(
            f"{f.band_centres[k]:.4g} Hz {f.band_rms[k] / 1e3:.3g} kN" for k in top)
            + "  (largest one-third-octave RMS of N)")
    if not math.isnan(f.defect_time):
        print(f"  P1 / P2        : {f.p1 / 1e3:.2f} / {f.p2 / 1e3:.2f} kN at t = "
              f"{f.p1_time * 1e3:.3f} / {f.p2_time * 1e3:.3f} ms (joint reached at "
              f"{f.defect_time * 1e3:.3f} ms)")


def _print_run(scene: Scene, speed_kmh: float, r, a, name: str = "Scene.kato2005()") -> None:
    st = r.settings
    x0, x1 = float(r.x_wheel[0]), float(r.x_wheel[-1])
    i_max = int(np.argmax(np.abs(a.dynamic)))
    k_name = "k_p" if scene.supports.layered else "k_s"
    print(f"{name}, {k_name} = {scene.supports.stiffness / 1e6:g} MN/m, "
          f"v = {speed_kmh:g} km/h ({kmh(speed_kmh):.2f} m/s)")
    print(f"  settings       : {st.integrator}, dt = {st.dt:.3g} s, {st.n_elements} "
          f"elements, X = {x0:.4g} -> {x1:.4g} m, fidelity {st.fidelity}")
    print(f"  excitation     : {_describe(scene)}")
    print(f"  amplitude      : {a.amplitude * 1e6:.3f} µm  (max |d|, d = y_B - y_qs; at "
          f"X = {a.x_wheel[i_max]:.3f} m)")
    print(f"  main frequency : {a.main_frequency:.1f} Hz  (resolution "
          f"{a.frequency_resolution:.2g} Hz)")
    print(f"  contact force  : {a.min_contact_force:.1f} .. {a.max_contact_force:.1f} N  "
          f"(static load {scene.static_load:.1f} N)")
    if a.lost_contact:
        free = r.contact_free_intervals()
        print(f"  lost contact   : yes, {len(free)} interval(s), first at "
              f"t = {free[0][0] * 1e3:.3f} ms, {a.loss_duration * 1e3:.3f} ms in all")
    else:
        print("  lost contact   : no")
    _print_forces(scene, a)
    print(f"  wall time      : {r.wall_time:.3f} s ({r.steps} steps)")


def _print_notes(notes: list[str], command: str) -> None:
    for note in notes:
        if note.startswith("warning:"):
            print(f"trackwheel {command}: {note}", file=sys.stderr)
        else:
            print(f"note: {note}")


def _finish_vehicle_run(scene: Scene, args: argparse.Namespace, r, x_d) -> int:
    try:
        _print_vehicle_run(scene, args.speed_kmh, r, x_d)
    except (RuntimeError, ValueError) as exc:  # a quasi-static solve, or the joint not reached
        print(f"trackwheel run: the analysis failed: {exc}", file=sys.stderr)
        return 1
    if args.plot is not None:
        from . import plots

        try:
            plots.dynamic(r).savefig(args.plot, dpi=150)
        except (OSError, ValueError) as exc:
            print(f"trackwheel run: cannot write --plot {args.plot}: {exc}", file=sys.stderr)
            return 1
    return 0


def _cmd_run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    _speeds_kmh([args.speed_kmh], "--speed-kmh", parser)
    if args.plot is not None:
        _output_file(args.plot, "--plot", parser, formats=_figure_formats())
    if args.vehicle != "single" and args.wheel_flat is not None:
        parser.error("--wheel-flat is only available with --vehicle single")
    if args.vehicle != "single" and args.brake_torque is not None:
        parser.error("--brake-torque is only available with --vehicle single")
    if args.window is not None and args.distance is None:
        parser.error("--window needs --distance (the window is for long runs)")
    try:
        scene = _vehicle_scene(_track_scene(args, args.support_stiffness), args.vehicle)
        scene, notes = _excited_scene(scene, args)
        if args.brake_torque is not None:
            scene = dataclasses.replace(scene, wheel=dataclasses.replace(
                scene.wheel, brake_torque=args.brake_torque))
        if args.distance is not None:
            scene = scene.windowed(args.window or Window())
    except _OptionError as exc:
        parser.error(str(exc))
    except (ValueError, TypeError) as exc:  # e.g. a support stiffness out of range
        parser.error(_option_error(exc))
    _print_notes(notes, "run")
    if args.distance is not None:
        return _window_run(scene, args, parser)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            r = simulate(scene, kmh(args.speed_kmh), **_simulate_kwargs(args))
    except (ValueError, TypeError) as exc:
        parser.error(_option_error(exc))
    except DivergenceError as exc:
        _print_warnings(caught, "run")
        print(f"trackwheel run: the simulation diverged: {exc}", file=sys.stderr)
        return 1
    except RuntimeError as exc:  # the kernel's static solve at the start failed
        _print_warnings(caught, "run")
        print(f"trackwheel run: the simulation could not start: {exc}", file=sys.stderr)
        return 1
    _print_warnings(caught, "run")
    x_d = defect_position(scene)
    if x_d is not None and not r.x_wheel[0] <= x_d <= r.x_wheel[-1]:
        x_d = None  # the run does not reach the joint's middle
    if scene.vehicle is not None:
        return _finish_vehicle_run(scene, args, r, x_d)
    try:
        a = analyse(r, defect_at=x_d)
    except RuntimeError as exc:  # a static solve of the quasi-static line failed
        print(f"trackwheel run: the analysis failed: {exc}", file=sys.stderr)
        return 1
    _print_run(scene, args.speed_kmh, r, a, _scene_name(scene, args))
    if args.plot is not None:
        from . import plots

        eig = _eigen(scene, np.linspace(0.0, scene.rail.length, 41), n_modes=4)
        try:
            plots.dynamic(r, a, eigen=eig).savefig(args.plot, dpi=150)
        except (OSError, ValueError) as exc:
            print(f"trackwheel run: cannot write --plot {args.plot}: {exc}", file=sys.stderr)
            return 1
        print(f"  plot           : {args.plot}")
    return 0


def _window_run(scene: Scene, args: argparse.Namespace, parser) -> int:
    """``run --distance``: the passage on the travelling window and its contact-force
    statistics, over the whole run and per 100 m."""
    if args.plot is not None:
        parser.error("--plot is not available with --distance (plot Result.normal_force "
                     "against Result.x_wheel from the API)")
    kw = _simulate_kwargs(args)
    kw.setdefault("fidelity", "linear/hertz")
    if args.x_end is None:
        kw["distance"] = args.distance
        kw.setdefault("x_start", 0.5 * scene.supports.spacing
                      - scene.active_vehicle.span[0])
    elif args.x_start is None:
        parser.error("--distance with --x-end needs --x-start")
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            r = simulate(scene, kmh(args.speed_kmh), **kw)
    except (ValueError, TypeError) as exc:
        parser.error(_option_error(exc))
    except DivergenceError as exc:
        _print_warnings(caught, "run")
        print(f"trackwheel run: the simulation diverged: {exc}", file=sys.stderr)
        return 1
    _print_warnings(caught, "run")
    N = np.atleast_2d(np.asarray(r.normal_force).T).T  # (samples, wheels)
    x = np.asarray(r.x_wheel).reshape(len(r.t), -1)[:, 0]
    w, zones = scene.window, scene.rail.absorbing_ends
    ends = f", {zones.length:g} m absorbing ends" if zones is not None else ""
    print(f"scene          : {_scene_name(scene, args)} on a travelling window of "
          f"{w.bays_behind} + {w.bays_ahead} bays ({scene.rail.length:g} m{ends}), "
          f"{kw['fidelity']}")
    print(f"run            : {x[-1] - x[0]:.1f} m at {args.speed_kmh:g} km/h, {r.steps} steps "
          f"in {r.wall_time:.1f} s ({1e6 * r.wall_time / max(r.steps, 1):.1f} us/step)")
    print(f"contact force  : {N.min() / 1e3:.2f} .. {N.max() / 1e3:.2f} kN, mean "
          f"{N.mean() / 1e3:.2f} kN, std {N.std() / 1e3:.2f} kN; lost contact: "
          f"{'yes' if (N <= 0.0).any() else 'no'}")
    print("per 100 m      :   from [m]   min [kN]   max [kN]   std [kN]")
    for x0 in np.arange(x[0], x[-1], 100.0):
        m = (x >= x0) & (x < x0 + 100.0)
        if m.sum() > 1:
            print(f"{'':17s}{x0:>8.1f}  {N[m].min() / 1e3:>9.2f}  {N[m].max() / 1e3:>9.2f}  "
                  f"{N[m].std() / 1e3:>9.2f}")
    return 0


def _print_sweep(df, store: Path, excitation: str) -> None:
    print(f"excitation: {excitation}")
    auto = df.attrs.get("fidelity_auto")
    if auto:
        print(f"--fidelity auto: {auto['chosen']} (adequate within {auto['tol']:g} on "
              f"{auto['sample_speed'] * 3.6:g} km/h, "
              f"{auto['sample_support_stiffness'] / 1e6:g} MN/m)")
    seeded = bool(df["seed"].notna().any())
    print(f"{'v [km/h]':>8}  {'k_s [MN/m]':>10}  " + ("seed  " if seeded else "")
          + f"{'amplitude [µm]':>14}  {'main f [Hz]':>11}  {'± [Hz]':>6}  "
          f"{'N min..max [kN]':>15}  {'N/P0':>6}  lost  error")
    for row in df.itertuples():
        head = (f"{row.speed_kmh:>8g}  {row.support_stiffness / 1e6:>10g}  "
                + (f"{row.seed:>4}  " if seeded else ""))
        if row.error:
            print(f"{head}{row.error}")
            continue
        print(f"{head}{row.amplitude * 1e6:>14.3f}  {row.main_frequency:>11.1f}  "
              f"{row.frequency_resolution:>6.1f}  "
              f"{row.min_contact_force / 1e3:>6.2f}..{row.max_contact_force / 1e3:<7.2f}  "
              f"{row.dynamic_factor:>6.3f}  {'yes' if row.lost_contact else 'no':>4}")
    if seeded and (df["error"] == "").any():
        from .sweep import summarise_seeds

        by = "speed" if df["support_stiffness"].nunique() == 1 else ["speed",
                                                                      "support_stiffness"]
        summary = summarise_seeds(df, ["max_contact_force", "dynamic_factor"], by=by)
        print("over the seeds (5th / 50th / 95th percentile):")
        for key, row in summary.iterrows():
            v, k = (key, None) if isinstance(by, str) else key
            where = f"{v * 3.6:>8g} km/h" + (f", {k / 1e6:g} MN/m" if k is not None else "")
            print(f"{where}: max N {_pcts(row, 'max_contact_force', 1e-3)} kN, N/P0 "
                  f"{_pcts(row, 'dynamic_factor', 1.0)} ({int(row[('n_seeds', '')])} seeds)")
    print(f"{len(df)} cases: {df.attrs.get('computed', 0)} computed, "
          f"{df.attrs.get('from_store', 0)} from the store {store}")


def _pcts(row, column: str, scale: float) -> str:
    return " / ".join(f"{row[(column, p)] * scale:.4g}" for p in ("p5", "p50", "p95"))


def _cmd_sweep(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    _speeds_kmh(args.speeds_kmh, "--speeds-kmh", parser)
    if args.out is not None:
        _output_file(args.out, "--out", parser)
    _writable_folder(args.store, "--store", parser, create=True)
    extra = {}
    if args.fidelity_tol is not None:
        if args.fidelity != "auto":
            parser.error("--fidelity-tol is only used with --fidelity auto")
        extra["fidelity_tol"] = args.fidelity_tol
    seeds = None
    if args.seeds is not None:
        seeds = [s for group in args.seeds for s in group]
        if len(set(seeds)) != len(seeds):
            parser.error(f"--seeds: a seed is given twice ({', '.join(map(str, seeds))})")
        if args.seed is not None:
            parser.error("give --seed (one realisation) or --seeds (several), not both")
    try:
        scene, notes = _excited_scene(_track_scene(args), args)
    except _OptionError as exc:
        parser.error(str(exc))
    _print_notes(notes, "sweep")
    try:
        df = sweep(scene, speed=[kmh(v) for v in args.speeds_kmh], seeds=seeds,
                   support_stiffness=args.support_stiffness, store=args.store,
                   progress=not args.no_progress, max_workers=args.workers,
                   **_simulate_kwargs(args), **extra)
    except (ValueError, TypeError) as exc:
        parser.error(_option_error(exc))
    _print_sweep(df, args.store, _describe(scene))
    if args.out is not None:
        try:
            df.to_csv(args.out, index=False)
        except OSError as exc:
            print(f"trackwheel sweep: cannot write --out {args.out}: {exc}", file=sys.stderr)
            return 1
        print(f"table written to {args.out}")
    n_failed = int((df["error"] != "").sum())
    if n_failed:
        print(f"{n_failed} case(s) failed (recorded with their error)", file=sys.stderr)
        return 1
    return 0


def _cmd_eigen(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    try:
        scene = _track_scene(args)
    except _OptionError as exc:
        parser.error(str(exc))
    length = scene.rail.length
    if not 0.0 <= args.position <= length:
        parser.error(f"--position {args.position:g} m is outside the rail; "
                     f"allowed range [0, {length:g}] m")
    try:
        res = _eigen(scene, [args.position], n_modes=args.n_modes)
    except ValueError as exc:  # e.g. more modes than the mesh has
        parser.error(str(exc).replace("n_modes", "--n-modes"))
    name = _scene_name(scene, args)
    print(f"{name}, wheel at X = {args.position:g} m ({res.n_elements} elements)")
    print("vertical modes:")
    for k, f in enumerate(res.frequencies[0], 1):
        print(f"  {k:>3}  {f:10.2f} Hz")
    if res.axial_frequencies.size:
        print("axial (x) modes of the rail: "
              + ", ".join(f"{f:.1f}" for f in res.axial_frequencies) + " Hz")
    return 0


def _frequency_mesh(scene: Scene, f_max: float, n_elements: int | None) -> tuple[int, str]:
    """Elements for the track up to ``f_max`` [Hz] (``n_elements`` if given): whole elements
    per support bay, at least ten per Euler-Bernoulli bending wavelength
    2 pi (EI / (m w^2))^(1/4) (shear shortens the wavelength a little; ten leave room), no fewer
    than the preset's. A note (empty if none) when MAX_ELEMENTS caps the count."""
    if n_elements is not None:
        return n_elements, ""
    r, d = scene.rail, scene.supports.spacing
    w = 2.0 * math.pi * max(f_max, 1.0)
    wavelength = 2.0 * math.pi * (r.bending_stiffness / (r.mass_per_length * w * w)) ** 0.25
    n_bays = max(round(r.length / d), 1)
    n = max(n_bays * math.ceil(10.0 * d / wavelength), r.n_elements)
    if n <= MAX_ELEMENTS:
        return n, ""
    n = max(MAX_ELEMENTS // n_bays, 1) * n_bays
    return n, (f"warning: {n} elements ({MAX_ELEMENTS} at most) give fewer than ten per bending "
               f"wavelength ({wavelength:.3g} m) at {f_max:g} Hz")


def _receptance_point(scene: Scene, at: str) -> tuple[float, str]:
    """--at: the point [m] and its description. Raises _OptionError."""
    from .plots import _receptance_points  # the points plots.receptance draws

    points = _receptance_points(scene)
    key = at.strip().lower().replace("-", "")
    if key in ("midspan", "support"):
        label = "mid-span" if key == "midspan" else "above a support"
        if label not in points:
            raise _OptionError(f"--at {at}: the rail has no supports")
        return points[label], label
    try:
        x = float(at)
    except ValueError:
        raise _OptionError(f"--at {at!r}: expected midspan, support or a position X [m]"
                           ) from None
    length = scene.rail.length
    if not 0.0 <= x <= length:
        raise _OptionError(f"--at {x:g} m is outside the rail; allowed range [0, {length:g}] m")
    return x, f"X = {x:g} m"


def _receptance_freqs(args: argparse.Namespace) -> np.ndarray:
    """--fmin/--fmax/--n [Hz]: log-spaced, or linear when --fmin is 0. Raises _OptionError."""
    if not 0.0 <= args.fmin < args.fmax:
        raise _OptionError(f"--fmin {args.fmin:g} / --fmax {args.fmax:g} Hz: allowed "
                           "0 <= fmin < fmax")
    if args.fmin == 0.0:
        return np.linspace(0.0, args.fmax, args.n)
    return np.geomspace(args.fmin, args.fmax, args.n)


def _print_receptance(scene: Scene, name: str, x: float, label: str, f: np.ndarray,
                      a: np.ndarray, n_elements: int) -> None:
    from .fidelity import pinned_pinned_frequencies

    print(f"{name}, {n_elements} elements")
    print(f"point receptance at X = {x:.4g} m ({label}), {f.size} frequencies "
          f"{f[0]:g} .. {f[-1]:g} Hz")
    k = int(np.argmax(np.abs(a)))
    print(f"  largest |alpha|: {abs(a[k]):.4g} m/N at {f[k]:.5g} Hz")
    f_e, f_t = pinned_pinned_frequencies(scene)
    print(f"  pinned-pinned frequency of one {scene.supports.spacing:g} m bay (closed form): "
          f"{f_e:.5g} Hz Euler-Bernoulli, {f_t:.5g} Hz Timoshenko")
    print(f"  {'f [Hz]':>10}  {'|alpha| [m/N]':>13}  {'phase [deg]':>11}")
    for i in np.unique(np.linspace(0, f.size - 1, min(f.size, 13)).round().astype(int)):
        print(f"  {f[i]:>10.5g}  {abs(a[i]):>13.4e}  {math.degrees(np.angle(a[i])):>11.1f}")


def _cmd_receptance(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    from .frequency import receptance

    if args.out is not None:
        _output_file(args.out, "--out", parser)
    if args.plot is not None:
        _output_file(args.plot, "--plot", parser, formats=_figure_formats())
    try:
        scene = _track_scene(args)
        f = _receptance_freqs(args)
        x, label = _receptance_point(scene, args.at)
    except _OptionError as exc:
        parser.error(str(exc))
    n_el, note = _frequency_mesh(scene, args.fmax, args.n_elements)
    _print_notes([note] if note else [], "receptance")
    try:
        a = receptance(scene, x, f, n_elements=n_el)
    except ValueError as exc:
        parser.error(_option_error(exc))
    _print_receptance(scene, _scene_name(scene, args), x, label, f, a, n_el)
    if args.out is not None:
        table = np.column_stack([f, a.real, a.imag, np.abs(a), np.degrees(np.angle(a))])
        if not _write_csv(args.out, table, "f_hz,re_m_per_n,im_m_per_n,abs_m_per_n,phase_deg",
                          "receptance"):
            return 1
    if args.plot is not None:
        from . import plots

        if not _save_figure(plots.receptance(scene, f, n_elements=n_el), args.plot,
                            "receptance"):
            return 1
    return 0


def _cmd_decay_rate(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    from .frequency import (EN15461_SPANS, ISO3095_BANDS, ISO3095_VERTICAL_LIMIT,
                            iso3095_band_edges)

    if args.out is not None:
        _output_file(args.out, "--out", parser)
    if args.plot is not None:
        _output_file(args.plot, "--plot", parser, formats=_figure_formats())
    try:
        scene = _track_scene(args, length=_DECAY_LENGTH)
    except _OptionError as exc:
        parser.error(str(exc))
    span = (EN15461_SPANS[-1] + 1.0) * scene.supports.spacing
    if scene.rail.length <= span:
        parser.error(f"the EN 15461 positions need a rail longer than {span:g} m (67 support "
                     f"spacings); {_scene_name(scene, args)} is {scene.rail.length:g} m: use "
                     f"--track ballasted (default {_DECAY_LENGTH:g} m)")
    n_el, note = _frequency_mesh(scene, iso3095_band_edges()[-1], args.n_elements)
    _print_notes([note] if note else [], "decay-rate")
    from .frequency import band_decay_rates

    dr = band_decay_rates(scene, args.per_band, n_el)
    limit = np.asarray(ISO3095_VERTICAL_LIMIT)
    print(f"{_scene_name(scene, args)}, {scene.rail.length:g} m, {n_el} elements")
    print(f"vertical track decay rate (EN 15461, {args.per_band} frequencies per band) and the "
          "ISO 3095:2013 lower limit")
    print(f"  {'band [Hz]':>9}  {'DR [dB/m]':>9}  {'limit':>6}")
    for fc, d, lim in zip(ISO3095_BANDS, dr, limit):
        print(f"  {fc:>9g}  {d:>9.3g}  {lim:>6g}  {'' if d >= lim else 'below the limit'}")
    print(f"  {int(np.sum(dr >= limit))} of {dr.size} bands at or above the limit")
    if args.out is not None:
        table = np.column_stack([ISO3095_BANDS, dr, limit])
        if not _write_csv(args.out, table, "band_hz,decay_rate_db_per_m,iso3095_limit_db_per_m",
                          "decay-rate"):
            return 1
    if args.plot is not None:
        from . import plots

        edges = iso3095_band_edges()
        f = np.geomspace(edges[0], edges[-1], 8 * edges.size)
        if not _save_figure(plots.decay_rate(scene, f, n_elements=n_el), args.plot,
                            "decay-rate"):
            return 1
    return 0


def _write_csv(path: Path, table: np.ndarray, header: str, command: str) -> bool:
    """Write ``table`` as CSV (17 digits: the values read back bit-identical); False on error."""
    try:
        np.savetxt(path, table, delimiter=",", header=header, comments="", fmt="%.17g")
    except OSError as exc:
        print(f"trackwheel {command}: cannot write --out {path}: {exc}", file=sys.stderr)
        return False
    print(f"  table          : {path}")
    return True


def _save_figure(fig, path: Path, command: str) -> bool:
    """Save ``fig`` to ``path`` (150 dpi); False, with a one-line error, if it cannot."""
    try:
        fig.savefig(path, dpi=150)
    except (OSError, ValueError) as exc:
        print(f"trackwheel {command}: cannot write --plot {path}: {exc}", file=sys.stderr)
        return False
    print(f"  plot           : {path}")
    return True


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``trackwheel`` console script; returns the exit code."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        return args.run(args, args.parser)
    except SystemExit as exc:  # argparse: --help/--version (0) and usage errors (2)
        return exc.code if isinstance(exc.code, int) else 1
    except BrokenPipeError:  # the reader left (`trackwheel run ... | head`): stop quietly
        # the interpreter flushes stdout again at exit: point it at devnull so that it can
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1


if __name__ == "__main__":
    sys.exit(main())
