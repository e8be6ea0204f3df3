"""Receptance cost (issue 12): 1000 frequencies on a 100 m track, target under 2 s.

A 100 m track at 8 elements per 0.6 m bay has 1334 elements (within today's MAX_ELEMENTS =
2000); the largest mesh allowed, 2000 elements (5 cm, 4000 unknowns), is timed too. Both beam
theories, single springs at 0.6 m with damping. Prints and writes
benchmarks/receptance.csv (best of three runs each).
"""

from __future__ import annotations

import dataclasses as dc
import os
import platform
import time

import numpy as np
from _common import write_csv

import trackwheel as tw


def main() -> None:
    s = tw.Scene.kato2005()
    f = np.geomspace(20.0, 5000.0, 1000)
    rows = []
    for beam in ("euler", "timoshenko"):
        for ne in (1334, tw.scene.MAX_ELEMENTS):
            sc = dc.replace(s, rail=dc.replace(s.rail, length=100.0, n_elements=ne, beam=beam),
                            supports=dc.replace(s.supports, spacing=0.6, damping=2e4))
            tw.receptance(sc, 50.3, f[:2])  # build and cache the rail model
            best = min(_timed(lambda: tw.receptance(sc, 50.3, f)) for _ in range(3))
            rows.append({"beam": beam, "length_m": 100.0, "n_elements": ne,
                         "n_frequencies": f.size, "seconds": round(best, 4),
                         "machine": f"{platform.processor() or platform.machine()}, "
                                    f"{os.cpu_count()} cores"})
            print(rows[-1])
    write_csv("receptance.csv", rows)


def _timed(fn) -> float:
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


if __name__ == "__main__":
    main()
