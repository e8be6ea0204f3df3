"""``trackwheel reproduce``: the paper's Figs. 3-8 into a folder (trackwheel.reproduce)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ...reproduce import REPRODUCE_STEPS, STORE_NAME, reproduce
from ..checks import writable_folder
from ..options import positive_int


def add(sub) -> None:
    p = sub.add_parser(
        "reproduce", help="recompute the paper's figures (Figs. 3-8) into a folder",
        description="Recompute the paper's figures for Scene.kato2005() and write PNG + CSV "
                    "files and summary.txt (our numbers beside the paper's claims) into --out. "
                    "Steps: " + "; ".join(f"{s.name} = {s.title}" for s in REPRODUCE_STEPS)
                    + f". The sweeps keep finished cases in OUT/{STORE_NAME}: a re-run "
                    "resumes. --only refreshes those steps' sections of summary.txt and keeps "
                    "the others. Each step prints its wall time; benchmarks/README.md records "
                    "measured ones.")
    p.add_argument("--out", required=True, type=Path, metavar="DIR",
                   help="output folder (created if missing)")
    p.add_argument("--quick", action="store_true",
                   help="coarse grids, 20 elements at 1e-5 s in the sweeps and short "
                        "convergence stretches, for a fast check")
    p.add_argument("--only", nargs="+", choices=[s.name for s in REPRODUCE_STEPS],
                   metavar="STEP", help="run only these steps (" + ", ".join(
                       s.name for s in REPRODUCE_STEPS) + ")")
    p.add_argument("--workers", type=positive_int, metavar="N",
                   help="processes for the sweeps (default: one per core)")
    p.set_defaults(run=run, parser=p)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    writable_folder(args.out, "--out", parser, create=True)
    try:
        reproduce(args.out, quick=args.quick, only=args.only, workers=args.workers)
    except (OSError, RuntimeError) as exc:  # e.g. the disk filled up, a run failed
        print(f"trackwheel reproduce: failed: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    return 0
