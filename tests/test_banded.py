"""The band LU and the bordered band solver (cpp/banded.hpp) against dense numpy solves.

Random matrices with a fixed seed, made well conditioned by diagonal dominance (the band LU does
not pivot, as for the kernel's mass and iteration matrices, which are positive definite or close
to it). With condition numbers kept below ~1e2, a backward-stable solve agrees with numpy's to
kappa n eps ~ 1e-12 relative; the tolerance is 1e-11 of the solution's norm.
"""

from __future__ import annotations

import numpy as np
import pytest

from trackwheel import _core

RTOL = 1e-11


def _band(rng, n, b):
    A = rng.standard_normal((n, n))
    i, j = np.indices((n, n))
    A[np.abs(i - j) > b] = 0.0
    A += np.diag(2.0 * np.abs(A).sum(axis=1) + 1.0)  # strictly diagonally dominant
    return A


@pytest.mark.parametrize("n, b", [(1, 0), (5, 1), (40, 3), (83, 7), (200, 7), (30, 29)])
def test_band_lu_solves_like_numpy(n, b):
    rng = np.random.default_rng(1000 * n + b)
    A = _band(rng, n, b)
    assert np.linalg.cond(A) < 1e2
    r = rng.standard_normal(n)
    x = _core.testing.band_solve(A, b, r)
    ref = np.linalg.solve(A, r)
    assert np.linalg.norm(x - ref) <= RTOL * np.linalg.norm(ref)


def test_band_lu_uses_only_the_band():
    """Entries outside the half bandwidth are not part of the band matrix."""
    rng = np.random.default_rng(7)
    A = _band(rng, 20, 2)
    r = rng.standard_normal(20)
    noisy = A + np.triu(rng.standard_normal((20, 20)), 3)
    np.testing.assert_array_equal(_core.testing.band_solve(noisy, 2, r), _core.testing.band_solve(A, 2, r))


@pytest.mark.parametrize("n, b, m", [(40, 3, 1), (83, 7, 3), (83, 7, 6), (160, 7, 9),
                                     (50, 2, 0)])
def test_bordered_solver_solves_like_numpy(n, b, m):
    """[A B; C D] with A banded and m border columns: 3 per wheel for one to three wheels (and
    none). The Schur complement D - C A^-1 B is kept well conditioned by a dominant D."""
    rng = np.random.default_rng(10 * n + m)
    A = _band(rng, n, b)
    B = rng.standard_normal((n, m))
    C = rng.standard_normal((m, n))
    D = rng.standard_normal((m, m)) + np.diag(np.full(m, 10.0 + n))
    full = np.block([[A, B], [C, D]])
    assert np.linalg.cond(full) < 1e2
    r1, r2 = rng.standard_normal(n), rng.standard_normal(m)
    x1, x2 = _core.testing.bordered_solve(A, b, B, C, D, r1, r2)
    ref = np.linalg.solve(full, np.concatenate([r1, r2]))
    x = np.concatenate([x1, x2])
    assert np.linalg.norm(x - ref) <= RTOL * np.linalg.norm(ref)


def test_bordered_solver_with_sparse_border_columns():
    """The kernel's border columns are mostly zero (a wheel touches one element): zero columns
    of B are skipped in A^-1 B, which must not change the solution."""
    rng = np.random.default_rng(3)
    n, b, m = 83, 7, 6
    A = _band(rng, n, b)
    B = np.zeros((n, m))
    B[10:18, 2] = rng.standard_normal(8)
    B[50:58, 5] = rng.standard_normal(8)
    C = np.zeros((m, n))
    C[2, 10:18] = rng.standard_normal(8)
    C[5, 50:58] = rng.standard_normal(8)
    D = np.diag(np.array([10.0, 0.05, 1.0, 10.0, 0.05, 1.0])) + 0.1 * rng.standard_normal((m, m))
    r1, r2 = rng.standard_normal(n), rng.standard_normal(m)
    x1, x2 = _core.testing.bordered_solve(A, b, B, C, D, r1, r2)
    ref = np.linalg.solve(np.block([[A, B], [C, D]]), np.concatenate([r1, r2]))
    assert np.linalg.norm(np.concatenate([x1, x2]) - ref) <= RTOL * np.linalg.norm(ref)


def test_singular_and_inconsistent_inputs_raise():
    A = np.eye(4)
    A[2, 2] = 0.0
    with pytest.raises(RuntimeError, match="singular"):
        _core.testing.band_solve(A, 1, np.ones(4))
    with pytest.raises(RuntimeError, match="singular"):
        _core.testing.bordered_solve(np.eye(3), 1, np.zeros((3, 1)), np.zeros((1, 3)), np.zeros((1, 1)),
                             np.ones(3), np.ones(1))
    with pytest.raises(ValueError, match="inconsistent shapes"):
        _core.testing.bordered_solve(np.eye(3), 1, np.zeros((3, 2)), np.zeros((1, 3)), np.eye(1),
                             np.ones(3), np.ones(1))
    with pytest.raises(ValueError, match="square"):
        _core.testing.band_solve(np.ones((2, 3)), 1, np.ones(2))


def _split_case(rng, n, idx, m):
    """(idx, E, F, G, D, r1, r2) of a split bordered system: contact-like blocks E, F, G over
    the band indices idx (n_groups x group_size, -1 none), a dominant D."""
    r = idx.size
    E = rng.standard_normal((r, r))
    F = rng.standard_normal((r, m))
    G = rng.standard_normal((m, r))
    D = rng.standard_normal((m, m)) + np.diag(np.full(m, 10.0 + n))
    return idx, E, F, G, D, rng.standard_normal(n), rng.standard_normal(m)


def _split_dense(A, case):
    """The same system assembled densely: [A + P E P^T, P F; G P^T, D] (P's column k the unit
    vector of idx_k, zero for -1; entries of E, F, G at a -1 index drop out)."""
    idx, E, F, G, D = case[:5]
    n, flat = len(A), idx.ravel()
    P = np.zeros((n, flat.size))
    for k, i in enumerate(flat):
        if i >= 0:
            P[i, k] = 1.0
    return np.block([[A + P @ E @ P.T, P @ F], [G @ P.T, D]])


def test_split_bordered_solver_equals_a_dense_solve():
    """The split form (the band factorised alone, the wheels' contact blocks through a small
    dense system, W = A^-1 P cached per group) is exact: it must equal a dense solve of the
    assembled matrix to round-off. Cases in turn on one solver: two wheels (8 coordinates each,
    3 border unknowns each) on separate elements; the same positions with new blocks (W reused:
    no band solve); one wheel moved, overlapping the other's element (a shared node: P has equal
    columns) and touching a fixed coordinate (-1); then a single group on a new solver."""
    rng = np.random.default_rng(11)
    n, b = 83, 7
    A = _band(rng, n, b)
    g0, g1 = np.arange(8, 16), np.arange(40, 48)
    moved = np.concatenate([[-1], np.arange(44, 51)])  # overlaps g1 on 44..47
    cases = [_split_case(rng, n, np.stack([g0, g1]), 6),
             _split_case(rng, n, np.stack([g0, g1]), 6),
             _split_case(rng, n, np.stack([moved, g1]), 6)]
    out = _core.testing.split_bordered_solve(A, b, cases)
    for case, (x1, x2, _) in zip(cases, out):
        full = _split_dense(A, case)
        assert np.linalg.cond(full) < 1e4
        ref = np.linalg.solve(full, np.concatenate(case[5:]))
        assert np.linalg.norm(np.concatenate([x1, x2]) - ref) <= RTOL * np.linalg.norm(ref)
    # band solves: 16 for the first case, none for new blocks at the same positions, 7 for the
    # moved group (its -1 column costs none)
    assert [o[2] for o in out] == [16, 16, 23]
    single = [_split_case(rng, n, g0[None, :], 3)]
    (x1, x2, _), = _core.testing.split_bordered_solve(A, b, single)
    ref = np.linalg.solve(_split_dense(A, single[0]), np.concatenate(single[0][5:]))
    assert np.linalg.norm(np.concatenate([x1, x2]) - ref) <= RTOL * np.linalg.norm(ref)
