"""Where a run of the full model starts: the kernel's initial state.

Docs: Model § Equations of motion, § The vehicle.

"static" (the paper's start) is the static equilibrium at the start position: the rail under
the wheel's load (a vehicle: every wheel's static load of the weight distribution at once, each
body where its springs carry those loads); "sudden" is the rail under its own weight with every
wheel just touching it (a vehicle's bodies with every spring unstretched): a sudden load. In
both every wheel rolls purely at the start, and ``drop_height`` lifts the wheels (and bodies).
"""

from __future__ import annotations

import numpy as np

from .. import _core
from ..scene import Scene
from . import kernel, profile


def initial_state(scene: Scene, model, speed: float, x_start: float, start: str,
                  drop_height: float) -> _core.SimState:
    """The kernel's state at the start of a run of ``scene`` on the rail ``model`` at ``speed``
    [m/s], the reference point at ``x_start`` [m] (rail coordinate), by ``start`` ("static" or
    "sudden"), the wheels lifted by ``drop_height`` [m]."""
    if scene.vehicle is not None:
        return _vehicle_state(scene, model, speed, x_start, start, drop_height)
    contact = kernel.contact_params(scene)
    # an out-of-round wheel starts at theta = 0, touching with its radius rho0 + Delta rho(0)
    contact.radius += profile.radius_change_at_start(scene)
    if start == "static":
        d = _core.static_solve(model, kernel.wheel_params(scene), contact, x_start)
        e, y = np.asarray(d["e"]), d["y_wheel"] + drop_height
    else:  # sudden: rail under its own weight, wheel just touching (or drop_height above)
        e = np.asarray(_core.rail_static(model))
        y = model.positions(e, [x_start])[0, 1] + contact.radius + drop_height
    return _sim_state(e, [_wheel_state(model, e, x_start, y, contact, speed)])


def _vehicle_state(scene: Scene, model, speed: float, x_start: float, start: str,
                   drop_height: float) -> _core.SimState:
    veh = scene.active_vehicle
    xs = [x_start + x for x in veh.positions]
    if start == "static":
        contacts = []
        for w in veh.wheels:
            c = kernel.contact_params(scene)
            c.radius = w.radius + sum(d.delta_rho(0.0, w.radius) for d in w.defects)
            contacts.append(c)
        sols = _core.static_solve_wheels(model, kernel.static_wheels_params(scene), contacts, xs)
        e = np.asarray(sols[0]["e"])
        ys = [d["y_wheel"] + drop_height for d in sols]
        body = kernel.static_bodies(scene, ys)  # lifted with the wheels by drop_height
    else:
        e = np.asarray(_core.rail_static(model))
        y_rail = model.positions(e, xs)[:, 1]
        ys = [y + w.radius + drop_height for y, w in zip(y_rail, veh.wheels)]
        body = kernel.static_bodies(scene, ys, gravity=0.0)
    contact = kernel.contact_params(scene)
    wheels = []
    for x, y, w in zip(xs, ys, veh.wheels):
        contact.radius = w.radius
        wheels.append(_wheel_state(model, e, x, y, contact, speed))
    return _sim_state(e, wheels, body)


def _wheel_state(model, e, x: float, y: float, contact, speed: float) -> _core.WheelState:
    """A wheel at (x, y) [m] on the rail e, rolling purely at ``speed`` [m/s]: t . V_A =
    rho_r theta', rho_r the rolling radius (rho plus the element's deflection under the load
    with the element compliance)."""
    c = _core.contact_eval(model, e, x, y, x, contact, np.zeros(10))
    w = _core.WheelState()
    w.y, w.ydot, w.theta = y, 0.0, 0.0
    w.thetadot = float(c["tangent"][0]) * speed / (c["rho"] + c["deflection"])
    w.s = c["s"]
    w.state = _core.SlipState.stick if c["active"] else _core.SlipState.free
    return w


def _sim_state(e: np.ndarray, wheels: list, body=None) -> _core.SimState:
    st = _core.SimState()
    st.e = e
    st.edot = np.zeros_like(e)
    st.wheels = wheels  # a copy in the binding: assign the whole list
    if body is not None:
        st.body = np.asarray(body, dtype=float)
        st.bodydot = np.zeros(len(body))
    return st
