"""Stick and slide of the rolling contact (docs: Model § Rolling and slip, § Equations of motion; issue 17): the Coulomb bound holds in
stick, and sliding starts when the tangential force reaches mu N.

With the wheel centre's forward motion prescribed at constant speed, J theta'' = T - rho lambda;
in steady pure rolling theta'' = 0, so a torque T needs the tangential force lambda = T / rho.
Coulomb's law allows it while T / rho <= mu N: a torque below mu N rho must stick, one above it
must slide. The torque is applied at t = 0 (the scene's constant torque). With the paper's
wheel inertia (J / rho^2 = 5 kg at the rim) the step excites the rail's axial modes and
lambda overshoots T / rho (up to ~2x, test_dynamics.py); with a light wheel (J = 1e-3 kg m^2,
0.1 kg at the rim, 1/2700 of the rail's mass) the rim follows the rail and lambda stays within
~1 % of T / rho, so the threshold can be approached to 5 % from both sides.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw

STICK, SLIDE = 1, 2
BASE = tw.Scene.kato2005()
MU, RHO0, P = BASE.contact.friction, BASE.wheel.radius, BASE.static_load
#: the generalized-alpha Newton iteration stops when the tangential-force correction is below
#: 1e-6 of the wheel load (simulate's convergence test), so lambda and the slip decision based
#: on it are exact to that force [N]
NEWTON_FORCE_TOL = 1e-6 * P
#: integrator -> time step [s]; each resolves the axial ringing and the contact mode
STEPS = {"generalized_alpha": 1e-5, "explicit": 1e-6}
SPEED = tw.kmh(36)


def run(factor, integrator, inertia=None, duration=5e-3):
    """The paper's scene with a torque T = factor mu P rho0 on the wheel."""
    wheel = dc.replace(BASE.wheel, torque=factor * MU * P * RHO0, inertia=inertia)
    return tw.simulate(dc.replace(BASE, wheel=wheel), SPEED, duration=duration,
                       dt=STEPS[integrator], n_elements=20, integrator=integrator)


def bound_tolerance(r, integrator):
    """Allowed excess of |lambda| over mu N at each sample [N].

    Generalized-alpha decides the slip state at the converged end of each step (and redoes the
    step when it changes), so the recorded stick samples obey the bound to the Newton tolerance
    on lambda. Explicit RK4 freezes the state over a step and decides it from the multiplier at
    the step's start, so a recorded stick sample may exceed mu N by lambda's change over that
    one step (plus round-off)."""
    if integrator == "generalized_alpha":
        return np.full(r.t.size, NEWTON_FORCE_TOL)
    change = np.abs(np.diff(np.abs(r.tangential_force) - MU * r.normal_force, prepend=np.nan))
    change[0] = 0.0
    return change + 1e-9 * P


@pytest.mark.parametrize("integrator", list(STEPS))
@pytest.mark.parametrize("factor", [0.8, 0.95, 1.05])
@pytest.mark.parametrize("inertia", [None, 1e-3])
def test_stick_obeys_coulomb_bound(integrator, factor, inertia):
    """While the recorded state is stick, |lambda| <= mu N at every sample (to the tolerance of
    bound_tolerance); while sliding, lambda = +-mu N (the prescribed multiplier: exactly for RK4,
    to the Newton tolerance for generalized-alpha, whose recorded N is one correction old)."""
    r = run(factor, integrator, inertia)
    lam, N, state = r.tangential_force, r.normal_force, r.slip_state
    stick, slide = state == STICK, state == SLIDE
    assert np.all(N > 0.0) and np.all(stick | slide)
    excess = np.abs(lam) - MU * N - bound_tolerance(r, integrator)
    assert np.all(excess[stick] <= 0.0), np.max(excess[stick]) / (MU * P)
    slide_tol = NEWTON_FORCE_TOL if integrator == "generalized_alpha" else 1e-12 * P
    np.testing.assert_allclose(np.abs(lam[slide]), MU * N[slide], rtol=0.0, atol=slide_tol)


@pytest.mark.parametrize("integrator", list(STEPS))
def test_slide_starts_when_lambda_reaches_mu_n(integrator):
    """The paper's wheel under T = 0.8 mu N rho: the overshoot of the torque step carries the
    sticking lambda up to mu N at ~2 ms. Every stick -> slide switch happens in the step in
    which |lambda| / (mu N) crosses 1: at the last stick sample the ratio is at most 1 (to the
    bound tolerance) and its linear extrapolation over one more sample reaches 1 (lambda rises
    by at most its previous change per step, to the curvature of the ringing, which the
    factor 2 on the slope covers)."""
    r = run(0.8, integrator)
    ratio = np.abs(r.tangential_force) / (MU * r.normal_force)
    tol = bound_tolerance(r, integrator) / (MU * P)
    onsets = np.flatnonzero((r.slip_state[1:] == SLIDE) & (r.slip_state[:-1] == STICK)) + 1
    assert onsets.size >= 1
    for k in onsets:
        assert r.t[k] > 1e-3  # after the ringing built up, not at the torque step
        assert ratio[k - 1] <= 1.0 + tol[k - 1]
        assert ratio[k - 1] + 2.0 * abs(ratio[k - 1] - ratio[k - 2]) >= 1.0


@pytest.mark.parametrize("integrator", list(STEPS))
@pytest.mark.parametrize("factor", [0.95, 1.05])
def test_light_wheel_slides_above_adhesion_only(integrator, factor):
    """A light wheel (see the module docstring): T = 0.95 mu N rho sticks throughout with
    lambda = T / rho within 2 % (half the 5 % distance to the threshold; the axial ringing
    measured ~1 %); T = 1.05 mu N rho cannot be held and slides from the first steps on
    (within 5e-5 s) with the wheel spinning faster than it rolls (slip velocity < 0)."""
    r = run(factor, integrator, inertia=1e-3)
    T = factor * MU * P * RHO0
    if factor < 1.0:
        assert np.all(r.slip_state == STICK)
        np.testing.assert_allclose(r.tangential_force, T / RHO0, rtol=0.02, atol=0.0)
    else:
        assert r.t[np.argmax(r.slip_state == SLIDE)] <= 5e-5
        late = r.t > 5e-5
        assert np.all(r.slip_state[late] == SLIDE)
        assert np.all(r.slip[late] < 0.0)
