"""The vehicle's suspensions and weight distribution against physics that does not share the
kernel's matrices (docs: Model § The vehicle).

The other vehicle tests compare two paths built from the same suspension matrices, closed forms
of undamped vehicles, or symmetric presets; a damper acting on the wrong velocity or a lever
rule with its arms swapped passes them. Here: the base excitation of a damped sprung mass
against its transmissibility, the energy balance with the dampers' dissipated power computed
from the suspension's extension, and the force and moment balance of an off-centre bogie, on
the kernel's own dynamics.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest
from test_invariants import cumulative_trapezoid

import trackwheel as tw
from trackwheel.vehicle import Bogie, Vehicle


def _sprung_wheel(wheel_mass, radius, body_mass, k, c, load=0.0) -> Vehicle:
    """One wheel under a body on a spring k [N/m] and damper c [N s/m] (a one-wheel 'bogie':
    its centre over the wheel, so its pitch is decoupled), ``load`` [N] on the body."""
    return Vehicle(wheels=(tw.Wheel(mass=wheel_mass, radius=radius, load=0.0),),
                   positions=(0.0,),
                   bogies=(Bogie(wheels=(0,), centre=0.0, mass=body_mass, pitch_inertia=1.0,
                                 primary_stiffness=k, primary_damping=c, load=load),))


@pytest.mark.parametrize("fidelity", ["linear/moving_mass", "linear/sprung"])
def test_base_excited_damped_suspension_has_the_closed_form_transmissibility(fidelity):
    """A 1000 kg body on k = 1 MN/m and c = 20 kN s/m (f_n = 5.03 Hz, zeta = 0.32) over a
    wheel rolling at 20 m/s on a 1 mm sine of 2 m wavelength (omega = 2 pi v / lambda =
    62.8 rad/s, omega / omega_n = 1.99) on a rigid track (supports and contact 1e12 N/m). The
    wheel centre's height Y(t) is the base motion of the body: whatever the track does,
    m z'' = -k (z - Y) - c (z' - Y'), so over whole periods of the steady state the complex
    amplitudes obey z / Y = (k + i c omega) / (k - m omega^2 + i c omega) (the base-excitation
    transmissibility; |z / Y| = sqrt(k^2 + (c omega)^2) / |k - m omega^2 + i c omega|).
    Measured over the last five periods of 1.5 s, after the transient has decayed by
    exp(-c t / 2m) = 4.5e-5 at 1 s: 3.9e-6 (generalized-alpha's period error (omega h)^2 / 12
    is 3e-6 at 1e-4 s); tolerance 1e-4. A damper on the bodies' absolute velocities instead of
    the extension rate gives k / (k - m omega^2 + i c omega), 70 % off."""
    m, k, c, v, lam = 1000.0, 1.0e6, 2.0e4, 20.0, 2.0
    scene = tw.Scene(rail=tw.Rail(length=40.0, n_elements=160),
                     supports=tw.Supports(stiffness=1e12), contact=tw.Contact(stiffness=1e12),
                     vehicle=_sprung_wheel(100.0, 0.46, m, k, c),
                     irregularity=tw.Irregularity.sine(lam, 1e-3))
    dt = 1e-4
    r = tw.simulate(scene, v, dt=dt, x_start=5.0, x_end=35.0, fidelity=fidelity,
                    progress=False)
    w = 2.0 * math.pi * v / lam
    n5 = round(5 * lam / v / dt)  # five whole periods
    tail = slice(r.t.size - 1 - n5, r.t.size - 1)
    phase = np.exp(-1j * w * r.t[tail])
    ratio = np.sum(r.body_z[tail, 0] * phase) / np.sum(r.y_wheel[tail] * phase)
    expected = (k + 1j * c * w) / (k - m * w * w + 1j * c * w)
    assert abs(ratio / expected - 1.0) < 1e-4
    # on the rigid track the wheel follows the profile: the base motion is the 1 mm sine
    assert abs(2.0 * np.mean(r.y_wheel[tail] * phase)) == pytest.approx(1e-3, rel=1e-3)


def test_energy_balance_with_the_suspension_dampers_dissipated_power():
    """Full model, the paper's undamped track and a 10 kg wheel under a 100 kg body on
    k = 3 MN/m and c = 10 kN s/m carrying 40 kN, at 100 km/h over a 20 um sine of 0.7 m
    (40 Hz, near the body's 27.6 Hz): the total energy changes by the work of the driving
    reaction and of the tangential force on the slip, less what the damper dissipates,
    c (g . u')^2 with g . u = z - Y the suspension's extension:
    E(t) - E(0) = int (R v + lambda g_slip) dt - sum c (Delta(z - Y))^2 / h.
    Generalized-alpha at rho_inf = 1 is the trapezoidal rule, whose position update makes
    Delta(z - Y) / h the mean of the step's end rates, so the last sum is the step's exact
    dissipation of the linear damper; the rest is tests/test_invariants.py's balance. Measured
    1.5e-7 of max |W|; tolerance 1e-5 (tests/test_brake.py's). The damper dissipates 2.6 % of
    the work here; on the bodies' absolute velocities, c (z'^2 + Y'^2), it would dissipate
    10 % less, 3e-3 of max |W|."""
    veh = _sprung_wheel(10.0, 0.1, 100.0, 3.0e6, 1.0e4, load=40e3)
    scene = dc.replace(tw.Scene.kato2005(), vehicle=veh,
                       irregularity=tw.Irregularity.sine(0.7, 2e-5))
    v = tw.kmh(100)
    r = tw.simulate(scene, v, dt=5e-6, x_start=1.0, x_end=4.0, rho_inf=1.0, energy=True,
                    progress=False)
    assert np.all(r.slip_state == 1)  # rolling: the tangential force does no work
    work = cumulative_trapezoid(r.reaction * v + r.tangential_force * r.slip, r.t)
    extension = r.body_z[:, 0] - r.y_wheel
    c = veh.bogies[0].primary_damping
    dissipated = np.concatenate([[0.0], np.cumsum(c * np.diff(extension) ** 2 / np.diff(r.t))])
    assert dissipated[-1] > 1e-2 * np.max(np.abs(work))
    np.testing.assert_allclose(r.energy - r.energy[0], work - dissipated, rtol=0,
                               atol=1e-5 * np.max(np.abs(work)))


def _off_centre_bogie() -> Vehicle:
    """A bogie of 1750 kg and 861 kg m^2 with 30 kN on its pivot, its centre 0.8 m from the rear
    wheel of a 2.5 m wheelbase, on wheels of 1100 kg (rear) and 900 kg (front)."""
    wheels = (tw.Wheel(mass=1100.0, radius=0.43, load=0.0),
              tw.Wheel(mass=900.0, radius=0.43, load=0.0))
    return Vehicle(wheels=wheels, positions=(0.0, 2.5),
                   bogies=(Bogie(wheels=(0, 1), centre=0.8, load=30e3),))


def test_off_centre_bogie_loads_obey_the_force_and_moment_balance():
    """Lever rule: the frame's weight and pivot load W = M_b g + F act at its centre x_c, each
    wheel's weight at the wheel, so the wheel loads P_i satisfy sum P_i = W + sum M_i g and
    sum (P_i - M_i g) x_i = x_c W (moments about x = 0), to round-off (1e-12)."""
    g = 9.8
    veh = _off_centre_bogie()
    b = veh.bogies[0]
    W = b.mass * g + b.load
    P = np.asarray(veh.static_loads(g))
    own = np.array([w.mass * g for w in veh.wheels])
    x = np.asarray(veh.positions)
    assert P.sum() == pytest.approx(W + own.sum(), rel=1e-12)
    assert np.dot(P - own, x) == pytest.approx(b.centre * W, rel=1e-12)
    assert P[0] - own[0] > 1.5 * (P[1] - own[1])  # the centre is nearer the rear wheel


def test_off_centre_bogie_starts_in_the_kernels_equilibrium():
    """The run's static start puts the off-centre bogie's wheel loads on the rail and its frame
    where the springs carry them; the kernel's own equations (the suspension matrices and the
    bodies' weights, not the lever rule) must then hold everything still. Standing (v = 0) on
    the paper's track, damped suspension, 5 ms: the frame moves less than 1e-8 m and 1e-8 rad
    (the static solve's tolerance, ~1e-6 N on the loads, moves it ~1e-12 m) and the contact
    forces stay the lever-rule loads within 1e-6 (the static solve's tolerance; measured: the
    frame does not move, the forces hold to 2e-11). Loads from a lever rule with swapped arms
    (25.9 and 40.9 kN for 42.8 and 23.9 kN) set the frame pitching by 5e-4 rad within 5 ms."""
    g = 9.8
    veh = _off_centre_bogie()
    scene = tw.Scene(rail=tw.Rail(length=6.0, n_elements=24), vehicle=veh)
    r = tw.simulate(scene, 0.0, x_start=1.5, duration=5e-3, dt=1e-5, progress=False)
    assert np.max(np.abs(r.body_z - r.body_z[0])) < 1e-8
    assert np.max(np.abs(r.body_phi - r.body_phi[0])) < 1e-8
    np.testing.assert_allclose(r.normal_force, np.broadcast_to(veh.static_loads(g),
                                                               r.normal_force.shape), rtol=1e-6)
