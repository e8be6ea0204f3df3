"""Wheel/rail contact (docs: Model § Contact): foot-of-normal search, normal force, analytic Jacobians.

``contact_eval`` returns the generalised force F on q = [X_A, Y_A, e_el(8)] (wheel centre and
the 8 coordinates of the rail element holding s*), K = -dF/dq and C = -dF/dqdot.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from test_ancf import fd_with_tolerance

from trackwheel import Scene, _core

RHO0 = 0.1  # wheel radius [m]
K_LIN = Scene.kato2005().contact_stiffness  # linearised Hertz, ~7.1e8 [N/m]
C_HERTZ = Scene.kato2005().hertz_constant  # [N/m^1.5]
X_WHEEL = 2.37  # inside element 9 of the 0.25 m mesh (xi = 0.48), away from element ends [m]


def params(law, stiffness, damping=0.0):
    cp = _core.ContactParams()
    cp.law = getattr(_core.ContactLaw, law)
    cp.stiffness = stiffness
    cp.damping = damping
    cp.radius = RHO0
    return cp


LAWS = {"linear": K_LIN, "hertz": C_HERTZ}


@pytest.fixture
def rail(make_rail):
    return make_rail(n_elements=20)


def bent_rail(model, seed=5):
    """The rail bent down by 1 mm (sine) with random nodal noise: s* in a curved, tilted,
    slightly stretched element."""
    rng = np.random.default_rng(seed)
    e = np.array(model.reference())
    s = np.arange(model.n_nodes) * model.element_length
    e[1::4] += -1e-3 * np.sin(math.pi * s / 5.0) + rng.normal(0, 2e-5, s.size)
    e[3::4] += -1e-3 * math.pi / 5.0 * np.cos(math.pi * s / 5.0) + rng.normal(0, 2e-4, s.size)
    e[0::4] += rng.normal(0, 2e-5, s.size)
    e[2::4] += rng.normal(0, 2e-4, s.size)
    return e


class ContactFunction:
    """F(q, qdot) with q = [X_A, Y_A, e_el] acting on a copy of the rail state ``e``."""

    def __init__(self, model, e, cp, q_dot=None):
        self.model, self.e, self.cp = model, e, cp
        self.q_dot = np.zeros(10) if q_dot is None else q_dot
        self.y_rail = model.positions(e, [X_WHEEL])[0, 1]
        self.el = None

    def at_penetration(self, delta):
        """q with the wheel centre above X_WHEEL so that it penetrates by about delta [m]."""
        ya = self.y_rail + RHO0 - delta
        self.el = self.eval_xy(X_WHEEL, ya, self.e)["element"]
        return np.concatenate([[X_WHEEL, ya], self.e[4 * self.el:4 * self.el + 8]])

    def eval_xy(self, xa, ya, e, q_dot=None):
        q_dot = self.q_dot if q_dot is None else q_dot
        return _core.contact_eval(self.model, e, xa, ya, X_WHEEL, self.cp, q_dot)

    def __call__(self, q, q_dot=None):
        e = self.e.copy()
        e[4 * self.el:4 * self.el + 8] = q[2:]
        d = self.eval_xy(q[0], q[1], e, q_dot)
        assert d["element"] == self.el  # the FD stencil stays in one element
        return d


def potential(law, stiffness, rho):
    """V(delta): linear k delta^2/2, Hertz 2/5 C_H delta^2.5 [J] (N = dV/d delta)."""
    delta = max(RHO0 - rho, 0.0)
    return 0.5 * stiffness * delta**2 if law == "linear" else 0.4 * stiffness * delta**2.5


# The FD step is H_REL = 1e-4 of the penetration delta: the force varies on the scale delta
# (Hertz N ~ delta^1.5 has F''' ~ F/delta^2), so the truncation error is ~(h/delta)^2 = 1e-8 at
# worst (measured 3e-10 for Hertz), round-off eps |F|/(h |K|) ~ eps delta/h ~ 2e-12. The
# tolerance of each check is estimated from the steps h and 2h (fd_with_tolerance in
# test_ancf.py) and must stay below TOL_CEILING, far under the smallest Jacobian term of
# interest (the contact-point motion term of the distance Hessian).
H_REL = 1e-4
DELTAS = [1e-4, 2e-5]
TOL_CEILING = 1e-7


@pytest.mark.parametrize("law", list(LAWS))
@pytest.mark.parametrize("delta", DELTAS)
@pytest.mark.parametrize("damping", [0.0, 3e4])
def test_contact_stiffness_matches_central_differences(rail, rel, law, delta, damping,
                                                      validation):
    """K = -dF/dq at rest (qdot = 0, so the damper adds no q-dependence)."""
    f = ContactFunction(rail, bent_rail(rail), params(law, LAWS[law], damping))
    q0 = f.at_penetration(delta)
    d = f(q0)
    assert d["active"] and d["N"] > 0
    K_fd, tol = fd_with_tolerance(lambda q: -f(q)["F"], q0, H_REL * delta, d["K"])
    assert tol < TOL_CEILING
    assert rel(K_fd, d["K"]) < tol
    if delta == DELTAS[0] and damping == 0.0:
        validation.record(
            f"contact.stiffness[{law}]", level="contact", kind="finite differences",
            quantity=f"{law} contact law on a bent rail, 0.1 mm penetration: contact stiffness "
                     "on wheel centre and rail element (moving contact point included)",
            reference="central differences of the contact force",
            measured=rel(K_fd, d["K"]), tolerance=tol)
    # conservative force: K is the Hessian of V(rho(q)), hence symmetric
    assert np.linalg.norm(d["K"] - d["K"].T) < 1e-12 * np.linalg.norm(d["K"])


@pytest.mark.parametrize("law", list(LAWS))
@pytest.mark.parametrize("delta", DELTAS)
def test_contact_force_is_minus_gradient_of_potential(rail, rel, law, delta, validation):
    f = ContactFunction(rail, bent_rail(rail, seed=9), params(law, LAWS[law]))
    q0 = f.at_penetration(delta)
    F = f(q0)["F"]
    dV, tol = fd_with_tolerance(lambda q: potential(law, LAWS[law], f(q)["rho"]), q0,
                                H_REL * delta, F)
    assert tol < TOL_CEILING
    assert rel(-dV, F) < tol
    if law == "hertz" and delta == DELTAS[0]:
        validation.record(
            "contact.hertz_force_is_potential_gradient", level="contact",
            kind="finite differences",
            quantity="Hertzian contact force on wheel centre and rail element, bent rail",
            reference="central differences of the potential 2/5 C_H δ^(5/2)",
            measured=rel(-dV, F), tolerance=tol)


@pytest.mark.parametrize("law", list(LAWS))
def test_contact_damping_matrix_matches_central_differences(rail, fd, rel, law):
    rng = np.random.default_rng(17)
    q_dot = rng.normal(0.0, 1e-2, 10)  # [m/s]: a closing/opening rate well below k delta / c
    f = ContactFunction(rail, bent_rail(rail), params(law, LAWS[law], damping=3e4), q_dot)
    q0 = f.at_penetration(1e-4)
    d = f(q0)
    assert d["active"]
    # F is affine in qdot while the contact is closed: the central difference is exact up to
    # round-off
    C_fd = -fd(lambda v: f(q0, v)["F"], q_dot, 1e-3)
    assert rel(C_fd, d["C"]) < 1e-9
    grad = d["grad_rho"]
    np.testing.assert_allclose(d["C"], 3e4 * np.outer(grad, grad), rtol=1e-14, atol=0)


@pytest.mark.parametrize("law", list(LAWS))
def test_contact_point_is_foot_of_normal(rail, law):
    e = bent_rail(rail)
    f = ContactFunction(rail, e, params(law, LAWS[law]))
    q0 = f.at_penetration(1e-4)
    d = f(q0)
    r = rail.positions(e, [d["s"]])[0]
    dvec = q0[:2] - r
    assert np.linalg.norm(dvec) == pytest.approx(d["rho"], rel=1e-14)
    np.testing.assert_allclose(d["normal"], dvec / d["rho"], atol=1e-14)
    assert abs(np.dot(d["normal"], d["tangent"])) < 1e-12  # (R_A - r) . r_s = 0
    assert d["y_contact"] == pytest.approx(r[1], rel=1e-14)
    assert d["phi"] == pytest.approx(math.atan2(d["tangent"][1], d["tangent"][0]), abs=1e-15)
    # the force law
    delta = RHO0 - d["rho"]
    expected = LAWS[law] * delta if law == "linear" else LAWS[law] * delta**1.5
    assert d["N"] == pytest.approx(expected, rel=1e-12)
    np.testing.assert_allclose(d["F"][:2], d["N"] * d["normal"], rtol=1e-14)


def test_straight_rail_contact_is_vertical(rail):
    e = np.array(rail.reference())
    cp = params("linear", K_LIN)
    d = _core.contact_eval(rail, e, 1.3, RHO0 - 1e-4, 1.0, cp, np.zeros(10))
    # the search stops when the Newton step is below 1e-13 L = 5e-13 m: s* and the normal's
    # tilt (ds / rho) are exact to that level
    assert d["s"] == pytest.approx(1.3, abs=1e-12)
    np.testing.assert_allclose(d["normal"], [0.0, 1.0], atol=1e-10)
    assert d["N"] == pytest.approx(K_LIN * 1e-4, rel=1e-9)
    # the rail element receives -N S_y(s*)^T: the y-position entries (F[3], F[7]) add up to
    # -N, and the y-slope entries make it act at s* (a point load, not a load plus a couple)
    assert d["F"][[3, 7]].sum() == pytest.approx(-d["N"], rel=1e-12)
    n, _, _ = _core.testing.hermite(d["s"] / 0.25 - d["element"], 0.25)
    np.testing.assert_allclose(d["F"][3::2], -d["N"] * np.asarray(n), rtol=1e-12, atol=1e-9)
    assert np.abs(d["F"][2::2]).max() < 1e-10 * d["N"]  # no x force from a vertical normal


@pytest.mark.parametrize("law", list(LAWS))
def test_no_force_without_penetration(rail, law):
    e = bent_rail(rail)
    f = ContactFunction(rail, e, params(law, LAWS[law], damping=3e4))
    q0 = f.at_penetration(-1e-5)  # a 10 um gap
    d = f(q0)
    assert not d["active"]
    assert d["N"] == 0.0
    assert np.all(d["F"] == 0.0) and np.all(d["K"] == 0.0) and np.all(d["C"] == 0.0)


def test_damper_cannot_pull(rail):
    """A fast opening rate makes k delta + c delta_dot negative: N is clipped to zero."""
    e = np.array(rail.reference())
    cp = params("linear", K_LIN, damping=1e5)
    opening = np.zeros(10)
    opening[1] = 10.0  # wheel centre moving up at 10 m/s: c delta_dot = -1e6 N > k delta
    d = _core.contact_eval(rail, e, 1.3, RHO0 - 1e-4, 1.3, cp, opening)
    assert d["N"] == 0.0 and not d["active"]
    closing = -opening
    d = _core.contact_eval(rail, e, 1.3, RHO0 - 1e-4, 1.3, cp, closing)
    assert d["N"] == pytest.approx(K_LIN * 1e-4 + 1e5 * 10.0, rel=1e-9)


@pytest.mark.parametrize("s_guess", [0.0, 1.0, 2.3, 2.5, 4.0, 5.0])
def test_contact_search_finds_the_same_point_from_any_start(rail, s_guess):
    """Newton on (R_A - r(s)) . r_s = 0 moves across elements: a gently bent rail has one foot
    of the normal under the wheel, found from anywhere along the rail."""
    e = bent_rail(rail)
    y = rail.positions(e, [X_WHEEL])[0, 1] + RHO0 - 1e-4
    cp = params("linear", K_LIN)
    ref = _core.contact_eval(rail, e, X_WHEEL, y, X_WHEEL, cp, np.zeros(10))
    d = _core.contact_eval(rail, e, X_WHEEL, y, s_guess, cp, np.zeros(10))
    assert d["s"] == pytest.approx(ref["s"], abs=1e-12)
    assert d["N"] == pytest.approx(ref["N"], rel=1e-9)
