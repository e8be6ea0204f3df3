"""The travelling window (issue 14): cost per step and peak memory against the distance run.

Each case runs in a fresh Python process on the ballasted preset on a window of 20 + 1 + 20
bays (24.6 m, 328 elements at the default 8 per bay), the Hertzian wheel on the linear path
(``fidelity="linear/hertz"``), 300 km/h, the default time step, and reports the kernel's wall
time per step (``Result.wall_time / steps``: the time loop only), Newton's iterations per step
(a count, the same on any machine), the whole call's wall time (with the profile table and the
start), the peak resident set size (``resource.getrusage(RUSAGE_SELF).ru_maxrss``) before and
after the run, and the bytes of the returned arrays. Cases:

- ``smooth 100 m / 1 km / 5 km``: a smooth track, one sample kept every 20 steps: the cost per
  step must not depend on the distance, the peak RSS only through the kept samples;
- ``fra5 1 km``: FRA class 5 (seed 0), the issue's target (< 60 s on one core); its rail profile
  is a cubic spline table over the kilometre (1 mm samples, 32 MB) streamed into the kernel:
  its chunks are built inside the time loop as the wheel reaches them, so they count in the
  time per step.

The same cases on the full model (``fidelity="full"``: the ANCF rail, the rolling contact,
generalized-alpha; same window, mesh and step) make the group ``full``; its target is 1 km of
FRA class 5 in under 5 minutes. Both groups' windows have the default 8-bay absorbing end zones
(``Window.absorbing_length``; on the full model they damp the rail's axial motion too: without
them the window's shifts make the tangential force ring and Newton's iterations grow with the
distance).

The group ``memory`` runs FRA class 5 over 100 m, 1 km and 5 km once each on the linear path
(one sample kept every 20 steps): the rail profile's spline table covers the distance run
(32 bytes per 1 mm interval, 30.5 MiB per km; ``profile_mib``), but beyond three chunks of
65 536 intervals the kernel streams it and holds at most ``profile_peak_mib`` of it at once
(the most intervals it ever held); the peak RSS grows by that, by the Python side's work space
while a chunk is built, and by the kept output (``window_memory.csv``).

The cases of a group run one after the other, ``--repeat`` times in turn (default 5; the full
group's 5 km case once, last: about 10 minutes), so that the machine's load shifts every case
alike; the CSV holds per case the median, the least and the largest time per step. Writes
``window.csv`` (linear) and ``window_full.csv`` (full) next to itself; an argument picks one
group:

    PYTHONPATH=python python benchmarks/window.py [linear|full|memory] [--repeat N]
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys

from _common import write_csv

CASE = r"""
import dataclasses as dc, json, resource, sys, time
import numpy as np
import trackwheel as tw
from trackwheel import spectra
from trackwheel.run.simulate import execute, plan_run  # documented internal hooks
kw = json.loads(sys.argv[1])
scene = tw.Scene.ballasted_track(window=tw.Window(20, 20))  # default 8-bay end zones
if kw.pop("fra5"):
    scene = dc.replace(scene, irregularity=tw.Irregularity.random(spectra.fra(5), seed=0))
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.perf_counter()
plan = plan_run(scene, tw.kmh(300), x_start=0.3, **kw)
r = execute(plan, progress=False)
table = plan.model.profile  # the kernel profile the run read, for its counters
wall = time.perf_counter() - t0
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
out = sum(v.nbytes for v in vars(r).values() if isinstance(v, np.ndarray))
print(json.dumps(dict(steps=r.steps, samples=len(r.t), newton=r.newton_iterations / r.steps, us_per_step=1e6 * r.wall_time / r.steps,
                      call_s=wall, baseline_mib=base / 1024, peak_mib=peak / 1024,
                      output_mib=out / 2**20, f_max_kn=float(r.normal_force.max()) / 1e3,
                      profile_mib=32 * table.n_intervals / 2**20,
                      profile_peak_mib=32 * table.peak_loaded_intervals / 2**20)))
"""

CASES = [
    ("smooth 100 m", dict(distance=100.0, output_every=20, fra5=False)),
    ("smooth 1 km", dict(distance=1000.0, output_every=20, fra5=False)),
    ("smooth 5 km", dict(distance=5000.0, output_every=20, fra5=False)),
    ("fra5 1 km", dict(distance=1000.0, fra5=True)),
]
#: the full model's cases repeated; its 5 km case (about 10 minutes) runs once, after them
FULL_REPEATED = ["smooth 100 m", "smooth 1 km", "fra5 1 km"]
#: the rail profile's memory against the distance: FRA class 5 over 100 m, 1 km and 5 km, once
MEMORY = [(f"fra5 {name}", dict(distance=dist, output_every=20, fra5=True,
                                 fidelity="linear/hertz"))
          for name, dist in (("100 m", 100.0), ("1 km", 1000.0), ("5 km", 5000.0))]
GROUPS = {
    "linear": ("window.csv", [(n, dict(kw, fidelity="linear/hertz")) for n, kw in CASES], []),
    "memory": ("window_memory.csv", [], MEMORY),
    "full": ("window_full.csv",
             [(n, dict(kw, fidelity="full")) for n, kw in CASES if n in FULL_REPEATED],
             [(n, dict(kw, fidelity="full")) for n, kw in CASES if n == "smooth 5 km"]),
}


def main(argv):
    repeat = 5
    if "--repeat" in argv:
        i = argv.index("--repeat")
        repeat = int(argv[i + 1])
        argv = argv[:i] + argv[i + 2:]
    for g in argv or ("linear", "full"):
        run_group(*GROUPS[g], repeat)


def run_case(name, kw):
    p = subprocess.run([sys.executable, "-c", CASE, json.dumps(kw)], capture_output=True,
                       text=True, check=True)
    d = json.loads(p.stdout.strip().splitlines()[-1])
    d["growth_mib"] = d["peak_mib"] - d["baseline_mib"]
    print(f"{name:14s} {d['steps']:>8d} steps {d['samples']:>7d} samples: "
          f"{d['us_per_step']:.1f} us/step, {d['newton']:.3f} Newton/step, call {d['call_s']:.1f} s;"
          f" peak RSS {d['peak_mib']:.1f} MiB (growth {d['growth_mib']:.1f}, output "
          f"{d['output_mib']:.1f} MiB) [{kw['fidelity']}]", flush=True)
    return d


def summary(name, runs):
    """One CSV row: the median run's fields (by time per step), with the spread of the time."""
    us = [d["us_per_step"] for d in runs]
    mid = sorted(runs, key=lambda d: d["us_per_step"])[(len(runs) - 1) // 2]
    row = dict(case=name, runs=len(runs), us_per_step_median=statistics.median(us),
               us_per_step_min=min(us), us_per_step_max=max(us))
    row.update((k, v) for k, v in mid.items() if k != "us_per_step")
    return {k: (round(v, 3) if isinstance(v, float) else v) for k, v in row.items()}


def run_group(csv_name, cases, once, repeat):
    runs = {name: [] for name, _ in cases + once}
    for _ in range(repeat):
        for name, kw in cases:
            runs[name].append(run_case(name, kw))
            write_csv(csv_name, [summary(n, r) for n, r in runs.items() if r])
    for name, kw in once:
        runs[name].append(run_case(name, kw))
        write_csv(csv_name, [summary(n, r) for n, r in runs.items() if r])


if __name__ == "__main__":
    main(sys.argv[1:])
