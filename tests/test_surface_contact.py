"""Contact on a rail with a running-surface profile r(X) (docs: Model § Irregularities).

The wheel touches the lifted surface p(s) = r(s) + R(x(s)) e_y. These tests check the kernel's
profile evaluation against scipy, the contact point as the foot of the normal on the lifted
surface, and every analytic derivative of the contact and the rolling constraint against
central differences with the profile's own curvature terms switched on.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline
from test_contact import K_LIN, RHO0, X_WHEEL, ContactFunction, bent_rail, params

import trackwheel as tw
from trackwheel import _core

AMP, WAVELENGTH = 3e-4, 0.1  # a 0.3 mm, 0.1 m corrugation: R'' up to 1.2 1/m [m, m]
DX = 1e-3  # profile grid [m]: WAVELENGTH / 100


def corrugation_profile(length=5.0):
    x = np.arange(0.0, length + DX / 2, DX)
    spline = CubicSpline(x, AMP * np.sin(2 * math.pi * x / WAVELENGTH))
    return spline, _core.Profile(0.0, DX, spline.c)


@pytest.fixture
def lifted(make_rail):
    """The 20-element test rail carrying the corrugation, and the scipy spline behind it."""
    plain = make_rail(n_elements=20)
    spline, profile = corrugation_profile()
    p = _core.RailParams()
    for name in ("length", "EA", "EI", "rhoA", "n_elements", "exact_curvature", "n_gauss",
                 "gravity", "pin_far_end"):
        setattr(p, name, getattr(plain_params(plain), name))
    return _core.RailModel(p, _core.SupportParams(), profile), spline


def plain_params(model):
    """RailParams of the conftest rail (EA, EI, rhoA of the paper's section, no supports)."""
    from conftest import EA, EI, RHO_A

    p = _core.RailParams()
    p.length, p.EA, p.EI, p.rhoA, p.n_elements, p.gravity = 5.0, EA, EI, RHO_A, 20, 0.0
    p.n_gauss = 5
    return p


class LiftedContact(ContactFunction):
    """ContactFunction with the wheel placed against the lifted surface, not the centre line."""

    def at_penetration(self, delta):
        # wheel centre 1 mm above touching (a centre far above the surface could see a
        # distance with several minima on a corrugation)
        y_centre_line = self.model.positions(self.e, [X_WHEEL])[0, 1]
        above = self.eval_xy(X_WHEEL, y_centre_line + RHO0 + 1e-3, self.e)
        self.y_rail = above["surface"][1]
        return super().at_penetration(delta)


def test_profile_matches_scipy_spline_and_continues_flat():
    spline, profile = corrugation_profile()
    xs = np.random.default_rng(3).uniform(0.0, 5.0, 200)
    got = np.array([profile(x) for x in xs])
    # Horner evaluation of the same coefficients: equal to scipy's up to a few ulp of the
    # largest term (c0 ~ 3e-4 m; derivatives ~1e-2 and 0.3 1/m)
    np.testing.assert_allclose(got[:, 0], spline(xs), rtol=0, atol=1e-18)
    np.testing.assert_allclose(got[:, 1], spline(xs, 1), rtol=0, atol=1e-15)
    np.testing.assert_allclose(got[:, 2], spline(xs, 2), rtol=0, atol=1e-12)
    # beyond the grid: the end value (the last cubic at u = dx, which scipy evaluates at the
    # breakpoint instead: equal to round-off, 1e-12 of the amplitude) and flat
    r_end = float(spline(spline.x[-1]))
    assert profile(7.0) == pytest.approx((r_end, 0.0, 0.0), abs=1e-12 * AMP)
    assert profile(-1.0) == (float(spline(0.0)), 0.0, 0.0)
    assert _core.Profile()(1.0) == (0.0, 0.0, 0.0)


def test_profile_rejects_bad_grid():
    with pytest.raises(ValueError, match="dx"):
        _core.Profile(0.0, 0.0, np.zeros((4, 3)))
    with pytest.raises(ValueError, match="finite"):
        _core.Profile(0.0, 1e-3, np.full((4, 3), np.nan))


def test_contact_is_foot_of_normal_on_lifted_surface(lifted):
    model, spline = lifted
    e = bent_rail(model)
    f = LiftedContact(model, e, params("linear", K_LIN))
    q0 = f.at_penetration(1e-4)
    d = f(q0)
    s = d["s"]
    r = model.positions(e, [s])[0]
    surface = np.array([r[0], r[1] + spline(r[0])])  # fixed to the track: R at x(s), not at s
    np.testing.assert_allclose(d["surface"], surface, rtol=0, atol=1e-15)
    # surface tangent by differences along s: (R_A - p) . p_s = 0 at s*
    h = 1e-6
    rp, rm = model.positions(e, [s + h])[0], model.positions(e, [s - h])[0]
    ps = (np.array([rp[0], rp[1] + spline(rp[0])]) - np.array([rm[0], rm[1] + spline(rm[0])]))
    ps /= 2 * h
    dvec = q0[:2] - surface
    assert abs(np.dot(dvec, ps)) < 1e-9 * np.linalg.norm(dvec) * np.linalg.norm(ps)
    assert d["rho"] == pytest.approx(np.linalg.norm(dvec), rel=1e-14)
    assert d["N"] == pytest.approx(K_LIN * (RHO0 - d["rho"]), rel=1e-12)


def fd_tolerance(f, q0, h, fd, rel):
    """FD Jacobian at step h and a tolerance from its own error estimate: the central
    difference's truncation error is c h^2, so |J(2h) - J(h)| ~ 3 c h^2 estimates it; the
    round-off floor eps |f| / h relative to |J| h... is added; the tolerance is 10x their sum."""
    J1, J2 = fd(f, q0, h), fd(f, q0, 2 * h)
    truncation = rel(J2, J1) / 3
    f0 = np.asarray(f(q0))
    roundoff = np.finfo(float).eps * np.linalg.norm(f0) / (h * np.linalg.norm(J1))
    return J1, 10 * (truncation + roundoff)


@pytest.mark.parametrize("law", ["linear", "hertz"])
def test_contact_stiffness_on_lifted_surface_matches_central_differences(lifted, fd, rel, law):
    """K = -dF/dq including the profile's curvature terms (the surface depends on e through
    R(x(e))); h = 1e-3 delta as in tests/test_contact.py, tolerance from the FD's own error
    estimate (about 1e-9 linear, 1e-6 Hertz: the profile's curvature term is ~1e-5 of K)."""
    model, _ = lifted
    from test_contact import LAWS

    f = LiftedContact(model, bent_rail(model), params(law, LAWS[law], 3e4))
    delta = 1e-4
    q0 = f.at_penetration(delta)
    d = f(q0)
    assert d["active"]
    K_fd, tol = fd_tolerance(lambda q: -f(q)["F"], q0, 1e-3 * delta, fd, rel)
    assert rel(K_fd, d["K"]) < tol
    assert np.linalg.norm(d["K"] - d["K"].T) < 1e-12 * np.linalg.norm(d["K"])


def test_rolling_jacobians_on_lifted_surface_match_central_differences(lifted, fd, rel):
    """dg/dq, b, db/dq and ds*/dq with the profile (cf. tests/test_dynamics.py without it),
    each within the FD's own error estimate."""
    model, _ = lifted
    rng = np.random.default_rng(11)
    e = bent_rail(model, seed=2)
    xa = X_WHEEL
    y_above = model.positions(e, [xa])[0, 1] + RHO0 + 1e-3
    base0 = _core.contact_eval(model, e, xa, y_above, xa, params("linear", K_LIN), np.zeros(10))
    ya = base0["surface"][1] + RHO0 - 1e-4
    qdot = np.concatenate([[27.0, 0.05], 0.02 * rng.standard_normal(8)])
    thetadot = 270.0
    base = _core.testing.rolling_eval(model, e, xa, ya, xa, qdot, thetadot)
    d0 = 4 * int(np.floor(base["s"] / model.element_length))

    def at(q, qd=qdot):
        ee = e.copy()
        ee[d0:d0 + 8] = q[2:]
        return _core.testing.rolling_eval(model, ee, q[0], q[1], base["s"], qd, thetadot)

    q0 = np.concatenate([[xa, ya], e[d0:d0 + 8]])
    for name, key in (("dg_dq", "g"), ("db_dq", "b"), ("ds_dq", "s")):
        J_fd, tol = fd_tolerance(lambda q, k=key: np.atleast_1d(at(q)[k]), q0, 1e-7, fd, rel)
        assert rel(np.atleast_2d(base[name]), J_fd) < tol, name
    # g is linear in the velocities: dg/dqdot = b exactly (theta' coefficient b[10] = -rho)
    J = fd(lambda v: [at(q0, v)["g"]], qdot, 1e-3)[0]
    np.testing.assert_allclose(np.asarray(base["b"])[:10], J, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("law, slide", [("linear", False), ("hertz", True)])
def test_iteration_matrix_with_a_rail_profile_matches_central_differences(law, slide):
    """The generalized-alpha iteration matrix on an irregular rail (a 0.5 m sine of 50 um:
    curvature 8e-3 1/m, slope 6e-4) against central differences of the residual, as
    tests/test_system.py does on the smooth rail (same steps, same 1e-6 tolerance; measured
    6e-9 and 1e-8): the profile's slope and curvature enter the contact geometry's Jacobian."""
    from test_system import DT, _probe_case, central_difference_error

    model, wheels, contact, s, st = _probe_case(law, slide, 1,
                                                irregularity=tw.Irregularity.sine(0.5, 5e-5))
    smooth = _probe_case(law, slide, 1)
    assert not np.allclose(_core.testing.ga_probe(*smooth, DT)["residual"],
                           _core.testing.ga_probe(model, wheels, contact, s, st, DT)["residual"])

    def R(x=None):
        return _core.testing.ga_probe(model, wheels, contact, s, st, DT, x)

    p0 = R()
    x0, J = p0["start"], p0["matrix"]
    h = np.full(len(x0), 1e3)
    h[model.n_free + 2] = 1.0  # the multiplier lambda [N]
    err = central_difference_error(R, x0, J, h)
    assert np.max(err) < 1e-6, (int(np.argmax(err)), float(np.max(err)))
