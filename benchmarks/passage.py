"""Issue 4 performance target: a full passage of the paper's scene at 300 km/h.

20 elements, generalized-alpha at dt = 1e-5 s, wheel from 0.25 m to 4.75 m (5400 steps).
Target: under 0.1 s wall on one core. Prints the median of N runs (default 9) and, as a baseline
timed in the same run, the explicit RK4 scheme at its default step over the same passage and at
the paper's dt = 1e-7 s over a 1/20 stretch (scaled), plus the kernel's Newton statistics.
Writes benchmarks/passage.csv.

    python benchmarks/passage.py [--repeats 9]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import time

from _common import write_csv

import trackwheel as tw


def timed(fn, repeats):
    walls = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        walls.append(time.perf_counter() - t0)
    return statistics.median(walls), min(walls), out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=9)
    args = ap.parse_args(argv)
    scene = tw.Scene.kato2005()
    v = tw.kmh(300)
    ga = dict(n_elements=20, dt=1e-5)  # the setting (not simulate's derived defaults)
    tw.simulate(scene, v, x_end=0.5, **ga)  # warm up (imports, caches)

    rows = []
    med, best, r = timed(lambda: tw.simulate(scene, v, **ga), args.repeats)
    kernel = statistics.median(
        [tw.simulate(scene, v, **ga).wall_time for _ in range(args.repeats)])
    rows.append(dict(case="generalized_alpha dt=1e-5 full passage", steps=r.steps,
                     median_s=med, best_s=best, kernel_median_s=kernel,
                     us_per_step=1e6 * kernel / r.steps,
                     newton_per_step=r.newton_iterations / r.steps))
    med, best, r = timed(lambda: tw.simulate(scene, v, integrator="explicit", n_elements=20,
                                             dt=1e-6), args.repeats)
    rows.append(dict(case=f"explicit RK4 dt={r.settings['dt']:.2e} full passage", steps=r.steps,
                     median_s=med, best_s=best, kernel_median_s=r.wall_time,
                     us_per_step=1e6 * r.wall_time / r.steps, newton_per_step=0.0))
    x_end = 0.25 + 4.5 / 20
    med, best, r = timed(
        lambda: tw.simulate(scene, v, integrator="explicit", n_elements=20, dt=1e-7,
                            x_end=x_end), 3)
    rows.append(dict(case="explicit RK4 dt=1e-7 (paper), 1/20 of the passage, x20",
                     steps=r.steps * 20, median_s=20 * med, best_s=20 * best,
                     kernel_median_s=20 * r.wall_time,
                     us_per_step=1e6 * r.wall_time / r.steps, newton_per_step=0.0))

    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}")
    for row in rows:
        print(f"{row['case']:<58s} steps={row['steps']:>8d}  median {row['median_s']:.4f} s"
              f"  (best {row['best_s']:.4f} s, kernel {row['kernel_median_s']:.4f} s, "
              f"{row['us_per_step']:.1f} us/step, Newton/step {row['newton_per_step']:.2f})")
    ga = rows[0]["median_s"]
    print(f"target: generalized-alpha full passage < 0.1 s: {ga:.4f} s -> "
          f"{'met' if ga < 0.1 else 'NOT met'}; paper's scheme / ours = {rows[2]['median_s'] / ga:.0f}x")
    write_csv("passage.csv", rows)


if __name__ == "__main__":
    main()
