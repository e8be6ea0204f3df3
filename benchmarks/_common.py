"""Shared by the benchmark scripts (run as `python benchmarks/<name>.py`, so this folder is on
sys.path)."""

from __future__ import annotations

import csv
from pathlib import Path

HERE = Path(__file__).resolve().parent


def write_csv(name: str, rows: list[dict]) -> Path:
    """Write ``rows`` (dicts with the same keys) to benchmarks/<name> and say where."""
    path = HERE / name
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {path}")
    return path
