"""Speed against accuracy: stability limits, derived defaults and automatic convergence.

The stability limit and the derived defaults live in :mod:`trackwheel.defaults` (re-exported
here); this module adds the automatic refinement.

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

from ..base import validate as v
from .analysis import analyse
from ..run.defaults import (
    MeshWarning,
    StabilityWarning,
    check_speed,
    default_settings,
    derived_dt,
    derived_mesh,
    stability_limit,
)
from ..run.results import Result
from ..scene import Scene
from ..run.simulate import simulate

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


class ConvergenceWarning(UserWarning):
    """:func:`converged` ran out of budget before the outputs met the tolerance."""


def headline(result: Result) -> tuple[float, float]:
    """(amplitude [m], main frequency [Hz]) of a run: max |d| and the spectral peak of
    d(t) = y_B(t) - y_qs(X_A(t)) (docs: Model § Outputs), from :func:`trackwheel.analyse`."""
    a = analyse(result)
    return float(a.amplitude), float(a.main_frequency)


# --------------------------------------------------------------------------------------------
# automatic convergence
@dataclass(frozen=True, eq=False)
class Convergence:
    """Outcome of :func:`converged`."""

    result: Result  #: the accepted run at ``dt``, ``n_elements``
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

    def __repr__(self) -> str:
        return (f"<trackwheel.Convergence: {'converged' if self.converged else 'NOT converged'} "
                f"to tol = {self.tol:g} after {len(self.history)} runs "
                f"({self.wall_time:.3g} s)>\n"
                f"  dt = {self.dt:.3g} s, {self.n_elements} elements\n"
                f"  amplitude {self.amplitude:.6g} m (est. error {self.amplitude_error:.2g}), "
                f"main frequency {self.main_frequency:.6g} Hz "
                f"(est. error {self.frequency_error:.2g})")

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


class _Ladder:
    """The runs of :func:`converged` at (dt, n_elements), each run once and remembered, and the
    error estimate of a run from its coarser neighbours."""

    def __init__(self, scene: Scene, speed: float, integrator: str, simulate_kwargs: dict):
        self.scene, self.speed, self.integrator = scene, speed, integrator
        self.kwargs = simulate_kwargs
        self.runs: dict = {}  # (dt, n_elements) -> (Result, amplitude, main frequency)
        self.history: list = []  # one dict per run, in the order they ran
        self.spent = 0.0  # simulation wall time so far [s]

    def cap(self, h: float, ne: int) -> float:
        """``h`` [s], for "explicit" at most a quarter of the mesh's stability limit (4 h
        stays stable)."""
        if self.integrator == "explicit":
            return min(h, 0.25 * stability_limit(self.scene, "explicit", n_elements=ne))
        return h

    def run(self, h: float, ne: int) -> tuple:
        """(Result, amplitude [m], main frequency [Hz]) of the run at (h, ne)."""
        key = (float(h), int(ne))
        if key not in self.runs:
            with warnings.catch_warnings():  # the n/4 estimation level may be below 1 per bay
                warnings.simplefilter("ignore", MeshWarning)
                r = simulate(self.scene, self.speed, integrator=self.integrator, dt=h,
                             n_elements=ne, **self.kwargs)
            amp, freq = headline(r)
            self.spent += r.wall_time
            self.runs[key] = (r, amp, freq)
            self.history.append({"dt": h, "n_elements": ne, "amplitude": amp,
                                 "main_frequency": freq, "wall_time": r.wall_time})
        return self.runs[key]

    def estimate(self, h: float, ne: int) -> tuple:
        """((amplitude error, frequency error), dt part, mesh part) of the run at (h, ne)."""
        q = [self.run(h * f, ne)[1:] for f in (4, 2, 1)]
        e_dt = tuple(_richardson(q[0][k], q[1][k], q[2][k], ORDER[self.integrator], 2.0)
                     for k in (0, 1))
        n2, n4 = max(1, round(ne / 2)), max(1, round(ne / 4))
        m = [self.run(h, n)[1:] for n in (n4, n2, ne)]
        e_x = tuple(_richardson(m[0][k], m[1][k], m[2][k], MESH_ORDER, ne / n2)
                    for k in (0, 1))
        return (e_dt[0] + e_x[0], e_dt[1] + e_x[1]), max(e_dt), max(e_x)


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
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    tol = v.number("tol", tol, low=0.0, low_open=True, high=0.5)
    v.choice("integrator", integrator, set(ORDER))
    max_refinements = v.integer("max_refinements", max_refinements, low=0, high=20)
    max_wall_time = v.number("max_wall_time", max_wall_time, low=0.0, low_open=True, unit="s")
    speed = check_speed(speed, positive=True)
    for bad in ("dt", "n_elements", "integrator"):
        if bad in simulate_kwargs:
            raise TypeError(f"converged() takes {bad} as its own argument")
    simulate_kwargs.setdefault("progress", False)
    simulate_kwargs.setdefault("output_every", 1)
    d = default_settings(scene, speed, integrator)
    h = d["dt"] if dt is None else v.number("dt", dt, low=0.0, low_open=True, high=1.0, unit="s")
    ne = d["n_elements"] if n_elements is None else v.n_elements(n_elements, low=4)
    ladder = _Ladder(scene, speed, integrator, simulate_kwargs)
    t_start = _time.perf_counter()
    # Steps coarser than derived_dt (150 per period of the wheel on its contact spring) damp that
    # oscillation numerically and can look converged: on the paper's scene at 300 km/h the
    # levels 4e-5, 2e-5, 1e-5 s changed the amplitude at second order while it was 2.4e-3 off.
    h = ladder.cap(min(h, derived_dt(scene)), ne)
    moves = 0
    reason = ""
    while True:
        err, e_dt, e_x = ladder.estimate(h, ne)
        if max(err) < tol:
            ok = True
            break
        ok = False
        if moves >= max_refinements:
            reason = f"max_refinements = {max_refinements} reached"
            break
        h_new, ne_new = (h / 2, ne) if e_dt >= e_x else (ladder.cap(h, 2 * ne), 2 * ne)
        last = ladder.run(h, ne)[0].wall_time
        need = last * (ne_new / ne) * (h / h_new) * 1.75  # new run + its coarser neighbours
        if ladder.spent + need > max_wall_time:
            reason = (f"the next refinement (about {need:.3g} s of simulation) would exceed "
                      f"max_wall_time = {max_wall_time} s")
            break
        moves += 1
        h, ne = h_new, ne_new
    r0, a0, f0 = ladder.run(h, ne)
    if not ok:
        warnings.warn(ConvergenceWarning(
            f"converged(): budget exhausted before amplitude and main frequency reached "
            f"tol = {tol:g} ({reason}); returning dt = {h:.3g} s, n_elements = {ne} with "
            f"estimated relative errors {err[0]:.2g} (amplitude), {err[1]:.2g} (frequency)"),
            stacklevel=2)
    return Convergence(result=r0, dt=float(h), n_elements=int(ne), amplitude=a0,
                       main_frequency=f0, amplitude_error=float(err[0]),
                       frequency_error=float(err[1]), converged=ok, tol=tol,
                       wall_time=_time.perf_counter() - t_start, history=ladder.history)
