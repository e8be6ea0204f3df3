"""``trackwheel periodic``: the steady state of the wheel on the periodic track in the frequency
domain, its contact-force harmonics and dynamic factor (or, over a random profile, the force's
one-third-octave bands and percentiles)."""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from pathlib import Path

from ...base.limits import MAX_SPEED
from ...base.units import kmh
from ...excitation import RandomProfile
from ...run.periodic import PERIODIC_FIDELITIES, periodic_response, random_response
from ...scene import Scene
from ..checks import option_error, output_options, speeds_kmh
from ..formatting import print_notes, save_figure
from ..options import excitation_options, finite_float, positive_int, track_option
from ..scenes import OptionError, describe, excited_scene, scene_name, track_scene


#: the bands printed: total RMS at least this fraction of the largest band's [-]
SHOWN = 1e-3


def add(sub) -> None:
    p = sub.add_parser(
        "periodic", help="the steady state in the frequency domain: force harmonics",
        description="The steady response of the wheel at constant speed on the --track made "
                    "infinite and periodic in its sleeper bay, in the frequency domain "
                    "(trackwheel.periodic_response; docs: Model § The periodic level): per "
                    "speed the contact-force harmonics (the sleeper passing at k v/d and, with "
                    "sine --irregularity, each sine and its side bands), the force's range, "
                    "the dynamic factor max N / P and max|d|. With a random --irregularity "
                    "(one spectrum), the force's one-third-octave band RMS and the dynamic "
                    "factor's percentiles under a Gaussian law, without realisations "
                    "(trackwheel.random_response). It refuses, naming why, what it cannot "
                    "model: contact loss, an undamped track (the paper's: give "
                    "--support-damping), joints and flats, several wheels.")
    p.add_argument("--speed-kmh", type=finite_float, nargs="+", required=True, metavar="V",
                   help=f"forward speed(s) [km/h], 0 < V <= {MAX_SPEED * 3.6:.4g}")
    p.add_argument("--support-stiffness", type=finite_float, metavar="K",
                   help="support stiffness k_s [N/m] (with --track ballasted the rail pad's, "
                        "default 180e6; kato2005: 140e6)")
    p.add_argument("--support-damping", type=finite_float, metavar="C",
                   help="support damping c_s [N s/m], > 0 (the rail pad's with --track "
                        "ballasted, default 18e3; the paper's track has none, and an undamped "
                        "periodic track has no steady state)")
    track_option(p)
    p.set_defaults(track="ballasted")
    excitation_options(p)
    p.add_argument("--contact", choices=PERIODIC_FIDELITIES, metavar="LEVEL",
                   help="the time-domain level reproduced: " + ", ".join(PERIODIC_FIDELITIES)
                        + " (default: linear/hertz for a Hertzian scene contact, else "
                          "linear/sprung)")
    p.add_argument("--harmonics", type=positive_int, default=6, metavar="N",
                   help="sleeper-passing harmonics and side bands reported, 1..64 (default 6)")
    p.add_argument("--out", type=Path, metavar="CSV",
                   help="write the force harmonics (speed_kmh, frequency_hz, amplitude_n, "
                        "phase_rad, source, order, component) or, with a random profile, the "
                        "band RMS to this file")
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save the force over two bays and its harmonics "
                        "(plots.periodic_force), or the band RMS (plots.random_force_bands "
                        "of the highest speed), to this file")
    p.set_defaults(run=run, parser=p)


def _scene(args: argparse.Namespace) -> tuple[Scene, list[str]]:
    """The --track scene with the support options and the excitation. Raises OptionError."""
    scene = track_scene(args, args.support_stiffness)
    if args.support_damping is not None:
        if not args.support_damping > 0.0:
            raise OptionError(f"--support-damping {args.support_damping:g}: allowed range "
                              "(0, inf) N s/m")
        scene = dataclasses.replace(scene, supports=dataclasses.replace(
            scene.supports, damping=args.support_damping))
    return excited_scene(scene, args)


def _random_part(scene: Scene):
    """The scene's one random profile (None: none). Raises OptionError if it is mixed."""
    parts = [] if scene.irregularity is None else list(scene.irregularity.parts)
    randoms = [p for p in parts if isinstance(p, RandomProfile)]
    if not randoms:
        return None
    if len(parts) > 1:
        raise OptionError("--irregularity: give one random spectrum alone, or sines (the "
                          "periodic level takes either a spectrum or a sum of sines)")
    return randoms[0]


def _print_harmonics(r, seconds: float) -> None:
    print(f"v = {r.speed * 3.6:g} km/h ({r.speed:.2f} m/s): sleeper passing "
          f"{r.sleeper_frequency:.4g} Hz, static load P = {r.mean_force / 1e3:.4g} kN, "
          f"{r.fidelity} (contact stiffness {r.contact_stiffness:.4g} N/m)")
    print("  force harmonics, N(t) = P + sum A cos(2 pi f t + phase), t = 0 over a support:")
    print(f"  {'f [Hz]':>10}  {'A [N]':>10}  {'phase [deg]':>11}  {'source':<15}  "
          f"{'order':>5}  component")
    for row in r.force_harmonics.itertuples():
        print(f"  {row.frequency_hz:>10.5g}  {row.amplitude_n:>10.4g}  "
              f"{math.degrees(row.phase_rad):>11.1f}  {row.source:<15}  {row.order:>5}  "
              f"{row.component}")
    print(f"  contact force  : {r.min_force / 1e3:.3f} .. {r.max_force / 1e3:.3f} kN, RMS of "
          f"N - P {r.force_rms:.4g} N")
    print(f"  dynamic factor : {r.dynamic_factor:.4f}  (max N / P)")
    print(f"  max|d|         : {r.amplitude * 1e6:.4g} µm, main frequency "
          f"{r.main_frequency:.4g} Hz  (d = y_B - y_qs)")
    print(f"  time           : {seconds * 1e3:.3g} ms")


def _print_random(r, seconds: float) -> None:
    print(f"v = {r.speed * 3.6:g} km/h: sigma of N - P {r.sigma:.4g} N "
          f"({r.sigma / r.static_load:.3g} P), RMS with the sleeper passing {r.rms:.4g} N, "
          f"P(N <= 0) = {r.loss_probability:.3g}")
    print(f"  one-third-octave bands above {SHOWN:g} of the largest:")
    print(f"  {'band [Hz]':>10}  {'random [N]':>10}  {'sleeper [N]':>11}  {'total [N]':>9}")
    bands = r.band_rms
    for b in bands[bands.rms_n >= SHOWN * bands.rms_n.max()].itertuples():
        print(f"  {b.centre_hz:>10.4g}  {b.rms_random_n:>10.4g}  {b.rms_sleeper_n:>11.4g}  "
              f"{b.rms_n:>9.4g}")
    print("  dynamic factor percentiles: " + ", ".join(
        f"{q.percentile:g} %: {q.dynamic_factor:.4f}" for q in r.percentiles.itertuples()))
    print(f"  time           : {seconds * 1e3:.3g} ms")


def _compute(scene: Scene, args: argparse.Namespace, part, parser) -> list:
    """Every speed's response (timed), or a one-line usage error naming the speed."""
    out = []
    for v in args.speed_kmh:
        t0 = time.perf_counter()
        try:
            if part is None:
                r = periodic_response(scene, kmh(v), n_harmonics=args.harmonics,
                                      fidelity=args.contact)
            else:
                r = random_response(scene, kmh(v), part.spectrum, wavelengths=part.wavelengths,
                                    fidelity=args.contact)
        except (ValueError, RuntimeError) as exc:
            text = option_error(exc).replace("Supports.damping", "--support-damping")
            parser.error(f"at {v:g} km/h: {text}")
        out.append((r, time.perf_counter() - t0))
    return out


def _write(results, part, path: Path) -> bool:
    import pandas as pd

    tables = []
    for r, _ in results:
        t = r.force_harmonics if part is None else r.band_rms
        tables.append(t.assign(speed_kmh=r.speed * 3.6)[["speed_kmh", *t.columns]])
    try:
        pd.concat(tables).to_csv(path, index=False)
    except OSError as exc:
        print(f"trackwheel periodic: cannot write --out {path}: {exc}", file=sys.stderr)
        return False
    print(f"table written to {path}")
    return True


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    output_options(args, parser)
    speeds_kmh(args.speed_kmh, "--speed-kmh", parser)
    if args.harmonics > 64:
        parser.error(f"--harmonics {args.harmonics}: allowed range 1..64")
    try:
        scene, notes = _scene(args)
        part = _random_part(scene)
    except OptionError as exc:
        parser.error(str(exc))
    except (ValueError, TypeError) as exc:  # e.g. a support stiffness out of range
        parser.error(option_error(exc))
    print_notes(notes, "periodic")
    results = _compute(scene, args, part, parser)
    k_name = "k_p" if scene.supports.layered else "k_s"
    print(f"{scene_name(scene, args)} made infinite and periodic in its "
          f"{scene.supports.spacing:g} m bay, {k_name} = {scene.supports.stiffness / 1e6:g} "
          f"MN/m, c = {scene.supports.damping / 1e3:g} kN s/m; excitation: {describe(scene)}")
    for r, seconds in results:
        (_print_harmonics if part is None else _print_random)(r, seconds)
    if args.out is not None and not _write(results, part, args.out):
        return 1
    if args.plot is not None:
        from ... import plots  # matplotlib only when a figure is drawn

        fig = (plots.periodic_force([r for r, _ in results]) if part is None
               else plots.random_force_bands(max(results, key=lambda x: x[0].speed)[0]))
        if not save_figure(fig, args.plot, "periodic"):
            return 1
    return 0
