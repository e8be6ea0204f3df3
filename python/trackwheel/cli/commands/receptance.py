"""``trackwheel receptance``: the track's point receptance over frequency."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from ...run import frequency
from ...scene import Scene
from ...run.defaults import pinned_pinned_frequencies
from ..checks import option_error, output_options
from ..formatting import frequency_elements, save_figure, write_csv
from ..options import damping_options, finite_float, mesh_option, positive_int, track_option
from ..scenes import OptionError, scene_name, track_scene


def add(sub) -> None:
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
    p.add_argument("--fmin", type=finite_float, default=20.0, metavar="F",
                   help="lowest frequency [Hz], >= 0 (default 20)")
    p.add_argument("--fmax", type=finite_float, default=5000.0, metavar="F",
                   help="highest frequency [Hz] (default 5000)")
    p.add_argument("--n", type=positive_int, default=400, metavar="N",
                   help="frequencies, log-spaced (linear from 0 Hz; default 400)")
    mesh_option(p)
    damping_options(p, contact=False)
    track_option(p, fidelity=False)
    p.add_argument("--out", type=Path, metavar="CSV",
                   help="write f_hz, re_m_per_n, im_m_per_n, abs_m_per_n, phase_deg to this file")
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save magnitude and phase at the mid-span and above the support "
                        "(plots.receptance) to this file")
    p.set_defaults(run=run, parser=p)


def _receptance_point(scene: Scene, at: str) -> tuple[float, str]:
    """--at: the point [m] and its description. Raises OptionError."""
    points = frequency.receptance_points(scene)  # the points plots.receptance draws
    key = at.strip().lower().replace("-", "")
    if key in ("midspan", "support"):
        label = "mid-span" if key == "midspan" else "above a support"
        if label not in points:
            raise OptionError(f"--at {at}: the rail has no supports")
        return points[label], label
    try:
        x = float(at)
    except ValueError:
        raise OptionError(f"--at {at!r}: expected midspan, support or a position X [m]"
                          ) from None
    length = scene.rail.length
    if not 0.0 <= x <= length:
        raise OptionError(f"--at {x:g} m is outside the rail; allowed range [0, {length:g}] m")
    return x, f"X = {x:g} m"


def _receptance_freqs(args: argparse.Namespace) -> np.ndarray:
    """--fmin/--fmax/--n [Hz]: log-spaced, or linear when --fmin is 0. Raises OptionError."""
    if not 0.0 <= args.fmin < args.fmax:
        raise OptionError(f"--fmin {args.fmin:g} / --fmax {args.fmax:g} Hz: allowed "
                          "0 <= fmin < fmax")
    if args.fmin == 0.0:
        return np.linspace(0.0, args.fmax, args.n)
    return np.geomspace(args.fmin, args.fmax, args.n)


def _print_receptance(scene: Scene, name: str, x: float, label: str, f: np.ndarray,
                      a: np.ndarray, n_elements: int) -> None:
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


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    output_options(args, parser)
    try:
        scene = track_scene(args)
        f = _receptance_freqs(args)
        x, label = _receptance_point(scene, args.at)
    except OptionError as exc:
        parser.error(str(exc))
    n_el = frequency_elements(scene, args.fmax, args.n_elements, "receptance")
    try:
        a = frequency.receptance(scene, x, f, n_elements=n_el)
    except ValueError as exc:
        parser.error(option_error(exc))
    _print_receptance(scene, scene_name(scene, args), x, label, f, a, n_el)
    if args.out is not None:
        table = np.column_stack([f, a.real, a.imag, np.abs(a), np.degrees(np.angle(a))])
        if not write_csv(args.out, table, "f_hz,re_m_per_n,im_m_per_n,abs_m_per_n,phase_deg",
                         "receptance"):
            return 1
    if args.plot is not None:
        from ... import plots  # matplotlib only when a figure is drawn

        if not save_figure(plots.receptance(scene, f, n_elements=n_el), args.plot,
                           "receptance"):
            return 1
    return 0
