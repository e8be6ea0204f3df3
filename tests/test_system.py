"""The system workspace (cpp/system.hpp): the generalized-alpha iteration matrix against
central finite differences of the residual, through the test-only binding ``_core.testing.ga_probe``.

The unknowns of a step are x = [e''_free, (Y'', theta'', lambda) per wheel]; the kernel
solves J dx = -r with J = dr/dx assembled analytically: the rail's M + gamma' h C_s +
beta' h^2 K_t, the contact stiffness (incl. the moving contact point), the rolling
constraint's border rows and columns (velocity level, scaled by 1/(gamma' h)) and the slide
row lambda - sigma mu N(q, qdot). ga_probe returns -r and J at any iterate, so column i of J
must equal -(R(x + h e_i) - R(x - h e_i)) / 2h with R = -r.

Step and tolerance: h = 1e3 m/s^2 on the accelerations moves the coordinates by
beta' h_t^2 x 1e3 ~ 3e-8 m (h_t = 1e-5 s), 1e-3 of the contact compression, so the O(h^2)
truncation is ~1e-7 of a column; h = 1 N on the multipliers, on which r is linear. Round-off
is eps |R| / h with |R| dominated by the axial forces of the rail, EA |e| ~ 1.4e9 N x 5 m,
i.e. ~2e-9 per unit of a column whose entries are ~1-10 kg. Measured: 1.3e-8 of a column's
largest entry (and 1e-5 with h = 1, where round-off dominates, falling as 1/h). Tolerance:
1e-6 of each column's largest entry. The scene has no contact damping, whose q-dependence the
matrix neglects on purpose. The out-of-round cases add an 8th-order polygon of 50 um at
theta = 0.3 rad: the radius change couples theta with the contact force (its moment
-N dDelta rho/dpsi and the force's dependence on theta). The locked cases hold the wheel by its
brake (Wheel.brake_torque, sliding): the theta row becomes the velocity row theta'_{n+1} / cv = 0.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel

V = tw.kmh(300)
DT = 1e-5


def central_difference_error(R, x0, J, h):
    """Per column, max |J - J_fd| / max |J| with J_fd the central differences of the residual:
    column i is -(R(x0 + h_i e_i) - R(x0 - h_i e_i)) / 2 h_i (R returns ga_probe's dict, whose
    "residual" is -r)."""
    cols = []
    for i in range(len(x0)):
        xp, xm = x0.copy(), x0.copy()
        xp[i] += h[i]
        xm[i] -= h[i]
        cols.append(-(R(xp)["residual"] - R(xm)["residual"]) / (2.0 * h[i]))
    return np.max(np.abs(J - np.stack(cols, axis=1)), axis=0) / np.max(np.abs(J), axis=0)


def _probe_case(law, slide, n_wheels, polygon=False, layered=False, irregularity=None,
                locked=False):
    scene = dc.replace(tw.Scene.kato2005(), irregularity=irregularity)
    if layered:  # damped pad-sleeper-ballast supports (the sleepers' z'' join the unknowns)
        scene = dc.replace(scene, supports=dc.replace(
            scene.supports, damping=2e4, sleeper_mass=150.0, ballast_stiffness=105e6,
            ballast_damping=5e4))
    if law == "hertz":
        scene = dc.replace(scene, contact=dc.replace(scene.contact, law="hertz"))
    if polygon:
        scene = dc.replace(scene, wheel=dc.replace(scene.wheel, defects=(tw.Polygon(8, 5e-5),)))
    model = _kernel.rail_model(scene, 20)
    contact = _kernel.contact_params(scene)
    d = _core.static_solve(model, _kernel.wheel_params(scene), contact, 1.3)
    e = np.asarray(d["e"])
    wheels, states = [], []
    for k in range(n_wheels):
        p = _kernel.wheel_params(scene)
        p.x_offset = 2.0 * k
        w = _core.WheelState()
        x = 1.3 + p.x_offset
        # wheel 0 at its static equilibrium; wheel 1 pressed 20 um into the rail (80 um with the
        # polygon, which takes 37 um off the radius at theta = 0.3)
        press = 8e-5 if polygon else 2e-5
        w.y = d["y_wheel"] if k == 0 else model.positions(e, [x])[0, 1] + 0.1 - press
        w.s = d["contact_s"] if k == 0 else x
        w.thetadot = V / scene.wheel.radius
        w.theta = 0.3 if polygon else 0.0
        w.state = _core.SlipState.slip if slide else _core.SlipState.stick
        w.sigma = -1.0
        if locked:  # held by a brake beyond adhesion, 3 mu P rho0
            p.brake_torque = 3.0 * 0.3 * scene.static_load * scene.wheel.radius
            w.locked, w.thetadot = True, 0.0
        wheels.append(p)
        states.append(w)
    st = _core.SimState()
    st.e, st.edot, st.wheels = e, np.zeros_like(e), states
    s = _core.SimSettings()
    s.speed, s.x_start, s.dt, s.t_end = V, 1.3, DT, DT
    return model, wheels, contact, s, st


@pytest.mark.parametrize("law, slide, n_wheels, polygon, layered, locked", [
    ("linear", False, 1, False, False, False), ("linear", True, 1, False, False, False),
    ("hertz", False, 2, False, False, False), ("hertz", True, 2, False, False, False),
    ("linear", False, 1, True, False, False), ("hertz", True, 2, True, False, False),
    ("linear", False, 1, False, True, False), ("hertz", True, 2, False, True, False),
    ("linear", True, 1, False, False, True), ("hertz", True, 2, True, False, True)])
def test_iteration_matrix_matches_central_differences(law, slide, n_wheels, polygon, layered,
                                                      locked, validation):
    model, wheels, contact, s, st = _probe_case(law, slide, n_wheels, polygon, layered,
                                                locked=locked)

    def R(x=None):
        return _core.testing.ga_probe(model, wheels, contact, s, st, DT, x)

    p0 = R()
    x0, J = p0["start"], p0["matrix"]
    nb = 3 * n_wheels
    ns = 9 if layered else 0  # the paper's nine supports
    assert J.shape == (len(x0), len(x0)) and len(x0) == model.n_free + nb + ns
    h = np.full(len(x0), 1e3)
    h[model.n_free + 2:model.n_free + nb:3] = 1.0  # the multipliers lambda [N]
    assert np.all(np.max(np.abs(J), axis=0) > 0.0)
    err = central_difference_error(R, x0, J, h)
    assert np.max(err) < 1e-6, (int(np.argmax(err)), float(np.max(err)))
    if (law, slide, n_wheels, polygon, layered, locked) == ("hertz", True, 2, False, True, False):
        validation.record(
            "dynamics.iteration_matrix", level="time integration", kind="finite differences",
            quantity="generalized-α iteration matrix: two sliding wheels, Hertz contact, "
                     "pad-sleeper-ballast supports",
            reference="central differences of the step's residual",
            measured=np.max(err), tolerance=1e-6, metric="of each column's max")
    # the border is really coupled: the rolling/slide rows and lambda columns are not empty
    for k in range(n_wheels):
        lam = model.n_free + 3 * k + 2
        assert np.count_nonzero(J[:model.n_free, lam]) >= 4
        assert np.count_nonzero(J[lam, :model.n_free]) >= 4
        th = model.n_free + 3 * k + 1
        if polygon:  # theta couples with the rail and Y through the radius change
            assert np.count_nonzero(J[:model.n_free, th]) >= 4
            assert J[model.n_free + 3 * k, th] != 0.0
        if locked:  # the theta row is the locked wheel's theta'_{n+1} / cv = 0 alone
            row = np.zeros(len(x0))
            row[th] = 1.0
            np.testing.assert_array_equal(J[th], row)


@pytest.mark.parametrize("law, slide, n_wheels", [("linear", False, 1), ("hertz", True, 2)])
def test_newton_on_the_probe_matrix_reaches_the_round_off_floor(law, slide, n_wheels):
    """Newton with the probe's matrix takes the residual from ~1e3-1e4 N to its round-off
    floor, eps EA |e| ~ 2e-6 N (the rail's axial forces), within five iterations: the matrix
    is the derivative of the very residual the kernel's Newton solves (measured: 3e-6 N and
    1e-7 N; bound 1e-4 N, far below the 1e-6 (F + M g) ~ 0.05 N the kernel accepts)."""
    model, wheels, contact, s, st = _probe_case(law, slide, n_wheels)
    p0 = _core.testing.ga_probe(model, wheels, contact, s, st, DT)
    x = p0["start"].copy()
    assert np.linalg.norm(p0["residual"]) > 1e3
    for _ in range(5):
        p = _core.testing.ga_probe(model, wheels, contact, s, st, DT, x)
        x = x + np.linalg.solve(p["matrix"], p["residual"])
    r = _core.testing.ga_probe(model, wheels, contact, s, st, DT, x)["residual"]
    assert np.linalg.norm(r) < 1e-4


@pytest.mark.parametrize("n_wheels, polygon, layered", [(1, True, False), (2, False, True),
                                                       (2, True, True)])
def test_split_matrix_solve_equals_the_dense_solve(n_wheels, polygon, layered):
    """Where the contact block is new at every Newton iteration (a rail profile or an
    out-of-round wheel; forced here by SimSettings.fresh_contact = 1) the kernel solves in split
    form: the rail band factorised alone, each wheel's contact block through a small dense
    system (exact, banded.hpp's SplitBorderedSolver). Its Newton correction must equal the dense
    solve of the assembled matrix J dx = -r to round-off, as the whole-matrix factorisation's
    does (fresh_contact = 0): 1e-10 of max |dx|, the bound of the condensed sleepers' test
    below (cond(J) ~ 7e4)."""
    model, wheels, contact, s, st = _probe_case("hertz", True, n_wheels, polygon, layered)
    for fresh in (1, 0):
        s.fresh_contact = fresh
        p = _core.testing.ga_probe(model, wheels, contact, s, st, DT)
        dense = np.linalg.solve(p["matrix"], p["residual"])
        assert np.max(np.abs(dense)) > 0.0
        np.testing.assert_allclose(p["solution"], dense, rtol=0,
                                   atol=1e-10 * np.max(np.abs(dense)))


@pytest.mark.parametrize("law, slide, n_wheels", [("linear", False, 1), ("hertz", True, 2)])
def test_condensed_sleepers_solve_equals_the_dense_solve(law, slide, n_wheels):
    """The kernel condenses the sleepers' diagonal block into the rail band (a Schur
    complement, exact) and back-substitutes their z''. Its Newton correction must equal the
    dense solve of the uncondensed matrix J dx = -r to round-off: cond(J) = 7e4 here, so
    1e-10 of max |dx| (measured 2e-15)."""
    model, wheels, contact, s, st = _probe_case(law, slide, n_wheels, layered=True)
    p = _core.testing.ga_probe(model, wheels, contact, s, st, DT)
    dense = np.linalg.solve(p["matrix"], p["residual"])
    assert np.max(np.abs(dense)) > 0.0
    np.testing.assert_allclose(p["solution"], dense, rtol=0,
                               atol=1e-10 * np.max(np.abs(dense)))
    # the sleepers are coupled: their columns reach the rail rows
    nf, nb = model.n_free, 3 * n_wheels
    assert np.count_nonzero(p["matrix"][:nf, nf + nb:]) >= 9
