"""The default rules against refined runs, and the default runs' measured stretch.

Writes ``default_rules.csv`` next to this file and prints it:

- ``mesh``: the ballasted preset (18 m rail; passage 5.1 -> 12.9 m, measured from 8.1 m), each
  beam theory, 100-400 km/h, elements per bay and step factor (of the derived step): max N / P
  and the bay-averaged profile's max / min over P;
- ``default``: ``tw.analyse(tw.simulate(scene, v))`` with every default (one wheel, quarter car,
  bogie, half car on the 30 m preset, the half car on the 50.4 m rail the command line takes),
  its dynamic factor and the X range measured, against the steady value (``analyse(steady=True)``
  of a 60 m rail from 5.1 m).

Usage: ``PYTHONPATH=python python benchmarks/default_rules.py [mesh] [default]`` (both by
default; the mesh table takes about 10 minutes on one core, the default runs 3).
"""

from __future__ import annotations

import csv
import dataclasses as dc
import math
import sys
from pathlib import Path

import numpy as np

import trackwheel as tw
from trackwheel.run.defaults import derived_dt

OUT = Path(__file__).with_name("default_rules.csv")


def mesh_row(v_kmh: float, beam: str, per_bay: int, dt_factor: float) -> dict:
    s = tw.Scene.ballasted_track(18.0, elements_per_bay=per_bay)
    s = dc.replace(s, rail=dc.replace(s.rail, beam=beam))
    r = tw.simulate(s, tw.kmh(v_kmh), x_start=5.1, x_end=12.9, dt=derived_dt(s) * dt_factor,
                    n_elements=s.rail.n_elements, progress=False)
    x, N, P, d = r.x_wheel, r.normal_force, s.static_load, s.supports.spacing
    start = math.ceil(8.1 / d) * d
    n = int((x[-1] - start) // d)
    prof = np.interp(start + d * np.arange(n * 128) / 128, x, N).reshape(n, 128).mean(axis=0)
    return dict(table="mesh", case=f"{beam} {v_kmh:g} km/h", per_bay=per_bay,
                dt_factor=dt_factor, max_n_over_p=N[x >= 8.1].max() / P,
                profile_max=prof.max() / P, profile_min=prof.min() / P)


def default_rows(v_kmh: float) -> list[dict]:
    rows = []
    base = tw.Scene.ballasted_track()
    long = tw.Scene.ballasted_track(60.0)
    steady = {}
    for name, veh in (("one wheel", None), ("quarter car", tw.Vehicle.quarter_car()),
                      ("bogie", tw.Vehicle.bogie()), ("half car", tw.Vehicle.half_car())):
        scene = base if veh is None else dc.replace(base, vehicle=veh)
        if name == "half car":
            scene = dc.replace(tw.Scene.ballasted_track(50.4), vehicle=veh)
        r = tw.simulate(scene, tw.kmh(v_kmh), progress=False)
        ref_scene = long if veh is None else dc.replace(long, vehicle=veh)
        if name not in steady:
            span = ref_scene.active_vehicle.span
            ref = tw.simulate(ref_scene, tw.kmh(v_kmh), x_start=5.1,
                              x_end=54.9 - (span[1] - span[0]), progress=False)
            steady[name] = ref
        ref = steady[name]
        for i in range(r.n_wheels):
            w = i if r.n_wheels > 1 else None
            a = tw.analyse(r, wheel=w)
            st = tw.analyse(ref, wheel=w, steady=True)
            rows.append(dict(table="default", case=f"{name} {v_kmh:g} km/h wheel {i}",
                             run_from=float(np.atleast_2d(r.x_wheel.T).T[0, i]),
                             measured_from=a.x_range[0], measured_to=a.x_range[1],
                             dynamic_factor=a.dynamic_factor,
                             steady_dynamic_factor=st.dynamic_factor,
                             whole_run_dynamic_factor=tw.analyse(r, wheel=w,
                                                                 measure="run").dynamic_factor))
    return rows


def main(parts) -> None:
    rows = []
    if "mesh" in parts:
        for beam, meshes in (("euler", (8, 16, 32)), ("timoshenko", (8, 12, 16, 32, 64))):
            for v in (100.0, 200.0, 300.0, 400.0 if beam == "euler" else None):
                if v is None:
                    continue
                for per_bay in meshes:
                    rows.append(mesh_row(v, beam, per_bay, 1.0))
                    print(rows[-1], flush=True)
                rows.append(mesh_row(v, beam, 8, 0.25))
                print(rows[-1], flush=True)
    if "default" in parts:
        for v in (300.0, 400.0):
            for row in default_rows(v):
                rows.append(row)
                print(row, flush=True)
    keys = sorted({k for row in rows for k in row}, key=lambda k: (k not in ("table", "case"), k))
    with OUT.open("w", newline="") as fh:
        w = csv.DictWriter(fh, keys)
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main(set(sys.argv[1:]) or {"mesh", "default"})
