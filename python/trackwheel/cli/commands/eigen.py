"""``trackwheel eigen``: the natural frequencies with the wheel at one position."""

from __future__ import annotations

import argparse

from ...reproduce import X_REPORT
from ...run.eigen import eigen
from ..options import finite_float, positive_int, track_option
from ..scenes import OptionError, scene_name, track_scene


def add(sub) -> None:
    p = sub.add_parser(
        "eigen", help="print the natural frequencies with the wheel at one position",
        description="Lowest vertical natural frequencies [Hz] of the wheel/rail/support system "
                    "of Scene.kato2005() with the wheel at --position, and the rail's lowest "
                    "axial frequencies.")
    p.add_argument("--position", type=finite_float, default=X_REPORT, metavar="X",
                   help=f"wheel position X [m], 0 <= X <= L (default {X_REPORT})")
    p.add_argument("--n-modes", type=positive_int, default=6, metavar="N",
                   help="number of vertical modes (default 6)")
    track_option(p)
    p.set_defaults(run=run, parser=p)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    try:
        scene = track_scene(args)
    except OptionError as exc:
        parser.error(str(exc))
    length = scene.rail.length
    if not 0.0 <= args.position <= length:
        parser.error(f"--position {args.position:g} m is outside the rail; "
                     f"allowed range [0, {length:g}] m")
    try:
        res = eigen(scene, [args.position], n_modes=args.n_modes)
    except ValueError as exc:  # e.g. more modes than the mesh has
        parser.error(str(exc).replace("n_modes", "--n-modes"))
    name = scene_name(scene, args)
    print(f"{name}, wheel at X = {args.position:g} m ({res.n_elements} elements)")
    print("vertical modes:")
    for k, f in enumerate(res.frequencies[0], 1):
        print(f"  {k:>3}  {f:10.2f} Hz")
    if res.axial_frequencies.size:
        print("axial (x) modes of the rail: "
              + ", ".join(f"{f:.1f}" for f in res.axial_frequencies) + " Hz")
    return 0
