"""Translate a :class:`~trackwheel.Scene` into the C++ kernel's parameter structs, and read
the kernel's vehicle matrices back.

The kernel's ``RailModel`` is immutable; it is built once per (scene, mesh) and cached. The
rail profile and the wheel's out-of-roundness it carries are built in :mod:`.profile`.

A documented internal module: tests and benchmarks build kernel objects through it
(``trackwheel.run.kernel.rail_model(scene, n_elements)``).
"""

from __future__ import annotations

from functools import lru_cache
from typing import NamedTuple

import numpy as np

from .. import _core
from ..scene import Scene
from . import profile


@lru_cache(maxsize=64)
def rail_model(scene: Scene, n_elements: int | None = None,
               profile_end: float | None = None, profile_shift: float = 0.0,
               support_origin: float = 0.0) -> _core.RailModel:
    """The kernel's rail of ``scene`` on ``n_elements`` (None: the scene's); its profile covers
    the track coordinates [0, ``profile_end``] [m] (None: the rail, [0, L]; a travelling
    window's run covers the track it passes), read at the rail's x = X - ``profile_shift``
    (the full path's travelling window: the start window's origin X_w [m]); its supports have
    the properties of the track's at X = ``support_origin`` + x (a travelling window: its
    origin X_w at the start [m])."""
    return _core.RailModel(rail_params(scene, n_elements), support_params(scene, support_origin),
                           profile.rail_profile(scene, profile_end, profile_shift))


def rail_params(scene: Scene, n_elements: int | None = None) -> _core.RailParams:
    """The kernel's rail parameters of ``scene`` on ``n_elements`` (None: the scene's)."""
    r = scene.rail
    p = _core.RailParams()
    p.length = r.length
    p.EA = r.axial_stiffness
    p.EI = r.bending_stiffness
    p.rhoA = r.mass_per_length
    p.n_elements = r.n_elements if n_elements is None else int(n_elements)
    p.exact_curvature = r.curvature == "exact"
    p.n_gauss = r.n_gauss
    p.gravity = scene.gravity if scene.rail_gravity else 0.0
    p.pin_far_end = r.far_end == "pinned"
    if r.beam == "timoshenko":
        # the full path's shear-deformable ANCF element; the linear path takes its own
        # Timoshenko matrices from beam_params and reads only the mesh and supports from here
        p.shear_stiffness = r.shear_stiffness
        p.rotary_inertia = r.rotary_inertia
    if r.absorbing_ends is not None:
        p.absorbing_length = r.absorbing_ends.length
        p.absorbing_damping = r.absorbing_damping
        p.absorbing_axial_damping = r.absorbing_ends.axial_c_max(r.axial_stiffness)
    return p


def support_params(scene: Scene, origin: float = 0.0) -> _core.SupportParams:
    """The kernel's supports of ``scene`` at their rail positions x_j, each property that of
    the track at X = ``origin`` + x_j [m]."""
    x = np.asarray(scene.support_positions, dtype=float)
    return _supports_at(scene, origin + x, position=x)


def _supports_at(scene: Scene, x: np.ndarray, position=None) -> _core.SupportParams:
    """The kernel's supports with the properties the scene's supports have at the track
    coordinates ``x`` [m] (:meth:`trackwheel.Supports.values`), placed at ``position``
    (None: at ``x``)."""
    sv = scene.supports.values(x)
    s = _core.SupportParams()
    s.position = sv.position.tolist() if position is None else np.asarray(position).tolist()
    s.stiffness = sv.stiffness.tolist()
    s.damping = sv.damping.tolist()
    if sv.layered:
        s.sleeper_mass = sv.sleeper_mass.tolist()
        s.ballast_stiffness = sv.ballast_stiffness.tolist()
        s.ballast_damping = sv.ballast_damping.tolist()
        unilateral_ballast(sv, s)
    return s


def unilateral_ballast(sv, s: _core.SupportParams) -> None:
    """The kernel's unilateral ballast into ``s`` from the resolved supports ``sv``: the void
    g_j [m] under each sleeper (only if some is > 0: a void makes that ballast push only) and
    the tensionless switch (every ballast pushes only)."""
    if np.any(sv.void > 0.0):
        s.void_gap = np.asarray(sv.void, dtype=float).tolist()
    s.tensionless = bool(sv.ballast_tensionless)


#: The per-support properties the travelling window streams (the kernel's
#: for_each_support_property): SupportParams' fields other than the positions and the
#: tensionless switch (one for the run).
STREAMED_PROPERTIES = ("stiffness", "damping", "sleeper_mass", "ballast_stiffness",
                       "ballast_damping", "void_gap")


def support_stream(scene: Scene, window, travel: float):
    """The supports a run on the travelling ``window`` (``_core.WindowParams``) meets over
    ``travel`` [m] of its rear wheel, one per sleeper from the start window's rear support at
    X_0 = origin + X_0,rail on, X_k = X_0 + k d (every sleeper that joins the window, O(travel
    / d) of them), as a ``_core.SupportParams`` for ``window.supports``; None if every one has
    the same properties (the window's rail is the track, as without streaming). A void streams
    like any property: it stays with its sleeper as the window travels (the kernel makes the
    window's sleepers unilateral from the start if any sleeper of the stream is)."""
    if scene.supports.uniform:
        return None
    d = window.bay
    rail_x = np.asarray(scene.support_positions, dtype=float)
    n = len(rail_x) + int(np.ceil(travel / d - 1e-9)) + 2  # one more shift at each end
    x = window.origin + rail_x[0] + d * np.arange(n)
    stream = _supports_at(scene, x)
    if all(len(set(getattr(stream, f))) <= 1 for f in STREAMED_PROPERTIES):
        return None
    return stream


def beam_params(scene: Scene) -> _core.BeamParams:
    """The linear track's beam theory: Euler-Bernoulli (shear stiffness 0) or Timoshenko."""
    b = _core.BeamParams()
    if scene.rail.beam == "timoshenko":
        b.shear_stiffness = scene.rail.shear_stiffness
        b.rotary_inertia = scene.rail.rotary_inertia
    return b


def wheel_params(scene: Scene) -> _core.WheelParams:
    """The kernel's wheel of the scene's single wheel ``Scene.wheel`` under its load."""
    return _wheel(scene.wheel, scene.gravity, scene.wheel.load)


def _wheel(w, gravity: float, load: float, x_offset: float = 0.0) -> _core.WheelParams:
    """The kernel's WheelParams of the Wheel ``w`` under the constant ``load`` [N] at
    ``x_offset`` [m] along the vehicle."""
    p = _core.WheelParams()
    p.mass = w.mass
    p.inertia = w.polar_inertia
    p.radius = w.radius
    p.load = load
    p.torque = w.torque
    p.brake_torque = w.brake_torque
    p.gravity = gravity
    p.x_offset = x_offset
    p.out_of_round = profile.defects_profile(w.defects, w.radius)
    return p


def wheels_params(scene: Scene) -> list:
    """One kernel WheelParams per wheel of the scene's vehicle, at its x_offset; a wheel under
    a bogie has no constant load (the suspension carries it). The single-wheel scene gives
    exactly ``[wheel_params(scene)]``."""
    veh = scene.active_vehicle
    if scene.vehicle is None:
        return [wheel_params(scene)]
    return [_wheel(w, scene.gravity, 0.0 if veh.bogie_of(i) is not None else w.load, x)
            for i, (w, x) in enumerate(zip(veh.wheels, veh.positions))]


def static_wheels_params(scene: Scene) -> list:
    """The kernel wheels for the static solve: each carrying its static load of the weight
    distribution as a constant force (F = P_w - M_w g)."""
    veh = scene.active_vehicle
    out = wheels_params(scene)
    for p, P, w in zip(out, veh.static_loads(scene.gravity), veh.wheels):
        p.load = P - w.mass * scene.gravity
    return out


def vehicle_params(scene: Scene) -> _core.VehicleParams:
    """The kernel's bodies (the bogies, then the car body) and suspensions (the primary ones in
    bogie and wheel order, then the secondary ones); empty for a vehicle without bodies."""
    veh = scene.active_vehicle
    vp = _core.VehicleParams()
    bodies, springs = [], []
    for j, b in enumerate(veh.bogies):
        bodies.append(_body(b.mass, b.pitch_inertia, scene.gravity, b.load))
        for w in b.wheels:
            springs.append(_spring(b.primary_stiffness, b.primary_damping, j,
                                   veh.positions[w] - b.centre, lower_wheel=w))
    if veh.car is not None:
        c, jc = veh.car, len(veh.bogies)
        bodies.append(_body(c.mass, c.pitch_inertia, scene.gravity, 0.0))
        for j, b in enumerate(veh.bogies):
            springs.append(_spring(c.secondary_stiffness, c.secondary_damping, jc,
                                   b.centre - c.centre, lower_body=j))
    vp.bodies = bodies
    vp.suspensions = springs
    return vp


def _body(mass, inertia, gravity, load):
    b = _core.BodyParams()
    # a body that cannot pitch (inertia None: every spring under its centre) takes M x 1 m^2:
    # no moment acts on it, so its pitch stays 0 whatever the value (the kernel needs one > 0)
    b.mass, b.gravity, b.load = mass, gravity, load
    b.inertia = mass * 1.0 if inertia is None else inertia
    return b


def _spring(k, c, upper, upper_arm, *, lower_wheel=-1, lower_body=-1):
    s = _core.SuspensionParams()
    s.stiffness, s.damping = k, c
    s.upper_body, s.upper_arm = upper, upper_arm
    s.lower_wheel, s.lower_body, s.lower_arm = lower_wheel, lower_body, 0.0
    return s


def contact_params(scene: Scene) -> _core.ContactParams:
    c = scene.contact
    p = _core.ContactParams()
    if c.law == "linear":
        p.law = _core.ContactLaw.linear
        p.stiffness = scene.contact_stiffness
    else:
        p.law = _core.ContactLaw.hertz
        p.stiffness = c.stiffness if c.stiffness is not None else scene.hertz_constant
    p.damping = c.damping
    p.radius = scene.wheel.radius
    p.friction = c.friction
    p.element_compliance = element_compliance(scene)
    return p


def element_compliance(scene: Scene) -> bool:
    """``Contact.element_compliance`` resolved: None is on for the Timoshenko rail, off for the
    Euler-Bernoulli one."""
    c = scene.contact.element_compliance
    return scene.rail.beam == "timoshenko" if c is None else bool(c)


class VehicleMatrices(NamedTuple):
    """The vehicle's constant matrices over u = [Y per wheel, (z, phi) per body]."""

    K: np.ndarray  #: K_v = sum k g g^T over the suspensions [N/m, N, N m]
    C: np.ndarray  #: C_v = sum c g g^T [N s/m, ...]
    mass: np.ndarray  #: the mass matrix's diagonal: wheels', bodies' masses [kg], inertias [kg m^2]


def vehicle_matrices(scene: Scene) -> VehicleMatrices:
    """(K_v, C_v, mass diagonal) of the scene's vehicle over u = [Y per wheel, (z, phi) per
    body], from the kernel (``vehicle.hpp``: K_v = sum k g g^T and C_v = sum c g g^T over the
    suspensions, g the gradient of a suspension's extension; the bodies' masses and pitch
    inertias), with the wheels' masses on the wheels' entries (the kernel keeps those with the
    wheels)."""
    veh = scene.active_vehicle
    vm = _core.vehicle_matrices(vehicle_params(scene), veh.n_wheels)
    mass = np.asarray(vm["mass"], dtype=float).copy()
    mass[:veh.n_wheels] = [w.mass for w in veh.wheels]
    return VehicleMatrices(np.asarray(vm["K"]), np.asarray(vm["C"]), mass)


def static_bodies(scene: Scene, y_wheels, gravity: float | None = None) -> np.ndarray:
    """[z_0, phi_0, z_1, phi_1, ...] [m, rad] of the vehicle's bodies (the bogies, then the car
    body) in static equilibrium above wheel centres held at heights ``y_wheels`` [m], from the
    kernel: the bodies' rows of K_v u = -G, each spring compressed by its static force (z = 0
    where every spring is unstretched). ``gravity`` [m/s^2] on the bodies (None: the scene's;
    0: only the bogies' constant pivot loads act); empty without bodies."""
    vp = vehicle_params(scene)
    if gravity is not None:
        bodies = list(vp.bodies)
        for b in bodies:
            b.gravity = gravity
        vp.bodies = bodies
    return np.asarray(_core.static_bodies(vp, np.asarray(y_wheels, dtype=float)))
