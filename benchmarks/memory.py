"""Peak memory of long runs: output decimation keeps it bounded.

Each case runs in a fresh Python process and reports its peak resident set size
(``resource.getrusage(RUSAGE_SELF).ru_maxrss``) after importing trackwheel and solving the
static start (the baseline) and after the run, with the bytes of the returned arrays. Cases:

- ``short``: explicit RK4, dt = 1e-7 s, 10^3 steps;
- ``1e6 steps, default decimation``: explicit RK4, dt = 1e-7 s, 10^6 steps at 50 km/h
  (0.1 s, X 0.25 -> 1.64 m); at most 100 000 samples are kept (output_every = 10);
- ``1e6 steps, every step kept``: generalized-alpha, dt = 1e-7 s, 10^6 steps,
  output_every = 1 -- what the output would cost without decimation (23 fields x 8 bytes per
  sample, ~184 MB).

Writes ``memory.csv`` next to itself.

    PYTHONPATH=python python benchmarks/memory.py
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

from _common import write_csv

HERE = Path(__file__).resolve().parent

CASE = r"""
import json, resource, sys, time
import numpy as np
import trackwheel as tw
kw = json.loads(sys.argv[1])
scene = tw.Scene.kato2005()
tw.static(scene, kw["x_start"])
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
r = tw.simulate(scene, tw.kmh(50), progress=False, **kw)
wall = time.perf_counter() - t0
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
out = sum(v.nbytes for v in vars(r).values() if isinstance(v, np.ndarray))
print(json.dumps(dict(steps=r.steps, samples=len(r.t), output_every=r.settings["output_every"],
                      baseline_mib=base / 1024, peak_mib=peak / 1024,
                      output_mib=out / 2**20, wall_s=wall)))
"""

CASES = [
    ("short", dict(integrator="explicit", dt=1e-7, x_start=0.25, duration=1e-4)),
    ("1e6 steps, default decimation", dict(integrator="explicit", dt=1e-7, x_start=0.25,
                                          duration=0.1)),
    ("1e6 steps, every step kept", dict(integrator="generalized_alpha", dt=1e-7, x_start=0.25,
                                       duration=0.1, output_every=1)),
]


def main():
    rows = []
    for name, kw in CASES:
        p = subprocess.run([sys.executable, "-c", CASE, json.dumps(kw)], capture_output=True,
                           text=True, check=True)
        d = json.loads(p.stdout.strip().splitlines()[-1])
        row = dict(case=name, **{k: (round(v, 1) if isinstance(v, float) else v)
                                 for k, v in d.items()})
        row["growth_mib"] = round(d["peak_mib"] - d["baseline_mib"], 1)
        rows.append(row)
        print(f"{name:32s} {d['steps']:>8d} steps {d['samples']:>8d} samples: peak RSS "
              f"{d['peak_mib']:6.1f} MiB (baseline {d['baseline_mib']:.1f}, growth "
              f"{row['growth_mib']:.1f}; output arrays {d['output_mib']:.1f} MiB) in "
              f"{d['wall_s']:.1f} s", flush=True)
    write_csv("memory.csv", rows)


if __name__ == "__main__":
    main()
