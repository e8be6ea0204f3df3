"""The periodic level (``trackwheel.periodic_response``) against the time domain's run to the
same steady state, and a speed x stiffness sweep.

Cases, all on the ballasted preset (UIC60 on pad-sleeper-ballast supports every 0.6 m) with the
linear/sprung wheel at 300 km/h:

- ``steady euler`` / ``steady timoshenko``: the time-domain linear level on the travelling
  window (20 + 20 bays, the default mesh and step; the cheapest way to a steady state in
  trackwheel) run from the first bay until ``steady_state`` finds its contact force settled
  to 1e-3 of the load (15 m; the Timoshenko rail's bays still differ by 1e-3 after 30 m, the
  node-crossing kicks of its element at v / l_e: settled to 3e-3 over 20 m), against
  ``periodic_response`` at its defaults (6
  sleeper-passing harmonics reported, 8 kept). Both run in this process, alternately,
  ``--repeat`` times (default 7; the periodic call 20 times per sample), timed in CPU time
  (``time.process_time``: both are single-threaded, and on a shared machine the CPU time of a
  millisecond call is steadier than its wall time); the CSV holds the medians, their ratio, the harmonics 1-3 of
  both (the window's shifts move the time domain's by ~1e-3, see docs: Model § The periodic
  level) and the kernel's work counts for the periodic call (integrand evaluations, zeros of
  the dispersion function found and the evaluations spent finding them, bisection rounds:
  the same on any machine).
- ``grid``: 50 speeds (50-400 km/h) x 20 pad stiffnesses (40-400 MN/m, log-spaced) as
  1000 direct ``periodic_response`` calls and as ``tw.sweep(..., fidelity="periodic/linear")``
  (whose rows add the steady outputs: max |d| against the quasi-static line, the main
  frequency, the force's RMS; the case hashes; the table), alternately, ``--repeat`` / 3 times
  (at least 3), one process: the median CPU and wall time and the cases refused.
- ``random``: ``random_response`` of ISO 3095 roughness over 4.4-44 cm at 100 km/h (side bands
  +-2, 120 profile frequencies per decade).

Writes ``periodic.csv`` next to itself:

    PYTHONPATH=python python benchmarks/periodic.py [--repeat N]
"""

from __future__ import annotations

import dataclasses as dc
import statistics
import sys
import time

import numpy as np

import trackwheel as tw
from _common import write_csv
from trackwheel import _core
from trackwheel.run.periodic import periodic_response, periodic_track, random_response
from trackwheel.run.periodic._moving import kernel_params
from trackwheel.run.periodic.response import DEFAULT_HARMONICS, DEFAULT_RTOL, HARMONIC_MARGIN

V = 300 / 3.6
#: periodic_response calls per timed sample (one call takes milliseconds)
PER_SAMPLE = 20


def scene(beam: str) -> tw.Scene:
    s = tw.Scene.ballasted_track()
    return dc.replace(s, rail=dc.replace(s.rail, beam=beam))


def time_domain(s: tw.Scene, distance: float, tol: float):
    run = tw.simulate(s.windowed(tw.Window(20, 20)), V, fidelity="linear/sprung",
                      distance=distance, x_start=0.3, progress=False)
    return tw.steady_state(run, n_harmonics=3, tol=tol)


def steady_case(beam: str, repeat: int, distance: float, tol: float) -> dict:
    s = scene(beam)
    periodic_response(s, V)  # warm: imports, caches
    tp, tt = [], []
    for _ in range(repeat):
        t0 = time.process_time()
        for _ in range(PER_SAMPLE):
            r = periodic_response(s, V, fidelity="linear/sprung")
        tp.append((time.process_time() - t0) / PER_SAMPLE)
        t0 = time.process_time()
        st = time_domain(s, distance, tol)
        tt.append(time.process_time() - t0)
    per, td = statistics.median(tp), statistics.median(tt)
    h = r.force_harmonics.amplitude_n.to_numpy()[:3]
    _, work = _core.periodic_receptance_matrix(kernel_params(periodic_track(s)), V, 0.0,
                                               DEFAULT_HARMONICS + HARMONIC_MARGIN, [0.0],
                                               DEFAULT_RTOL, stats=True)
    return {"case": f"steady {beam}", "distance_m": distance, "steady_tol": tol,
            "periodic_ms": 1e3 * per,
            "time_domain_ms": 1e3 * td,
            "ratio": td / per, "periodic_h1_n": h[0], "periodic_h2_n": h[1],
            "periodic_h3_n": h[2], "time_domain_h1_n": st.harmonics[1][0],
            "time_domain_h2_n": st.harmonics[1][1], "time_domain_h3_n": st.harmonics[1][2],
            "kernel_points": work["points"], "kernel_poles": work["poles"],
            "kernel_den_evaluations": work["den_evaluations"], "kernel_rounds": work["rounds"],
            "cases": 1, "refused": 0}


def _direct(base, speeds, pads) -> int:
    """periodic_response over the grid in plain loops; the number refused."""
    refused = 0
    for k in pads:
        s = dc.replace(base, supports=dc.replace(base.supports, stiffness=float(k)))
        for v in speeds:
            try:
                periodic_response(s, float(v))
            except ValueError:
                refused += 1
    return refused


def sweep_case(repeat: int) -> list[dict]:
    """The 50 x 20 grid as direct periodic_response calls and as tw.sweep(fidelity=
    "periodic/linear") (its rows: the steady outputs, max |d| with the quasi-static line
    cached per stiffness, the case hashes, the table), alternately, ``repeat`` times."""
    base = scene("euler")
    speeds = np.linspace(50.0, 400.0, 50) / 3.6
    pads = np.geomspace(40e6, 400e6, 20)
    periodic_response(base, speeds[0])
    tw.sweep(base, speeds[:2], pads[:2], fidelity="periodic/linear", progress=False)  # warm
    times = {"direct": [], "sweep": []}
    refused = failed = 0
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        refused = _direct(base, speeds, pads)
        times["direct"].append((time.process_time() - c0, time.perf_counter() - t0))
        t0, c0 = time.perf_counter(), time.process_time()
        df = tw.sweep(base, speeds, pads, fidelity="periodic/linear", progress=False)
        times["sweep"].append((time.process_time() - c0, time.perf_counter() - t0))
        failed = int((df.error != "").sum())
    out = []
    for name, label in (("direct", "periodic_response x 1000"),
                        ("sweep", "sweep(fidelity='periodic/linear')")):
        cpu = statistics.median(c for c, _ in times[name])
        wall = statistics.median(w for _, w in times[name])
        out.append({"case": f"grid 50 speeds x 20 pads: {label}", "periodic_ms": 1e3 * cpu,
                    "wall_ms": 1e3 * wall, "cases": speeds.size * pads.size,
                    "refused": refused if name == "direct" else failed})
    return out


def random_case() -> dict:
    s = scene("euler")
    t0 = time.process_time()
    rr = random_response(s, 100 / 3.6, tw.spectra.iso3095(), wavelengths=(0.044, 0.44))
    return {"case": "random ISO 3095, 100 km/h", "periodic_ms": 1e3 * (time.process_time() - t0),
            "cases": 1, "refused": 0, "sigma_n": rr.sigma}


def main(argv) -> None:
    repeat = int(argv[argv.index("--repeat") + 1]) if "--repeat" in argv else 7
    rows = [steady_case("euler", repeat, 15.0, 1e-3),
            steady_case("timoshenko", repeat, 20.0, 3e-3),
            *sweep_case(max(3, repeat // 3)),
            random_case()]
    keys = sorted({k for r in rows for k in r}, key=lambda k: list(rows[0]).index(k)
                  if k in rows[0] else 99)
    for r in rows:
        print("  ".join(f"{k}={r[k]:.4g}" if isinstance(r.get(k), float) else f"{k}={r[k]}"
                        for k in keys if k in r))
    write_csv("periodic.csv", [{k: r.get(k, "") for k in keys} for r in rows])


if __name__ == "__main__":
    main(sys.argv[1:])
