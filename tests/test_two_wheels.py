"""Two wheels in the kernel (issue 11): the model holds a list of wheels, each with its own
contact search, rolling constraint, slip state and 3-wide border of the bordered band solve.
The Python API stays one wheel; these tests go through the bindings (``_core.simulate`` and
``_core.simulate_linear`` with a list of ``WheelParams`` and one ``WheelState`` per wheel).
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel

L = 20.0  # [m]: 80 elements of 0.25 m, the paper's element length
SEPARATION = 10.0  # [m]
X0 = 5.0  # [m]: wheel A at 5 m, wheel B at 15 m
V = tw.kmh(300)
FIELDS = ("y_wheel", "ydot_wheel", "normal_force", "tangential_force", "y_contact",
          "contact_s", "acc_contact")


@pytest.fixture(scope="module")
def long_track():
    scene = tw.Scene.kato2005()
    scene = dc.replace(scene, rail=dc.replace(scene.rail, length=L, n_elements=80))
    model = _kernel.rail_model(scene, 80)
    return scene, model, np.asarray(_core.rail_static(model))


def _wheels(scene, offsets, loads=None):
    out = []
    for i, o in enumerate(offsets):
        p = _kernel.wheel_params(scene)
        p.x_offset = o
        if loads is not None:  # P = F + M g set to loads[i]: F = loads[i], no wheel weight
            p.load, p.gravity = loads[i], 0.0
        out.append(p)
    return out


def _full_run(scene, model, e0, offsets, n_steps, dt=1e-5):
    """A sudden start: the rail under its own weight, each wheel just touching it, rolling."""
    states = []
    for o in offsets:
        x = X0 + o
        w = _core.WheelState()
        w.y = model.positions(e0, [x])[0, 1] + scene.wheel.radius
        w.s = x
        w.thetadot = V / scene.wheel.radius
        w.state = _core.SlipState.free
        states.append(w)
    st = _core.SimState()
    st.e, st.edot, st.wheels = e0.copy(), np.zeros_like(e0), states
    s = _core.SimSettings()
    s.speed, s.x_start, s.dt, s.t_end = V, X0, dt, n_steps * dt
    return _core.simulate(model, _wheels(scene, offsets), _kernel.contact_params(scene), s, st)


def test_far_apart_wheels_each_reproduce_their_single_run_until_waves_meet(long_track):
    """Generalized-alpha, 1e-5 s. The fastest wave the mesh carries has the group velocity
    c = 2 sqrt(omega_max) (EI/m)^(1/4) of a bending wave at the mesh's highest frequency
    (omega_max, an upper bound: it is the axial/contact top of the spectrum, and above the
    axial bar speed sqrt(EA/m) = 5.1 km/s), so nothing from the other wheel arrives before
    t_a = separation / c (~0.5 ms here). The implicit step couples every coordinate, but the
    inverse of its iteration matrix M + gamma' h C + beta' h^2 K decays like
    exp(-d / (EI beta' h^2 / m)^(1/4)), a length of ~4 cm at this step, so 10 m away the other
    wheel's influence is far below round-off. Before t_a / 2 each wheel's response therefore
    equals its single-wheel run to round-off: 1e-12 of the response range (measured: exactly
    equal up to 0.5 ms, differences of ~1e-12 from t_a on, then growing as the waves meet).
    The tangential force is the exception that proves the rule: Newton stops when every
    wheel's corrections are small, so a wheel may take an extra iteration in the two-wheel run;
    that moves the displacements by far less than round-off but lambda by up to its Newton
    tolerance, 1e-6 of the wheel load (measured 2.5e-8 N)."""
    scene, model, e0 = long_track
    omega = _core.highest_frequency(model, _kernel.wheel_params(scene),
                                    _kernel.contact_params(scene), e0, X0,
                                    model.positions(e0, [X0])[0, 1] + scene.wheel.radius)
    r = scene.rail
    c = 2.0 * np.sqrt(omega) * (r.bending_stiffness / r.mass_per_length) ** 0.25
    assert c > np.sqrt(r.axial_stiffness / r.mass_per_length)
    t_arrival = SEPARATION / c
    n = 60
    both = _full_run(scene, model, e0, (0.0, SEPARATION), n)
    assert both["y_wheel"].shape == (n + 1, 2)
    early = both["t"] < 0.5 * t_arrival
    assert early.sum() >= 20
    for k, offset in enumerate((0.0, SEPARATION)):
        one = _full_run(scene, model, e0, (offset,), n)
        for f in FIELDS:
            ref = one[f][:, 0]
            err = np.max(np.abs(both[f][early, k] - ref[early]))
            tol = 1e-6 * scene.static_load if f == "tangential_force" else 1e-12 * np.ptp(ref)
            assert err <= tol, (k, f, err, tol)
        # and the wheel did respond in that window (a sudden load: it sinks and bounces)
        assert np.ptp(one["normal_force"][early, 0]) > 0.1 * scene.static_load


def _linear_run(scene, model, offsets, loads, level):
    s = _core.SimSettings()
    s.speed, s.x_start, s.dt, s.t_end = V, X0, 1e-5, 200 * 1e-5
    opt = _core.LinearOptions()
    opt.wheel_model = getattr(_core.WheelModel, level)
    return _core.simulate_linear(model, _wheels(scene, offsets, loads),
                                 _kernel.contact_params(scene), s, opt)


@pytest.mark.parametrize("level", ["moving_force", "sprung"])
def test_linear_two_wheels_are_the_superposition_of_single_wheels(long_track, level):
    """The linear track with moving forces (or linear sprung wheels) and no rail weight is a
    linear system in the wheel loads, and every step is a linear map: the two-wheel run with
    loads (P_A, P_B) equals the run with (P_A, 0) plus the run with (0, P_B), at both wheels and
    every sample, to round-off: 1e-11 of each field's largest magnitude for displacements and
    forces (eps = 2.2e-16 per operation, accumulated over 200 steps and a few hundred operations
    per coordinate and step; measured 4e-13), 1e-9 for the contact-point acceleration, which is
    the small remainder of inertia and stiffness terms of the iteration matrix (its condition
    number ~ (omega_max h)^2 amplifies round-off; measured 1.1e-11). A wheel with no load changes nothing: (P_A, 0) at wheel
    A equals the one-wheel run of A exactly."""
    scene, model, _ = long_track
    scene = dc.replace(scene, rail_gravity=False)
    model = _kernel.rail_model(scene, 80)
    P = scene.static_load
    offsets = (0.0, SEPARATION)
    both = _linear_run(scene, model, offsets, (P, 0.7 * P), level)
    only_a = _linear_run(scene, model, offsets, (P, 0.0), level)
    only_b = _linear_run(scene, model, offsets, (0.0, 0.7 * P), level)
    single_a = _linear_run(scene, model, (0.0,), (P,), level)
    for f in ("y_contact", "acc_contact", "normal_force", "phi"):
        total = only_a[f] + only_b[f]
        scale = np.max(np.abs(both[f]))
        assert scale > 0.0, f
        rtol = 1e-9 if f == "acc_contact" else 1e-11
        assert np.max(np.abs(both[f] - total)) <= rtol * scale, f
        ref = single_a[f][:, 0]
        if level == "moving_force":
            assert np.max(np.abs(only_a[f][:, 0] - ref)) <= 1e-12 * np.max(np.abs(ref)), f
    # the wheels feel each other: B's load moves the rail under A (the superposition is not
    # two uncoupled runs)
    assert np.max(np.abs(only_b["y_contact"][:, 0])) > 0.0


def test_bindings_check_the_wheel_list(long_track):
    scene, model, e0 = long_track
    st = _core.SimState()
    st.e, st.edot, st.wheels = e0.copy(), np.zeros_like(e0), [_core.WheelState()]
    s = _core.SimSettings()
    s.speed, s.x_start, s.dt, s.t_end = V, X0, 1e-5, 1e-4
    contact = _kernel.contact_params(scene)
    with pytest.raises(ValueError, match="1 wheel states; the model has 2 wheels"):
        _core.simulate(model, _wheels(scene, (0.0, 1.0)), contact, s, st)
    with pytest.raises(ValueError, match="at least one wheel"):
        _core.simulate(model, [], contact, s, st)
    bad = _wheels(scene, (0.0,))
    bad[0].mass = 0.0
    with pytest.raises(ValueError, match="wheel 0 mass must be > 0 kg"):
        _core.simulate(model, bad, contact, s, st)
