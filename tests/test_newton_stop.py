"""Newton's stopping rule on the full path (docs: Model § Equations of motion): a step has
converged when its last correction is within the tolerance, or when the error that correction
leaves, estimated from the iteration's contraction theta as theta / (1 - theta) e_k, is (while
theta <= (1 - rho_inf) / 10: off at rho_inf = 1).

Checked against runs at ``newton_tol=1e-13`` (a hundredth of the default): the contact-point
displacement within the default tolerance 1e-11 m over the whole run (each step's error is
within it; measured 7.7e-14 m on the paper's scene, 2.9e-12 m under the half car, whose
reference takes 2.77 iterations a step), the contact force within 1e-6 of the wheel load (the
precision the rule asks of the tangential force; measured 9.9e-5 N and 3.7e-3 N), and a
vehicle's four wheels converging in as many iterations per step as its single wheel.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw

V = tw.kmh(300)
PAPER = {"dt": 1e-5, "n_elements": 20, "x_start": 0.25, "x_end": 1.25, "progress": False}
CAR = {"dt": 2e-5, "n_elements": 200, "duration": 0.02, "progress": False}


def _car_scenes():
    """(half car, its wheel alone under its static load) on a 50 m rail (0.25 m elements)."""
    car = tw.Vehicle.half_car()
    w = car.wheels[0]
    single = dc.replace(w, load=car.static_loads(tw.scene.GRAVITY)[0] - w.mass * tw.scene.GRAVITY)
    rail = dc.replace(tw.Rail(), length=50.0)
    return (tw.Scene(rail=rail, vehicle=car),
            tw.Scene(rail=rail, vehicle=tw.Vehicle.single_wheel(single)))


@pytest.mark.parametrize("case", ["paper", "half_car"])
def test_default_tolerance_holds(case):
    scene, kw = (tw.Scene.kato2005(), PAPER) if case == "paper" else (_car_scenes()[0], CAR)
    ref = tw.simulate(scene, V, newton_tol=1e-13, **kw)
    r = tw.simulate(scene, V, **kw)  # newton_tol 1e-11 m
    assert np.max(np.abs(r.y_contact - ref.y_contact)) <= 1e-11
    load = max(np.max(scene.active_vehicle.static_loads(scene.gravity)), scene.static_load)
    assert np.max(np.abs(r.normal_force - ref.normal_force)) <= 1e-6 * load


def test_rule_is_off_without_numerical_damping():
    """At rho_inf = 1 a stopped iteration's perturbation of the step (about theta) is not
    damped: a wheel driven at 0.09 P rho0 then grew a step-to-step oscillation of its
    tangential force from 17 N to the friction limit (14 kN) within 5500 steps. With the rule
    off its tangential force stays smooth: the second difference between steps stays below 5 %
    of the force (measured 49 N of 5.3 kN; the oscillating run's reached 20 kN)."""
    scene = tw.Scene.kato2005()
    P, rho0 = scene.static_load, scene.wheel.radius
    scene = dc.replace(scene, wheel=dc.replace(scene.wheel, torque=0.09 * P * rho0))
    r = tw.simulate(scene, tw.kmh(100), x_end=1.0, dt=2.5e-6, n_elements=20, rho_inf=1.0,
                    progress=False)
    assert np.all(r.slip_state == 1)
    lam = r.tangential_force[1000:]
    assert np.max(np.abs(np.diff(lam, 2))) < 0.05 * np.max(np.abs(lam))


def test_vehicle_converges_like_its_wheel():
    car, single = _car_scenes()
    its = [tw.simulate(s, V, **CAR) for s in (car, single)]
    per_step = [r.newton_iterations / r.steps for r in its]
    # modified Newton needs two iterations a step (a correction, then the contraction's
    # estimate); four wheels away from the rail's ends contract as one does
    assert per_step[1] <= 2.05
    assert per_step[0] <= 1.05 * per_step[1], per_step
