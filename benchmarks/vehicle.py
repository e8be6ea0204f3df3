"""Per-step cost of a 4-wheel half car against a single wheel on the same track, on the full and
the linear paths (targets: 1.5x, issue 15; 1.3x, issue 26).

Tracks: the paper's rail and supports lengthened to 25 m (the half car's wheels then run from
the rail's near end to 0.6 m from its far end) and to 50 m (the car 4 m clear of the near end,
25 m of the far one), each on 0.25 m elements (the paper's) and on simulate's derived default
mesh (8 per support bay); 300 km/h, generalized-alpha at dt = 2e-5 s for 0.05 s (2500 steps).
The single wheel
is the half car's wheel (1100 kg, radius 0.43 m) under the half car's static wheel load; the half
car is ``Vehicle.half_car()``. Per-step cost = the kernel's wall time / steps, the median of
``--repeats`` runs (default 7), both vehicles timed in the same run, alternating. Writes
benchmarks/vehicle.csv.

    python benchmarks/vehicle.py [--repeats 7]
"""

from __future__ import annotations

import argparse
import dataclasses as dc
import os
import platform
import statistics

from _common import write_csv

import trackwheel as tw

LENGTHS, DT, DURATION = (25.0, 50.0), 2e-5, 0.05
ELEMENTS_PER_METRE = (4, 16)  # 0.25 m elements; the derived default, 8 per 0.5 m bay
LEVELS = {"full": "full", "linear": "linear/sprung"}


def scenes(length: float) -> dict:
    rail = dc.replace(tw.Rail(), length=length)
    car = tw.Vehicle.half_car()
    w = car.wheels[0]
    single = dc.replace(w, load=car.static_loads(tw.scene.GRAVITY)[0] - w.mass * tw.scene.GRAVITY)
    return {"single wheel": tw.Scene(rail=rail, wheel=single),
            "half car": tw.Scene(rail=rail, vehicle=car)}


def per_step(scene, fidelity, n_elements) -> tuple[float, float]:
    """(wall time per step [s], Newton iterations per step)."""
    r = tw.simulate(scene, tw.kmh(300), dt=DT, n_elements=n_elements, duration=DURATION,
                    fidelity=fidelity, progress=False)
    return r.wall_time / r.steps, r.newton_iterations / r.steps


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    rows = []
    for length, epm in ((L, e) for L in LENGTHS for e in ELEMENTS_PER_METRE):
        sc, ne = scenes(length), round(epm * length)
        for path, fidelity in LEVELS.items():
            cost = {name: [] for name in sc}
            iters = {}
            for _ in range(args.repeats):
                for name, scene in sc.items():
                    c, iters[name] = per_step(scene, fidelity, ne)
                    cost[name].append(c)
            med = {name: statistics.median(c) for name, c in cost.items()}
            ratio = med["half car"] / med["single wheel"]
            print(f"{length:4.0f} m, {ne:4d} elements, {path:6s}: single wheel {med['single wheel'] * 1e6:7.2f} "
                  f"us/step ({iters['single wheel']:.2f} Newton it./step), half car "
                  f"{med['half car'] * 1e6:7.2f} us/step ({iters['half car']:.2f}), ratio "
                  f"{ratio:.3f} (target <= 1.3)")
            rows.append(dict(path=path, fidelity=fidelity, length_m=length, elements=ne,
                             single_us=med["single wheel"] * 1e6,
                             half_car_us=med["half car"] * 1e6, ratio=ratio,
                             single_newton=iters["single wheel"],
                             half_car_newton=iters["half car"], repeats=args.repeats,
                             dt=DT, steps=round(DURATION / DT),
                         machine=f"{platform.processor() or platform.machine()}, "
                                 f"{os.cpu_count()} cores"))
    write_csv("vehicle.csv", rows)


if __name__ == "__main__":
    main()
