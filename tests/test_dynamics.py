"""Dynamics: wheel, contact, rolling constraint, integrators (issue 4, docs: Model § Wheel, § Contact, § Rolling and slip, § Equations of motion).

Each test asserts a physical or numerical fact; tolerances are justified next to them.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel


def fryba(x, t, P, v, L, EI, m, n_terms=60):
    """Deflection (positive down) of a simply supported beam under a constant force P moving at
    v from rest (Fryba; docs: Model § Validation)."""
    w = np.zeros_like(np.asarray(t, dtype=float))
    for n in range(1, n_terms + 1):
        wn = (n * math.pi / L) ** 2 * math.sqrt(EI / m)
        Wn = n * math.pi * v / L
        qn = (2 * P / (m * L)) / (wn**2 - Wn**2) * (np.sin(Wn * t) - Wn / wn * np.sin(wn * t))
        w = w + qn * np.sin(n * math.pi * x / L)
    return w


def bare_beam_scene(load=10.0, wheel_mass=1e-3, contact=1e6, **rail):
    """A simply supported rail without intermediate supports and without its own weight."""
    return tw.Scene(
        rail=tw.Rail(**rail),
        supports=tw.Supports(positions=(), spacing=0.5),
        wheel=tw.Wheel(mass=wheel_mass, load=load),
        contact=tw.Contact(stiffness=contact),
        rail_gravity=False,
    )


# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("integrator,dt", [("generalized_alpha", 1e-5), ("explicit", 1e-6)])
def test_static_equilibrium_at_rest_stays(integrator, dt):
    """Zero speed from static equilibrium: nothing moves. Drift below 1e-9 of the static
    deflection over 0.01 s (the static state is solved to ~1e-13 m)."""
    scene = tw.Scene.kato2005()
    st = tw.static(scene, 2.5)
    r = tw.simulate(scene, 0.0, x_start=2.5, duration=0.01, integrator=integrator, dt=dt)
    drift = np.max(np.abs(r.y_contact - st.y_contact))
    assert drift < 1e-9 * abs(st.y_contact)
    assert np.max(np.abs(r.y_wheel - st.y_wheel)) < 1e-9 * abs(st.y_contact)


def test_moving_force_matches_fryba(validation):
    """A light stiff-contact wheel (moving-force limit) on a bare simply supported beam at
    100 km/h matches Fryba's series under the load within 2 % of the peak deflection.

    Load 10 N keeps the deflection small (L/1000) so geometric nonlinearity is < 1e-5; the wheel
    mass 1 g on a 1 MN/m contact (400x the beam's midspan stiffness 48EI/L^3) adds < 0.3 %."""
    scene = bare_beam_scene()
    rail = scene.rail
    v = tw.kmh(100)
    r = tw.simulate(scene, v, x_start=0.0, x_end=rail.length, start="sudden", dt=2e-5)
    w = fryba(r.x_wheel, r.t, scene.static_load, v, rail.length, rail.bending_stiffness,
              rail.mass_per_length)
    err = np.max(np.abs(-r.y_contact - w)) / np.max(np.abs(w))
    assert err < 0.02
    validation.record(
        "dynamics.moving_force_fryba", level="time integration", kind="closed form",
        quantity="full model, light stiff wheel at 100 km/h over a bare simply supported "
                 "rail: deflection under the load",
        reference="Frýba's modal series for a constant force moving over a simply supported "
                  "beam from rest",
        measured=err, tolerance=0.02, metric="of max deflection")


def initial_rail_velocity(model):
    """A smooth vertical velocity field 0.01 sin(pi x / L) m/s on the rail coordinates."""
    e = np.asarray(model.reference())
    x = e[0::4]
    edot = np.zeros_like(e)
    edot[1::4] = 0.01 * np.sin(np.pi * x / 5.0)
    edot[3::4] = 0.01 * np.pi / 5.0 * np.cos(np.pi * x / 5.0)
    edot[1] = edot[-3] = 0.0  # fixed coordinates
    return edot


def free_vibration(rho_inf, dt, n_steps=1000, integrator="generalized_alpha"):
    """Wheel resting on the paper's track at zero speed, rail given an initial velocity field."""
    scene = tw.Scene.kato2005()
    model = _kernel.rail_model(scene)
    wheel, contact = _kernel.wheel_params(scene), _kernel.contact_params(scene)
    d = _core.static_solve(model, wheel, contact, 2.5)
    init = _core.SimState()
    e = np.asarray(d["e"])
    edot = initial_rail_velocity(model)
    w = _core.WheelState()
    w.y, w.ydot, w.theta, w.thetadot, w.s = d["y_wheel"], 0.0, 0.0, 0.0, d["contact_s"]
    w.state = _core.SlipState.stick
    init.e, init.edot, init.wheels = e, edot, [w]
    s = _core.SimSettings()
    s.integrator = getattr(_core.Integrator, integrator)
    s.speed, s.x_start, s.dt, s.t_end = 0.0, 2.5, dt, n_steps * dt
    s.rho_inf, s.record_energy, s.newton_tol = rho_inf, True, 1e-14
    return _core.simulate(model, [wheel], contact, s, init)


def test_energy_conserved_undamped(validation):
    """rho_inf = 1 (trapezoidal rule, no numerical damping) and no physical damping: the total
    energy drifts by less than 1e-6 of the vibration energy over 1000 steps."""
    out = free_vibration(1.0, 1e-5)
    E = np.asarray(out["energy"])
    model = _kernel.rail_model(tw.Scene.kato2005())
    edot0 = np.asarray(initial_rail_velocity(model))
    E_vib = 0.5 * edot0 @ model.mass_dense() @ edot0
    assert out["steps"] == 1000
    assert np.max(np.abs(E - E[0])) < 1e-6 * E_vib
    validation.record(
        "dynamics.energy_conserved", level="time integration", kind="closed form",
        quantity="generalized-α with ρ∞ = 1, undamped free vibration, 1000 steps: total "
                 "energy drift",
        reference="energy conservation (no damping, no work done)",
        measured=np.max(np.abs(E - E[0])) / E_vib, tolerance=1e-6,
        metric="of the vibration energy")


def test_energy_decays_with_numerical_damping():
    """rho_inf < 1 damps the high modes: the energy at the end is below the start."""
    out = free_vibration(0.5, 1e-5, n_steps=300)
    E = np.asarray(out["energy"])
    assert E[-1] < E[0] - 1e-3 * (E.max() - E.min())


@pytest.mark.parametrize("integrator,order", [("generalized_alpha", 2.0), ("explicit", 4.0)])
def test_convergence_order(integrator, order, validation):
    """Self-convergence of the rail's vertical coordinates at t = 0.4 ms on the free vibration
    (nearly linear): the observed order log2(err(4 us)/err(2 us)) against a 0.25 us reference is
    the scheme's order within 0.5 (generalized-alpha 2, RK4 4)."""
    T = 4e-4
    dts = (4e-6, 2e-6, 2.5e-7)
    finals = [np.asarray(free_vibration(0.8, dt, int(round(T / dt)), integrator)
                         ["final_state"].e)[1::4] for dt in dts]
    errs = [np.max(np.abs(f - finals[-1])) for f in finals[:-1]]
    p = math.log2(errs[0] / errs[1])
    assert abs(p - order) < 0.5, (errs, p)
    name = "generalized-α" if integrator == "generalized_alpha" else "explicit RK4"
    validation.record(
        f"dynamics.convergence_order[{integrator}]", level="time integration",
        kind="closed form",
        quantity=f"{name}, free vibration of the paper's track: observed order of the rail "
                 "coordinates",
        reference=f"the scheme's formal order, {order:g}",
        measured=abs(p - order), tolerance=0.5, metric="absolute (order)")


def test_pure_rolling_on_stiff_rail():
    """Very stiff straight rail: pure rolling gives v_error below 1e-8 % and theta' = v/rho."""
    scene = tw.Scene(rail=tw.Rail(youngs_modulus=2.058e15), supports=tw.Supports(stiffness=1e13),
                     rail_gravity=False)
    v = tw.kmh(100)
    # the constraint holds to the Newton tolerance: 1e-14 m on displacements keeps the velocity
    # residual ~1e-9 m/s, far below the 1e-8 % (2.8e-9 m/s) asked for
    r = tw.simulate(scene, v, x_end=1.0, n_elements=20, dt=1e-5, newton_tol=1e-14)
    assert np.max(np.abs(r.v_error)) < 1e-8
    rho = scene.wheel.radius - r.penetration
    assert np.allclose(r.thetadot, v / rho, rtol=1e-10, atol=0)
    assert np.all(r.slip_state == 1)


@pytest.mark.parametrize("factor,expect_slip", [(0.4, False), (1.2, True)])
def test_torque_slip_threshold(factor, expect_slip):
    """A driving torque T = factor mu N rho: above 1 the wheel slides, spinning faster than it
    rolls (slip velocity < 0, friction +mu N); below it sticks with lambda = T/rho on average.
    The torque is applied suddenly at t = 0, which rings the rail's axial modes (the far end is
    a roller): the step response of lambda overshoots up to twice T/rho, so the sticking case
    uses T < mu N rho / 2 (at 0.8 the overshoot gives a brief physical slip at ~2 ms)."""
    base = tw.Scene.kato2005()
    mu, rho0, P = base.contact.friction, base.wheel.radius, base.static_load
    scene = dc.replace(base, wheel=dc.replace(base.wheel, torque=factor * mu * P * rho0))
    r = tw.simulate(scene, tw.kmh(100), x_end=1.0, dt=1e-5)
    tail = slice(len(r.t) // 2, None)
    if expect_slip:
        assert np.all(r.slip_state[tail] == 2)
        assert np.all(r.slip[tail] < 0)
        # lambda = mu N holds to the Newton tolerance on the tangential force (1e-6 of the load)
        np.testing.assert_allclose(r.tangential_force[tail], mu * r.normal_force[tail],
                                   rtol=0, atol=1e-6 * P)
    else:
        assert np.all(r.slip_state == 1)
        # J theta'' = T - rho lambda with theta'' ~ 0 (dynamic fluctuations of N are ~5 %)
        lam = r.tangential_force[tail]
        assert abs(np.mean(lam) - factor * mu * P) < 0.05 * factor * mu * P
        assert np.all(np.abs(lam) <= mu * r.normal_force[tail])


def test_wheel_dropped_loses_contact_and_lands():
    """Released 1 mm above the rail, the wheel falls freely under (F + M g)/M until it lands:
    t_land = sqrt(2 h M / P) within 2 % (rail at rest under its own weight); the contact-free
    interval is reported."""
    scene = tw.Scene.kato2005()
    h = 1e-3
    r = tw.simulate(scene, tw.kmh(100), start="sudden", drop_height=h, x_end=0.4, dt=1e-6)
    intervals = r.contact_free_intervals()
    assert r.lost_contact and intervals
    t_land_expected = math.sqrt(2 * h * scene.wheel.mass / scene.static_load)
    t0, t1 = intervals[0]
    assert t0 == 0.0
    assert abs(t1 - t_land_expected) < 0.02 * t_land_expected
    assert np.any(r.normal_force[r.t > t1] > 0)


def test_explicit_far_above_stability_limit_diverges():
    """RK4 at 5x its predicted stability limit: DivergenceError naming the time and the cause,
    within a few hundred steps."""
    scene = tw.Scene.kato2005()
    with pytest.warns(tw.StabilityWarning), pytest.raises(tw.DivergenceError) as info:
        tw.simulate(scene, tw.kmh(300), integrator="explicit", dt=5e-5)
    err = info.value
    assert err.step < 300
    assert err.time == pytest.approx(err.step * 5e-5)
    assert "stability limit" in err.cause
    assert "t = " in str(err)


def test_rolling_jacobians_against_finite_differences(validation):
    """dg/dq, dg/dqdot (= b), db/dq and ds*/dq of the rolling constraint against central
    differences at a deformed rail state (fixed seed)."""
    scene = tw.Scene.kato2005()
    model = _kernel.rail_model(scene)
    rng = np.random.default_rng(7)
    e = np.asarray(_core.static_solve(model, _kernel.wheel_params(scene),
                                      _kernel.contact_params(scene), 1.3)["e"])
    e = e + 1e-4 * rng.standard_normal(e.size) * np.tile([0.1, 1, 1e-2, 1e-2], e.size // 4)
    xa, ya = 1.3, float(model.positions(e, [1.3])[0, 1]) + 0.0999
    qdot = np.concatenate([[27.0, 0.05], 0.02 * rng.standard_normal(8)])
    thetadot = 270.0
    base = _core.testing.rolling_eval(model, e, xa, ya, xa, qdot, thetadot)
    el = int(np.floor(base["s"] / model.element_length))
    d0 = 4 * el

    def at(q, qd=qdot):
        ee = e.copy()
        ee[d0:d0 + 8] = q[2:]
        return _core.testing.rolling_eval(model, ee, q[0], q[1], base["s"], qd, thetadot)

    q0 = np.concatenate([[xa, ya], e[d0:d0 + 8]])
    h = 1e-7
    G = np.zeros(10)
    Bq = np.zeros((11, 10))
    S = np.zeros(10)
    for k in range(10):
        dq = np.zeros(10)
        dq[k] = h
        p, m = at(q0 + dq), at(q0 - dq)
        G[k] = (p["g"] - m["g"]) / (2 * h)
        Bq[:, k] = (np.asarray(p["b"]) - np.asarray(m["b"])) / (2 * h)
        S[k] = (p["s"] - m["s"]) / (2 * h)
    np.testing.assert_allclose(base["dg_dq"], G, rtol=1e-6, atol=1e-6 * np.abs(G).max())
    validation.record(
        "dynamics.rolling_constraint_jacobian", level="time integration",
        kind="finite differences",
        quantity="rolling constraint on a deformed rail: dg/dq (wheel centre and rail element)",
        reference="central differences of the constraint g",
        measured=np.abs(np.asarray(base["dg_dq"]) - G).max() / np.abs(G).max(),
        tolerance=1e-6, metric="of max |dg/dq|")
    np.testing.assert_allclose(base["db_dq"], Bq, rtol=1e-6, atol=1e-6 * np.abs(Bq).max())
    np.testing.assert_allclose(base["ds_dq"], S, rtol=1e-6, atol=1e-6 * np.abs(S).max())
    # g is linear in the velocities: dg/dqdot = b exactly (theta' coefficient b[10] = -rho)
    J = np.zeros(10)
    for k in range(10):
        dq = np.zeros(10)
        dq[k] = 1e-3
        J[k] = (at(q0, qdot + dq)["g"] - at(q0, qdot - dq)["g"]) / 2e-3
    np.testing.assert_allclose(np.asarray(base["b"])[:10], J, rtol=1e-9, atol=1e-12)


def test_deterministic_bit_identical():
    scene = tw.Scene.kato2005()
    a = tw.simulate(scene, tw.kmh(200), x_end=1.0)
    b = tw.simulate(scene, tw.kmh(200), x_end=1.0)
    for name in ("y_contact", "normal_force", "tangential_force", "theta", "acc_contact"):
        assert np.array_equal(getattr(a, name), getattr(b, name))


def test_explicit_and_generalized_alpha_agree(validation):
    """The two integrators solve the same equations: y_B agree within 1 % of the dynamic
    amplitude over the first bays at 300 km/h (generalized-alpha at 2.5 us, RK4 at 2 us)."""
    scene = tw.Scene.kato2005()
    ga = tw.simulate(scene, tw.kmh(300), x_end=1.5, dt=2.5e-6)
    ex = tw.simulate(scene, tw.kmh(300), x_end=1.5, dt=2e-6, integrator="explicit")
    y_ex = np.interp(ga.t, ex.t, ex.y_contact)
    dyn = np.ptp(ga.y_contact - np.polyval(np.polyfit(ga.t, ga.y_contact, 3), ga.t))
    assert np.max(np.abs(y_ex - ga.y_contact)) < 0.01 * max(dyn, 1e-9) + 2e-8
    validation.record(
        "paths.explicit_equals_generalized_alpha", level="paths agree", kind="path agreement",
        quantity="full model, explicit RK4 at 2 µs over the first bays at 300 km/h: y_B",
        reference="generalized-α at 2.5 µs",
        measured=np.max(np.abs(y_ex - ga.y_contact)), tolerance=0.01 * max(dyn, 1e-9) + 2e-8,
        metric="m")


@pytest.mark.parametrize("kwargs,match", [
    (dict(speed=-1.0), "speed"),
    (dict(speed=float("nan")), "speed"),
    (dict(speed=10.0, dt=0.0), "dt"),
    (dict(speed=10.0, dt=-1e-5), "dt"),
    (dict(speed=10.0, x_start=2.0, x_end=1.0), "x_end"),
    (dict(speed=10.0, x_start=6.0), "x_start"),
    (dict(speed=10.0, integrator="euler"), "integrator"),
    (dict(speed=10.0, rho_inf=1.5), "rho_inf"),
    (dict(speed=0.0), "duration"),
    (dict(speed=10.0, output_every=0), "output_every"),
])
def test_bad_arguments(kwargs, match):
    speed = kwargs.pop("speed")
    with pytest.raises(ValueError, match=match):
        tw.simulate(tw.Scene.kato2005(), speed, **kwargs)


def test_output_limit_raises_before_running():
    with pytest.raises(ValueError, match="output_every"):
        tw.simulate(tw.Scene.kato2005(), 1.0, dt=1e-9, output_every=1)


def test_output_decimation():
    r = tw.simulate(tw.Scene.kato2005(), tw.kmh(300), x_end=1.0, output_every=10, dt=1e-5)
    assert r.steps == round((1.0 - 0.25) / tw.kmh(300) / 1e-5)
    assert len(r.t) == r.steps // 10 + 1
    np.testing.assert_allclose(np.diff(r.t), 10e-5, rtol=1e-9)
