"""Time simulation of the wheel rolling over the flexible rail (docs: Model § Wheel, § Contact, § Rolling and slip, § Equations of motion, § Outputs).

:func:`simulate` runs in four stages, one function each: resolve the arguments (validation,
defaults from :mod:`trackwheel.defaults`, the scene rewritten for the fidelity level) into a
:class:`RunPlan`; build the kernel's settings; run the kernel (the whole time loop in C++ with
the GIL released, progress and Ctrl-C through a callback); wrap its output as a
:class:`~trackwheel.results.Result`.
"""

from __future__ import annotations

import dataclasses as dc
import math
import time as _time
from dataclasses import dataclass

import numpy as np

from . import _core, _kernel
from . import _validate as v
from ._errors import DivergenceError
from .defaults import (
    check_speed,
    default_end,
    default_start,
    derived_dt,
    derived_mesh,
    explicit_limit,
    start_position,
    warn_above_stability_limit,
    warn_unresolved_mesh,
)
from .results import Result, RunSettings, result_from_kernel, sample_bytes
from .scene import MAX_ELEMENTS, Scene
from .vehicle import static_bodies

__all__ = [
    "FIDELITY_LEVELS",
    "MAX_OUTPUT_BYTES",
    "DivergenceError",
    "Result",
    "RunSettings",
    "simulate",
]

#: Model fidelity levels, most to least detailed (issue 7). "full" is the paper's model: the
#: nonlinear ANCF rail, the scene's contact law, contact-point search with obliquity, the rolling
#: constraint with slip. "ancf/sprung" and "ancf/hertz" force the contact law. The "linear/..."
#: levels use the linear rail with constant matrices (factorised once, or modal with ``n_modes``)
#: and a vertical contact at X_A: a moving force P, a moving mass (rigid contact), a sprung wheel
#: (linear bilateral contact spring k) or a Hertzian wheel (unilateral). Every level takes the
#: scene's beam theory: ``Rail(beam="timoshenko")`` is the shear-deformable ANCF rail on the
#: "full" and "ancf/..." levels and the linear Timoshenko beam on the "linear/..." ones.
FIDELITY_LEVELS = ("full", "ancf/sprung", "ancf/hertz", "linear/hertz", "linear/sprung",
                   "linear/moving_mass", "linear/moving_force")

#: Output arrays larger than this raise before the run starts [bytes].
MAX_OUTPUT_BYTES = 2 * 1024**3
#: Default number of kept samples: output_every is chosen so that at most this many are kept.
DEFAULT_MAX_SAMPLES = 100_000
#: Most time steps one run may take [-] (10^12: far beyond any practical run; keeps the step and
#: decimation counts inside the kernel's integer types).
MAX_STEPS = 10**12
#: Target wall time between progress callbacks [s]. The callback is where the kernel checks for
#: Ctrl-C, so this bounds the interruption latency; the interval in steps comes from a
#: conservative cost estimate of _STEP_COST_PER_ELEMENT seconds per rail element and step (the
#: measured costs are 1.6-3.4 us per element and step for generalized-alpha and explicit RK4).
_PROGRESS_INTERVAL = 0.05
_STEP_COST_PER_ELEMENT = 4e-6

_INTEGRATORS = {"generalized_alpha": _core.Integrator.generalized_alpha,
                "explicit": _core.Integrator.explicit}


@dataclass(frozen=True)
class RunPlan:
    """A resolved run: everything the kernel needs, and the settings the Result reports."""

    scene: Scene  #: the scene, its contact law replaced for the "*/sprung", "*/hertz" levels
    settings: RunSettings
    model: object  #: _core.RailModel of the scene on settings.n_elements
    init: object  #: _core.SimState at the start (None for the linear levels)
    n_steps: int
    energy: bool  #: record the total mechanical energy
    max_newton: int
    newton_tol: float  #: [m]
    rolling: bool  #: the rolling flag as given (the linear kernel path has no constraint)
    window: object = None  #: _core.WindowParams of a travelling window, or None

    @property
    def linear(self) -> bool:
        return self.settings.fidelity.startswith("linear/")


def _with_law(scene: Scene, law: str) -> Scene:
    """The scene with its contact law replaced; stiffness None takes the Hertz values."""
    if scene.contact.law == law:
        return scene
    k = scene.contact_stiffness if law == "linear" else None
    if law == "hertz" and scene.contact.stiffness is not None:
        # a given linear k becomes the Hertz constant with the same stiffness at the static load
        k = (scene.contact.stiffness / (1.5 * scene.static_load ** (1 / 3))) ** 1.5
    return dc.replace(scene, contact=dc.replace(scene.contact, law=law, stiffness=k))


def _scene_for(scene: Scene, fidelity: str) -> Scene:
    if fidelity in ("ancf/sprung", "linear/sprung"):
        return _with_law(scene, "linear")
    if fidelity in ("ancf/hertz", "linear/hertz"):
        return _with_law(scene, "hertz")
    return scene


def _vehicle_initial_state(scene, model, speed, x_start, start, drop_height):
    """The start of a vehicle run: "static" solves the rail under every wheel's static load of
    the weight distribution at once, then sets each body where its springs carry those loads;
    "sudden" puts every wheel just touching the rail under its own weight and the bodies with
    every spring unstretched (the vehicle falls onto the track)."""
    veh = scene.active_vehicle
    contact = _kernel.contact_params(scene)
    xs = [x_start + x for x in veh.positions]
    if start == "static":
        contacts = []
        for w in veh.wheels:
            c = _kernel.contact_params(scene)
            c.radius = w.radius + sum(d.delta_rho(0.0, w.radius) for d in w.defects)
            contacts.append(c)
        sols = _core.static_solve_wheels(model, _kernel.static_wheels_params(scene), contacts, xs)
        e = np.asarray(sols[0]["e"])
        ys = [d["y_wheel"] + drop_height for d in sols]
        body = static_bodies(veh, scene.gravity, ys)  # lifted with the wheels by drop_height
    else:
        e = np.asarray(_core.rail_static(model))
        y_rail = model.positions(e, xs)[:, 1]
        ys = [y + w.radius + drop_height for y, w in zip(y_rail, veh.wheels)]
        body = static_bodies(veh, 0.0, ys)
    states = []
    for x, y, w in zip(xs, ys, veh.wheels):
        contact.radius = w.radius
        c = _core.contact_eval(model, e, x, y, x, contact, np.zeros(10))
        ws = _core.WheelState()
        ws.y, ws.ydot, ws.theta = y, 0.0, 0.0
        ws.thetadot = float(c["tangent"][0]) * speed / c["rho"]  # pure rolling at the start
        ws.s = c["s"]
        ws.state = _core.SlipState.stick if c["active"] else _core.SlipState.free
        states.append(ws)
    st = _core.SimState()
    st.e = e
    st.edot = np.zeros_like(e)
    st.wheels = states
    st.body = np.asarray(body, dtype=float)
    st.bodydot = np.zeros(len(body))
    return st


def _initial_state(scene, model, speed, x_start, start, drop_height):
    if scene.vehicle is not None:
        return _vehicle_initial_state(scene, model, speed, x_start, start, drop_height)
    wheel = _kernel.wheel_params(scene)
    contact = _kernel.contact_params(scene)
    # an out-of-round wheel starts at theta = 0, touching with its radius rho0 + Delta rho(0)
    contact.radius += _kernel.radius_change_at_start(scene)
    st = _core.SimState()
    if start == "static":
        d = _core.static_solve(model, wheel, contact, x_start)
        e, y = np.asarray(d["e"]), d["y_wheel"] + drop_height
    else:  # sudden: rail under its own weight, wheel just touching (or drop_height above)
        e = np.asarray(_core.rail_static(model))
        y_rail = model.positions(e, [x_start])[0, 1]
        y = y_rail + contact.radius + drop_height
    c = _core.contact_eval(model, e, x_start, y, x_start, contact, np.zeros(10))
    w = _core.WheelState()
    w.y = y
    w.ydot = 0.0
    w.theta = 0.0
    # pure rolling at the start: t . V_A = rho thetadot
    w.thetadot = float(c["tangent"][0]) * speed / c["rho"]
    w.s = c["s"]
    w.state = _core.SlipState.stick if c["active"] else _core.SlipState.free
    st.e = e
    st.edot = np.zeros_like(e)
    st.wheels = [w]  # a copy in the binding: assign the whole list
    return st


def simulate(scene: Scene, speed: float, *, integrator: str = "generalized_alpha",
             dt: float | None = None, n_elements: int | None = None,
             x_start: float | None = None, x_end: float | None = None,
             duration: float | None = None, output_every: int | None = None,
             rho_inf: float = 0.8, baumgarte: float = 0.0, rolling: bool = True,
             start: str = "static", drop_height: float = 0.0,
             progress: bool | None = None, energy: bool = False,
             fidelity: str = "full", n_modes: int | None = None, max_newton: int = 25,
             newton_tol: float = 1e-11, distance: float | None = None) -> Result:
    """Simulate the wheel passing over the rail at constant forward ``speed`` [m/s].

    Parameters
    ----------
    scene : Scene
    speed : forward speed 0 <= v <= ``defaults.MAX_SPEED`` (300) [m/s]
        (``trackwheel.kmh(300)`` converts from km/h).
    integrator : "generalized_alpha" (default; Chung-Hulbert/Arnold-Bruls, Newton on the analytic
        Jacobian, velocity-level rolling constraint) or "explicit" (the paper's way: acceleration
        -level constraint, classical RK4, optional Baumgarte stabilisation).
    dt : time step [s]; default derived from the scene, ``trackwheel.default_settings``: 150
        steps per period of the wheel on its contact spring (4.96e-6 s for the paper's scene;
        explicit: also at most half the predicted stability limit), the same at every
        fidelity level. An explicit dt above the predicted stability limit
        warns (``trackwheel.StabilityWarning``) before the run.
    n_elements : rail elements; default: with dt also unset, derived from the scene (8 per
        support bay, at least ``scene.rail.n_elements``: 80 for the paper's scene), which keeps
        the amplitude within 1 % of a refined run at 50-400 km/h (benchmarks/README.md); with
        dt given, ``scene.rail.n_elements``. The same at every fidelity level. Fewer elements
        than support bays warn (``trackwheel.MeshWarning``).
    x_start, x_end : wheel-centre start and end [m]; default the middle of the first support bay
        and the middle of the last (``trackwheel.defaults.default_start`` / ``default_end``:
        0.25 m and 4.75 m for the paper's scene). With ``speed = 0``
        give ``duration`` instead of ``x_end``. With a ``scene.vehicle`` they place the
        vehicle's reference point (x = 0 of ``Vehicle.positions``; every wheel must stay on the
        rail): by default its rear wheel starts in the middle of the first support bay and its
        leading wheel ends in the middle of the last. Its start ("static") is the whole
        vehicle's static state (docs: Model § The vehicle).
    duration : simulated time [s] (overrides ``x_end``).
    distance : distance run [m], ``x_end = x_start + distance`` (give one of ``x_end``,
        ``distance``, ``duration``). On a travelling window (``scene.window``,
        docs: Model § The travelling window) ``x_end`` and ``distance`` are not bounded by the
        rail: kilometres cost the same per metre and keep only the decimated samples in
        memory; there the default run is one window length, and every wheel starts at X >= 0
        (default: the rear wheel in the middle of the first bay). The window runs at every
        fidelity level (the full model with either integrator; the linear levels with all
        coordinates, ``n_modes = None``); ``x_wheel`` and ``contact_s`` stay in the track
        coordinate X.
    output_every : keep every n-th step; default: all steps up to 100 000 samples, decimated
        beyond.
    rho_inf : generalized-alpha spectral radius at infinite frequency, in [0, 1] (1: no numerical
        damping, energy-conserving trapezoidal rule for linear problems).
    baumgarte : explicit only, Baumgarte alpha [1/s] for g' + alpha g = 0 (0 = off, the paper's).
    rolling : True: rolling constraint with slip judgement (mu = scene.contact.friction); False:
        frictionless contact (no tangential force).
    start : "static" (static equilibrium at x_start, the paper's start) or "sudden" (rail under its
        own weight, wheel just touching: a sudden load).
    drop_height : lift the wheel this much above its start height [m] (it falls and lands).
    progress : show a progress bar (None: for runs estimated to take more than a few seconds).
    fidelity : model level, one of ``FIDELITY_LEVELS`` (default "full": the paper's model).
        The "linear/..." levels run the constant-matrix fast path (generalized-alpha only; no
        rolling constraint: ``tangential_force``, ``slip``, ``v_error`` are zero and
        ``contact_s = x_wheel``).
    n_modes : "linear/..." levels only: modal superposition with the lowest ``n_modes`` vertical
        rail modes (None: all coordinates, the band matrix factorised once).
    energy : also record the total mechanical energy [J] per sample: kinetic + strain + support
        springs + contact potential + potentials of gravity on the rail, of the wheel load
        (F + M g) Y_A and of the torque (-T theta). Conserved without damping when the wheel does
        not move forward (the driving reaction does work when it does); sliding friction
        (lambda times the slip velocity) and a brake (-T_b |theta'| while it turns) dissipate.

    Raises
    ------
    DivergenceError : the solution diverged; carries ``time``, ``step`` and ``cause``.
    ValueError, TypeError : bad arguments, naming the parameter and the allowed range.
    """
    plan = resolve(scene, speed, integrator=integrator, dt=dt, n_elements=n_elements,
                   x_start=x_start, x_end=x_end, duration=duration, output_every=output_every,
                   rho_inf=rho_inf, baumgarte=baumgarte, rolling=rolling, start=start,
                   drop_height=drop_height, energy=energy, fidelity=fidelity, n_modes=n_modes,
                   max_newton=max_newton, newton_tol=newton_tol, distance=distance)
    show = None if progress is None else v.boolean("progress", progress)
    out, wall = _run(plan, kernel_settings(plan), show)
    return result_from_kernel(out, plan.scene, plan.settings, wall, plan.energy)


def _check_fidelity(fidelity, integrator: str, n_modes, ne: int):
    """(fidelity, n_modes) checked against each other, the integrator and the mesh."""
    v.choice("fidelity", fidelity, set(FIDELITY_LEVELS))
    linear = fidelity.startswith("linear/")
    if linear and integrator != "generalized_alpha":
        raise ValueError(f"integrator = {integrator!r} is not available with fidelity = "
                         f"{fidelity!r}; the linear levels use 'generalized_alpha'")
    if n_modes is not None:
        if not linear:
            raise ValueError(f"n_modes is only used with the linear fidelity levels, not "
                             f"{fidelity!r}")
        n_modes = v.integer("n_modes", n_modes, low=1, high=2 * (ne + 1) - 2)
    return fidelity, n_modes


def _end_of(x0: float, x_end, distance):
    """``x_end``, or ``x0 + distance`` [m] from the resolved start ``x0`` (one of them)."""
    if distance is None:
        return x_end
    if x_end is not None:
        raise ValueError("give x_end or distance, not both")
    return x0 + v.number("distance", distance, low=0.0, low_open=True, unit="m")


def _window_passage(scene: Scene, speed: float, x_start, x_end, duration, distance):
    """(X_0, time) on a travelling window: the track is unbounded ahead, X >= 0 for every
    wheel; default start: the rear wheel in the middle of the first bay; default end: one
    window length on."""
    rear, _ = scene.active_vehicle.span
    lo = -rear
    x0 = 0.5 * scene.supports.spacing - rear if x_start is None else v.number(
        "x_start", x_start, low=lo, unit="m")
    if duration is not None:
        return x0, v.number("duration", duration, low=0.0, low_open=True, unit="s")
    if speed == 0.0:
        raise ValueError("speed = 0: give duration [s] (x_end cannot be reached)")
    if distance is not None:
        x1 = x0 + v.number("distance", distance, low=0.0, low_open=True, unit="m")
        if x_end is not None:
            raise ValueError("give x_end or distance, not both")
    else:
        x1 = x0 + scene.rail.length if x_end is None else v.number(
            "x_end", x_end, low=lo, unit="m")
    if x1 <= x0:
        raise ValueError(f"x_end = {x1} m must be greater than x_start = {x0} m")
    return x0, (x1 - x0) / speed


def window_params(scene: Scene, ne: int, x0: float):
    """The kernel's window for a run of ``scene`` on ``ne`` elements from X_0 = ``x0``: the
    rear wheel held in the bay after ``bays_behind`` bays; the origin a whole number of bays,
    so the supports stand where they stand on a fixed rail from X = 0."""
    w, d = scene.window, scene.supports.spacing
    rear, _ = scene.active_vehicle.span
    n_bays = round(scene.rail.length / d)
    if ne % n_bays:
        raise ValueError(f"n_elements = {ne} must be a multiple of the window's {n_bays} bays "
                         "(a whole number of elements per bay)")
    p = _core.WindowParams()
    p.bay = d
    p.elements_per_bay = ne // n_bays
    p.hold = (w.bays_behind + 1) * d
    p.origin = (math.floor((x0 + rear) / d + 1e-9) - w.bays_behind) * d
    return p


def _passage(scene: Scene, speed: float, x_start, x_end, duration,
             distance=None) -> tuple[float, float]:
    """(X_0 [m], simulated time [s]) from the start and either the end, the distance or the
    duration."""
    if scene.window is not None:
        return _window_passage(scene, speed, x_start, x_end, duration, distance)
    L = scene.rail.length
    rear, front = scene.active_vehicle.span
    if distance is not None:
        x_end = _end_of(start_position(scene, x_start) if scene.vehicle is None else (
            default_start(scene) - rear if x_start is None else x_start), x_end, distance)
    if scene.vehicle is not None:
        return _vehicle_passage(scene, speed, x_start, x_end, duration, rear, front)
    x0 = start_position(scene, x_start)
    x1 = default_end(scene, x0) if x_end is None and duration is None else x_end
    return x0, _time_to_end(scene, speed, x0, x1, duration, (0.0, L), 0.0)


def _vehicle_passage(scene: Scene, speed: float, x_start, x_end, duration, rear: float,
                     front: float) -> tuple[float, float]:
    """(X_0, time) for a vehicle: X_0 places its reference point (x = 0); every wheel must stay
    on the rail. Defaults: the rear wheel starts in the middle of the first support bay, the
    leading wheel ends in the middle of the last."""
    L = scene.rail.length
    lo, hi = -rear, L - front
    if hi < lo:
        raise ValueError(f"the vehicle's wheels span {front - rear:.4g} m, longer than the "
                         f"rail ({L} m): lengthen Scene.rail.length")
    x0 = default_start(scene) - rear if x_start is None else v.number(
        "x_start", x_start, low=lo, high=hi, unit="m")
    x1 = (max(default_end(scene, x0 + front) - front, x0)
          if x_end is None and duration is None else x_end)
    return x0, _time_to_end(scene, speed, x0, x1, duration, (lo, hi), front)


def _time_to_end(scene: Scene, speed: float, x0: float, x_end, duration,
                 allowed: tuple[float, float], front: float) -> float:
    """Simulated time [s] from X_0 = ``x0`` to ``x_end`` (validated in ``allowed`` [m]) or for
    ``duration`` [s], checking that the leading wheel, ``front`` [m] ahead of X_0, stays on
    the rail."""
    lo, hi = allowed
    L, who = scene.rail.length, "wheel" if scene.vehicle is None else "leading wheel"
    if duration is not None:
        t_end = v.number("duration", duration, low=0.0, low_open=True, unit="s")
        if x0 + speed * t_end > hi:
            raise ValueError(f"duration = {duration} s takes the {who} to X = "
                             f"{x0 + front + speed * t_end:.4g} m, beyond the rail end {L} m")
        return t_end
    if speed == 0.0:
        raise ValueError("speed = 0: give duration [s] (x_end cannot be reached)")
    x1 = v.number("x_end", x_end, low=lo, high=hi, unit="m")
    if x1 <= x0:
        room = ("" if scene.vehicle is None else " (the rail leaves the vehicle no room to "
                f"move; allowed x range [{lo:.4g}, {hi:.4g}] m)")
        raise ValueError(f"x_end = {x1} m must be greater than x_start = {x0} m{room}")
    return (x1 - x0) / speed


def _time_step(scene: Scene, dt, integrator: str, linear: bool, model, init, x0: float) -> float:
    """The time step [s]: ``dt`` checked, or the derived default (explicit: at most half the
    predicted stability limit). An explicit ``dt`` above the limit warns before the run."""
    explicit = integrator == "explicit" and not linear
    wheel, contact = _kernel.wheel_params(scene), _kernel.contact_params(scene)
    if dt is None:
        dt = derived_dt(scene)
        if explicit:
            dt = min(dt, 0.5 * explicit_limit(model, wheel, contact, init.e, x0,
                                              init.wheels[0].y)[0])
        return dt
    dt = v.number("dt", dt, low=0.0, low_open=True, high=1.0, unit="s")
    if explicit:  # issue 6: warn before a doomed run (stack: here, resolve, simulate, caller)
        warn_above_stability_limit(model, wheel, contact, init.e, x0, init.wheels[0].y, dt,
                                   stacklevel=5)
    return dt


def _steps(dt: float, t_end: float, dt_default: bool) -> int:
    n_steps = round(t_end / dt)
    if n_steps < 1:
        raise ValueError(f"dt = {dt} s ({'default' if dt_default else 'given'}) is longer than "
                         f"the simulated time {t_end:.6g} s; allowed range (0, {t_end:.6g}] s")
    if n_steps > MAX_STEPS:
        raise ValueError(f"dt = {dt} s takes {n_steps:.3g} steps to cover {t_end:.6g} s, above "
                         f"the limit of {MAX_STEPS:.0e} steps; allowed range "
                         f"[{t_end / MAX_STEPS:.3g}, {t_end:.6g}] s")
    return n_steps


def _output_every(output_every, n_steps: int, energy: bool) -> int:
    """``output_every`` checked (default: at most DEFAULT_MAX_SAMPLES samples) against the
    output size limit MAX_OUTPUT_BYTES (the sample size from the kernel's output table)."""
    if output_every is None:
        output_every = max(1, math.ceil(n_steps / DEFAULT_MAX_SAMPLES))
    output_every = v.integer("output_every", output_every, low=1, high=2**31 - 1)
    n_samples = n_steps // output_every + 1
    per_sample = sample_bytes(energy)
    if n_samples * per_sample > MAX_OUTPUT_BYTES:
        raise ValueError(
            f"output_every = {output_every} keeps {n_samples} samples "
            f"({n_samples * per_sample / 2**30:.1f} GiB), above the limit of "
            f"{MAX_OUTPUT_BYTES / 2**30:.0f} GiB: increase output_every to at least "
            f"{math.ceil(n_steps * per_sample / MAX_OUTPUT_BYTES)}")
    return output_every


def resolve(scene: Scene, speed: float, *, integrator, dt, n_elements, x_start, x_end, duration,
            output_every, rho_inf, baumgarte, rolling, start, drop_height, energy, fidelity,
            n_modes, max_newton, newton_tol, distance=None) -> RunPlan:
    """Validate the arguments of :func:`simulate`, resolve its defaults (the same derived mesh
    and step at every fidelity level) and rewrite the scene for the fidelity level."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    speed = check_speed(speed)
    v.choice("integrator", integrator, set(_INTEGRATORS))
    v.choice("start", start, {"static", "sudden"})
    ne = (derived_mesh(scene) if dt is None else scene.rail.n_elements) if n_elements is None \
        else v.integer("n_elements", n_elements, low=1, high=MAX_ELEMENTS)
    x0, t_end = _passage(scene, speed, x_start, x_end, duration, distance)
    rho_inf = v.number("rho_inf", rho_inf, low=0.0, high=1.0)
    baumgarte = v.number("baumgarte", baumgarte, low=0.0, unit="1/s")
    drop_height = v.number("drop_height", drop_height, low=0.0, high=scene.wheel.radius,
                           unit="m")
    max_newton = v.integer("max_newton", max_newton, low=1, high=1000)
    newton_tol = v.number("newton_tol", newton_tol, low=0.0, low_open=True, unit="m")
    if not isinstance(rolling, bool):
        raise TypeError("rolling must be True or False")
    fidelity, n_modes = _check_fidelity(fidelity, integrator, n_modes, ne)
    if fidelity == "linear/moving_force" and scene.active_vehicle.n_bodies:
        raise ValueError("fidelity = 'linear/moving_force' has no wheel dynamics, so no "
                         "suspension; a vehicle with bogies or a car body needs one of "
                         "'linear/moving_mass', 'linear/sprung', 'linear/hertz', 'ancf/...', "
                         "'full'")
    linear = fidelity.startswith("linear/")
    if linear and any(w.brake_torque > 0.0 for w in scene.active_vehicle.wheels):
        # the linear levels have no wheel rotation (a defect sits at theta = v t / rho0)
        raise ValueError(f"Wheel.brake_torque > 0 needs the wheel's rotation, which fidelity = "
                         f"{fidelity!r} does not model; use 'full', 'ancf/sprung' or "
                         f"'ancf/hertz'")
    if scene.window is not None and n_modes is not None:
        raise ValueError("Scene.window needs all coordinates: n_modes = None")
    energy = v.boolean("energy", energy)
    warn_unresolved_mesh(scene, ne, stacklevel=4)  # here, resolve, simulate, the caller
    scene = _scene_for(scene, fidelity)
    window = None if scene.window is None else window_params(scene, ne, x0)
    profile_end = None if window is None else (
        x0 + speed * t_end + scene.active_vehicle.span[1] + scene.rail.length)
    # the full path reads the profile in the rail coordinate s = X - X_w of the start window
    # (the kernel shifts it as the window travels); the linear path reads it at X
    s0 = 0.0 if window is None or linear else window.origin
    model = _kernel.rail_model(scene, ne, profile_end, s0)
    init = None if linear else _initial_state(scene, model, speed, x0 - s0, start, drop_height)
    h = _time_step(scene, dt, integrator, linear, model, init, x0 - s0)
    n_steps = _steps(h, t_end, dt is None)
    output_every = _output_every(output_every, n_steps, energy)
    settings = RunSettings(
        integrator=integrator, dt=h, n_elements=ne, speed=speed, x_start=x0,
        t_end=n_steps * h, output_every=output_every, rho_inf=rho_inf, baumgarte=baumgarte,
        rolling=rolling and not linear, start=start, drop_height=drop_height, fidelity=fidelity,
        n_modes=n_modes)
    return RunPlan(scene=scene, settings=settings, model=model, init=init, n_steps=n_steps,
                   energy=energy, max_newton=max_newton, newton_tol=newton_tol,
                   rolling=rolling, window=window)


def kernel_settings(plan: RunPlan) -> _core.SimSettings:
    """The kernel's settings struct for ``plan`` (progress_every is set by the runner)."""
    st = plan.settings
    s = _core.SimSettings()
    s.integrator = _INTEGRATORS[st.integrator]
    s.speed = st.speed
    s.x_start = st.x_start
    s.t_end = st.t_end
    s.dt = st.dt
    s.rho_inf = st.rho_inf
    s.baumgarte = st.baumgarte
    s.rolling = plan.rolling
    s.output_every = st.output_every
    s.max_newton = plan.max_newton
    s.newton_tol = plan.newton_tol
    s.record_energy = plan.energy
    if plan.window is not None:
        s.window = plan.window
    return s


def _progress(plan: RunPlan, s, show: bool | None):
    """(callback, bar) for the kernel; sets ``s.progress_every``. The callback is where the
    kernel checks for Ctrl-C, so there is always one, about every _PROGRESS_INTERVAL seconds."""
    n_steps, ne = plan.n_steps, plan.settings.n_elements
    est = n_steps * _STEP_COST_PER_ELEMENT * (ne + 10)  # conservative wall-time estimate [s]
    every = max(1, min(20_000, int(_PROGRESS_INTERVAL / (_STEP_COST_PER_ELEMENT * (ne + 10)))))
    if not (est > 5.0 if show is None else show):
        s.progress_every = every
        return (lambda step, total: None), None
    from tqdm.auto import tqdm

    bar = tqdm(total=n_steps, unit="step", desc=f"simulate {plan.settings.speed * 3.6:.0f} km/h")
    s.progress_every = max(1, min(every, n_steps // 100 or 1))

    def callback(step, total):
        bar.update(step - bar.n)

    return callback, bar


def _run(plan: RunPlan, s, show: bool | None) -> tuple[dict, float]:
    """Run the kernel on ``plan`` with settings ``s``: (its output dict, wall time [s])."""
    callback, bar = _progress(plan, s, show)
    wheels, contact = _kernel.wheels_params(plan.scene), _kernel.contact_params(plan.scene)
    vehicle = _kernel.vehicle_params(plan.scene)
    t0 = _time.perf_counter()
    try:
        if plan.linear:
            opt = _core.LinearOptions()
            opt.wheel_model = getattr(_core.WheelModel, plan.settings.fidelity.split("/")[1])
            opt.n_modes = plan.settings.n_modes or 0
            opt.sudden = plan.settings.start == "sudden"
            opt.drop_height = plan.settings.drop_height
            opt.beam = _kernel.beam_params(plan.scene)
            out = _core.simulate_linear(plan.model, wheels, contact, s, opt, callback, vehicle)
        else:
            out = _core.simulate(plan.model, wheels, contact, s, plan.init, callback, vehicle)
    finally:
        if bar is not None:
            bar.close()
    return out, _time.perf_counter() - t0
