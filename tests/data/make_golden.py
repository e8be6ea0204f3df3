"""Record the golden outputs of tests/test_golden.py (issue 11).

Run once on the pre-redesign code (commit 618a45c) to freeze its results; the kernel redesign
must then reproduce them to round-off. Re-running it on later code would make the test vacuous,
so only re-run it on a deliberate, explained change of results::

    python tests/data/make_golden.py   # writes tests/data/golden.npz

Every setting is explicit, so a change of a default does not change what is compared. Runs are
short and decimated (``output_every``) to keep the file small.

Re-recorded since, group by group (``--groups``), each for a deliberate change of results:

- ``ga_full``, ``hertz_damped``, ``slip_torque``, ``sudden_drop``, ``standing_sudden``
  (generalized-alpha on the full path): Newton also stops when the error its last correction
  leaves, theta / (1 - theta) e_k, is within the tolerance, while theta <= (1 - rho_inf) / 10
  (docs: Model § Equations of motion); and the bordered solve takes C's non-zeros only and
  A^-1 B by band solves that stop where the columns have decayed below 1e-17 of their largest
  entry (reordered sums, below round-off). Against the earlier record: Newton iterations 2831
  -> 2400, 2839 -> 2401, 1255 -> 1200, 4159 -> 4027 (the standing wheel's unchanged); largest
  changes relative to each array's maximum 6e-7 (accelerations; the standing wheel's sudden
  start 4.7e-7), the free-rolling tangential
  force 0.085 N of its 42 N maximum (1.8e-6 of the wheel load, about its Newton tolerance
  1e-6 P; the slip, 7.6e-8 m/s at most, is round-off of the rolling constraint), the sudden
  drop's reaction and tangential force 1.5e-4 of their maxima.
- ``linear_moving_mass``, ``linear_sprung``: a wheel's coupling vector is kept as its four
  non-zeros and A^-1 s as its element's four cached columns (docs: Model § The vehicle),
  which sums the same products in another order: 3.2e-9 (the rigid moving mass,
  whose contact row divides by c_q = beta' h^2) and 1.1e-10 of the largest acceleration.
"""

from __future__ import annotations

import dataclasses as dc
from pathlib import Path

import numpy as np

import trackwheel as tw
from trackwheel.eigen import rail_frequencies

#: Result fields stored for every time run (arrays); counters are stored as 0-d arrays.
ARRAYS = ("t", "x_wheel", "y_wheel", "ydot_wheel", "theta", "thetadot", "contact_s",
          "y_contact", "normal_force", "tangential_force", "slip", "slip_state", "v_error",
          "phi", "acc_contact", "acc_A", "acc_B", "acc_C", "acc_D", "acc_E", "reaction",
          "penetration", "energy")
COUNTERS = ("steps", "newton_iterations", "state_changes", "stability_limit")

V = 300 / 3.6  # [m/s]
BASE = {"dt": 1e-5, "n_elements": 20, "x_start": 0.25, "x_end": 1.25, "output_every": 8,
        "rho_inf": 0.8, "baumgarte": 0.0, "rolling": True, "start": "static",
        "drop_height": 0.0, "progress": False, "energy": True, "max_newton": 25,
        "newton_tol": 1e-11, "integrator": "generalized_alpha", "fidelity": "full",
        "n_modes": None, "duration": None}


def _scene_hertz_damped():
    s = tw.Scene.kato2005()
    return dc.replace(s, contact=dc.replace(s.contact, law="hertz", damping=2e4))


def _scene_damped_supports():
    s = tw.Scene.kato2005()
    return dc.replace(s, supports=dc.replace(s.supports, damping=5e4))


def _scene_slip():
    s = tw.Scene.kato2005()
    return dc.replace(s, wheel=dc.replace(s.wheel, torque=3000.0),
                      contact=dc.replace(s.contact, friction=0.3))


#: name -> (scene factory, speed [m/s], settings overriding BASE)
RUNS = {
    "ga_full": (tw.Scene.kato2005, V, {}),
    "rk4_full": (tw.Scene.kato2005, V, {"integrator": "explicit", "dt": 5e-7, "x_end": 0.5,
                                        "output_every": 80, "baumgarte": 50.0}),
    "ga_rho1_norolling": (tw.Scene.kato2005, V, {"rho_inf": 1.0, "rolling": False,
                                                 "x_end": 0.75}),
    "linear_hertz": (tw.Scene.kato2005, V, {"fidelity": "linear/hertz", "x_end": 2.25,
                                            "output_every": 16}),
    "linear_sprung": (tw.Scene.kato2005, V, {"fidelity": "linear/sprung", "x_end": 2.25,
                                             "output_every": 16}),
    "linear_moving_mass": (tw.Scene.kato2005, V, {"fidelity": "linear/moving_mass",
                                                  "x_end": 2.25, "output_every": 16}),
    "linear_moving_force": (tw.Scene.kato2005, V, {"fidelity": "linear/moving_force",
                                                   "x_end": 2.25, "output_every": 16}),
    "linear_modal": (tw.Scene.kato2005, V, {"fidelity": "linear/hertz", "n_modes": 12,
                                            "x_end": 2.25, "output_every": 16}),
    "linear_sudden": (_scene_damped_supports, V, {"fidelity": "linear/hertz", "start": "sudden",
                                                  "drop_height": 2e-5, "x_end": 1.25}),
    "hertz_damped": (_scene_hertz_damped, V, {"fidelity": "ancf/hertz"}),
    "sudden_drop": (_scene_damped_supports, V, {"start": "sudden", "drop_height": 5e-5,
                                                "dt": 2e-6, "x_end": 0.5, "output_every": 20}),
    "slip_torque": (_scene_slip, V, {"x_end": 0.75, "output_every": 4}),
    "standing_sudden": (tw.Scene.kato2005, 0.0, {"start": "sudden", "duration": 0.004,
                                                 "x_end": None, "x_start": 2.5,
                                                 "output_every": 4}),
}

EIGEN_POSITIONS = (0.25, 1.0, 1.3, 2.5)
STATIC_POSITIONS = (1.3, 2.5)
QS_POSITIONS = tuple(np.linspace(0.25, 4.75, 19))


def time_runs():
    """{name: Result} of RUNS through the public API."""
    out = {}
    for name, (make_scene, speed, over) in RUNS.items():
        kw = {**BASE, **over}
        if kw["duration"] is not None:
            kw.pop("x_end")
        out[name] = tw.simulate(make_scene(), speed, **kw)
    return out


def golden_arrays():
    """{key: ndarray} of everything compared by tests/test_golden.py."""
    data = {}
    for name, r in time_runs().items():
        for f in ARRAYS:
            data[f"{name}/{f}"] = np.asarray(getattr(r, f), dtype=float)
        for f in COUNTERS:
            data[f"{name}/{f}"] = np.asarray(getattr(r, f), dtype=float)
    scene = tw.Scene.kato2005()
    e = tw.eigen(scene, EIGEN_POSITIONS, n_modes=6, n_elements=20, n_axial=3)
    data["eigen/frequencies"] = e.frequencies
    data["eigen/axial_frequencies"] = e.axial_frequencies
    data["rail_frequencies"] = rail_frequencies(scene, 6, n_elements=20)
    for x in STATIC_POSITIONS:
        s = tw.static(scene, x, n_elements=20)
        for f in ("y_wheel", "contact_s", "y_contact", "normal_force", "rail_coordinates"):
            data[f"static_{x}/{f}"] = np.asarray(getattr(s, f), dtype=float)
    q = tw.quasi_static(scene, QS_POSITIONS, n_elements=20)
    for f in ("y_contact", "y_wheel", "contact_s", "normal_force"):
        data[f"quasi_static/{f}"] = np.asarray(getattr(q, f))
    return data


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description="record tests/data/golden.npz")
    ap.add_argument("--groups", nargs="+", default=None,
                    help="re-record only these groups (run names), keep the rest as stored")
    args = ap.parse_args()
    path = Path(__file__).with_name("golden.npz")
    data = golden_arrays()
    if args.groups:
        with np.load(path) as d:
            kept = {k: d[k] for k in d.files if k.split("/")[0] not in args.groups}
        data = {**kept, **{k: v for k, v in data.items() if k.split("/")[0] in args.groups}}
    np.savez_compressed(path, **data)
    print(f"wrote {path} ({path.stat().st_size / 1024:.0f} kB)")
