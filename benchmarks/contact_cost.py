"""Per-step cost of the element compliance (docs: Model § Contact, "The rail under the load
between nodes") and of the shear element's director term, against a build of the code before
them, on the issue's quarter car (benchmarks/contact_ripple.py) at the default settings: 8
elements per bay on the 20 + 20-bay window, the derived step 2.81e-5 s, 200 km/h.

Cases, each run in its own process, alternating within one pass (so that a change of the
machine's load hits every case alike), median over the passes:

- ``base``: the build at ``--base`` (a worktree of the commit before; its package on
  PYTHONPATH), today's default (no element compliance exists there);
- ``off``: this build, ``Contact(element_compliance=False)`` (the director term only);
- ``on``: this build, the default (element compliance on for the Timoshenko rail).

Per case: CPU time per step [us] (``time.process_time`` of the ``simulate`` call over its
steps) and Newton iterations per step (machine-independent), on the full model (6 m) and the
linear sprung level (30 m).

    python benchmarks/contact_cost.py --base /work/wt/contact-base [--passes 7]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

from _common import write_csv

HERE = Path(__file__).resolve().parent
RUN = """
import dataclasses, json, sys, time
sys.path.insert(0, {bench!r})
import trackwheel as tw
from trackwheel import Bogie, Vehicle
g = 9.81
base = tw.Scene.ballasted_track(elements_per_bay=8)
rail = dataclasses.replace(base.rail, beam="timoshenko", shear_coefficient=0.4)
wheel = tw.Wheel(mass=600.0, radius=0.46, load=0.0, youngs_modulus=210e9, poisson_ratio=0.3)
bogie = Bogie(wheels=(0,), centre=0.0, mass=996.0, pitch_inertia=1.0, primary_stiffness=1.2e6,
              primary_damping=0.0, load=80e3 - 1596.0 * g)
kw = {{}} if {compliance!r} is None else {{"element_compliance": {compliance!r}}}
contact = tw.Contact(law="linear", stiffness=1.3374e9, **kw)
s = dataclasses.replace(base, rail=rail, contact=contact,
                        vehicle=Vehicle(wheels=(wheel,), positions=(0.0,), bogies=(bogie,)))
s = s.windowed(tw.Window(20, 20))
out = {{}}
for fid, dist in (("full", 6.0), ("linear/sprung", 30.0)):
    t0 = time.process_time()
    r = tw.simulate(s, tw.kmh(200), distance=dist, fidelity=fid, progress=False)
    cpu = time.process_time() - t0
    out[fid] = dict(us_per_step=1e6 * cpu / r.steps, newton_per_step=r.newton_iterations / r.steps,
                    steps=r.steps, dt=r.settings.dt, n_elements=r.settings.n_elements)
print(json.dumps(out))
"""


def run(python_path: str, compliance) -> dict:
    env = dict(os.environ, PYTHONPATH=python_path)
    code = RUN.format(bench=str(HERE), compliance=compliance)
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--base", required=True, help="worktree of the code before (built)")
    ap.add_argument("--passes", type=int, default=7)
    args = ap.parse_args()
    here = str(HERE.parent / "python")
    cases = {"base": (str(Path(args.base) / "python"), None), "off": (here, False),
             "on": (here, None)}
    runs = {c: [] for c in cases}
    for i in range(args.passes):
        for c, (path, comp) in cases.items():
            runs[c].append(run(path, comp))
        print(f"pass {i + 1}: " + ", ".join(
            f"{c} {runs[c][-1]['full']['us_per_step']:.0f}/"
            f"{runs[c][-1]['linear/sprung']['us_per_step']:.1f} us" for c in cases), flush=True)
    rows = []
    for fid in ("full", "linear/sprung"):
        base = statistics.median(r[fid]["us_per_step"] for r in runs["base"])
        for c in cases:
            us = statistics.median(r[fid]["us_per_step"] for r in runs[c])
            ratios = [r[fid]["us_per_step"] / b[fid]["us_per_step"]
                      for r, b in zip(runs[c], runs["base"])]
            rows.append(dict(fidelity=fid, case=c, us_per_step=round(us, 2),
                             ratio_to_base=round(us / base, 3),
                             pairwise_ratio_median=round(statistics.median(ratios), 3),
                             newton_per_step=round(runs[c][0][fid]["newton_per_step"], 4),
                             steps=runs[c][0][fid]["steps"], dt=runs[c][0][fid]["dt"],
                             n_elements=runs[c][0][fid]["n_elements"], passes=args.passes))
            print(rows[-1])
    write_csv("contact_cost.csv", rows)


if __name__ == "__main__":
    main()
