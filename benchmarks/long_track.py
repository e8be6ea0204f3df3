"""Issue 12 targets for long rails: cost per time step against rail length, and a 100 m passage.

1. Per-step cost at rail lengths 25, 50, 100, 200 m (8 elements per support bay), on the linear
   path ("linear/sprung") and the full model ("full"), over a short stretch of travel: the cost
   per step per element should be constant within 20 % (everything per step is banded, O(n)).
2. A 100 m passage at 300 km/h (1.2 s of travel, X = 2 m to 102 m of a 104 m rail with 10 m
   absorbing ends) on the linear path (target < 10 s on one core) and the full model (< 60 s).

The track is :func:`track` (single spring supports) or, with ``--track ballasted``,
:func:`ballasted` (Scene.ballasted_track: pad, sleeper, ballast, its own wheel). Derived time
step (150 steps per period of the wheel on its contact spring). Writes
benchmarks/long_track.csv (benchmarks/long_track_ballasted.csv).

    python benchmarks/long_track.py [--stretch 0.2] [--skip-full-passage] [--track ballasted]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import platform
import time

from _common import write_csv

import trackwheel as tw

ZONE = 10.0  # absorbing end zone at each end [m]


def track(length: float) -> tw.Scene:
    """A UIC60-like rail (E = 210 GPa, A = 7.69e-3 m^2, I = 3.055e-5 m^4, the set issue 12's
    ballasted preset is to use) on single spring supports every 0.6 m (the pads alone:
    180 MN/m, 18 kN s/m), `length` [m] long with absorbing ends, under the paper's wheel."""
    s = tw.Scene.kato2005()
    rail = dataclasses.replace(s.rail, length=length, youngs_modulus=210e9, area=7.69e-3,
                               second_moment=3.055e-5,
                               absorbing_ends=tw.AbsorbingEnds(min(ZONE, length / 4)))
    sup = tw.Supports(stiffness=180e6, damping=18e3, spacing=0.6)
    return dataclasses.replace(s, rail=rail, supports=sup)


def ballasted(length: float) -> tw.Scene:
    """Scene.ballasted_track with 8 elements per 0.6 m bay, `length` rounded to whole bays,
    with the same absorbing ends as :func:`track`."""
    s = tw.Scene.ballasted_track(0.6 * round(length / 0.6), elements_per_bay=8)
    rail = dataclasses.replace(s.rail, absorbing_ends=tw.AbsorbingEnds(min(ZONE, length / 4)))
    return dataclasses.replace(s, rail=rail)


def run(scene, fidelity, x0, x1):
    speed = tw.kmh(300)
    t0 = time.perf_counter()
    r = tw.simulate(scene, speed, fidelity=fidelity, x_start=x0, x_end=x1, progress=False)
    wall = time.perf_counter() - t0
    return wall, r


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--stretch", type=float, default=0.2, help="travel per cost run [m]")
    ap.add_argument("--skip-full-passage", action="store_true")
    ap.add_argument("--track", choices=("single", "ballasted"), default="single")
    args = ap.parse_args(argv)
    make = ballasted if args.track == "ballasted" else track
    rows = []
    for fidelity in ("linear/sprung", "full"):
        for length in (25.0, 50.0, 100.0, 200.0):
            scene = make(length)
            x0 = length / 2
            wall, r = run(scene, fidelity, x0, x0 + args.stretch)
            ne, steps = r.settings.n_elements, r.steps
            per = wall / steps / ne
            rows.append(dict(case="per_step", fidelity=fidelity, length_m=scene.rail.length,
                             n_elements=ne, steps=steps, wall_s=round(wall, 4),
                             us_per_step_per_element=round(per * 1e6, 4)))
            print(f"{fidelity:14s} L = {length:5.0f} m, {ne:5d} elements: {steps} steps in "
                  f"{wall:.3f} s, {per * 1e6:.3f} us per step per element", flush=True)
    for fidelity in ("linear/sprung", "full"):
        if fidelity == "full" and args.skip_full_passage:
            continue
        scene = make(104.0)
        wall, r = run(scene, fidelity, 2.0, 102.0)
        rows.append(dict(case="passage_100m", fidelity=fidelity, length_m=scene.rail.length,
                         n_elements=r.settings.n_elements, steps=r.steps,
                         wall_s=round(wall, 3), us_per_step_per_element=""))
        print(f"{fidelity:14s} 100 m passage at 300 km/h: {r.steps} steps, "
              f"{wall:.2f} s", flush=True)
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores")
    write_csv("long_track.csv" if args.track == "single" else "long_track_ballasted.csv", rows)


if __name__ == "__main__":
    main()
