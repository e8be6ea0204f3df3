"""Per-step cost of a unilateral ballast whose sleepers change state against the intact track
(target: at most 1.3x), on the full path and a linear level.

Track: ``Scene.ballasted_track()`` (30 m, 200 elements, 49 sleepers at 0.6 m); 300 km/h,
generalized-alpha at dt = 2e-5 s over X = 9 m .. 21 m. The voided track has tensionless ballast
and a 0.3 mm void under every third sleeper from X = 10 m to 20 m, which the wheel closes and
leaves open again: its sleepers change state during the run (the events are counted). Per-step
cost = the kernel's wall time / steps, the median of ``--repeats`` runs (default 7), intact and
voided alternating in one process. Also the machine-independent Newton iterations per step. Writes benchmarks/voids.csv.

    python benchmarks/voids.py [--repeats 7]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics

from _common import write_csv

import trackwheel as tw
from trackwheel.run import kernel

SCENE = tw.Scene.ballasted_track()
RUN = {"x_start": 9.0, "x_end": 21.0, "dt": 2e-5, "progress": False}
LEVELS = {"full": "full", "linear": "linear/sprung"}
_support_params = kernel.support_params


def voided(s):
    """The kernel's supports with the voids (SupportParams edited on the way to the kernel)."""
    s.void_gap = [3e-4 if 10.0 <= x <= 20.0 and j % 3 == 0 else 0.0
                  for j, x in enumerate(s.position)]
    s.tensionless = True


def use(edit):
    def support_params(scene, *args, **kwargs):
        s = _support_params(scene, *args, **kwargs)
        if edit:
            edit(s)
        return s
    kernel.support_params = support_params
    kernel.rail_model.cache_clear()


def run(fidelity, edit):
    use(edit)
    r = tw.simulate(SCENE, tw.kmh(300), fidelity=fidelity, **RUN)
    return r


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    cases = {"intact": None, "voided": voided}
    rows = []
    for path, fidelity in LEVELS.items():
        cost = {name: [] for name in cases}
        last = {}
        for _ in range(args.repeats):
            for name, edit in cases.items():
                r = run(fidelity, edit)
                cost[name].append(r.wall_time / r.steps)
                last[name] = r
        base = statistics.median(cost["intact"])
        for name in cases:
            r, c = last[name], statistics.median(cost[name])
            rows.append({"path": path, "case": name, "steps": r.steps,
                         "per_step_us": round(1e6 * c, 2), "ratio": round(c / base, 3),
                         "newton_per_step": round(r.newton_iterations / r.steps, 3),
                         "ballast_events": r.ballast_events,
                         "machine": f"{platform.machine()} {os.cpu_count()} cpus"})
            print(rows[-1])
    use(None)
    write_csv("voids.csv", rows)


if __name__ == "__main__":
    main()
