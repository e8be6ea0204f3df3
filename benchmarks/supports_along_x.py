"""Per-support properties: the cost of a run over a track that varies along X against the uniform
track (docs: Model § Supports varying along the track).

The ballasted preset (30 m, 8 elements per bay) at 300 km/h from 8 m to 22 m, on the full and the
linear/hertz level, three tracks: uniform; a cosine transition of the ballast stiffness
50 -> 200 MN/m at 15 m over 3 m with a lognormal scatter (cv 0.3) on it; and the uniform values
given as one value per sleeper (a check: the same kernel input, the same counts). The cases are
alternated, each timed ``--repeats`` times (the kernel's own wall time, median); the ratios are
taken within the run. Machine-independent counts beside them: steps and Newton iterations.
The per-support values cost only at model build (resolved once per scene, cached); the kernel
held per-support vectors before.

    python benchmarks/supports_along_x.py [--repeats 7]
"""

from __future__ import annotations

import argparse
import dataclasses as dc
import statistics

from _common import write_csv

import trackwheel as tw


def tracks():
    base = tw.Scene.ballasted_track(elements_per_bay=8)
    sup = base.supports
    n = len(base.support_positions)
    varying = sup.transition(15.0, ramp=3.0, shape="cosine",
                             ballast_stiffness=(50e6, 200e6)).scattered(0.3, seed=1)
    per_sleeper = dc.replace(sup, ballast_stiffness=[sup.ballast_stiffness] * n)
    return {"uniform": base, "transition + scatter": dc.replace(base, supports=varying),
            "uniform, one value per sleeper": dc.replace(base, supports=per_sleeper)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    v = tw.kmh(300)
    rows = []
    for fidelity in ("full", "linear/hertz"):
        kw = dict(x_start=8.0, x_end=22.0, fidelity=fidelity, progress=False)
        scenes = tracks()
        walls = {name: [] for name in scenes}
        runs = {}
        for name, s in scenes.items():  # warm up: model build, quasi-static caches
            runs[name] = tw.simulate(s, v, **kw)
        for _ in range(args.repeats):  # alternate the cases
            for name, s in scenes.items():
                walls[name].append(tw.simulate(s, v, **kw).wall_time)
        ref = statistics.median(walls["uniform"])
        for name, r in runs.items():
            med = statistics.median(walls[name])
            rows.append(dict(fidelity=fidelity, track=name, steps=r.steps,
                             newton_iterations=r.newton_iterations,
                             kernel_median_s=med, us_per_step=1e6 * med / r.steps,
                             ratio_to_uniform=med / ref))
            print(f"{fidelity:13s} {name:32s} {r.steps} steps, {r.newton_iterations} Newton, "
                  f"{1e6 * med / r.steps:7.2f} us/step, x{med / ref:.3f}")
    write_csv("supports_along_x.csv", rows)


if __name__ == "__main__":
    main()
