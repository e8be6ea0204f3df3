"""Issue 12: the full model's per-step cost with and without the shear-deformable rail.

The same passage on the full path with ``Rail(beam="euler")`` (the ANCF cable) and
``Rail(beam="timoshenko")`` (the shear-deformable ANCF element), on the same mesh and time step
(the Euler-Bernoulli scene's derived ones), alternating the two, median of 5 runs each; the
ratio comes from one run of this script on an otherwise idle machine. Two tracks: the paper's
(5 m, 80 elements) and the ballasted preset (50.4 m, 8 elements per bay, 10 m absorbing ends).
Writes benchmarks/shear.csv.

    python benchmarks/shear.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import dataclasses
import platform
import statistics
import time

from _common import write_csv

import trackwheel as tw


def scenes():
    """(name, Euler-Bernoulli scene, x_start [m], x_end [m]) of the two tracks."""
    b = tw.Scene.ballasted_track(50.4, elements_per_bay=8)
    b = dataclasses.replace(b, rail=dataclasses.replace(b.rail,
                                                        absorbing_ends=tw.AbsorbingEnds(10.0)))
    return [("kato2005", tw.Scene.kato2005(), 2.0, 3.0), ("ballasted 50.4 m", b, 24.0, 26.0)]


def timed(scene, settings, x0, x1):
    t0 = time.perf_counter()
    r = tw.simulate(scene, tw.kmh(300), x_start=x0, x_end=x1, progress=False, **settings)
    return time.perf_counter() - t0, r.steps


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    rows = []
    for name, euler, x0, x1 in scenes():
        timo = dataclasses.replace(euler, rail=dataclasses.replace(euler.rail, beam="timoshenko"))
        settings = tw.default_settings(euler)
        walls = {"euler": [], "timoshenko": []}
        steps = 0
        for _ in range(args.repeat):  # alternating, so drifts of the machine hit both alike
            for beam, scene in (("euler", euler), ("timoshenko", timo)):
                wall, steps = timed(scene, settings, x0, x1)
                walls[beam].append(wall)
        med = {k: statistics.median(v) for k, v in walls.items()}
        ne = settings["n_elements"]
        for beam, m in med.items():
            rows.append(dict(track=name, beam=beam, n_elements=ne, dt=settings["dt"],
                             steps=steps, median_wall_s=round(m, 4),
                             us_per_step=round(m / steps * 1e6, 2),
                             ratio_to_euler=round(m / med["euler"], 3),
                             machine=platform.machine()))
        print(f"{name}: {ne} elements, {steps} steps; per step euler "
              f"{med['euler'] / steps * 1e6:.1f} us, timoshenko "
              f"{med['timoshenko'] / steps * 1e6:.1f} us, ratio "
              f"{med['timoshenko'] / med['euler']:.2f}", flush=True)
    write_csv("shear.csv", rows)


if __name__ == "__main__":
    main()
