"""Issue 7 performance target: the linear fast path runs the Fig. 7 sweep at least 5x faster than
the ANCF path, with headline outputs within 0.5 %.

Fig. 7 sweep: the paper's scene at 140 MN/m, speeds 50..400 km/h in steps of 50, full passage
(0.25 -> 4.75 m), serial in one process (max_workers=1, so the ratio is the kernels', not the
pool's). Two settings: the derived defaults (trackwheel.default_settings: 80 elements, 4.96e-6 s,
what a user who sets nothing gets) and the paper's mesh (20 elements, dt = 1e-5 s). Median of
N runs (default 5) of each sweep, both paths timed in the same run. Writes fidelity.csv.

    python benchmarks/fidelity.py [--repeats 5]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import numpy as np
import pandas as pd

import trackwheel as tw

SPEEDS = [tw.kmh(v) for v in range(50, 401, 50)]


def sweep(scene, fidelity, settings):
    return tw.sweep(scene, speed=SPEEDS, max_workers=1, progress=False, fidelity=fidelity,
                    **settings)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args(argv)
    scene = tw.Scene.kato2005()
    rows = []
    for label, settings in [("derived defaults", tw.default_settings(scene)),
                            ("paper mesh", dict(n_elements=20, dt=1e-5))]:
        walls = {"full": [], "linear/sprung": []}
        tables = {}
        for _ in range(args.repeats):
            for lv in walls:
                t0 = time.perf_counter()
                tables[lv] = sweep(scene, lv, settings)
                walls[lv].append(time.perf_counter() - t0)
        full, lin = tables["full"], tables["linear/sprung"]
        d_amp = np.max(np.abs(lin.amplitude / full.amplitude - 1))
        d_f = np.max(np.abs(lin.main_frequency / full.main_frequency - 1))
        d_n = np.max(np.abs(lin.max_contact_force / full.max_contact_force - 1))
        tf, tl = statistics.median(walls["full"]), statistics.median(walls["linear/sprung"])
        rows.append(dict(settings=label, n_elements=settings["n_elements"], dt=settings["dt"],
                         full_s=tf, linear_s=tl, speedup=tf / tl, max_d_amplitude=d_amp,
                         max_d_main_frequency=d_f, max_d_peak_force=d_n))
        print(f"{label:17s} ({settings['n_elements']} elements, dt={settings['dt']:.3g} s): "
              f"ANCF {tf:.2f} s, linear {tl:.2f} s -> {tf / tl:.1f}x; max differences: "
              f"amplitude {d_amp:.3%}, main frequency {d_f:.3%}, peak force {d_n:.3%}")
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "fidelity.csv")
    pd.DataFrame(rows).to_csv(out, index=False)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
