"""The planar ANCF cable element (docs: Model § Rail): energies, forces, Jacobians, mass, quadrature.

Element vector e = [x1, y1, x1_s, y1_s, x2, y2, x2_s, y2_s]; positions in m, slopes in m/m.
Random states are the straight element of length le = 0.25 m (the paper's mesh) perturbed by
1e-3 .. 1e-2 of le in the positions and of 1 in the slopes (strains and rotations of the same
order, far beyond a rail's service deformation but still "moderate"), plus one stretched,
rotated and translated element.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from trackwheel import Rail, _core

EA = Rail().axial_stiffness  # [N]
EI = Rail().bending_stiffness  # [N m^2]
RHO_A = Rail().mass_per_length  # [kg/m]

L_EL = 0.25  # element length of the paper's 20-element mesh [m]
X_DOFS = [0, 2, 4, 6]  # (x1, x1_s, x2, x2_s)
Y_DOFS = [1, 3, 5, 7]  # (y1, y1_s, y2, y2_s)

#: FD step [m or m/m]. Central differences have truncation error ~ (h / l_nl)^2 with l_nl the
#: scale on which the force changes (>= 1e-3 for these states) and round-off ~ eps |Q| / (h |K|);
#: with h = 1e-6 both are below 1e-9 relative for K (measured: <= 1e-10).
H_FD = 1e-6
#: FD step for Q = dU/de: the energy's third derivatives are larger relative to Q than the
#: force's are to K (truncation 1e-8 of Q at h = 1e-6), so a smaller step; round-off stays below
#: 1e-10 of Q.
H_FD_ENERGY = 1e-7
#: Ceiling for the estimated FD tolerances below [-]: the smallest physical Jacobian term a check
#: must see is the exact curvature's d2g term, 2e-6 of K (total, state 2); the Jacobian
#: tolerance must stay below 1e-8 (estimates: <= 1.2e-9), the gradient one below 1e-7
#: (estimates: <= 9e-9), so that no term of 1e-7 of Q or 1e-8 of K can be dropped unseen.
TOL_CEILING = 1e-8
TOL_CEILING_ENERGY = 1e-7
#: Safety factor of the FD tolerance over its estimate: the estimated truncation error is the
#: leading term only, and round-off is a bound for random rounding (measured errors are 0.3-1.7
#: times the estimate).
FD_SAFETY = 10.0


def fd_with_tolerance(f, x, h, exact):
    """Central-difference Jacobian of ``f`` at ``x`` with step ``h`` and a tolerance on
    ||J_fd - exact|| / ||exact|| estimated from the FD error itself.

    Truncation: J_h = J + c h^2 + O(h^4), so (J_2h - J_h) / 3 estimates the error c h^2 of J_h
    (Richardson). Round-off: each difference quotient carries ~eps |f(x)| / h, sqrt(n) of them
    per column norm. Returns (J_h, FD_SAFETY x (truncation + round-off) / ||exact||); dropping
    a Jacobian term fails by the ratio of its size to this tolerance.
    """
    from conftest import central_jacobian

    j_h = central_jacobian(f, x, h)
    j_2h = central_jacobian(f, x, 2.0 * np.asarray(h))
    f0 = np.asarray(f(np.asarray(x, dtype=float)), dtype=float)
    truncation = np.linalg.norm(j_2h - j_h) / 3.0
    roundoff = np.finfo(float).eps * np.linalg.norm(f0) * math.sqrt(j_h.size) / np.min(h)
    return j_h, FD_SAFETY * (truncation + roundoff) / np.linalg.norm(exact)


def reference_element(le=L_EL):
    return np.array([0.0, 0.0, 1.0, 0.0, le, 0.0, 1.0, 0.0])


def rigid(e, angle, shift=(0.0, 0.0), stretch=1.0):
    """Rotate the element's positions and slopes by ``angle`` [rad], scale them by ``stretch``
    and translate the positions by ``shift`` [m]."""
    R = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    nodes = (R @ np.asarray(e, dtype=float).reshape(4, 2).T).T * stretch
    nodes[0] += shift
    nodes[2] += shift
    return nodes.ravel()


def block_rotation(angle):
    """8x8 block-diagonal rotation acting on every 2-vector of the element."""
    R = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    return np.kron(np.eye(4), R)


def random_states(seed=20050101):
    rng = np.random.default_rng(seed)
    scale = np.array([L_EL, L_EL, 1.0, 1.0, L_EL, L_EL, 1.0, 1.0])
    states = []
    for _ in range(3):
        amp = 10.0 ** rng.uniform(-3.0, -2.0)
        states.append(reference_element() + amp * scale * rng.uniform(-1.0, 1.0, 8))
    bent = reference_element() + 5e-3 * scale * rng.uniform(-1.0, 1.0, 8)
    states.append(rigid(bent, angle=0.6, shift=(1.3, -0.4), stretch=1.02))
    return states


STATES = random_states()
PARTS = {
    "axial": (_core.testing.cable_axial, True),
    "bending_exact": (_core.testing.cable_bending, True),
    "bending_simplified": (_core.testing.cable_bending, False),
    "total_exact": (_core.testing.cable_elastic, True),
    "total_simplified": (_core.testing.cable_elastic, False),
}


@pytest.mark.parametrize("part", list(PARTS))
@pytest.mark.parametrize("i_state", range(len(STATES)))
def test_elastic_force_is_gradient_of_energy(section, fd, rel, part, i_state, validation):
    fun, exact = PARTS[part]
    c = section(exact=exact)
    e = STATES[i_state]
    Q, _, _ = fun(c, e)
    Q_fd, tol = fd_with_tolerance(lambda x: fun(c, x)[2], e, H_FD_ENERGY, Q)
    assert tol < TOL_CEILING_ENERGY
    assert rel(Q_fd, Q) < tol
    if part == "total_exact" and i_state == 3:
        validation.record(
            "element.cable_force_is_energy_gradient", level="element", kind="finite differences",
            quantity="ANCF cable element, exact curvature: elastic force Q of a bent, stretched "
                     "and rotated element",
            reference="central differences of the strain energy U (Q = dU/de)",
            measured=rel(Q_fd, Q), tolerance=tol, metric="relative")


@pytest.mark.parametrize("part", list(PARTS))
@pytest.mark.parametrize("i_state", range(len(STATES)))
def test_elastic_jacobian_matches_central_differences(section, fd, rel, part, i_state,
                                                      validation):
    fun, exact = PARTS[part]
    c = section(exact=exact)
    e = STATES[i_state]
    _, K, _ = fun(c, e)
    K_fd, tol = fd_with_tolerance(lambda x: fun(c, x)[0], e, H_FD, K)
    assert tol < TOL_CEILING
    assert rel(K_fd, K) < tol
    if part == "total_exact" and i_state == 3:
        validation.record(
            "element.cable_tangent", level="element", kind="finite differences",
            quantity="ANCF cable element, exact curvature: tangent stiffness K of a bent, "
                     "stretched and rotated element",
            reference="central differences of the elastic force (K = dQ/de)",
            measured=rel(K_fd, K), tolerance=tol, metric="relative")
    # K is the Hessian of the strain energy: symmetric to round-off
    assert np.linalg.norm(K - K.T) < 1e-12 * np.linalg.norm(K)


def deflected_element(section):
    """(|Q|, U) of the element with one end deflected by 1e-4 m (a rail deflection under a
    wheel): the force and energy scale that round-off is measured against."""
    e = reference_element()
    e[5] -= 1e-4
    Q, _, U = _core.testing.cable_elastic(section, e)
    return np.linalg.norm(Q), U


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize("angle, shift", [(0.0, (3.0, -1.0)), (0.7, (0.0, 0.0)),
                                          (-2.1, (1.7, 0.4)), (math.pi, (5.0, 0.0))])
def test_rigid_motion_gives_zero_elastic_force(section, exact, angle, shift):
    c = section(exact=exact)
    e = rigid(reference_element(), angle, shift)
    Q, _, U = _core.testing.cable_elastic(c, e)
    # round-off: |r_s| = 1 to ~1e-15, so the strain (and curvature) are ~1e-15 while the
    # comparison state has a rotation of 4e-4 rad: 1e-9 leaves a wide margin
    q_scale, u_scale = deflected_element(c)
    assert np.linalg.norm(Q) < 1e-9 * q_scale
    assert abs(U) < 1e-12 * u_scale


@pytest.mark.parametrize("exact", [True, False])
def test_elastic_force_is_objective(section, rel, exact):
    """Q(R e + t) = R Q(e), K(R e + t) = R K(e) R^T for a deformed element: the energy depends
    only on stretch and (for the exact curvature) on the true curvature."""
    c = section(exact=exact)
    e = STATES[0]
    Q0, K0, U0 = _core.testing.cable_elastic(c, e)
    angle = 0.9
    Q1, K1, U1 = _core.testing.cable_elastic(c, rigid(e, angle, shift=(2.0, -0.5)))
    T = block_rotation(angle)
    assert rel(Q1, T @ Q0) < 1e-10
    assert rel(K1, T @ K0 @ T.T) < 1e-10
    assert U1 == pytest.approx(U0, rel=1e-10)


def hermite_beam_stiffness(EI_, le):
    """Euler-Bernoulli beam element on (w1, w1', w2, w2') [N/m, N, N m]."""
    return EI_ / le**3 * np.array([[12, 6 * le, -12, 6 * le],
                                  [6 * le, 4 * le**2, -6 * le, 2 * le**2],
                                  [-12, -6 * le, 12, -6 * le],
                                  [6 * le, 2 * le**2, -6 * le, 4 * le**2]])


def hermite_bar_stiffness(EA_, le):
    """EA int N_i' N_j' ds for the cubic Hermite functions on (u1, u1', u2, u2')."""
    return EA_ / (30.0 * le) * np.array([[36, 3 * le, -36, 3 * le],
                                        [3 * le, 4 * le**2, -3 * le, -le**2],
                                        [-36, -3 * le, 36, -3 * le],
                                        [3 * le, -le**2, -3 * le, 4 * le**2]])


def hermite_consistent_mass(m, le):
    """Consistent mass of the cubic Hermite element on (w1, w1', w2, w2') [kg, kg m, kg m^2]."""
    return m * le / 420.0 * np.array([[156, 22 * le, 54, -13 * le],
                                     [22 * le, 4 * le**2, 13 * le, -3 * le**2],
                                     [54, 13 * le, 156, -22 * le],
                                     [-13 * le, -3 * le**2, -22 * le, 4 * le**2]])


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize("le", [0.25, 0.1, 1.3])
def test_linearised_element_is_euler_bernoulli_beam_plus_bar(section, exact, le, validation):
    c = section(length=le, exact=exact)
    Q, K, _ = _core.testing.cable_elastic(c, reference_element(le))
    scale = np.abs(K).max()
    assert np.abs(Q).max() < 1e-12 * scale * le  # the straight rail is unstressed
    # bending in y: exactly the Hermite beam (the integrand is a polynomial the 5-point rule
    # integrates exactly, so only round-off separates them)
    np.testing.assert_allclose(K[np.ix_(Y_DOFS, Y_DOFS)], hermite_beam_stiffness(EI, le),
                               rtol=0, atol=1e-12 * scale)
    # stretching in x: the cubic Hermite bar
    np.testing.assert_allclose(K[np.ix_(X_DOFS, X_DOFS)], hermite_bar_stiffness(EA, le),
                               rtol=0, atol=1e-12 * scale)
    if exact and le == 0.25:
        gap = max(np.abs(K[np.ix_(Y_DOFS, Y_DOFS)] - hermite_beam_stiffness(EI, le)).max(),
                  np.abs(K[np.ix_(X_DOFS, X_DOFS)] - hermite_bar_stiffness(EA, le)).max())
        validation.record(
            "element.cable_linearised_is_beam_and_bar", level="element", kind="closed form",
            quantity="ANCF cable element linearised at the straight rail (0.25 m): stiffness",
            reference="Euler-Bernoulli Hermite beam EI/l³ [12 6l ...] in y and the cubic bar "
                      "EA/(30 l) [36 3l ...] in x",
            measured=gap / scale, tolerance=1e-12, metric="of max |K|")
    # no x-y coupling about the straight configuration
    assert np.abs(K[np.ix_(X_DOFS, Y_DOFS)]).max() <= 1e-14 * scale


@pytest.mark.parametrize("le", [0.25, 0.1, 1.3])
def test_mass_matrix_is_consistent_hermite_mass(section, le, validation):
    M = _core.testing.cable_mass(section(length=le))
    Mh = hermite_consistent_mass(RHO_A, le)
    np.testing.assert_allclose(M[np.ix_(Y_DOFS, Y_DOFS)], Mh, rtol=0, atol=1e-13 * Mh.max())
    if le == 0.25:
        validation.record(
            "element.cable_mass", level="element", kind="closed form",
            quantity="ANCF cable element (0.25 m): mass matrix",
            reference="consistent Hermite mass ρA l/420 [156 22l 54 -13l ...]",
            measured=np.abs(M[np.ix_(Y_DOFS, Y_DOFS)] - Mh).max() / Mh.max(),
            tolerance=1e-13, metric="of max |M|")
    np.testing.assert_allclose(M[np.ix_(X_DOFS, X_DOFS)], Mh, rtol=0, atol=1e-13 * Mh.max())
    assert np.abs(M[np.ix_(X_DOFS, Y_DOFS)]).max() == 0.0
    # a rigid translation carries the element mass rho A le
    t = np.array([1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0])
    assert t @ M @ t == pytest.approx(RHO_A * le, rel=1e-14)


def test_hermite_functions_interpolate_nodes_and_differentiate(fd):
    le = 0.37
    n0, ns0, _ = _core.testing.hermite(0.0, le)
    n1, ns1, _ = _core.testing.hermite(1.0, le)
    np.testing.assert_allclose(n0, [1, 0, 0, 0], atol=1e-15)
    np.testing.assert_allclose(ns0, [0, 1, 0, 0], atol=1e-14)
    np.testing.assert_allclose(n1, [0, 0, 1, 0], atol=1e-15)
    np.testing.assert_allclose(ns1, [0, 0, 0, 1], atol=1e-14)
    for xi in (0.13, 0.5, 0.91):
        n, ns, nss = _core.testing.hermite(xi, le)
        assert n[0] + n[2] == pytest.approx(1.0, abs=1e-15)  # rigid translation
        # derivatives are with respect to s = xi le; the functions are cubics, so the central
        # difference error is h^2/6 n''' <= ~1e-11 for h = 1e-6 le
        h = 1e-6
        np.testing.assert_allclose(
            fd(lambda x: _core.testing.hermite(x[0], le)[0], [xi], h)[:, 0] / le, ns, rtol=0, atol=1e-8)
        np.testing.assert_allclose(
            fd(lambda x: _core.testing.hermite(x[0], le)[1], [xi], h)[:, 0] / le, nss, rtol=0, atol=1e-7)


@pytest.mark.parametrize("n", range(1, 11))
def test_gauss_points_integrate_degree_2n_minus_1_exactly(n):
    xi, w = _core.testing.gauss_points(n)
    assert np.all((xi > 0) & (xi < 1))
    for k in range(2 * n):
        assert w @ xi**k == pytest.approx(1.0 / (k + 1), rel=1e-13, abs=1e-15)
    if n <= 4:  # degree 2n is not integrated exactly: the rule is no better than claimed
        assert abs(w @ xi ** (2 * n) - 1.0 / (2 * n + 1)) > 1e-6


@pytest.mark.parametrize("n", [0, 11])
def test_gauss_points_outside_table_raise(n):
    with pytest.raises(ValueError):
        _core.testing.gauss_points(n)


@pytest.mark.parametrize("i_state", range(len(STATES)))
def test_more_gauss_points_do_not_change_the_forces(section, rel, i_state):
    e = STATES[i_state]
    # Green strain: eps is quartic in xi, eps^2 of degree 8 <= 2*5 - 1: 5 points are exact.
    # Simplified curvature: r_s x r_ss is cubic, kappa^2 of degree 6: exact too.
    for fun, exact in ((_core.testing.cable_axial, True), (_core.testing.cable_bending, False)):
        Q5, K5, U5 = fun(section(exact=exact, n_gauss=5), e)
        Q7, K7, U7 = fun(section(exact=exact, n_gauss=7), e)
        assert rel(Q7, Q5) < 1e-12 and rel(K7, K5) < 1e-12
        assert U7 == pytest.approx(U5, rel=1e-12)
    # exact curvature divides by |r_s|^3 (not a polynomial); for moderate stretch the
    # quadrature error is tiny
    Q5, K5, U5 = _core.testing.cable_elastic(section(n_gauss=5), e)
    Q7, K7, U7 = _core.testing.cable_elastic(section(n_gauss=7), e)
    assert rel(Q7, Q5) < 1e-6 and rel(K7, K5) < 1e-6
