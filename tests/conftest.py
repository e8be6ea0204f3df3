"""Shared fixtures: the paper's rail section, a direct RailModel factory and central differences.

The low-level tests build ``trackwheel._core`` objects directly, so that a rail without supports
(the simply supported beam of docs: Model § Validation), without gravity or with supports at arbitrary
positions can be set up independently of the Scene layer.
"""

from __future__ import annotations

import numpy as np
import pytest
from trackwheel import Rail, _core

# The paper's rail section (docs: Model § Scene; the preset values themselves are checked in
# test_scene.py): EA [N], EI [N m^2], rho A [kg/m].
EA = Rail().axial_stiffness
EI = Rail().bending_stiffness
RHO_A = Rail().mass_per_length


@pytest.fixture
def section():
    """Factory for one element's CableSection of the paper's rail, length ``l`` [m]."""

    def make(length=0.25, exact=True, n_gauss=5):
        c = _core.CableSection()
        c.length = length
        c.EA = EA
        c.EI = EI
        c.rhoA = RHO_A
        c.exact_curvature = exact
        c.n_gauss = n_gauss
        return c

    return make


@pytest.fixture
def make_rail():
    """Factory for a RailModel of the paper's section with explicit supports.

    ``supports`` [m] may be empty (the bare simply supported beam); ``stiffness`` [N/m] is one
    value for all supports; ``gravity`` [m/s^2] defaults to 0 (rail weight off).
    """

    def make(length=5.0, n_elements=20, supports=(), stiffness=0.0, damping=0.0, gravity=0.0,
             pin_far_end=False, exact=True, n_gauss=5):
        p = _core.RailParams()
        p.length = length
        p.EA = EA
        p.EI = EI
        p.rhoA = RHO_A
        p.n_elements = n_elements
        p.exact_curvature = exact
        p.n_gauss = n_gauss
        p.gravity = gravity
        p.pin_far_end = pin_far_end
        s = _core.SupportParams()
        s.position = [float(x) for x in supports]
        s.stiffness = [float(stiffness)] * len(supports)
        s.damping = [float(damping)] * len(supports)
        return _core.RailModel(p, s)

    return make


def central_jacobian(f, x, h):
    """Central finite-difference Jacobian of f at x: column i = (f(x + h e_i) - f(x - h e_i))/2h.

    ``h`` is a scalar or one step per coordinate. Truncation error O(h^2 f'''), round-off
    O(eps |f| / h).
    """
    x = np.asarray(x, dtype=float)
    h = np.broadcast_to(np.asarray(h, dtype=float), x.shape)
    cols = []
    for i in range(x.size):
        xp = x.copy()
        xm = x.copy()
        xp[i] += h[i]
        xm[i] -= h[i]
        cols.append((np.asarray(f(xp), dtype=float) - np.asarray(f(xm), dtype=float))
                    / (2.0 * h[i]))
    return np.stack(cols, axis=-1)


@pytest.fixture
def fd():
    """The central-difference Jacobian helper (see :func:`central_jacobian`)."""
    return central_jacobian


def rel_err(a, b):
    """||a - b|| / ||b|| (Frobenius)."""
    return float(np.linalg.norm(np.asarray(a) - np.asarray(b)) / np.linalg.norm(b))


@pytest.fixture
def rel():
    return rel_err
