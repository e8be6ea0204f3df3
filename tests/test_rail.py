"""The assembled rail (docs: Model § Scene, § Rail): mass, gravity, boundary conditions, supports, tangent."""

from __future__ import annotations

import math

import numpy as np
import pytest
from trackwheel import Rail

RHO_A = Rail().mass_per_length  # [kg/m]
G = 9.8  # [m/s^2]

#: supports on nodes (1.0, 2.5) and between nodes (0.6, 1.3, 3.77) of the 0.25 m mesh
SUPPORTS = (0.6, 1.0, 1.3, 2.5, 3.77)
KS = 140e6  # [N/m]


def deformed_rail(model, seed=7, amplitude=1e-3):
    """A smooth bend of ``amplitude`` [m] plus random nodal noise on every coordinate."""
    rng = np.random.default_rng(seed)
    e = np.array(model.reference())
    L = model.element_length * (model.n_nodes - 1)
    s = np.arange(model.n_nodes) * model.element_length
    e[1::4] += -amplitude * np.sin(math.pi * s / L) + rng.normal(0, 0.05 * amplitude, s.size)
    e[3::4] += (-amplitude * math.pi / L * np.cos(math.pi * s / L)
                + rng.normal(0, 0.5 * amplitude, s.size))
    e[0::4] += rng.normal(0, 0.05 * amplitude, s.size)
    e[2::4] += rng.normal(0, 0.5 * amplitude, s.size)
    return e


@pytest.mark.parametrize("n_elements", [1, 7, 20, 40])
def test_mass_matrix_sums_to_rail_mass(make_rail, n_elements):
    L = 5.0
    model = make_rail(length=L, n_elements=n_elements)
    M = np.array(model.mass_dense())
    n = model.n_dof
    x_pos = np.arange(0, n, 4)  # x of every node
    y_pos = np.arange(1, n, 4)
    assert M[np.ix_(x_pos, x_pos)].sum() == pytest.approx(RHO_A * L, rel=1e-13)
    assert M[np.ix_(y_pos, y_pos)].sum() == pytest.approx(RHO_A * L, rel=1e-13)
    assert model.total_mass == pytest.approx(RHO_A * L, rel=1e-15)
    np.testing.assert_allclose(M, M.T, rtol=0, atol=0)
    assert np.all(np.linalg.eigvalsh(M) > 0)  # positive definite


def test_band_mass_is_the_free_block_of_the_full_mass(make_rail):
    model = make_rail(n_elements=20, supports=SUPPORTS, stiffness=KS)
    free = np.array(model.free_to_full)
    M = np.array(model.mass_dense())
    np.testing.assert_array_equal(np.array(model.mass_band_dense()), M[np.ix_(free, free)])


@pytest.mark.parametrize("pin", [False, True], ids=["roller", "pinned"])
def test_boundary_conditions_fix_the_end_coordinates(make_rail, pin):
    model = make_rail(n_elements=20, pin_far_end=pin)
    n = model.n_dof
    expected_fixed = {0, 1, n - 3} | ({n - 4} if pin else set())  # x0, y0, yL (, xL)
    assert set(range(n)) - set(model.free_to_full) == expected_fixed
    assert model.n_free == n - len(expected_fixed)


def test_reference_is_the_straight_rail(make_rail):
    model = make_rail(length=5.0, n_elements=20)
    e = np.array(model.reference())
    s = np.linspace(0.0, 5.0, 41)
    np.testing.assert_allclose(model.positions(e, s), np.column_stack([s, 0 * s]), atol=1e-15)


def test_consistent_gravity_load_is_mass_times_gravity(make_rail):
    """Q_g = -int rhoA g S_y^T ds = M a with a the rigid field (0, -g): the consistent load."""
    model = make_rail(n_elements=20, gravity=G)
    M = np.array(model.mass_dense())
    a = np.zeros(model.n_dof)
    a[1::4] = -G
    Qg = np.array(model.gravity_force())
    np.testing.assert_allclose(Qg, M @ a, rtol=0, atol=1e-12 * np.abs(Qg).max())
    assert Qg[1::4].sum() == pytest.approx(-RHO_A * G * 5.0, rel=1e-13)  # rail weight
    assert np.all(Qg[0::2] == 0.0)  # nothing along x


@pytest.mark.parametrize("exact", [True, False])
def test_assembled_tangent_matches_central_differences(make_rail, fd, rel, exact, validation):
    model = make_rail(n_elements=20, supports=SUPPORTS, stiffness=KS, exact=exact)
    e = deformed_rail(model)
    K = np.array(model.tangent_dense(e))
    # h = 1e-6 on O(1) coordinates: central-difference error ~1e-9 relative (test_ancf.py)
    K_fd = fd(lambda x: model.internal_force(x)[0], e, 1e-6)
    assert rel(K_fd, K) < 1e-6
    if exact:
        validation.record(
            "rail.tangent", level="rail", kind="finite differences",
            quantity="assembled rail (20 elements, supports on and between nodes): tangent "
                     "stiffness at a bent, noisy state",
            reference="central differences of the internal force",
            measured=rel(K_fd, K), tolerance=1e-6, metric="relative")
    assert np.linalg.norm(K - K.T) < 1e-12 * np.linalg.norm(K)


def test_internal_force_is_gradient_of_elastic_and_support_energy(make_rail, fd, rel,
                                                                  validation):
    model = make_rail(n_elements=20, supports=SUPPORTS, stiffness=KS)
    e = deformed_rail(model, seed=11)
    Q, _ = model.internal_force(e)
    Q_fd = fd(lambda x: model.internal_force(x)[1], e, 1e-6)
    assert rel(Q_fd, Q) < 1e-6
    validation.record(
        "rail.force_is_energy_gradient", level="rail", kind="finite differences",
        quantity="assembled rail: internal force (elastic + supports) at a bent, noisy state",
        reference="central differences of the elastic and support energy",
        measured=rel(Q_fd, Q), tolerance=1e-6, metric="relative")


def test_support_between_nodes_acts_through_shape_functions(make_rail):
    """A single support at X: generalised force k_s S_y(X)^T y(X), net vertical force k_s y(X),
    and the support energy 1/2 k_s y(X)^2, for X on and between nodes."""
    for X in (1.0, 1.3, 3.77):
        model = make_rail(n_elements=20, supports=(X,), stiffness=KS)
        bare = make_rail(n_elements=20)
        e = deformed_rail(model, seed=3)
        Q, U = model.internal_force(e)
        Q0, U0 = bare.internal_force(e)
        y = model.positions(e, [X])[0, 1]
        dQ = np.array(Q) - np.array(Q0)
        assert dQ[1::4].sum() == pytest.approx(KS * y, rel=1e-10)
        assert np.all(dQ[0::2] == 0.0)
        assert U - U0 == pytest.approx(0.5 * KS * y * y, rel=1e-8)


@pytest.mark.parametrize("exact", [True, False])
def test_rigid_motion_of_the_whole_rail_gives_zero_force(make_rail, exact):
    model = make_rail(n_elements=20, exact=exact)
    e = np.array(model.reference()).reshape(-1, 2)
    ang = 0.4
    R = np.array([[math.cos(ang), -math.sin(ang)], [math.sin(ang), math.cos(ang)]])
    moved = (R @ e.T).T
    moved[0::2] += (2.0, -1.0)  # translate positions only
    Q, _ = model.internal_force(moved.ravel())
    # scale: the force of the sine bend of amplitude 1e-3 m
    Qb, _ = model.internal_force(deformed_rail(model))
    assert np.abs(Q).max() < 1e-9 * np.abs(Qb).max()
