"""Speed against accuracy: stability limits, derived defaults and automatic convergence (issue 6).

- :func:`stability_limit` predicts the largest stable time step of an integrator. For the
  explicit RK4 scheme (the paper's way, docs: Model § Equations of motion) it is ``2 sqrt(2) / omega_max`` with
  omega_max the highest eigenfrequency of the assembled system (rail + supports + wheel on its
  contact spring, linearised at the static state at the start position; power iteration in the
  kernel). ``simulate(..., integrator="explicit", dt=...)`` warns with :class:`StabilityWarning`
  before it runs when dt is above it. benchmarks/stability_map.py measures the limit by bisection
  on real runs: measured/predicted = 1.004-1.013 on 10 to 80 elements at 50-400 km/h.
- :func:`default_settings` derives a time step and a mesh from the scene and the speed so that
  the headline outputs (amplitude and main frequency of the contact-point vibration, docs: Model § Outputs)
  are within 1 % of a converged run (measured: 0.4 % at 50-400 km/h; see its docstring).
- :func:`converged` refines dt and n_elements until the estimated errors of amplitude and main
  frequency are below ``tol``, and returns the run, the settings chosen and the estimate.
"""

from __future__ import annotations

import math
import time as _time
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _core, _kernel
from . import _validate as v
from .scene import MAX_ELEMENTS, Scene

__all__ = [
    "Convergence",
    "ConvergenceWarning",
    "StabilityWarning",
    "converged",
    "default_settings",
    "derived_dt",
    "derived_mesh",
    "headline",
    "stability_limit",
]

#: Order of accuracy in dt of each integrator (generalized-alpha: second order for any rho_inf;
#: classical RK4: fourth), used by the Richardson error estimate of :func:`converged`.
ORDER = {"generalized_alpha": 2, "explicit": 4}

#: Formal order assumed for the mesh in the Richardson estimate of :func:`converged`. The cubic
#: element's nodal displacements converge at O(l_e^4), but the amplitude under a moving point
#: contact converges irregularly (element-passing excitation); 2 is the conservative choice
#: (observed 3-4 on the paper's scene).
MESH_ORDER = 2


class StabilityWarning(UserWarning):
    """The requested time step is above the predicted stability limit of the integrator."""


class ConvergenceWarning(UserWarning):
    """:func:`converged` ran out of budget before the outputs met the tolerance."""


# --------------------------------------------------------------------------------------------
# stability limits
def _start_state(scene: Scene, ne: int, x0: float):
    model = _kernel.rail_model(scene, ne)
    wheel = _kernel.wheel_params(scene)
    contact = _kernel.contact_params(scene)
    st = _core.static_solve(model, wheel, contact, x0)
    return model, wheel, contact, np.asarray(st["e"]), float(st["y_wheel"])


def _explicit_limit(model, wheel, contact, e, x0: float, y: float) -> tuple[float, float]:
    """(dt_max [s], omega_max [rad/s]) of explicit RK4 at the given state."""
    omega = _core.highest_frequency(model, wheel, contact, e, x0, y)
    return _core.explicit_stability_limit(omega), omega


def stability_limit(scene: Scene, integrator: str = "explicit", *, n_elements: int | None = None,
                    speed: float = 0.0, rho_inf: float = 0.8,
                    x_start: float | None = None) -> float:
    """Predicted largest stable time step [s] of ``integrator`` for ``scene``.

    ``"explicit"`` (classical RK4, the paper's scheme): the stability interval of RK4 on the
    imaginary axis is |omega dt| <= 2 sqrt(2), so dt_max = 2 sqrt(2) / omega_max, with omega_max
    [rad/s] the highest eigenfrequency of the assembled system -- the ANCF rail on its supports
    with the wheel mass on its contact spring (docs: Model § Rail, § Wheel, § Contact), linearised at the static state
    with the wheel at ``x_start`` (default: the start of :func:`trackwheel.simulate`, the middle
    of the first support bay) -- found by power iteration in the kernel. omega_max grows as
    1/l_e^2 (the shortest bending wave of an element), so dt_max falls by 4x per mesh doubling
    (about 1.0e-5 s for the paper's 20 elements, 6.4e-7 s for 80). The speed does not enter: the
    linearised system does not depend on it (the convective terms of the moving contact are
    small), which benchmarks/stability_map.py confirms from 50 to 400 km/h; ``speed`` [m/s] is
    accepted for symmetry with :func:`trackwheel.simulate` and checked only.

    ``"generalized_alpha"``: unconditionally stable for linear problems for every ``rho_inf`` in
    [0, 1] (Chung & Hulbert 1993), so the result is ``math.inf``. What fails first at large steps
    is Newton's iteration at contact loss/landing and stick/slip transitions, which no linear
    analysis predicts; benchmarks/stability_map.py measures where it stops converging.

    Raises ValueError / TypeError naming the parameter for bad arguments.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    v.choice("integrator", integrator, {"explicit", "generalized_alpha"})
    v.number("speed", speed, low=0.0, high=300.0, unit="m/s")
    v.number("rho_inf", rho_inf, low=0.0, high=1.0)
    ne = scene.rail.n_elements if n_elements is None else v.integer(
        "n_elements", n_elements, low=1, high=MAX_ELEMENTS)
    L, ds = scene.rail.length, scene.supports.spacing
    x0 = (0.5 * ds if 0.5 * ds < L else 0.5 * L) if x_start is None else v.number(
        "x_start", x_start, low=0.0, high=L, unit="m")
    if integrator == "generalized_alpha":
        return math.inf
    dt_max, _ = _explicit_limit(*_start_state(scene, ne, x0), x0)
    return dt_max


def warn_above_stability_limit(model, wheel, contact, e, x0: float, y: float, dt: float,
                               stacklevel: int = 3) -> float:
    """Warn (:class:`StabilityWarning`) if the explicit time step ``dt`` [s] is above the
    predicted RK4 limit at the given state; returns the limit [s]. Used by ``simulate``."""
    dt_max, omega = _explicit_limit(model, wheel, contact, e, x0, y)
    if dt > dt_max:
        warnings.warn(StabilityWarning(
            f"dt = {dt:.3g} s is above the predicted stability limit of the explicit RK4 scheme, "
            f"{dt_max:.3g} s (2 sqrt(2)/omega_max, highest eigenfrequency "
            f"{omega / (2 * math.pi):.4g} Hz for this mesh): the run will almost certainly "
            f"diverge. Use dt <= {dt_max:.3g} s, fewer elements, or "
            f"integrator='generalized_alpha' (unconditionally stable)"), stacklevel=stacklevel)
    return dt_max


# --------------------------------------------------------------------------------------------
# headline outputs
def headline(result) -> tuple[float, float]:
    """(amplitude [m], main frequency [Hz]) of a run: max |d| and the spectral peak of
    d(t) = y_B(t) - y_qs(X_A(t)) (docs: Model § Outputs), from :func:`trackwheel.analyse`."""
    from .analysis import analyse  # analysis imports simulate, which imports this module

    a = analyse(result)
    return float(a.amplitude), float(a.main_frequency)


# --------------------------------------------------------------------------------------------
# derived defaults
#: Elements per support bay of the derived default mesh (see :func:`default_settings`).
ELEMENTS_PER_BAY = 8
#: Time steps per period of the highest frequency of interest (see :func:`default_settings`).
STEPS_PER_PERIOD = 150


def _wheel_frequency(scene: Scene) -> float:
    """sqrt(k/M) / 2 pi [Hz]: the wheel mass on the (linearised) contact spring -- the highest
    physical frequency the paper's outputs resolve (about 1.34 kHz for its scene)."""
    return math.sqrt(scene.contact_stiffness / scene.wheel.mass) / (2.0 * math.pi)


def derived_mesh(scene: Scene) -> int:
    """Default number of rail elements: ELEMENTS_PER_BAY per support bay, at least the scene's
    own ``rail.n_elements`` (80 for the paper's scene). See :func:`default_settings`."""
    bays = max(1, round(scene.rail.length / scene.supports.spacing))
    return int(max(scene.rail.n_elements, ELEMENTS_PER_BAY * bays))


def derived_dt(scene: Scene) -> float:
    """Default generalized-alpha time step [s]: STEPS_PER_PERIOD steps per period of the wheel
    on its contact spring (4.96e-6 s for the paper's scene). See :func:`default_settings`."""
    return 1.0 / (STEPS_PER_PERIOD * _wheel_frequency(scene))


def default_settings(scene: Scene, speed: float | None = None,
                     integrator: str = "generalized_alpha") -> dict:
    """Time step [s] and mesh derived from the scene, as ``dict(dt=..., n_elements=...)``: what
    :func:`trackwheel.simulate` uses when neither is given (for the ANCF fidelity levels).

    Target (issue 6): at most 1 % error of the amplitude max |d| (docs: Model § Outputs) against a refined
    run. The scene's former defaults (20 elements, dt = 1e-5 s) miss it by up to 5.5 %
    (benchmarks/README.md, "Speed against accuracy").

    - ``n_elements``: ELEMENTS_PER_BAY = 8 elements per support bay (l_e = d_s / 8; at least
      the scene's own mesh). Reason: the cubic ANCF element interpolates the rail under a moving
      point contact with a contact-point stiffness that varies across each element, so the wheel
      is excited at the element-passing frequency v / l_e and its harmonics. With l_e = d_s / 2
      (20 elements) or d_s / 4 (40) this spurious excitation meets the track's main resonance
      (about 340 Hz for the paper's scene) within 50-400 km/h -- at 300 km/h for 20 elements,
      150 km/h for 40 -- and moves the amplitude by 4-5 %; with d_s / 8 the effect stays below
      0.5 % (160-element runs as reference).
    - ``dt``: STEPS_PER_PERIOD = 150 steps per period of the highest frequency of interest, the
      wheel on its contact spring f_w = sqrt(k/M)/2 pi (1.34 kHz for the paper's scene, so
      dt = 4.96e-6 s). Phase errors of generalized-alpha grow with the passage time, so the
      slowest speed (50 km/h) sets the step: 1e-5 s gives -0.9 % there, 2.5e-6 s -0.2 %.
      The explicit scheme takes at most half its stability limit on the derived mesh.

    ``speed`` [m/s] is checked and otherwise unused: the rule holds from 50 to 400 km/h.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    v.choice("integrator", integrator, {"explicit", "generalized_alpha"})
    if speed is not None:
        v.number("speed", speed, low=0.0, high=300.0, unit="m/s")
    ne = derived_mesh(scene)
    dt = derived_dt(scene)
    if integrator == "explicit":
        dt = min(dt, 0.5 * stability_limit(scene, "explicit", n_elements=ne))
    return dict(dt=float(dt), n_elements=int(ne))


# --------------------------------------------------------------------------------------------
# automatic convergence
@dataclass(frozen=True, eq=False)
class Convergence:
    """Outcome of :func:`converged`."""

    result: object  #: the accepted run (trackwheel.Result) at ``dt``, ``n_elements``
    dt: float  #: time step chosen [s]
    n_elements: int  #: mesh chosen [-]
    amplitude: float  #: max |d| of the accepted run [m]
    main_frequency: float  #: main frequency of d(t) of the accepted run [Hz]
    amplitude_error: float  #: estimated relative error of ``amplitude`` [-] (see converged)
    frequency_error: float  #: estimated relative error of ``main_frequency`` [-]
    converged: bool  #: both estimated errors below tol
    tol: float  #: the tolerance asked for [-]
    wall_time: float  #: total wall time of all runs [s]
    history: list = field(default_factory=list)  #: one dict per run: dt, n_elements, outputs

    @property
    def error(self) -> float:
        """The larger of the two estimated relative errors [-]."""
        return max(self.amplitude_error, self.frequency_error)


def _rel(a: float, b: float) -> float:
    return abs(a - b) / max(abs(b), 1e-300)


def _richardson(q_coarse: float, q_mid: float, q_fine: float, p: float, ratio: float) -> float:
    """Relative error estimate of q_fine from three levels, each refined by ``ratio``.

    With c the relative changes between the levels, the observed order is
    p_obs = log(c_prev / c_last) / log(ratio). Inside the asymptotic range (p - 1 <= p_obs <=
    p + 2) the Richardson estimate with the formal order, c_last / (ratio^p - 1); otherwise --
    slower convergence, a change of sign, or a coincidentally tiny last change -- the
    conservative max(c_last, c_prev)."""
    c_last, c_prev = _rel(q_mid, q_fine), _rel(q_coarse, q_mid)
    if c_last == 0.0 and c_prev == 0.0:
        return 0.0
    if c_last > 0.0 and c_prev > 0.0:
        p_obs = math.log(c_prev / c_last) / math.log(ratio)
        if p - 1.0 <= p_obs <= p + 2.0:
            return c_last / (ratio**p - 1.0)
    return max(c_last, c_prev)


def converged(scene: Scene, speed: float, *, tol: float = 1e-3,
              integrator: str = "generalized_alpha", dt: float | None = None,
              n_elements: int | None = None, max_refinements: int = 6,
              max_wall_time: float = 120.0, **simulate_kwargs) -> Convergence:
    """Refine dt and n_elements until amplitude and main frequency (docs: Model § Outputs) are within
    ``tol`` (relative, estimated) of their converged values; return the run, the settings and
    the error estimate.

    Starting from ``dt`` (at most :func:`derived_dt`, see below) and ``n_elements`` (default
    :func:`default_settings`), the error of the current run (dt, n) is estimated from two coarser
    levels in each direction -- (2 dt, n), (4 dt, n) and (dt, n/2), (dt, n/4), each a quarter to a
    half of the current run's cost -- by Richardson extrapolation with the formal order
    (:func:`_richardson`: 2 for generalized-alpha and 4 for RK4 in dt, MESH_ORDER = 2 in the mesh),
    used only when the observed order is in the asymptotic range, else the larger of the last two
    changes is taken, so that a coincidentally small change does not stop the refinement. The
    estimated error of a run is the dt part plus the mesh part, for the amplitude and the main
    frequency separately. If both are below ``tol`` the current run is accepted; otherwise the
    direction with the larger estimated error is refined (dt/2 or 2n) and the estimate repeated. For
    "explicit", dt is kept at most a quarter of the mesh's stability limit, so that 4 dt stays
    stable. A ``dt`` above :func:`derived_dt` is lowered to it: coarser steps damp the
    wheel-on-contact-spring oscillation numerically, and such pre-asymptotic levels can change the
    outputs at the expected order while being wrong by more than tol.

    Budget: at most ``max_refinements`` refinements and ``max_wall_time`` [s] of simulation (a
    refinement whose runs would exceed it, judged from the cost of the last run, is not
    started). When it runs out, the last run is returned with ``converged=False``, its error
    estimate, and a :class:`ConvergenceWarning`. ``simulate_kwargs`` go to
    :func:`trackwheel.simulate` (e.g. ``x_end`` for a shorter stretch, ``rho_inf``);
    ``output_every`` is fixed to 1 and ``progress`` off unless given.
    """
    from .simulate import simulate

    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    tol = v.number("tol", tol, low=0.0, low_open=True, high=0.5)
    v.choice("integrator", integrator, set(ORDER))
    max_refinements = v.integer("max_refinements", max_refinements, low=0, high=20)
    max_wall_time = v.number("max_wall_time", max_wall_time, low=0.0, low_open=True, unit="s")
    speed = v.number("speed", speed, low=0.0, low_open=True, high=300.0, unit="m/s")
    for bad in ("dt", "n_elements", "integrator"):
        if bad in simulate_kwargs:
            raise TypeError(f"converged() takes {bad} as its own argument")
    simulate_kwargs.setdefault("progress", False)
    simulate_kwargs.setdefault("output_every", 1)
    d = default_settings(scene, speed, integrator)
    h = d["dt"] if dt is None else v.number("dt", dt, low=0.0, low_open=True, high=1.0, unit="s")
    ne = d["n_elements"] if n_elements is None else v.integer("n_elements", n_elements, low=4,
                                                               high=MAX_ELEMENTS)
    explicit = integrator == "explicit"

    def cap(h_, ne_):
        if explicit:
            return min(h_, 0.25 * stability_limit(scene, "explicit", n_elements=ne_))
        return h_

    runs: dict = {}
    history: list = []
    spent = [0.0]
    t_start = _time.perf_counter()

    def run(h_, ne_):
        key = (float(h_), int(ne_))
        if key not in runs:
            r = simulate(scene, speed, integrator=integrator, dt=h_, n_elements=ne_,
                         **simulate_kwargs)
            amp, freq = headline(r)
            spent[0] += r.wall_time
            runs[key] = (r, amp, freq)
            history.append(dict(dt=h_, n_elements=ne_, amplitude=amp, main_frequency=freq,
                                wall_time=r.wall_time))
        return runs[key]

    def estimate(h_, ne_):
        """((amp_err, freq_err), dt part, mesh part) of the run at (h_, ne_)."""
        q = [run(h_ * f, ne_)[1:] for f in (4, 2, 1)]
        e_dt = tuple(_richardson(q[0][k], q[1][k], q[2][k], ORDER[integrator], 2.0)
                     for k in (0, 1))
        n2, n4 = max(1, round(ne_ / 2)), max(1, round(ne_ / 4))
        m = [run(h_, n)[1:] for n in (n4, n2, ne_)]
        e_x = tuple(_richardson(m[0][k], m[1][k], m[2][k], MESH_ORDER, ne_ / n2)
                    for k in (0, 1))
        return (e_dt[0] + e_x[0], e_dt[1] + e_x[1]), max(e_dt), max(e_x)

    # Steps coarser than derived_dt (150 per period of the wheel on its contact spring) damp that
    # oscillation numerically and can look converged: on the paper's scene at 300 km/h the
    # levels 4e-5, 2e-5, 1e-5 s changed the amplitude at second order while it was 2.4e-3 off.
    h = cap(min(h, derived_dt(scene)), ne)
    moves = 0
    reason = ""
    while True:
        err, e_dt, e_x = estimate(h, ne)
        if max(err) < tol:
            ok = True
            break
        ok = False
        if moves >= max_refinements:
            reason = f"max_refinements = {max_refinements} reached"
            break
        h_new, ne_new = (h / 2, ne) if e_dt >= e_x else (cap(h, 2 * ne), 2 * ne)
        last = runs[(float(h), int(ne))][0].wall_time
        need = last * (ne_new / ne) * (h / h_new) * 1.75  # new run + its coarser neighbours
        if spent[0] + need > max_wall_time:
            reason = (f"the next refinement (about {need:.3g} s of simulation) would exceed "
                      f"max_wall_time = {max_wall_time} s")
            break
        moves += 1
        h, ne = h_new, ne_new
    r0, a0, f0 = runs[(float(h), int(ne))]
    if not ok:
        warnings.warn(ConvergenceWarning(
            f"converged(): budget exhausted before amplitude and main frequency reached "
            f"tol = {tol:g} ({reason}); returning dt = {h:.3g} s, n_elements = {ne} with "
            f"estimated relative errors {err[0]:.2g} (amplitude), {err[1]:.2g} (frequency)"),
            stacklevel=2)
    return Convergence(result=r0, dt=float(h), n_elements=int(ne), amplitude=a0,
                       main_frequency=f0, amplitude_error=float(err[0]),
                       frequency_error=float(err[1]), converged=ok, tol=tol,
                       wall_time=_time.perf_counter() - t_start, history=history)
