"""Time simulation of the wheel rolling over the flexible rail (docs: Model § Wheel, § Contact,
§ Rolling and slip, § Equations of motion, § Outputs).

:func:`simulate` runs in four stages: resolve the arguments (validation, defaults from
:mod:`.defaults`, the scene rewritten for the fidelity level, the start state) into a
:class:`~trackwheel.run.plan.RunPlan` (:mod:`.plan`); build the kernel's settings
(:func:`kernel_settings`); run the kernel (the whole time loop in C++ with the GIL released,
progress and Ctrl-C through a callback, :func:`run_kernel`); wrap its output as a
:class:`~trackwheel.Result` (:func:`~trackwheel.run.results.result_from_kernel`).

Two documented internal hooks split the call for benchmarks and tests that look at what the
kernel reads: :func:`plan_run` (the RunPlan ``simulate`` would run: its rail model
``plan.model``, whose ``profile`` is the kernel's rail profile) and :func:`execute` (run it).
"""

from __future__ import annotations

import inspect
import time as _time

from .. import _core
from ..base import validate as v
from ..base.errors import DivergenceError
from ..base.limits import MAX_OUTPUT_BYTES, MAX_STEPS
from ..scene import Scene
from . import kernel
from .plan import (
    DEFAULT_MAX_SAMPLES,
    FIDELITY_LEVELS,
    PERIODIC_LEVEL,
    TIME_DOMAIN_LEVELS,
    RunPlan,
    resolve,
)
from .results import Result, RunSettings, result_from_kernel

__all__ = [
    "DEFAULT_MAX_SAMPLES",
    "FIDELITY_LEVELS",
    "MAX_OUTPUT_BYTES",
    "MAX_STEPS",
    "PERIODIC_LEVEL",
    "TIME_DOMAIN_LEVELS",
    "DivergenceError",
    "Result",
    "RunPlan",
    "RunSettings",
    "execute",
    "kernel_settings",
    "plan_run",
    "simulate",
]

#: Target wall time between progress callbacks [s]. The callback is where the kernel checks for
#: Ctrl-C, so this bounds the interruption latency; the interval in steps comes from a
#: conservative cost estimate of _STEP_COST_PER_ELEMENT seconds per rail element and step (the
#: measured costs are 1.6-3.4 us per element and step for generalized-alpha and explicit RK4).
_PROGRESS_INTERVAL = 0.05
_STEP_COST_PER_ELEMENT = 4e-6


def simulate(scene: Scene, speed: float, *, integrator: str = "generalized_alpha",
             dt: float | None = None, n_elements: int | None = None,
             x_start: float | None = None, x_end: float | None = None,
             duration: float | None = None, output_every: int | None = None,
             rho_inf: float = 0.8, baumgarte: float = 0.0, rolling: bool = True,
             start: str = "static", drop_height: float = 0.0,
             progress: bool | None = None, energy: bool = False,
             fidelity: str = "full", n_modes: int | None = None, max_newton: int = 25,
             newton_tol: float = 1e-11, distance: float | None = None,
             support_forces: bool = False) -> Result:
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
    fidelity : model level, one of ``TIME_DOMAIN_LEVELS`` (default "full": the paper's model;
        ``FIDELITY_LEVELS``' last, "periodic/linear", has no time history and is refused:
        ``trackwheel.periodic_response``).
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
    support_forces : also record every support's rail-seat force, ballast force and sleeper
        displacement per kept sample, arrays (n_samples, n_supports) (``Result.ballast_force``
        etc., :data:`~trackwheel.run.results.SUPPORT_FIELDS`); a fixed rail only. Every run
        keeps each support's envelope along the track (``Result.sleeper_envelope()``), on a
        travelling window too.

    Raises
    ------
    DivergenceError : the solution diverged; carries ``time``, ``step`` and ``cause``.
    ValueError, TypeError : bad arguments, naming the parameter and the allowed range.
    """
    plan = resolve(scene, speed, integrator=integrator, dt=dt, n_elements=n_elements,
                   x_start=x_start, x_end=x_end, duration=duration, output_every=output_every,
                   rho_inf=rho_inf, baumgarte=baumgarte, rolling=rolling, start=start,
                   drop_height=drop_height, energy=energy, fidelity=fidelity, n_modes=n_modes,
                   max_newton=max_newton, newton_tol=newton_tol, distance=distance,
                   support_forces=support_forces)
    return execute(plan, progress)


#: simulate's keyword arguments and defaults, as :func:`plan_run` passes them to resolve
_RESOLVE_DEFAULTS = {name: p.default for name, p in inspect.signature(simulate).parameters.items()
                     if p.kind is inspect.Parameter.KEYWORD_ONLY and name != "progress"}


def plan_run(scene: Scene, speed: float, **kwargs) -> RunPlan:
    """The :class:`~trackwheel.run.plan.RunPlan` that ``simulate(scene, speed, **kwargs)``
    would run (``progress`` is not part of it): the resolved settings, the rail model
    ``plan.model`` (its ``profile``: the kernel's rail profile, whose streaming counters a
    benchmark reads after :func:`execute`) and the start state. A documented internal hook."""
    kwargs.pop("progress", None)
    unknown = sorted(set(kwargs) - set(_RESOLVE_DEFAULTS))
    if unknown:
        raise TypeError(f"plan_run got unknown simulate keyword(s) {unknown}")
    return resolve(scene, speed, **{**_RESOLVE_DEFAULTS, **kwargs})


def execute(plan: RunPlan, progress: bool | None = None) -> Result:
    """Run ``plan`` (from :func:`plan_run`) in the kernel and return its :class:`Result`;
    ``progress`` as in :func:`simulate`. A documented internal hook."""
    show = None if progress is None else v.boolean("progress", progress)
    out, wall = run_kernel(plan, kernel_settings(plan), show)
    return result_from_kernel(out, plan.scene, plan.settings, wall, plan.energy)


def kernel_settings(plan: RunPlan) -> _core.SimSettings:
    """The kernel's settings struct for ``plan`` (progress_every is set by the runner)."""
    st = plan.settings
    s = _core.SimSettings()
    s.integrator = getattr(_core.Integrator, st.integrator)
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
    s.record_supports = plan.support_forces
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


def run_kernel(plan: RunPlan, s, show: bool | None) -> tuple[dict, float]:
    """Run the kernel on ``plan`` with settings ``s`` (:func:`kernel_settings`): (its output
    dict, wall time [s])."""
    callback, bar = _progress(plan, s, show)
    wheels, contact = kernel.wheels_params(plan.scene), kernel.contact_params(plan.scene)
    vehicle = kernel.vehicle_params(plan.scene)
    t0 = _time.perf_counter()
    try:
        if plan.linear:
            opt = _core.LinearOptions()
            opt.wheel_model = getattr(_core.WheelModel, plan.settings.fidelity.split("/")[1])
            opt.n_modes = plan.settings.n_modes or 0
            opt.sudden = plan.settings.start == "sudden"
            opt.drop_height = plan.settings.drop_height
            opt.beam = kernel.beam_params(plan.scene)
            out = _core.simulate_linear(plan.model, wheels, contact, s, opt, callback, vehicle)
        else:
            out = _core.simulate(plan.model, wheels, contact, s, plan.init, callback, vehicle)
    finally:
        if bar is not None:
            bar.close()
    return out, _time.perf_counter() - t0
