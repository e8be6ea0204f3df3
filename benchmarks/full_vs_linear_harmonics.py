"""Full model against the linear level on fine meshes: the first three sleeper-passing
harmonics of the contact force (docs: Model § Shear-deformable rail, the director's stretch).

The quarter car of benchmarks/contact_ripple.py at 200 km/h on a 14.4 m fixed rail (24 bays),
x = 4.2 -> 10.2 m, harmonics of the contact force averaged over the bays 7.2 -> 10.2 m (both
levels start from their own static state at the same place, so the start-up's share is common
to both). Prints the relative differences full/linear - 1 per mesh; with ``--csv`` writes
full_vs_linear_harmonics.csv. Runs with whatever trackwheel is on the path (a build without
``Contact.element_compliance`` takes its default).

    python benchmarks/full_vs_linear_harmonics.py [--meshes 32 64] [--csv]
"""

from __future__ import annotations

import argparse
import dataclasses as dc
import time

import numpy as np
from _common import write_csv

import trackwheel as tw
from trackwheel import Bogie, Vehicle


def scene(epb: int, compliance: bool | None) -> tw.Scene:
    base = tw.Scene.ballasted_track(length=14.4, elements_per_bay=epb)
    g = base.gravity
    wheel = tw.Wheel(mass=600.0, radius=0.46, load=0.0, youngs_modulus=210e9, poisson_ratio=0.3)
    bogie = Bogie(wheels=(0,), centre=0.0, mass=996.0, pitch_inertia=1.0,
                  primary_stiffness=1.2e6, primary_damping=0.0, load=80e3 - 1596.0 * g)
    kw = {} if compliance is None else {"element_compliance": compliance}
    return dc.replace(base, rail=dc.replace(base.rail, beam="timoshenko"),
                      vehicle=Vehicle(wheels=(wheel,), positions=(0.0,), bogies=(bogie,)),
                      contact=tw.Contact(law="linear", stiffness=1.3374e9, **kw))


def harmonics(r, x0: float, x1: float, d: float = 0.6, n: int = 128) -> np.ndarray:
    nb = round((x1 - x0) / d)
    xs = x0 + d * np.arange(nb * n) / n
    f = np.interp(xs, r.x_wheel, r.normal_force).reshape(nb, n).mean(axis=0)
    return 2.0 * np.abs(np.fft.rfft(f)[1:4]) / n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--meshes", type=int, nargs="+", default=[8, 32, 64])
    ap.add_argument("--compliance", choices=["default", "on", "off"], default="default")
    ap.add_argument("--csv", action="store_true")
    args = ap.parse_args()
    comp = {"default": None, "on": True, "off": False}[args.compliance]
    rows = []
    for epb in args.meshes:
        s = scene(epb, comp)
        h, wall = {}, {}
        for fid in ("linear/sprung", "full"):
            t0 = time.perf_counter()
            r = tw.simulate(s, tw.kmh(200), x_start=4.2, x_end=10.2,
                            dt=tw.default_settings(s)["dt"], n_elements=s.rail.n_elements,
                            fidelity=fid, progress=False)
            h[fid], wall[fid] = harmonics(r, 7.2, 10.2), time.perf_counter() - t0
        diff = h["full"] / h["linear/sprung"] - 1.0
        row = dict(elements_per_bay=epb, compliance=args.compliance,
                   **{f"h{k + 1}_linear": round(float(h["linear/sprung"][k]), 2) for k in range(3)},
                   **{f"h{k + 1}_diff": float(diff[k]) for k in range(3)},
                   wall_full_s=round(wall["full"], 1))
        print(row, flush=True)
        rows.append(row)
    if args.csv:
        write_csv("full_vs_linear_harmonics.csv", rows)


if __name__ == "__main__":
    main()
