"""The moving contact on the shear-deformable (Timoshenko) rail: bay-averaged contact force and
its ripple above 1 kHz against the mesh, with and without the element's fixed-end compliance
under the contact (docs: Model § Contact, "The rail under the load between nodes").

Scene (a quarter car on a ballasted UIC60 track): UIC60 Timoshenko rail (kappa 0.4,
G = E / 2.6), sleepers every 0.6 m, pad 180 MN/m and 18 kN s/m, half sleeper 150 kg, ballast
105 MN/m and 48 kN s/m; a 600 kg wheel under a 996 kg bogie on a 1.2 MN/m primary spring, 80 kN
static wheel load, linear contact 1.3374e9 N/m; travelling window 20 + 20 bays; smooth track.
The quarter car is a one-wheel ``Bogie`` (its pitch inertia does not enter: the wheel sits
under the bogie's centre) whose pivot load brings the static wheel load to 80 kN.

Measured on the steady part (``trackwheel.steady_state``, whole bays, so the bay-periodic
content is periodic in the FFT and nothing leaks): the bay-averaged contact-force profile's
max/min [kN], its first sleeper-passing harmonics, and the ripple: the force with every Fourier
component below 1 kHz removed, rms and peak |.| [N].

    python benchmarks/contact_ripple.py [--quick]   # writes contact_ripple.csv

The linear sprung level runs at 4 to 64 elements per bay, the full model at 8 and 32 (its
tangential force's standard deviation over the steady part is recorded too).
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np
from _common import write_csv

import trackwheel as tw
from trackwheel import Bogie, Vehicle

G = 9.81
WHEEL_LOAD = 80e3
CONTACT_STIFFNESS = 1.3374e9
RIPPLE_FROM = 1000.0  # [Hz]


def scene(elements_per_bay: int = 8, *, element_compliance: bool | None = None,
          beam: str = "timoshenko", law: str = "linear", primary_damping: float = 0.0,
          window: tw.Window | None = None) -> tw.Scene:
    """The quarter car on the ballasted UIC60 track (module docstring)."""
    base = tw.Scene.ballasted_track(elements_per_bay=elements_per_bay)
    rail = dataclasses.replace(base.rail, beam=beam, shear_coefficient=0.4)
    wheel = tw.Wheel(mass=600.0, radius=0.46, load=0.0, youngs_modulus=210e9, poisson_ratio=0.3)
    bogie = Bogie(wheels=(0,), centre=0.0, mass=996.0, pitch_inertia=1.0,
                  primary_stiffness=1.2e6, primary_damping=primary_damping,
                  load=WHEEL_LOAD - (600.0 + 996.0) * G)
    veh = Vehicle(wheels=(wheel,), positions=(0.0,), bogies=(bogie,))
    kw = {} if element_compliance is None else {"element_compliance": element_compliance}
    if law == "linear":
        contact = tw.Contact(law="linear", stiffness=CONTACT_STIFFNESS, **kw)
    else:  # Hertz with the same stiffness at the static load
        ch = (CONTACT_STIFFNESS / (1.5 * WHEEL_LOAD ** (1 / 3))) ** 1.5
        contact = tw.Contact(law="hertz", stiffness=ch, **kw)
    s = dataclasses.replace(base, rail=rail, vehicle=veh, contact=contact)
    return s.windowed(tw.Window(20, 20) if window is None else window)


def measure(result: tw.Result) -> dict:
    """Bay profile max/min [N], harmonics [N], ripple above RIPPLE_FROM rms and peak [N]."""
    r = result.wheel(0) if result.n_wheels > 1 else result
    ss = tw.steady_state(r, tol=2e-3, n_harmonics=4)
    v = float(result.settings.speed)
    d = result.scene.supports.spacing
    t = np.asarray(r.t)
    f = np.asarray(r.normal_force)
    t1 = ss.t_from + ss.n_bays * d / v
    keep = (t >= ss.t_from) & (t < t1 - 0.5 * (t[1] - t[0]))
    seg = f[keep] - f[keep].mean()
    freq = np.fft.rfftfreq(seg.size, t[1] - t[0])
    c = np.fft.rfft(seg)
    c[freq < RIPPLE_FROM] = 0.0
    hp = np.fft.irfft(c, seg.size)
    lam = np.asarray(r.tangential_force)[keep]
    return dict(fmax=float(ss.bay_profile.max()), fmin=float(ss.bay_profile.min()),
                h1=float(ss.harmonics[1][0]), h2=float(ss.harmonics[1][1]),
                ripple_rms=float(np.sqrt(np.mean(hp**2))), ripple_peak=float(np.abs(hp).max()),
                n_bays=ss.n_bays, bay_difference=ss.bay_difference,
                tangential_std=float(lam.std()))


def run(s: tw.Scene, speed_kmh: float, *, distance: float = 24.0, fidelity: str = "full",
        dt: float | None = None) -> tuple[dict, float]:
    """(measure of the run, wall time [s]) at the scene's mesh and dt (default: derived)."""
    dt = tw.default_settings(s)["dt"] if dt is None else dt
    t0 = time.perf_counter()
    res = tw.simulate(s, tw.kmh(speed_kmh), distance=distance, dt=dt,
                      n_elements=s.rail.n_elements, fidelity=fidelity, progress=False)
    return measure(res), time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="8 and 32 el/bay, 200 km/h only")
    args = ap.parse_args()
    speeds = (200.0,) if args.quick else (100.0, 200.0)
    # the linear level at every mesh; the full model (10x the cost per step, more at fine
    # meshes) at the default mesh and at 32 el/bay
    plan = {"linear/sprung": (8, 32) if args.quick else (4, 8, 16, 32, 64), "full": (8, 32)}
    rows = []
    for fidelity, meshes in plan.items():
        for speed in speeds:
            for epb in meshes:
                for comp in (False, True):
                    m, wall = run(scene(epb, element_compliance=comp), speed, fidelity=fidelity)
                    row = dict(fidelity=fidelity, speed_kmh=speed, elements_per_bay=epb,
                               element_compliance=comp, **{k: round(x, 3) if isinstance(
                                   x, float) else x for k, x in m.items()}, wall_s=round(wall, 1))
                    print(row, flush=True)
                    rows.append(row)
    write_csv("contact_ripple.csv", rows)


if __name__ == "__main__":
    main()
