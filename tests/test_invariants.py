"""Balances the solution must keep (issue 17): the work-energy theorem with the recorded energy
and driving reaction, and the rolling constraint under Baumgarte stabilisation."""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw

BASE = tw.Scene.kato2005()


def cumulative_trapezoid(y, x):
    return np.concatenate([[0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(x))])


@pytest.mark.parametrize("torque_factor", [0.0, 0.3])
def test_energy_changes_by_the_work_of_the_driving_reaction(torque_factor):
    """Without damping the total energy (kinetic + strain + supports + contact + potentials of
    gravity, of the wheel load P Y_A and of the torque, -T theta) changes only by the work of
    the horizontal force R that holds X_A = X_0 + v t: E(t) - E(0) = int_0^t R v dt.

    Generalized-alpha with rho_inf = 1 is the trapezoidal rule, which conserves this balance
    for the linear part exactly and for the mild nonlinearity to the Newton tolerance; the work
    integral uses the same trapezoid on every step. Measured: 3e-9 of max |W| (6e-9 J of 2.3 J
    without torque, 2e-8 J of 3200 J with T = 0.3 mu P rho0, stick); tolerance 1e-6 of max |W|
    (a missing M g in the load potential alone is 4e-3 of it, a wrong torque sign 2)."""
    P, rho0 = BASE.static_load, BASE.wheel.radius
    scene = dc.replace(BASE, wheel=dc.replace(BASE.wheel,
                                              torque=torque_factor * 0.3 * P * rho0))
    v = tw.kmh(100)
    r = tw.simulate(scene, v, x_end=1.0, dt=2.5e-6, n_elements=20, rho_inf=1.0, energy=True)
    assert np.all(r.slip_state == 1)
    work = cumulative_trapezoid(r.reaction * v, r.t)
    assert np.max(np.abs(work)) > 1.0  # the reaction does work: the check is not vacuous
    np.testing.assert_allclose(r.energy - r.energy[0], work, rtol=0,
                               atol=1e-6 * np.max(np.abs(work)))


def test_baumgarte_keeps_the_constraint_drift_at_round_off():
    """Explicit RK4 integrates the rolling constraint at acceleration level, g' = -alpha g with
    Baumgarte's alpha, so the velocity-level residual g (the slip velocity) decays at rate alpha
    instead of drifting.
    alpha = 1e5 1/s with h = 2 us (alpha h = 0.2, well inside RK4's stability region): the
    drift stays at round-off, max |g| < 1e-9 m/s (measured 2e-11) over 9 ms, as without
    stabilisation (measured 2e-12); a destabilising sign would grow it by e^(alpha t) = e^900."""
    for alpha in (0.0, 1e5):
        r = tw.simulate(BASE, tw.kmh(300), x_end=1.0, dt=2e-6, n_elements=20,
                        integrator="explicit", baumgarte=alpha)
        assert np.all(r.slip_state == 1)
        assert np.max(np.abs(r.slip)) < 1e-9
