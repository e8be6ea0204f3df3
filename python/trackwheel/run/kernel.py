"""Translate a :class:`~trackwheel.scene.Scene` into the C++ kernel's parameter structs.

The kernel's ``RailModel`` is immutable; it is built once per (scene, mesh) and cached.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from . import _core
from .scene import Scene

#: The kernel interpolates the rail profile by a cubic spline through samples X_i = i dx over
#: the whole rail, dx at most PROFILE_DX [m] and at most 1/PROFILE_POINTS_PER_WAVELENGTH of the
#: profile's shortest wavelength: the spline's error is ~(2 pi dx / lambda)^4 / 384 < 2e-6 of
#: the amplitude, and a joint's cusp is rounded over about 1 mm only.
PROFILE_DX = 1e-3
PROFILE_POINTS_PER_WAVELENGTH = 40
#: The wheel's out-of-roundness reaches the kernel the same way, as a periodic cubic spline
#: through samples every WHEEL_ARC_STEP [m] of its circumference (rounding a new flat's corners
#: over about that arc).
WHEEL_ARC_STEP = 5e-4
#: A rail profile of more than STREAM_MIN_CHUNKS spline chunks is streamed into the kernel,
#: which keeps its chunks STREAM_RETENTION [m] (or four vehicle spans) behind the furthest X
#: read (:func:`profile`).
STREAM_MIN_CHUNKS = 3
STREAM_RETENTION = 200.0


@lru_cache(maxsize=64)
def rail_model(scene: Scene, n_elements: int | None = None,
               profile_end: float | None = None, profile_shift: float = 0.0) -> _core.RailModel:
    """The kernel's rail of ``scene`` on ``n_elements`` (None: the scene's); its profile covers
    the track coordinates [0, ``profile_end``] [m] (None: the rail, [0, L]; a travelling
    window's run covers the track it passes), read at the rail's x = X - ``profile_shift``
    (the full path's travelling window: the start window's origin X_w [m])."""
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
    s = _core.SupportParams()
    pos = scene.support_positions
    s.position = list(pos)
    s.stiffness = [scene.supports.stiffness] * len(pos)
    s.damping = [scene.supports.damping] * len(pos)
    if scene.supports.layered:
        s.sleeper_mass = [scene.supports.sleeper_mass] * len(pos)
        s.ballast_stiffness = [scene.supports.ballast_stiffness] * len(pos)
        s.ballast_damping = [scene.supports.ballast_damping] * len(pos)
    return _core.RailModel(p, s, profile(scene, profile_end, profile_shift))


def beam_params(scene: Scene) -> _core.BeamParams:
    """The linear track's beam theory: Euler-Bernoulli (shear stiffness 0) or Timoshenko."""
    b = _core.BeamParams()
    if scene.rail.beam == "timoshenko":
        b.shear_stiffness = scene.rail.shear_stiffness
        b.rotary_inertia = scene.rail.rotary_inertia
    return b


def profile(scene: Scene, end: float | None = None, shift: float = 0.0) -> _core.Profile:
    """The scene's rail profile as the kernel's piecewise cubic over [0, L] (or [0, ``end``]
    [m]; none: empty), patch-filtered if ``scene.contact.patch_filter``, as a function of
    X - ``shift`` [m].

    A table of more than STREAM_MIN_CHUNKS chunks of SPLINE_CHUNK intervals (a travelling
    window's run over hundreds of metres) is streamed: the kernel draws its chunks as the
    vehicle advances and keeps those within :func:`stream_retention` behind the leading
    wheel, so its memory does not grow with the distance.

    Raises ValueError where the profile curves upwards more sharply than the wheel (r'' >=
    1/rho0, e.g. a dipped joint's cusp): the wheel would bridge the dip on two points, which
    the single contact point of the model cannot represent. A streamed profile raises it
    where the run reaches the chunk that holds the point.
    """
    irr = scene.irregularity
    if irr is None or not irr.parts:
        return _core.Profile()
    from . import irregularity

    dx = min(PROFILE_DX, irr.shortest_wavelength() / PROFILE_POINTS_PER_WAVELENGTH)
    end = scene.rail.length if end is None else end
    if scene.contact.patch_filter:
        x0, h, c, worst, at = _filtered_table(irr, end, dx, irregularity.contact_half_width(scene))
        _check_curvature(scene, worst, at)
        return _core.Profile(x0 - shift, h, c)
    x0, h, n = irr.spline_grid(0.0, end, dx)
    chunk = irregularity.SPLINE_CHUNK  # read here: tests shrink it

    def chunks():
        for _, c, worst, at in irr.spline_chunks(0.0, end, dx, chunk=chunk):
            _check_curvature(scene, worst, at)
            yield c
            del c  # the kernel has copied it

    if n - 1 > STREAM_MIN_CHUNKS * chunk:
        return _core.Profile(x0 - shift, h, n - 1, chunks, stream_retention(scene))
    # chunk by chunk into the kernel: no whole-table array in Python
    return _core.Profile(x0 - shift, h, n - 1, chunks())


def stream_retention(scene: Scene) -> float:
    """How far behind the furthest X read a streamed profile keeps its chunks [m]: the
    vehicle's span (its rear wheels read that far behind the leading one) four times over,
    at least STREAM_RETENTION; the contact point never moves back by more than a rail
    deflection's slope times the span."""
    behind, ahead = scene.active_vehicle.span
    return max(STREAM_RETENTION, 4.0 * (ahead - behind))


def _check_curvature(scene: Scene, worst: float, at: float) -> None:
    if worst >= 1.0 / scene.wheel.radius:
        raise ValueError(
            f"Scene.irregularity curves upwards by {worst:.3g} 1/m at X = {at:.4g} m, more "
            f"than the wheel's 1/rho0 = {1 / scene.wheel.radius:.3g} 1/m: the wheel would "
            "bridge it on two points, which one contact point cannot represent; allowed: "
            "r'' < 1/rho0 (round the profile, or set Contact(patch_filter=True) to average it "
            "over the contact patch)")


def _filtered_table(irr, end: float, dx: float, half_width: float):
    """:meth:`Irregularity.spline_table`'s tuple for the patch-filtered profile, the spline
    through all samples at once (the filter's running integral spans the whole table)."""
    from scipy.interpolate import CubicSpline

    x0, h, r = irr.table(0.0, end, dx, half_width=half_width)
    x = x0 + h * np.arange(r.size)
    spline = CubicSpline(x, r)
    curvature = spline(x, 2)
    worst = int(np.argmax(curvature))
    return x0, h, spline.c, float(curvature[worst]), float(x[worst])


def wheel_params(scene: Scene) -> _core.WheelParams:
    w = scene.wheel
    p = _core.WheelParams()
    p.mass = w.mass
    p.inertia = w.polar_inertia
    p.radius = w.radius
    p.load = w.load
    p.torque = w.torque
    p.brake_torque = w.brake_torque
    p.gravity = scene.gravity
    p.out_of_round = out_of_round(scene)
    return p


def wheels_params(scene: Scene) -> list:
    """One kernel WheelParams per wheel of the scene's vehicle, at its x_offset; a wheel under
    a bogie has no constant load (the suspension carries it). The single-wheel scene gives
    exactly ``[wheel_params(scene)]``."""
    veh = scene.active_vehicle
    if scene.vehicle is None:
        return [wheel_params(scene)]
    out = []
    for i, (w, x) in enumerate(zip(veh.wheels, veh.positions)):
        p = _core.WheelParams()
        p.mass = w.mass
        p.inertia = w.polar_inertia
        p.radius = w.radius
        p.load = 0.0 if veh.bogie_of(i) is not None else w.load
        p.torque = w.torque
        p.brake_torque = w.brake_torque
        p.gravity = scene.gravity
        p.x_offset = x
        p.out_of_round = _out_of_round(w.defects, w.radius)
        out.append(p)
    return out


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
    b.mass, b.inertia, b.gravity, b.load = mass, inertia, gravity, load
    return b


def _spring(k, c, upper, upper_arm, *, lower_wheel=-1, lower_body=-1):
    s = _core.SuspensionParams()
    s.stiffness, s.damping = k, c
    s.upper_body, s.upper_arm = upper, upper_arm
    s.lower_wheel, s.lower_body, s.lower_arm = lower_wheel, lower_body, 0.0
    return s


def out_of_round(scene: Scene) -> _core.Profile:
    """The wheel's defects summed as the kernel's periodic piecewise cubic Delta rho(psi) over
    one revolution (round wheel: empty)."""
    return _out_of_round(scene.wheel.defects, scene.wheel.radius)


@lru_cache(maxsize=64)
def _out_of_round(defects: tuple, rho0: float) -> _core.Profile:
    # cached: wheel_params is built several times per run (start, step, kernel call) and for
    # every static solve, and the spline is the same each time
    if not defects:
        return _core.Profile()
    from scipy.interpolate import CubicSpline

    n = max(64, math.ceil(2.0 * math.pi * rho0 / WHEEL_ARC_STEP))
    drho = sum(d.table(rho0, n)[2] for d in defects)
    psi = 2.0 * math.pi * np.arange(n + 1) / n
    spline = CubicSpline(psi, np.append(drho, drho[0]), bc_type="periodic")
    return _core.Profile(0.0, 2.0 * math.pi / n, spline.c)


def radius_change_at_start(scene: Scene) -> float:
    """Delta rho [m] at psi = 0, where the wheel stands at the start (theta = 0)."""
    return float(sum(d.delta_rho(0.0, scene.wheel.radius) for d in scene.wheel.defects))


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
    return p
