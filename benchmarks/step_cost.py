"""Per-step cost of the kernel's time-domain paths, for before/after comparisons of kernel changes.

Two measures per case:

- CPU time per step [us] (``time.process_time``, best of ``--repeats`` runs: less sensitive than
  wall time to other jobs on a shared machine);
- with ``--callgrind``, instructions per step (valgrind's callgrind, counting only inside the
  kernel's time loop, ``trackwheel::run_time_loop``, divided by the steps): machine-independent
  and exact, so two builds compare without noise.

The cases cover both paths on the paper's scene and on a ballasted track with sleepers, with a
travelling window and with a two-wheel bogie, and the full path on irregularity.py's smooth and
rough scenes and on vehicle.py's single wheel and half car (25 m, 100 elements; 50 m, 200). Compare two builds by running the script with
each on ``PYTHONPATH`` (alternately, for the times) and comparing the JSON lines it prints::

    PYTHONPATH=python python benchmarks/step_cost.py [--repeats 5] [--callgrind] [--csv]
"""

from __future__ import annotations

import argparse
import dataclasses as dc
import json
import os
import re
import subprocess
import sys
import tempfile
import time

V = 300 / 3.6  # [m/s]


def cases(short: bool) -> dict:
    """name -> (scene, speed [m/s], simulate keywords); short: fewer steps (for callgrind)."""
    import trackwheel as tw

    kato = tw.Scene.kato2005()
    bt = tw.Scene.ballasted_track(12.0)
    win = tw.Scene.ballasted_track(window=tw.Window(bays_behind=4, bays_ahead=4,
                                                    absorbing_length=1.2))
    bogie = dc.replace(bt, vehicle=tw.Vehicle.bogie(wheelbase=2.5))
    f = 0.2 if short else 1.0
    base = {"progress": False, "output_every": 10}
    # benchmarks/irregularity.py's scenes (damped supports; FRA class 5) and benchmarks/
    # vehicle.py's (a half car and its single wheel on a 25 m track, 100 elements)
    damped = dc.replace(kato, supports=dc.replace(kato.supports, damping=2e4))
    rough = dc.replace(damped, irregularity=tw.Irregularity.random(
        tw.spectra.fra(5), seed=0, wavelengths=(1.524, 50.0)))
    rail25 = dc.replace(tw.Rail(), length=25.0)
    car = tw.Vehicle.half_car()
    w = car.wheels[0]
    single = dc.replace(w, load=car.static_loads(tw.scene.GRAVITY)[0] - w.mass * tw.scene.GRAVITY)
    vkw = {**base, "dt": 2e-5, "n_elements": 100, "duration": 0.05 * f}
    rail50 = dc.replace(tw.Rail(), length=50.0)
    vkw50 = {**vkw, "n_elements": 200}
    return {
        "full/damped_smooth": (damped, V, {**base, "x_end": 0.25 + 4.5 * f}),
        "full/damped_fra5": (rough, V, {**base, "x_end": 0.25 + 4.5 * f}),
        "full/wheel_25m_100": (tw.Scene(rail=rail25, wheel=single), V, vkw),
        "full/half_car_25m_100": (tw.Scene(rail=rail25, vehicle=car), V, vkw),
        # the same on a 50 m rail: the car clear of the rail's ends
        "full/wheel_50m_200": (tw.Scene(rail=rail50, wheel=single), V, vkw50),
        "full/half_car_50m_200": (tw.Scene(rail=rail50, vehicle=car), V, vkw50),
        "linear_sprung/wheel_50m_200": (tw.Scene(rail=rail50, wheel=single), V,
                                        {**vkw50, "fidelity": "linear/sprung"}),
        "linear_sprung/half_car_50m_200": (tw.Scene(rail=rail50, vehicle=car), V,
                                           {**vkw50, "fidelity": "linear/sprung"}),
        "full/kato_20": (kato, V, {**base, "dt": 1e-5, "n_elements": 20, "x_end": 0.25 + f}),
        "full/ballasted_80": (bt, V, {**base, "x_start": 5.0, "x_end": 5.0 + 0.5 * f}),
        "explicit/kato_20": (kato, V, {**base, "integrator": "explicit", "dt": 1e-6,
                                       "n_elements": 20, "x_end": 0.25 + 0.25 * f}),
        "linear_hertz/kato": (kato, V, {**base, "fidelity": "linear/hertz", "dt": 1e-5,
                                        "x_end": 0.25 + 4.5 * f}),
        "linear_sprung/kato": (kato, V, {**base, "fidelity": "linear/sprung", "dt": 1e-5,
                                         "x_end": 0.25 + 4.5 * f}),
        "linear_hertz/ballasted_window": (win, V, {**base, "fidelity": "linear/hertz",
                                                   "distance": 10.0 * f}),
        "linear_hertz/bogie": (bogie, V, {**base, "fidelity": "linear/hertz", "x_start": 3.0,
                                          "x_end": 3.0 + 3.0 * f}),
    }


def run_case(name: str, short: bool) -> int:
    """Runs one case; returns its steps."""
    import trackwheel as tw

    scene, speed, kw = cases(short)[name]
    return tw.simulate(scene, speed, **kw).steps


def cpu_per_step(name: str, repeats: int) -> float:
    """Best CPU time per step over ``repeats`` runs [us]."""
    best, steps = float("inf"), 1
    run_case(name, True)  # warm up (imports, caches)
    for _ in range(repeats):
        t0 = time.process_time()
        steps = run_case(name, False)
        best = min(best, time.process_time() - t0)
    return 1e6 * best / steps


def instructions_per_step(name: str) -> float:
    """Instructions inside the time loop per step, counted by callgrind."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        code = (f"import sys; sys.path.insert(0, {os.path.dirname(__file__)!r}); "
                f"import step_cost; print(step_cost.run_case({name!r}, True))")
        res = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                              "--toggle-collect=trackwheel::run_time_loop*",
                              sys.executable, "-c", code],
                             capture_output=True, text=True, check=True)
        steps = int(res.stdout.strip().splitlines()[-1])
        text = open(out).read()
    total = int(re.search(r"^(?:summary|totals):\s+(\d+)", text, re.MULTILINE).group(1))
    return total / steps


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5, help="runs per case for the CPU time")
    ap.add_argument("--callgrind", action="store_true", help="instructions per step instead")
    ap.add_argument("--only", nargs="+", default=None, help="case names")
    ap.add_argument("--csv", action="store_true", help="also write benchmarks/step_cost.csv")
    args = ap.parse_args(argv)
    names = args.only or list(cases(True))
    out = {}
    for name in names:
        out[name] = (instructions_per_step(name) if args.callgrind
                     else cpu_per_step(name, args.repeats))
    print(json.dumps({k: round(v, 3) for k, v in out.items()}))
    if args.csv:
        from _common import write_csv

        unit = "instructions_per_step" if args.callgrind else "cpu_us_per_step"
        write_csv("step_cost.csv", [{"case": k, unit: v} for k, v in out.items()])


if __name__ == "__main__":
    main()
