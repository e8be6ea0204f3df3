"""Run the long hypothesis profiles of tests/test_hypothesis.py and tests/test_hypothesis_newer.py
and record how many examples ran.

Each property runs in its own pytest process: those of test_hypothesis.py with
``TRACKWHEEL_HYPOTHESIS_PROFILE=long``, those of test_hypothesis_newer.py as their ``_long``
variants under ``-m slow``; ``--examples`` per property (10 000 by default) through
``TRACKWHEEL_HYPOTHESIS_EXAMPLES``. A time budget can stop the sequence between properties
without losing the counts of the finished ones. Hypothesis's own
statistics (``--hypothesis-show-statistics``) give the passing/failing/invalid counts; they are
printed and written to ``hypothesis_long.csv`` next to this script.

    python benchmarks/hypothesis_long.py                 # 10 000 examples per property
    python benchmarks/hypothesis_long.py --budget 1200   # stop starting new ones after 20 min

Run from the repository root with the package importable (``PYTHONPATH=python`` for the dev
build). Exit code 1 if any property failed.
"""

from __future__ import annotations

import argparse
import csv
import os
import re
import subprocess
import sys
import time
from pathlib import Path

from _common import write_csv

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
PROPERTIES = ["test_kmh", "test_scene_construction", "test_static", "test_eigen",
              "test_short_simulation"]
#: the newer APIs' properties (tests/test_hypothesis_newer.py, their "_long" variants)
NEWER = ["test_layered_supports", "test_window", "test_profiles", "test_wheel_defects",
         "test_vehicles", "test_receptance", "test_decay_rate"]


def run_one(name: str, examples: int, timeout: float) -> dict:
    env = dict(os.environ, TRACKWHEEL_HYPOTHESIS_PROFILE="long",
               TRACKWHEEL_HYPOTHESIS_EXAMPLES=str(examples))
    node = (f"tests/test_hypothesis_newer.py::{name}_long" if name in NEWER
            else f"tests/test_hypothesis.py::{name}")
    cmd = [sys.executable, "-m", "pytest", node, "-q", *(["-m", "slow"] if name in NEWER else []),
           "-p", "no:cacheprovider", "--hypothesis-show-statistics",
           # third-party noise when hypothesis formats a failure report
           "-W", "ignore:mypy_extensions.TypedDict is deprecated:DeprecationWarning"]
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True,
                           timeout=timeout)
        out, status = p.stdout + p.stderr, ("passed" if p.returncode == 0 else "FAILED")
    except subprocess.TimeoutExpired as exc:
        out = (exc.stdout or b"").decode() if isinstance(exc.stdout, bytes) else (exc.stdout or "")
        status = "timeout"
    wall = time.perf_counter() - t0
    counts = {k: 0 for k in ("passing", "failing", "invalid")}
    # one line per phase (generate, shrink, ...): sum them
    # "N passing examples, N failing examples, N invalid" (older hypothesis) or "N passing, N
    # failing, and N invalid test cases" (6.1xx)
    for m in re.finditer(r"(\d+) passing(?: examples?)?, (\d+) failing(?: examples?)?,"
                         r"(?: and)? (\d+) invalid", out):
        counts["passing"] += int(m.group(1))
        counts["failing"] += int(m.group(2))
        counts["invalid"] += int(m.group(3))
    if status != "passed":
        print(out[-4000:], file=sys.stderr)
    return dict(property=name, status=status, **counts, wall_s=round(wall, 1),
                examples_per_s=round(counts["passing"] / wall, 1) if wall > 0 else 0.0)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--examples", type=int, default=10_000, help="examples per property")
    ap.add_argument("--budget", type=float, default=1200.0,
                    help="total wall-time budget [s]; no property starts after it is spent")
    ap.add_argument("--only", nargs="+", choices=PROPERTIES + NEWER, metavar="PROPERTY",
                    help="run these properties only (their rows replace those in the CSV)")
    args = ap.parse_args(argv)
    start = time.perf_counter()
    rows = []
    for name in args.only or PROPERTIES + NEWER:
        left = args.budget - (time.perf_counter() - start)
        if left <= 0:
            rows.append(dict(property=name, status="not run (budget)", passing=0, failing=0,
                             invalid=0, wall_s=0.0, examples_per_s=0.0))
            continue
        row = run_one(name, args.examples, timeout=left)
        rows.append(row)
        print(f"{name:26s} {row['status']:8s} {row['passing']:6d} passing "
              f"{row['invalid']:5d} invalid {row['wall_s']:7.1f} s "
              f"({row['examples_per_s']:.0f}/s)", flush=True)
    total = sum(r["passing"] for r in rows)
    print(f"total: {total} passing examples in {time.perf_counter() - start:.0f} s")
    if args.only:  # keep the rows of the properties not run now
        old = HERE / "hypothesis_long.csv"
        if old.exists():
            with old.open() as f:
                kept = [r for r in csv.DictReader(f) if r["property"] not in args.only]
            rows = kept + rows
    write_csv("hypothesis_long.csv", rows)
    return 0 if all(r["status"] == "passed" for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
