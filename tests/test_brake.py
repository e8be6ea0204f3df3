"""The wheel brake (``Wheel.brake_torque``, docs: Model § Rolling and slip) and issue 13's check
that a wheel locked from rolling does not bring its flat round again.

Sign convention: theta is positive in the rolling direction and the rolling wheel's slip
velocity g = t.(V_A - S e') - rho theta' turns positive when the spin falls behind the forward
speed, so the sliding force on the wheel is lambda = -mu N (backwards) and the theta row reads
    J theta'' = -rho lambda - T_b sign(theta') = mu N rho - T_b      (turning forward).
Beyond adhesion, T_b > mu N rho0, the spin falls at the constant rate (T_b - mu N rho0) / J from
theta'_0 = v / rho0 to zero, at t_lock = J v / (rho0 (T_b - mu N rho0)); then the brake holds
the wheel (theta' = 0) while the torque it must hold, |T - rho lambda| = mu N rho0 < T_b, and the
wheel slides locked along the rail with lambda = -mu N.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw

V = tw.kmh(100)
BASE = tw.Scene.kato2005()
P, RHO0, MU = BASE.static_load, BASE.wheel.radius, BASE.contact.friction
J = BASE.wheel.polar_inertia
T_B = 3.0 * MU * P * RHO0  # three times adhesion: the spin falls at 2 mu P rho0 / J
T_LOCK = J * V / (RHO0 * (T_B - MU * P * RHO0))  # 4.9 ms, 0.14 m of travel at 100 km/h


def braked(scene, brake_torque=T_B, **wheel):
    return dc.replace(scene, wheel=dc.replace(scene.wheel, brake_torque=brake_torque, **wheel))


def damped():
    """The paper's track with damped supports (the flat's impacts ring down between passes)."""
    return dc.replace(BASE, supports=dc.replace(BASE.supports, damping=2e4))


def assert_theta_held(run, i):
    """theta after the lock at sample i: generalized-alpha's velocity row theta'_{n+1} = 0 lets
    the algorithmic acceleration of theta decay by (1 - gamma) / gamma = 0.64 per step
    (rho_inf = 0.8), which moves theta by ~1e-3 h^2 |theta''| ~ 1e-9 rad in all (measured
    6e-10 and 1e-9; 1e-8 rad is 1e-9 m on the wheel's rim); 0.5 ms (100 steps) on it is
    constant to round-off. RK4 sets theta' = 0: theta is constant at once."""
    assert np.ptp(run.theta[i:]) <= 1e-8
    settled = run.t >= run.t[i] + 5e-4
    assert np.ptp(run.theta[settled]) <= 4 * np.finfo(float).eps * abs(run.theta[i])


def lock_index(run):
    """First sample at which the spin has reached zero (generalized-alpha's locked theta' is
    zero to round-off, ~1e-17 rad/s, of either sign)."""
    stopped = run.thetadot <= 1e-14 * run.thetadot[0]
    assert np.any(stopped)
    return int(np.argmax(stopped))


@pytest.mark.parametrize("integrator, dt", [("generalized_alpha", 5e-6), ("explicit", 2e-6)])
def test_the_brake_spins_the_wheel_down_and_locks_it_sliding(integrator, dt):
    """Spin-down time against t_lock = J v / (rho0 (T_b - mu N rho0)) with N = P: N fluctuates
    by eps = max|N/P - 1| (0.75 % here: the start on the damped track), which moves t_lock by
    at most mu P rho0 eps / (T_b - mu P rho0) = eps / 2; the lock is found at the first sample
    after the crossing (one step h) and rho = rho0 - delta differs by delta / rho0 ~ 7e-4 in
    theta'_0 and the friction moment. Measured: within 0.09 % (generalized-alpha) and 0.03 %
    (RK4). Then, locked: theta' = 0 (to round-off) and theta constant, and the tangential
    force is the sliding friction -mu N (the slide row; to 1e-6: Newton's tolerance 1e-11 m
    moves N by k x 1e-11 ~ 1e-7 of P; measured 1.4e-9, RK4 0). The angular impulse balances
    the lost spin, J theta'_0 = int (T_b + rho lambda) dt up to t_lock, to 1e-3 (trapezoid
    over samples and rho ~ rho0; measured 4e-4 and 2e-4)."""
    run = tw.simulate(braked(damped()), V, duration=0.01, dt=dt, n_elements=40,
                      integrator=integrator, progress=False)
    i = lock_index(run)
    eps = np.max(np.abs(run.normal_force[:i] / P - 1.0))
    assert eps < 0.02  # N ~ P holds: the closed form applies
    assert abs(run.t[i] - T_LOCK) <= (0.5 * eps + 1e-3) * T_LOCK + dt
    assert V * run.t[i] < 0.15  # locked within 0.15 m of travel
    assert np.all(run.slip_state == 2)  # beyond adhesion from the first step
    after = slice(i + 1, None)  # RK4 locks at the start of the step after the crossing
    # RK4 sets theta' = 0; generalized-alpha solves its row to round-off (measured 3e-18 rad/s)
    assert np.max(np.abs(run.thetadot[after])) <= 1e-14 * run.thetadot[0]
    assert_theta_held(run, i)
    np.testing.assert_allclose(run.tangential_force[after], -MU * run.normal_force[after],
                               rtol=1e-6)
    impulse = np.trapezoid(T_B + RHO0 * run.tangential_force[:i + 1], run.t[:i + 1])
    np.testing.assert_allclose(impulse, J * run.thetadot[0], rtol=1e-3)


def test_a_locked_wheel_does_not_bring_its_flat_round_again():
    """Issue 13: a 45 mm new flat (depth 5.1 mm, half angle 0.23 rad) at psi = pi. Rolling, it
    strikes the rail every 2 pi rho0 of rolled distance (test_irregularity_response.py's
    test_a_wheel_flat_returns_with_the_rolling_angle_not_the_distance): over the metre run here
    the force peaks at several P and the wheel leaves the rail (measured 10.8 P). Braked
    beyond adhesion the wheel locks at theta = 0.68 rad after 0.14 m, away from the flat, and
    slides locked for 0.86 m > 2 pi rho0 = 0.63 m: theta stays put (assert_theta_held: 1e-9
    rad of settling, then round-off; the flat is 0.23 rad wide) and the contact stays on the round
    part of the wheel, so the force is the braked round wheel's (same run without the flat) and
    stays within 1 % of P (measured 0.2 %, the start's ring), while the rolling wheel strikes in
    the same stretch. The two runs agree to Newton's tolerance, not bit for bit: the out-of-round
    wheel takes its contact block new at every Newton iteration, the round one keeps the whole
    matrix, so their iterates stop at different points within newton_tol = 1e-11 m of
    displacement, i.e. ~1e-11 m x ~1e9 N/m of contact stiffness = 1e-2 N = 2e-7 P; bound 1e-6 P
    (measured 1.3e-9 P)."""
    scene = damped()
    flat = dc.replace(scene, wheel=dc.replace(
        scene.wheel, defects=(tw.WheelFlat(0.045, at_angle=math.pi),)))
    kw = dict(duration=1.0 / V, n_elements=40, dt=5e-6, progress=False)
    rolling = tw.simulate(flat, V, **kw)
    locked = tw.simulate(braked(flat), V, **kw)
    round_wheel = tw.simulate(braked(scene), V, **kw)
    i = lock_index(locked)
    travel = locked.x_wheel - locked.x_wheel[0]
    assert travel[i] < 0.15 and travel[-1] - travel[i] > 2 * math.pi * RHO0
    phi_f = math.asin(0.045 / (2 * RHO0))
    assert abs(locked.theta[i] - math.pi) > phi_f  # locked off the flat
    assert_theta_held(locked, i)
    after = slice(i, None)
    assert np.max(rolling.normal_force[after]) > 2.0 * P  # the rolling wheel's flat strikes
    assert rolling.lost_contact
    assert not locked.lost_contact
    assert np.max(np.abs(locked.normal_force[after] / P - 1.0)) < 0.01
    np.testing.assert_allclose(locked.normal_force, round_wheel.normal_force, rtol=0,
                               atol=1e-6 * P)


@pytest.mark.parametrize("integrator, dt", [("generalized_alpha", 5e-6), ("explicit", 2e-6)])
def test_a_locked_wheel_is_released_when_the_torque_to_hold_it_exceeds_the_brake(integrator, dt):
    """Without friction (rolling=False, lambda = 0) under a torque T = -2 T_b the wheel turning
    forward decelerates at (T - T_b) / J = -3 T_b / J, locks at t1 = J theta'_0 / (3 T_b); the
    holding torque |T| = 2 T_b exceeds T_b, so it is released at once and turns backwards with
    the brake now opposing that: theta'' = (T + T_b) / J = -T_b / J. theta'(t) follows the two
    lines to one step's change h 3 T_b / J (where the lock falls inside a step; 0.12 rad/s for
    RK4, measured 0.07; 0.0096 for generalized-alpha) of the 278 rad/s spin; a brake that did
    not reverse on release would decelerate three times faster after t1."""
    tb = 1000.0
    scene = braked(BASE, brake_torque=tb, torque=-2.0 * tb)
    run = tw.simulate(scene, V, duration=0.01, dt=dt, n_elements=20, integrator=integrator,
                      rolling=False, progress=False)
    w0 = run.thetadot[0]
    t1 = J * w0 / (3.0 * tb)
    expect = np.where(run.t < t1, w0 - 3.0 * tb * run.t / J, -tb * (run.t - t1) / J)
    assert run.t[-1] > 2.0 * t1
    np.testing.assert_allclose(run.thetadot, expect, rtol=0, atol=dt * 3.0 * tb / J)


def cumulative_trapezoid(y, x):
    return np.concatenate([[0.0], np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(x))])


def test_energy_balance_with_the_brake_and_sliding_friction():
    """Undamped paper scene, trapezoidal rule (rho_inf = 1, as in test_invariants.py): the total
    energy changes by the work of the driving reaction, of sliding friction (lambda times the
    slip velocity g) and of the brake (-T_b |theta'| while turning, nothing locked):
    E(t) - E(0) = int (R v + lambda g - T_b |theta'|) dt. Measured 5e-8 of max |W| (the lock
    falls inside a step: the kinetic energy J theta'_n^2 / 2 ~ 2e-3 J of that step is
    lost outside the brake's work, 1e-6 of the 1900 J of spin); tolerance 1e-5. Leaving out the
    brake's or the friction's work breaks it by order 1."""
    scene = braked(BASE)
    run = tw.simulate(scene, V, duration=0.01, dt=2.5e-6, n_elements=20, rho_inf=1.0,
                      energy=True, progress=False)
    assert np.max(np.abs(run.thetadot[lock_index(run):])) <= 1e-14 * run.thetadot[0]
    brake = -T_B * np.abs(run.thetadot)
    work = cumulative_trapezoid(run.reaction * V + run.tangential_force * run.slip + brake, run.t)
    assert np.max(np.abs(work)) > 1e3
    np.testing.assert_allclose(run.energy - run.energy[0], work, rtol=0,
                               atol=1e-5 * np.max(np.abs(work)))


def test_bad_brake_input_is_refused():
    with pytest.raises(ValueError, match=r"Wheel\.brake_torque.*\[0, 1e\+06\] N m"):
        tw.Wheel(brake_torque=-1.0)
    with pytest.raises(ValueError, match="Wheel.brake_torque"):
        tw.Wheel(brake_torque=math.nan)
    for fidelity in ("linear/hertz", "linear/moving_mass"):
        with pytest.raises(ValueError, match=r"brake_torque.*'full', 'ancf/sprung'"):
            tw.simulate(braked(BASE), V, fidelity=fidelity, x_end=2.6, progress=False)


def test_cli_brake_torque_brakes_the_wheel(capsys):
    """``trackwheel run --brake-torque T_B`` runs the API's braked scene (printed results of a
    braked and an unbraked run differ) and refuses a negative T_B or a linear level with a
    one-line error naming the option."""
    from trackwheel import cli

    cheap = ["--speed-kmh", "100", "--n-elements", "20", "--dt", "1e-5", "--x-end", "0.75"]
    assert cli.main(["run", *cheap]) == 0
    free = capsys.readouterr().out
    assert cli.main(["run", *cheap, "--brake-torque", str(T_B)]) == 0
    assert capsys.readouterr().out.split("wall")[0] != free.split("wall")[0]
    for argv, word in ((["--brake-torque", "-1"], "--brake-torque = -1.0"),
                       (["--brake-torque", "5000", "--fidelity", "linear/hertz"],
                        "--brake-torque > 0 needs the wheel's rotation")):
        assert cli.main(["run", *cheap, *argv]) == 2
        err = capsys.readouterr().err
        assert len(err.splitlines()) == 1 and word in err, err


def test_a_brake_beyond_adhesion_is_reported_where_a_user_looks(capsys):
    """T_b = 3 mu P rho0: the wheel slides from the start and locks at t_lock (module
    docstring; N stays within 1.5 % of P on the paper's track, so within 3 % here). The result
    (sliding/locked masks, intervals, repr), the analysis (slide_duration, locked_duration,
    repr) and ``trackwheel run`` all say so; below adhesion the CLI says it did not slide."""
    from trackwheel import cli

    r = tw.simulate(braked(BASE), V, x_end=0.75, n_elements=20, dt=1e-5, progress=False)
    (t0, t1), = r.locked_intervals()
    assert t0 == pytest.approx(T_LOCK, rel=0.03) and t1 == r.t[-1]
    assert r.sliding_intervals()[0][0] < 0.1 * T_LOCK  # sliding from the first steps
    a = tw.analyse(r)
    dt = r.t[1] - r.t[0]
    assert a.locked_duration == pytest.approx(r.t[-1] - T_LOCK, rel=0.03, abs=2 * dt)
    assert a.slide_duration >= a.locked_duration > 0.0
    assert "slid" in repr(r) and "locked" in repr(a)
    free = tw.analyse(tw.simulate(BASE, V, x_end=0.75, n_elements=20, dt=1e-5, progress=False))
    assert free.slide_duration == free.locked_duration == 0.0 and "slid" not in repr(free)
    cheap = ["--speed-kmh", "100", "--n-elements", "20", "--dt", "1e-5", "--x-end", "0.75"]
    assert cli.main(["run", *cheap, "--brake-torque", f"{T_B:.6g}"]) == 0
    line = [ln for ln in capsys.readouterr().out.splitlines() if "sliding" in ln][0]
    t_lock = float(line.split("locked (theta' = 0) from t = ")[1].split(" ms")[0]) * 1e-3
    assert t_lock == pytest.approx(T_LOCK, rel=0.03)
    assert f"> adhesion limit mu P rho0 = {MU * P * RHO0:.0f} N m" in line
    assert cli.main(["run", *cheap, "--brake-torque", "1000"]) == 0
    line = [ln for ln in capsys.readouterr().out.splitlines() if "sliding" in ln][0]
    assert line.endswith("sliding        : no (brake torque 1000 N m <= adhesion limit mu P "
                         f"rho0 = {MU * P * RHO0:.0f} N m)")
