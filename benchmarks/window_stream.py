"""The travelling window over supports that vary from bay to bay, and over voids: cost per
metre against the uniform window.

The ballasted preset on a window of 20 + 1 + 20 bays at 300 km/h, default mesh and step, one
sample kept every 20 steps. Each case runs the same distance over three beds in one process,
alternately (``repeats`` times each; the medians and their ratios to the uniform bed): the
varied bed is a lognormal scatter per sleeper (cv 0.3 on k_b, 0.2 on k_p, 0.1 on m_s and c_b)
with a transition (k_b x3, k_p x1.5 over a linear ramp of 1.2 m) at a third of the distance, so
that nearly every shift changes the window's supports; the voided bed is the varied bed with a
0.15 mm void under every fourth sleeper (the wheel closes each and leaves it open behind:
about two ballast events per voided sleeper), alternated with the other two. Reported per case:
the wall time of the kernel per metre (``Result.wall_time / distance``: the time loop, which
holds the shifts, their re-assembly and refactorisation and the rest state's solve) and the
process's CPU time per metre over the same call (robust to waiting for a core), Newton's
iterations per step, the factorisations and the ballast events (counts, the same on any
machine).

- ``linear 1 km``: ``fidelity="linear/hertz"``, 1 km (the issue's target distance), 3 repeats;
- ``linear 100 m``: the same over 100 m, 5 repeats (cost per metre constant in the distance:
  compare with the 1 km row);
- ``full 15 m``: the full model over 15 m, 5 repeats (a kilometre of the full model takes
  half an hour; the cost per shift is constant, so the ratio per metre is the same).

Run: ``python benchmarks/window_stream.py`` (about 6 minutes on one core); writes
``window_stream.csv``.
"""

from __future__ import annotations

import dataclasses as dc
import statistics
import sys
import time

import numpy as np

from _common import write_csv

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel
from trackwheel.run import simulate as sim

V = tw.kmh(300)
D = 0.6


def factors(x: np.ndarray, at: float) -> dict:
    """Per-sleeper scale factors of the properties at X = x [m]: the scatter times the
    transition at X = ``at``."""
    k = np.rint(x / D).astype(int)
    s = np.clip((x - at) / 1.2 + 0.5, 0.0, 1.0)
    out = {"ballast_stiffness": 1.0 + 2.0 * s, "stiffness": 1.0 + 0.5 * s,
           "sleeper_mass": np.ones_like(x), "ballast_damping": np.ones_like(x)}
    for i, (name, cv) in enumerate([("ballast_stiffness", 0.3), ("stiffness", 0.2),
                                     ("sleeper_mass", 0.1), ("ballast_damping", 0.1)]):
        sig = np.sqrt(np.log1p(cv * cv))
        xi = np.random.default_rng([7, i]).standard_normal(k.max() + 1)[k]
        out[name] = out[name] * np.exp(sig * xi - 0.5 * sig * sig)
    return out


#: the voided bed's void [m] under every VOID_EVERY-th sleeper
VOID, VOID_EVERY = 1.5e-4, 4


def supports(scene, x, position, at, voids=False) -> _core.SupportParams:
    s = kernel._supports_at(scene, x, position)
    for name, f in factors(x, at).items():
        setattr(s, name, list(np.asarray(getattr(s, name)) * f))
    if voids:
        s.void_gap = list(np.where(np.rint(x / D).astype(int) % VOID_EVERY == 0, VOID, 0.0))
    return s


def plans(fidelity: str, distance: float):
    """(uniform plan, varied plan, voided plan) of the window over ``distance`` [m]."""
    scene = tw.Scene.ballasted_track(window=tw.Window(20, 20))
    kw = dict(x_start=12.3, distance=distance, fidelity=fidelity, output_every=20,
              n_elements=scene.rail.n_elements)
    uniform = sim.plan_run(scene, V, **kw)
    return uniform, varied(scene, kw, distance, False), varied(scene, kw, distance, True)


def varied(scene, kw, distance, voids):
    p = sim.plan_run(scene, V, **kw)
    w, x = p.window, np.asarray(scene.support_positions)
    at = p.settings.x_start + distance / 3
    model = _core.RailModel(kernel.rail_params(scene, p.settings.n_elements),
                            supports(scene, w.origin + x, x, at, voids), p.model.profile)
    n = len(x) + int(np.ceil(distance / D)) + 2
    w.supports = supports(scene, w.origin + x[0] + D * np.arange(n), None, at, voids)
    init = p.init
    if init is not None:
        from trackwheel.run.start import initial_state
        init = initial_state(scene, model, V, p.settings.x_start - w.origin, "static", 0.0)
    return dc.replace(p, model=model, window=w, init=init)


def run(plan):
    s = sim.kernel_settings(plan)
    cpu = time.process_time()
    out, wall = sim.run_kernel(plan, s, False)
    cpu = time.process_time() - cpu
    return (wall, cpu, out["steps"], out["newton_iterations"], out["factorizations"],
            out["ballast_events"])


KEYS = ("uniform", "varied", "voided")


def case(name: str, fidelity: str, distance: float, repeats: int) -> dict:
    cases = dict(zip(KEYS, plans(fidelity, distance)))
    walls = {k: [] for k in KEYS}
    cpus = {k: [] for k in KEYS}
    counts = {}
    for _ in range(repeats):
        for key, plan in cases.items():
            wall, cpu, *counts[key] = run(plan)
            walls[key].append(wall)
            cpus[key].append(cpu)
    med = {k: statistics.median(walls[k]) for k in KEYS}
    mcpu = {k: statistics.median(cpus[k]) for k in KEYS}
    row = {"case": name, "distance_m": distance, "repeats": repeats}
    row.update({f"{k}_ms_per_m": round(1e3 * med[k] / distance, 3) for k in KEYS})
    row["ratio"] = round(med["varied"] / med["uniform"], 3)
    row["ratio_voided"] = round(med["voided"] / med["uniform"], 3)
    # the process's CPU time: what the run itself took on a shared machine (a wall time also
    # holds the time the run waited for a core)
    row.update({f"{k}_cpu_ms_per_m": round(1e3 * mcpu[k] / distance, 3) for k in KEYS})
    row["cpu_ratio"] = round(mcpu["varied"] / mcpu["uniform"], 3)
    row["cpu_ratio_voided"] = round(mcpu["voided"] / mcpu["uniform"], 3)
    for k in KEYS:
        steps, newton, fact, events = counts[k]
        row[f"newton_per_step_{k}"] = round(newton / steps, 4)
        row[f"factorizations_{k}"] = fact
        row[f"ballast_events_{k}"] = events
    print(row, flush=True)
    return row


def main(argv) -> None:
    rows = [case("linear 100 m", "linear/hertz", 100.0, 5),
            case("linear 1 km", "linear/hertz", 1000.0, 3),
            case("full 15 m", "full", 15.0, 5)]
    write_csv("window_stream.csv", rows)


if __name__ == "__main__":
    main(sys.argv[1:])
