"""A run resolved before the kernel starts: the arguments of :func:`trackwheel.simulate`
validated, its defaults taken (the same derived mesh and time step at every fidelity level,
:mod:`.defaults`), the scene rewritten for the fidelity level, the rail model built and the
start state solved, as one :class:`RunPlan`.
"""

from __future__ import annotations

import dataclasses as dc
import math
from dataclasses import dataclass

from ..base import validate as v
from ..base.limits import MAX_OUTPUT_BYTES, MAX_STEPS
from ..base.units import check_speed_units
from ..scene import Scene
from . import kernel
from .defaults import (
    check_speed,
    derived_dt,
    derived_mesh,
    explicit_limit,
    warn_above_stability_limit,
    warn_unresolved_mesh,
)
from .passage import passage, window_params
from .results import RunSettings, sample_bytes
from .start import initial_state

#: The time-domain levels, most to least detailed. "full" is the paper's model: the
#: nonlinear ANCF rail, the scene's contact law, contact-point search with obliquity, the rolling
#: constraint with slip. "ancf/sprung" and "ancf/hertz" force the contact law. The "linear/..."
#: levels use the linear rail with constant matrices (factorised once, or modal with ``n_modes``)
#: and a vertical contact at X_A: a moving force P, a moving mass (rigid contact), a sprung wheel
#: (linear bilateral contact spring k) or a Hertzian wheel (unilateral). Every level takes the
#: scene's beam theory: ``Rail(beam="timoshenko")`` is the shear-deformable ANCF rail on the
#: "full" and "ancf/..." levels and the linear Timoshenko beam on the "linear/..." ones.
TIME_DOMAIN_LEVELS = ("full", "ancf/sprung", "ancf/hertz", "linear/hertz", "linear/sprung",
                      "linear/moving_mass", "linear/moving_force")
#: The least detailed level: the steady state of the linear levels' model on the infinite track
#: periodic in its bay, in the frequency domain (``trackwheel.periodic_response``, the scene's
#: contact law linearised: "linear/hertz" for a Hertzian contact, else "linear/sprung"). No
#: time history: ``simulate`` refuses it; ``adequacy`` and ``sweep`` run it.
PERIODIC_LEVEL = "periodic/linear"
#: Model fidelity levels, most to least detailed (docs: Model § The periodic level for the last)
FIDELITY_LEVELS = TIME_DOMAIN_LEVELS + (PERIODIC_LEVEL,)

#: Default number of kept samples: output_every is chosen so that at most this many are kept.
DEFAULT_MAX_SAMPLES = 100_000
#: The time integrators of the full model (the linear levels take "generalized_alpha").
INTEGRATORS = ("generalized_alpha", "explicit")


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
    #: record each support's forces per kept sample (a fixed rail)
    support_forces: bool = False

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
    try:
        return dc.replace(scene, contact=dc.replace(scene.contact, law=law, stiffness=k))
    except ValueError as exc:  # e.g. a stiff linear contact under a tiny load: a huge C_H
        raise ValueError(f"the fidelity level's {law} contact law from Contact(law="
                         f"{scene.contact.law!r}, stiffness={scene.contact.stiffness:g}) at the "
                         f"static load P = {scene.static_load:.4g} N: {exc}; give the scene a "
                         f"{law} Contact, or a fidelity level of its own law") from None


def _scene_for(scene: Scene, fidelity: str) -> Scene:
    if fidelity in ("ancf/sprung", "linear/sprung"):
        return _with_law(scene, "linear")
    if fidelity in ("ancf/hertz", "linear/hertz"):
        return _with_law(scene, "hertz")
    return scene


def _check_fidelity(fidelity, integrator: str, n_modes, ne: int):
    """(fidelity, n_modes) checked against each other, the integrator and the mesh."""
    if fidelity == PERIODIC_LEVEL:
        raise ValueError(
            f"fidelity = {PERIODIC_LEVEL!r} is the periodic level, a steady state in the "
            "frequency domain with no time history to simulate: use "
            "trackwheel.periodic_response(scene, speed) (or sweep/adequacy, which run it); "
            f"simulate's levels: {', '.join(TIME_DOMAIN_LEVELS)}")
    v.choice("fidelity", fidelity, set(TIME_DOMAIN_LEVELS))
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


def _time_step(scene: Scene, dt, integrator: str, linear: bool, model, init, x0: float) -> float:
    """The time step [s]: ``dt`` checked, or the derived default (explicit: at most half the
    predicted stability limit). An explicit ``dt`` above the limit warns before the run."""
    explicit = integrator == "explicit" and not linear
    wheel, contact = kernel.wheel_params(scene), kernel.contact_params(scene)
    if dt is None:
        dt = derived_dt(scene)
        if explicit:
            dt = min(dt, 0.5 * explicit_limit(model, wheel, contact, init.e, x0,
                                              init.wheels[0].y)[0])
        return dt
    dt = v.number("dt", dt, low=0.0, low_open=True, high=1.0, unit="s")
    if explicit:  # warn before a doomed run (stack: here, resolve, simulate, caller)
        warn_above_stability_limit(model, wheel, contact, init.e, x0, init.wheels[0].y, dt,
                                   stacklevel=5)
    return dt


def _steps(dt: float, t_end: float, dt_default: bool, speed: float, length: dict) -> int:
    """Steps of ``dt`` [s] over ``t_end`` [s]; ``length`` names the input that set the run's
    length ({"distance": m}, {"duration": s} or {"x_end": m}), which a too long run names when
    ``dt`` is the derived default."""
    n_steps = round(t_end / dt)
    if n_steps < 1:
        raise ValueError(f"dt = {dt} s ({'default' if dt_default else 'given'}) is longer than "
                         f"the simulated time {t_end:.6g} s; allowed range (0, {t_end:.6g}] s")
    if n_steps > MAX_STEPS:
        (name, value), = length.items()
        unit = "s" if name == "duration" else "m"
        # the run's length in the input's own terms at the step dt: time, or distance
        most = MAX_STEPS * dt * (1.0 if name == "duration" else speed)
        if name == "x_end":
            most += value - speed * t_end  # x_end - (run distance) is x_start
        if dt_default:
            raise ValueError(f"{name} = {value:.6g} {unit} takes {n_steps:.3g} steps of the "
                             f"derived dt = {dt:.3g} s ({t_end:.6g} s at {speed:g} m/s), above "
                             f"the limit of {MAX_STEPS:.0e} steps; allowed: {name} up to "
                             f"{most:.6g} {unit}")
        raise ValueError(f"dt = {dt} s takes {n_steps:.3g} steps to cover {t_end:.6g} s "
                         f"({name} = {value:.6g} {unit}), above the limit of {MAX_STEPS:.0e} "
                         f"steps; allowed range [{t_end / MAX_STEPS:.3g}, {t_end:.6g}] s (or "
                         f"{name} up to {most:.6g} {unit})")
    return n_steps


def _output_every(output_every, n_steps: int, energy: bool, n_supports: int = 0) -> int:
    """``output_every`` checked (default: at most DEFAULT_MAX_SAMPLES samples) against the
    output size limit MAX_OUTPUT_BYTES (the sample size from the kernel's output table, with
    the per-support fields of ``n_supports`` recorded supports)."""
    if output_every is None:
        output_every = max(1, math.ceil(n_steps / DEFAULT_MAX_SAMPLES))
    output_every = v.integer("output_every", output_every, low=1, high=2**31 - 1)
    n_samples = n_steps // output_every + 1
    per_sample = sample_bytes(energy, n_supports)
    if n_samples * per_sample > MAX_OUTPUT_BYTES:
        raise ValueError(
            f"output_every = {output_every} keeps {n_samples} samples "
            f"({n_samples * per_sample / 2**30:.1f} GiB), above the limit of "
            f"{MAX_OUTPUT_BYTES / 2**30:.0f} GiB: increase output_every to at least "
            f"{math.ceil(n_steps * per_sample / MAX_OUTPUT_BYTES)}")
    return output_every


def resolve(scene: Scene, speed: float, *, integrator, dt, n_elements, x_start, x_end, duration,
            output_every, rho_inf, baumgarte, rolling, start, drop_height, energy, fidelity,
            n_modes, max_newton, newton_tol, distance=None, support_forces=False) -> RunPlan:
    """Validate the arguments of :func:`simulate`, resolve its defaults (the same derived mesh
    and step at every fidelity level) and rewrite the scene for the fidelity level."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    speed = check_speed(speed)
    check_speed_units(speed, stacklevel=4)  # here, resolve, simulate, the caller
    v.choice("integrator", integrator, set(INTEGRATORS))
    v.choice("start", start, {"static", "sudden"})
    ne = (derived_mesh(scene) if dt is None else scene.rail.n_elements) if n_elements is None \
        else v.n_elements(n_elements)
    x0, t_end = passage(scene, speed, x_start, x_end, duration, distance)
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
    support_forces = v.boolean("support_forces", support_forces)
    if support_forces and scene.window is not None:
        raise ValueError("support_forces=True needs a fixed rail: on a travelling window the "
                         "supports change identity as it moves; each support's envelope along "
                         "the track is kept anyway (Result.sleeper_envelope())")
    warn_unresolved_mesh(scene, ne, stacklevel=4)  # here, resolve, simulate, the caller
    scene = _scene_for(scene, fidelity)
    window = None if scene.window is None else window_params(scene, ne, x0)
    profile_end = None if window is None else (
        x0 + speed * t_end + scene.active_vehicle.span[1] + scene.rail.length)
    # the full path reads the profile in the rail coordinate s = X - X_w of the start window
    # (the kernel shifts it as the window travels); the linear path reads it at X
    s0 = 0.0 if window is None or linear else window.origin
    # the track's supports along the run, streamed into the window (None: all alike); the
    # start window's rail has those at its place
    stream = None if window is None else kernel.support_stream(scene, window, speed * t_end)
    if stream is not None:
        window.supports = stream
    model = kernel.rail_model(scene, ne, profile_end, s0,
                              0.0 if stream is None else window.origin)
    init = None if linear else initial_state(scene, model, speed, x0 - s0, start, drop_height)
    h = _time_step(scene, dt, integrator, linear, model, init, x0 - s0)
    length = ({"duration": duration} if duration is not None else
              {"distance": distance} if distance is not None else {"x_end": x0 + speed * t_end})
    n_steps = _steps(h, t_end, dt is None, speed, length)
    output_every = _output_every(output_every, n_steps, energy,
                                 len(scene.support_positions) if support_forces else 0)
    settings = RunSettings(
        integrator=integrator, dt=h, n_elements=ne, speed=speed, x_start=x0,
        t_end=n_steps * h, output_every=output_every, rho_inf=rho_inf, baumgarte=baumgarte,
        rolling=rolling and not linear, start=start, drop_height=drop_height, fidelity=fidelity,
        n_modes=n_modes)
    return RunPlan(scene=scene, settings=settings, model=model, init=init, n_steps=n_steps,
                   energy=energy, max_newton=max_newton, newton_tol=newton_tol,
                   rolling=rolling, window=window, support_forces=support_forces)
