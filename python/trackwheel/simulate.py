"""Time simulation of the wheel rolling over the flexible rail (MODEL.md §3-§6, §8).

The whole time loop runs in the C++ kernel with the GIL released; Python only prepares the
initial state and wraps the output arrays.
"""

from __future__ import annotations

import dataclasses as dc
import math
import time as _time
from dataclasses import field

import numpy as np

from . import _core, _kernel
from . import _validate as v
from ._errors import DivergenceError
from .scene import MAX_ELEMENTS, Scene

__all__ = ["DivergenceError", "Result", "simulate", "DEFAULT_DT", "FIDELITY_LEVELS",
           "MAX_OUTPUT_BYTES"]

#: Model fidelity levels, most to least detailed (issue 7). "full" is the paper's model: the
#: nonlinear ANCF rail, the scene's contact law, contact-point search with obliquity, the rolling
#: constraint with slip. "ancf/sprung" and "ancf/hertz" force the contact law. The "linear/..."
#: levels use the linear Euler-Bernoulli rail with constant matrices (factorised once, or modal
#: with ``n_modes``) and a vertical contact at X_A: a moving force P, a moving mass (rigid
#: contact), a sprung wheel (linear bilateral contact spring k) or a Hertzian wheel (unilateral).
FIDELITY_LEVELS = ("full", "ancf/sprung", "ancf/hertz", "linear/hertz", "linear/sprung",
                   "linear/moving_mass", "linear/moving_force")

#: Default time steps [s]. Generalized-alpha: 1e-5 s resolves the highest physical frequency of
#: the paper's scene (the wheel on its contact spring, ~1.4 kHz) with ~70 steps per period;
#: explicit RK4: half its stability limit, at most 1e-6 s.
DEFAULT_DT = {"generalized_alpha": 1e-5, "explicit": 1e-6}
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

#: The kernel's output table, one row per recorded field: (name, unit, doc, per_wheel, dtype).
#: It defines Result's array fields (below) and the output-size estimate; adding an output is
#: one row in cpp/output.cpp.
OUTPUT_FIELDS: tuple[tuple[str, str, str, bool, str], ...] = tuple(
    tuple(f) for f in _core.OUTPUT_FIELDS)

_INTEGRATORS = {"generalized_alpha": _core.Integrator.generalized_alpha,
                "explicit": _core.Integrator.explicit}


class _ResultMethods:
    """Derived views of a :class:`Result`."""

    @property
    def in_contact(self) -> np.ndarray:
        """Boolean mask of samples with N > 0."""
        return self.normal_force > 0.0

    @property
    def lost_contact(self) -> bool:
        """True if the wheel left the rail at any kept sample."""
        return bool(np.any(~self.in_contact))

    def contact_free_intervals(self) -> list[tuple[float, float]]:
        """[(t_lift, t_land), ...] of the kept samples without contact [s]."""
        free = ~self.in_contact
        out = []
        i = 0
        n = len(free)
        while i < n:
            if free[i]:
                j = i
                while j + 1 < n and free[j + 1]:
                    j += 1
                out.append((float(self.t[i]), float(self.t[j])))
                i = j + 1
            else:
                i += 1
        return out


def _result_doc() -> str:
    lines = ["Output of :func:`simulate`, one entry per kept sample (every ``output_every`` steps).",
             "", "Array fields (from the kernel's output table ``OUTPUT_FIELDS``), each of shape",
             "(n_samples,), in SI units:", ""]
    for name, unit, doc, _per_wheel, dtype in OUTPUT_FIELDS:
        kind = "int" if dtype.startswith("int") else (f"[{unit}]" if unit else "[-]")
        lines.append(f"- ``{name}`` {kind}: {doc}")
    lines += ["", "``energy`` is None unless ``simulate(..., energy=True)``. Accelerations converge",
              "more slowly in dt than displacements with generalized-alpha (its algorithmic",
              "accelerations lag): ``acc_contact`` is about 5 % RMS off at 1e-5 s and 0.5 % at",
              "1e-6 s for the paper's scene at 300 km/h, so use dt <= 1e-6 s for Fig. 8-type",
              "acceleration studies.", "",
              "Other fields: ``scene``, ``settings`` (integrator, dt, n_elements, speed, x_start,",
              "...), ``steps``, ``newton_iterations`` (generalized-alpha), ``state_changes``",
              "(slip/contact switches), ``stability_limit`` (predicted explicit RK4 limit at the",
              "start) [s], ``wall_time`` [s], ``final_state`` (kernel state at the end, for",
              "restarts)."]
    return "\n".join(lines)


Result = dc.make_dataclass(
    "Result",
    [("scene", Scene), ("settings", dict),
     *[(f[0], "np.ndarray | None" if f[0] == "energy" else "np.ndarray") for f in OUTPUT_FIELDS],
     ("steps", int), ("newton_iterations", int), ("state_changes", int),
     ("stability_limit", float), ("wall_time", float),
     ("final_state", object, field(repr=False))],
    bases=(_ResultMethods,), frozen=True,
    namespace={"__doc__": _result_doc(), "__module__": __name__})


def _sample_bytes(energy: bool) -> int:
    """Bytes one kept sample of a one-wheel run takes, from the output table."""
    return sum(4 if dtype.startswith("int") else 8 for name, _u, _d, _w, dtype in OUTPUT_FIELDS
               if energy or name != "energy")


def _with_law(scene: Scene, law: str) -> Scene:
    """The scene with its contact law replaced; stiffness None takes the Hertz values."""
    if scene.contact.law == law:
        return scene
    k = scene.contact_stiffness if law == "linear" else None
    if law == "hertz" and scene.contact.stiffness is not None:
        # a given linear k becomes the Hertz constant with the same stiffness at the static load
        k = (scene.contact.stiffness / (1.5 * scene.static_load ** (1 / 3))) ** 1.5
    return dc.replace(scene, contact=dc.replace(scene.contact, law=law, stiffness=k))


def _initial_state(scene, model, speed, x_start, start, drop_height):
    wheel = _kernel.wheel_params(scene)
    contact = _kernel.contact_params(scene)
    if start == "static":
        d = _core.static_solve(model, wheel, contact, x_start)
        e, y = np.asarray(d["e"]), d["y_wheel"] + drop_height
    else:  # sudden: rail under its own weight, wheel just touching (or drop_height above)
        e = np.asarray(_core.rail_static(model))
        y_rail = model.positions(e, [x_start])[0, 1]
        y = y_rail + scene.wheel.radius + drop_height
    c = _core.contact_eval(model, e, x_start, y, x_start, contact, np.zeros(10))
    w = _core.WheelState()
    w.y = y
    w.ydot = 0.0
    w.theta = 0.0
    # pure rolling at the start: t . V_A = rho thetadot
    w.thetadot = float(c["tangent"][0]) * speed / c["rho"]
    w.s = c["s"]
    w.state = _core.SlipState.stick if c["active"] else _core.SlipState.free
    st = _core.SimState()
    st.e = e
    st.edot = np.zeros_like(e)
    st.wheels = [w]
    return st


def simulate(scene: Scene, speed: float, *, integrator: str = "generalized_alpha",
             dt: float | None = None, n_elements: int | None = None,
             x_start: float | None = None, x_end: float | None = None,
             duration: float | None = None, output_every: int | None = None,
             rho_inf: float = 0.8, baumgarte: float = 0.0, rolling: bool = True,
             start: str = "static", drop_height: float = 0.0,
             progress: bool | None = None, energy: bool = False,
             fidelity: str = "full", n_modes: int | None = None, max_newton: int = 25,
             newton_tol: float = 1e-11) -> Result:
    """Simulate the wheel passing over the rail at constant forward ``speed`` [m/s].

    Parameters
    ----------
    scene : Scene
    speed : forward speed v >= 0 [m/s] (``trackwheel.kmh(300)`` converts from km/h).
    integrator : "generalized_alpha" (default; Chung-Hulbert/Arnold-Bruls, Newton on the analytic
        Jacobian, velocity-level rolling constraint) or "explicit" (the paper's way: acceleration
        -level constraint, classical RK4, optional Baumgarte stabilisation).
    dt : time step [s]; default derived from the scene, ``trackwheel.default_settings``: 150
        steps per period of the wheel on its contact spring (4.96e-6 s for the paper's scene;
        explicit: also at most half the predicted stability limit); the "linear/..." levels
        use ``DEFAULT_DT[integrator]``. An explicit dt above the predicted stability limit
        warns (``trackwheel.StabilityWarning``) before the run.
    n_elements : rail elements; default: with dt also unset, derived from the scene (8 per
        support bay, at least ``scene.rail.n_elements``: 80 for the paper's scene), which keeps
        the amplitude within 1 % of a refined run at 50-400 km/h (benchmarks/README.md); with
        dt given, or for the "linear/..." levels, ``scene.rail.n_elements``.
    x_start, x_end : wheel-centre start and end [m]; default the middle of the first support bay
        and the middle of the last (0.25 m and 4.75 m for the paper's scene). With ``speed = 0``
        give ``duration`` instead of ``x_end``.
    duration : simulated time [s] (overrides ``x_end``).
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
        not move forward (the driving reaction does work when it does).

    Raises
    ------
    DivergenceError : the solution diverged; carries ``time``, ``step`` and ``cause``.
    ValueError, TypeError : bad arguments, naming the parameter and the allowed range.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    L = scene.rail.length
    speed = v.number("speed", speed, low=0.0, high=v.MAX_SPEED, unit="m/s")
    v.choice("integrator", integrator, set(_INTEGRATORS))
    v.choice("start", start, {"static", "sudden"})
    # issue 6: derived defaults (convergence.default_settings) for the ANCF levels, <= 1 %
    # amplitude error at 50-400 km/h; a given dt keeps the scene's mesh it was chosen for
    derived = not str(fidelity).startswith("linear/")
    if n_elements is None:
        from .convergence import derived_mesh

        ne = derived_mesh(scene) if (derived and dt is None) else scene.rail.n_elements
    else:
        ne = v.integer("n_elements", n_elements, low=1, high=MAX_ELEMENTS)
    ds = scene.supports.spacing
    x0 = (0.5 * ds if 0.5 * ds < L else 0.5 * L) if x_start is None else v.number(
        "x_start", x_start, low=0.0, high=L, unit="m")
    if duration is not None:
        t_end = v.number("duration", duration, low=0.0, low_open=True, unit="s")
        if x0 + speed * t_end > L:
            raise ValueError(f"duration = {duration} s takes the wheel to "
                             f"X = {x0 + speed * t_end:.4g} m, beyond the rail end {L} m")
    else:
        if speed == 0.0:
            raise ValueError("speed = 0: give duration [s] (x_end cannot be reached)")
        x1 = max(L - 0.5 * ds, x0) if x_end is None else v.number(
            "x_end", x_end, low=0.0, high=L, unit="m")
        if x1 <= x0:
            raise ValueError(f"x_end = {x1} m must be greater than x_start = {x0} m")
        t_end = (x1 - x0) / speed
    rho_inf = v.number("rho_inf", rho_inf, low=0.0, high=1.0)
    baumgarte = v.number("baumgarte", baumgarte, low=0.0, unit="1/s")
    drop_height = v.number("drop_height", drop_height, low=0.0, high=scene.wheel.radius,
                           unit="m")
    max_newton = v.integer("max_newton", max_newton, low=1, high=1000)
    newton_tol = v.number("newton_tol", newton_tol, low=0.0, low_open=True, unit="m")
    if not isinstance(rolling, bool):
        raise TypeError("rolling must be True or False")
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
    if fidelity in ("ancf/sprung", "linear/sprung"):
        scene = _with_law(scene, "linear")
    elif fidelity in ("ancf/hertz", "linear/hertz"):
        scene = _with_law(scene, "hertz")

    model = _kernel.rail_model(scene, ne)
    init = None if linear else _initial_state(scene, model, speed, x0, start, drop_height)
    wheel = _kernel.wheel_params(scene)
    contact = _kernel.contact_params(scene)
    dt_default = dt is None
    if dt is None:
        if derived:
            from .convergence import derived_dt

            dt = derived_dt(scene)
        else:
            dt = DEFAULT_DT[integrator]
        if integrator == "explicit" and not linear:
            omega = _core.highest_frequency(model, wheel, contact, init.e, x0, init.wheels[0].y)
            dt = min(dt, 0.5 * _core.explicit_stability_limit(omega))
    else:
        dt = v.number("dt", dt, low=0.0, low_open=True, high=1.0, unit="s")
        if integrator == "explicit" and not linear:  # issue 6: warn before a doomed run
            from .convergence import warn_above_stability_limit

            warn_above_stability_limit(model, wheel, contact, init.e, x0, init.wheels[0].y, dt)
    n_steps = int(round(t_end / dt))
    if n_steps < 1:
        raise ValueError(f"dt = {dt} s ({'default' if dt_default else 'given'}) is longer than "
                         f"the simulated time {t_end:.6g} s; allowed range (0, {t_end:.6g}] s")
    if n_steps > MAX_STEPS:
        raise ValueError(f"dt = {dt} s takes {n_steps:.3g} steps to cover {t_end:.6g} s, above "
                         f"the limit of {MAX_STEPS:.0e} steps; allowed range "
                         f"[{t_end / MAX_STEPS:.3g}, {t_end:.6g}] s")
    if output_every is None:
        output_every = max(1, math.ceil(n_steps / DEFAULT_MAX_SAMPLES))
    output_every = v.integer("output_every", output_every, low=1, high=2**31 - 1)
    n_samples = n_steps // output_every + 1
    per_sample = _sample_bytes(v.boolean("energy", energy))
    if n_samples * per_sample > MAX_OUTPUT_BYTES:
        raise ValueError(
            f"output_every = {output_every} keeps {n_samples} samples "
            f"({n_samples * per_sample / 2**30:.1f} GiB), above the limit of "
            f"{MAX_OUTPUT_BYTES / 2**30:.0f} GiB: increase output_every to at least "
            f"{math.ceil(n_steps * per_sample / MAX_OUTPUT_BYTES)}")

    s = _core.SimSettings()
    s.integrator = _INTEGRATORS[integrator]
    s.speed = speed
    s.x_start = x0
    s.t_end = n_steps * dt
    s.dt = dt
    s.rho_inf = rho_inf
    s.baumgarte = baumgarte
    s.rolling = rolling
    s.output_every = output_every
    s.max_newton = max_newton
    s.newton_tol = newton_tol
    s.record_energy = v.boolean("energy", energy)

    bar = None
    callback = None
    # a bar for runs estimated (conservatively) to take more than a few seconds
    est = n_steps * _STEP_COST_PER_ELEMENT * (ne + 10)
    show = (est > 5.0) if progress is None else v.boolean("progress", progress)
    # Ctrl-C is checked at every callback: about every _PROGRESS_INTERVAL seconds of wall time
    every = max(1, min(20_000, int(_PROGRESS_INTERVAL / (_STEP_COST_PER_ELEMENT * (ne + 10)))))
    if show:
        from tqdm.auto import tqdm

        bar = tqdm(total=n_steps, unit="step", desc=f"simulate {speed * 3.6:.0f} km/h")
        s.progress_every = max(1, min(every, n_steps // 100 or 1))

        def callback(step, total):
            bar.update(step - bar.n)
    else:
        s.progress_every = every

        def callback(step, total):  # still lets Ctrl-C through every progress_every steps
            return None

    t0 = _time.perf_counter()
    try:
        if linear:
            opt = _core.LinearOptions()
            opt.wheel_model = getattr(_core.WheelModel, fidelity.split("/")[1])
            opt.n_modes = 0 if n_modes is None else n_modes
            opt.sudden = start == "sudden"
            opt.drop_height = drop_height
            d = _core.simulate_linear(model, [wheel], contact, s, opt, callback)
        else:
            d = _core.simulate(model, [wheel], contact, s, init, callback)
    finally:
        if bar is not None:
            bar.close()
    wall = _time.perf_counter() - t0

    settings = dict(integrator=integrator, dt=dt, n_elements=ne, speed=speed, x_start=x0,
                    t_end=n_steps * dt, output_every=output_every, rho_inf=rho_inf,
                    baumgarte=baumgarte, rolling=rolling and not linear, start=start,
                    drop_height=drop_height, fidelity=fidelity, n_modes=n_modes)
    # one wheel: the per-wheel (n_samples, 1) columns become (n_samples,)
    arrays = {name: (d[name][:, 0] if per_wheel else d[name])
              for name, _unit, _doc, per_wheel, _dtype in OUTPUT_FIELDS}
    if not energy:
        arrays["energy"] = None
    return Result(scene=scene, settings=settings, **arrays, steps=d["steps"],
                  newton_iterations=d["newton_iterations"], state_changes=d["state_changes"],
                  stability_limit=d["stability_limit"], wall_time=wall,
                  final_state=d["final_state"])
