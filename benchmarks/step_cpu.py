"""Per-step CPU time of each kernel path, for before/after comparisons of kernel changes.

Best CPU time (``time.process_time``: less sensitive than wall time to other jobs on a shared
machine) of several runs per case: generalized-alpha passages at 20/40/80 elements (300 km/h,
dt = 1e-5 s), explicit RK4 at dt = 1e-6 s and 1e-7 s, and the linear sprung/Hertz levels.
Run it with two builds alternately (e.g. two venvs) and compare; prints one JSON line and, with
``--csv``, writes benchmarks/step_cpu.csv.

    python benchmarks/step_cpu.py [--csv]
"""

from __future__ import annotations

import argparse
import json
import time

import trackwheel as tw

SCENE = tw.Scene.kato2005()
V = tw.kmh(300)


def cpu_per_step(fn, repeats: int) -> float:
    """Best CPU time per step over ``repeats`` runs [us]."""
    best, steps = float("inf"), 1
    for _ in range(repeats):
        t0 = time.process_time()
        r = fn()
        best = min(best, time.process_time() - t0)
        steps = r.steps
    return 1e6 * best / steps


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--csv", action="store_true", help="also write benchmarks/step_cpu.csv")
    args = ap.parse_args(argv)
    tw.simulate(SCENE, V, x_end=0.5, dt=1e-5, n_elements=20, progress=False)  # warm up
    out = {}
    for ne in (20, 40, 80):
        out[f"generalized_alpha_{ne}"] = cpu_per_step(
            lambda ne=ne: tw.simulate(SCENE, V, dt=1e-5, n_elements=ne, progress=False), 5)
    for dt, x_end in ((1e-6, 1.0), (1e-7, 0.25 + 4.5 / 80)):
        out[f"explicit_20_dt{dt:g}"] = cpu_per_step(
            lambda dt=dt, x_end=x_end: tw.simulate(SCENE, V, integrator="explicit", dt=dt,
                                                   n_elements=20, x_end=x_end, progress=False),
            3)
    for level in ("linear/sprung", "linear/hertz"):
        out[level] = cpu_per_step(
            lambda level=level: tw.simulate(SCENE, V, fidelity=level, dt=1e-5, progress=False),
            15)
    print(json.dumps({k: round(v, 3) for k, v in out.items()}))
    if args.csv:
        from _common import write_csv

        write_csv("step_cpu.csv", [{"case": k, "cpu_us_per_step": v} for k, v in out.items()])


if __name__ == "__main__":
    main()
