"""Issue 13 performance targets: what an irregularity costs, and a Monte Carlo sweep.

(a) Per-step cost of a run with a random rail profile (FRA class 5, 1.524-50 m) against the
    same run on the smooth rail, on the full model and on the linear path ("linear/hertz"), at
    300 km/h over the paper's passage with simulate's derived defaults. Smooth and rough runs
    alternate (so drift of a shared machine hits both alike); the median of --repeats runs
    (default 7) of each; the ratio is taken within this one run. Two costs per run: the wall
    time of the whole ``simulate`` call (Python side included: the profile is sampled into the
    kernel's table there) and the kernel's own ``Result.wall_time``. Target: ratio <= 1.15.
(b) --realisations (default 200) random realisations of the passage at 300 km/h on the linear
    path (``sweep(..., seeds=range(200))``) on a 2-process pool; target < 20 s. Then the same
    sweep on a Dask LocalCluster (2 worker processes, 1 thread each), whose rows must be
    identical to the pool's (all but wall_time, exactly).

The scene is the paper's with damped supports (c_s = 2e4 N s/m per support). Writes
benchmarks/irregularity.csv.

    python benchmarks/irregularity.py [--repeats 7] [--realisations 200] [--no-dask]
                                      [--only-monte-carlo]
"""

from __future__ import annotations

import argparse
import dataclasses as dc
import os
import platform
import statistics
import time

from _common import write_csv

import trackwheel as tw

SPEED = tw.kmh(300)
WAVELENGTHS = (1.524, 50.0)  # [m], inside FRA's validity band (1.524-304.8 m)
LINEAR = "linear/hertz"


def scenes() -> tuple[tw.Scene, tw.Scene]:
    """(smooth, rough): the paper's scene with damped supports, without and with FRA class 5."""
    base = tw.Scene.kato2005()
    smooth = dc.replace(base, supports=dc.replace(base.supports, damping=2e4))
    irr = tw.Irregularity.random(tw.spectra.fra(5), seed=0, wavelengths=WAVELENGTHS)
    return smooth, dc.replace(smooth, irregularity=irr)


def per_step(scene: tw.Scene, fidelity: str) -> tuple[float, float, int]:
    """(wall of the simulate call [s], kernel wall [s], steps) of one passage."""
    t0 = time.perf_counter()
    r = tw.simulate(scene, SPEED, fidelity=fidelity, progress=False)
    return time.perf_counter() - t0, r.wall_time, r.steps


def cost_rows(repeats: int) -> list[dict]:
    smooth, rough = scenes()
    rows = []
    for fidelity in ("full", LINEAR):
        per_step(smooth, fidelity)  # warm up: imports, caches, the profile's components
        per_step(rough, fidelity)
        runs = {"smooth": [], "rough": []}
        for _ in range(repeats):
            runs["smooth"].append(per_step(smooth, fidelity))
            runs["rough"].append(per_step(rough, fidelity))
        med = {k: (statistics.median(w for w, _, _ in v), statistics.median(k_ for _, k_, _ in v),
                   v[0][2]) for k, v in runs.items()}
        for name in ("smooth", "rough"):
            wall, kernel, steps = med[name]
            rows.append(dict(
                part="a", case=f"{fidelity}, {name}", steps=steps, median_wall_s=wall,
                median_kernel_s=kernel, us_per_step=1e6 * wall / steps,
                ratio_wall=wall / med["smooth"][0], ratio_kernel=kernel / med["smooth"][1]))
        print(f"{fidelity:>12}: {med['smooth'][2]} steps, per step smooth "
              f"{1e6 * med['smooth'][0] / med['smooth'][2]:.2f} us, rough "
              f"{1e6 * med['rough'][0] / med['rough'][2]:.2f} us; ratio (call) "
              f"{med['rough'][0] / med['smooth'][0]:.3f}, ratio (kernel) "
              f"{med['rough'][1] / med['smooth'][1]:.3f}  (target <= 1.15 full, 1.10 linear)")
    return rows


def monte_carlo_rows(n: int, dask: bool) -> list[dict]:
    _, rough = scenes()
    seeds = list(range(n))
    kw = dict(seeds=seeds, fidelity=LINEAR, progress=False)
    t0 = time.perf_counter()
    pool = tw.sweep(rough, SPEED, max_workers=2, **kw)
    wall = time.perf_counter() - t0
    n_failed = int((pool.error != "").sum())
    print(f"{n} realisations on a 2-process pool: {wall:.1f} s (target < 20 s), "
          f"{n_failed} failed; sum of case walls {pool.wall_time_s.sum():.1f} s")
    print(tw.summarise_seeds(pool, ["max_contact_force_N", "dynamic_factor"]).to_string())
    rows = [dict(part="b", case=f"{n} realisations, 2-process pool", steps=int(pool.steps.sum()),
                 median_wall_s=wall, median_kernel_s=float(pool.wall_time_s.sum()),
                 us_per_step=1e6 * wall / int(pool.steps.sum()), ratio_wall=float("nan"),
                 ratio_kernel=float("nan"))]
    if dask:
        import distributed

        t0 = time.perf_counter()
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                      dashboard_address=None) as cluster, \
                distributed.Client(cluster) as client:
            t1 = time.perf_counter()
            remote = tw.sweep(rough, SPEED, executor=client.get_executor(), **kw)
            wall_d = time.perf_counter() - t1
        same = remote.drop(columns="wall_time_s").equals(pool.drop(columns="wall_time_s"))
        print(f"the same on a Dask LocalCluster (2 processes): {wall_d:.1f} s "
              f"(+{t1 - t0:.1f} s cluster start); rows identical to the pool's: {same}")
        rows.append(dict(part="b", case=f"{n} realisations, Dask LocalCluster (identical rows: "
                                        f"{same})", steps=int(remote.steps.sum()),
                         median_wall_s=wall_d, median_kernel_s=float(remote.wall_time_s.sum()),
                         us_per_step=1e6 * wall_d / int(remote.steps.sum()),
                         ratio_wall=float("nan"), ratio_kernel=float("nan")))
        if not same:
            raise SystemExit("Dask rows differ from the process pool's")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--realisations", type=int, default=200)
    ap.add_argument("--no-dask", action="store_true")
    ap.add_argument("--only-monte-carlo", action="store_true", help="skip part (a)")
    args = ap.parse_args(argv)
    print(f"trackwheel {tw.__version__}, {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, Python {platform.python_version()}")
    print(f"load average {os.getloadavg()[0]:.1f}")
    rows = ([] if args.only_monte_carlo else cost_rows(args.repeats)) + monte_carlo_rows(
        args.realisations, not args.no_dask)
    print(f"load average {os.getloadavg()[0]:.1f}")
    # part (b) alone keeps part (a)'s table
    write_csv("irregularity_monte_carlo.csv" if args.only_monte_carlo else "irregularity.csv",
              rows)


if __name__ == "__main__":
    main()
