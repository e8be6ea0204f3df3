"""What a run returns: :class:`RunSettings` (the settings it used) and :class:`Result`.

The kernel returns a dict of named arrays; :func:`result_from_kernel` is the only place that
turns it into a :class:`Result`.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from .scene import Scene

__all__ = ["Result", "RunSettings", "result_from_kernel"]


@dataclass(frozen=True)
class RunSettings:
    """The settings a :func:`trackwheel.simulate` run used, after defaults were resolved.

    Item access (``settings["dt"]``) works too, for code written when this was a dict.
    """

    integrator: str  #: "generalized_alpha" or "explicit"
    dt: float  #: time step [s]
    n_elements: int  #: rail elements [-]
    speed: float  #: forward speed v [m/s]
    x_start: float  #: wheel-centre start X_0 [m]
    t_end: float  #: simulated time, steps x dt [s]
    output_every: int  #: one kept sample every this many steps [-]
    rho_inf: float  #: generalized-alpha spectral radius at infinite frequency [-]
    baumgarte: float  #: Baumgarte alpha of the explicit scheme [1/s] (0: off)
    rolling: bool  #: rolling constraint with slip (False: frictionless, or a linear level)
    start: str  #: "static" or "sudden"
    drop_height: float  #: height the wheel was lifted above its start [m]
    fidelity: str = "full"  #: model level, one of trackwheel.FIDELITY_LEVELS
    n_modes: int | None = None  #: modes of the linear levels' modal path (None: all coordinates)

    @property
    def x_end(self) -> float:
        """Wheel-centre end X_0 + v t_end [m]."""
        return self.x_start + self.speed * self.t_end

    def __getitem__(self, name: str):
        if name not in self.keys():
            raise KeyError(name)
        return getattr(self, name)

    def get(self, name: str, default=None):
        return getattr(self, name) if name in self.keys() else default

    def keys(self) -> tuple[str, ...]:
        return tuple(f.name for f in dataclasses.fields(self))

    def asdict(self) -> dict:
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class Result:
    """Output of :func:`trackwheel.simulate`, one entry per kept sample (every ``output_every``
    steps). All arrays have shape (n_samples,) and SI units.
    """

    scene: Scene
    settings: RunSettings  #: the settings used (integrator, dt, n_elements, speed, ...)
    t: np.ndarray  #: time [s]
    x_wheel: np.ndarray  #: X_A, wheel-centre position (prescribed X_0 + v t) [m]
    y_wheel: np.ndarray  #: Y_A, wheel-centre height [m]
    ydot_wheel: np.ndarray  #: dY_A/dt [m/s]
    theta: np.ndarray  #: rolling angle [rad]
    thetadot: np.ndarray  #: rolling rate [rad/s]
    contact_s: np.ndarray  #: s*, rail coordinate of the contact point [m]
    y_contact: np.ndarray  #: y_B = y(s*), rail displacement under the wheel [m]
    normal_force: np.ndarray  #: N [N] (0 without contact)
    tangential_force: np.ndarray  #: lambda, tangential contact force on the wheel [N]
    slip: np.ndarray  #: slip velocity t.(V_A - S edot) - rho thetadot [m/s]
    slip_state: np.ndarray  #: 0 no contact, 1 stick, 2 slide (int)
    v_error: np.ndarray  #: paper's eq. 28, (dX/dt - rho dtheta/dt)/(dX/dt) 100 [%]
    phi: np.ndarray  #: rail obliquity at the contact point [rad]
    #: vertical acceleration of the contact point d2 y_B/dt2 = S_y e'' + 2 s' S_y,s e' + s'^2 y_ss
    #: (s'' y_s neglected) [m/s^2]. Accelerations converge more slowly in dt than displacements
    #: with generalized-alpha (its algorithmic accelerations lag): about 5 % RMS at 1e-5 s and
    #: 0.5 % at 1e-6 s for the paper's scene at 300 km/h, so use dt <= 1e-6 s for Fig. 8-type
    #: acceleration studies (the paper, too, needed a smaller step for accelerations).
    acc_contact: np.ndarray
    acc_A: np.ndarray  #: rho cos(phi) theta' v phi_s [m/s^2] (docs: Model § Outputs)
    acc_B: np.ndarray  #: rho cos(phi) theta' phi_t [m/s^2]
    acc_C: np.ndarray  #: rho cos(phi) v^2 phi_s^2 [m/s^2]
    acc_D: np.ndarray  #: rho cos(phi) phi_t^2 [m/s^2]
    acc_E: np.ndarray  #: 2 rho cos(phi) phi_t v phi_s [m/s^2]
    reaction: np.ndarray  #: horizontal force holding X_A = X_0 + v t [N]
    penetration: np.ndarray  #: rho0 - rho [m] (negative: gap)
    energy: np.ndarray | None  #: total mechanical energy [J] (``energy=True`` only)
    steps: int  #: time steps taken
    newton_iterations: int  #: total Newton iterations (generalized-alpha)
    state_changes: int  #: slip/contact state switches
    stability_limit: float  #: predicted explicit RK4 stability limit at the start [s]
    wall_time: float  #: [s]
    final_state: object = field(repr=False)  #: kernel state at the end (for restarts)

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
        free = np.concatenate(([False], ~self.in_contact, [False]))
        edges = np.flatnonzero(np.diff(free.astype(np.int8)))
        return [(float(self.t[i]), float(self.t[j - 1])) for i, j in zip(edges[::2], edges[1::2])]

    def __repr__(self) -> str:
        s = self.settings
        n = self.t.size
        lost = self.lost_contact
        return "\n".join([
            (f"<trackwheel.Result: {n} samples, t = {self.t[0]:.4g}..{self.t[-1]:.4g} s, "
             f"{self.steps} steps in {self.wall_time:.3g} s>"),
            (f"  settings : {s.fidelity}, {s.integrator}, dt = {s.dt:.3g} s, {s.n_elements} "
            f"elements, v = {s.speed:.4g} m/s, X = {s.x_start:.4g} -> {s.x_end:.4g} m"),
            f"  y_contact: {self.y_contact.min():.4g} .. {self.y_contact.max():.4g} m",
            (f"  normal force: {self.normal_force.min():.4g} .. {self.normal_force.max():.4g} N, "
            f"lost contact: {'yes' if lost else 'no'}"),
        ])


#: Result fields read from the kernel's output dict under another name.
_KERNEL_NAMES = {"slip_state": "state"}
#: Result fields that do not come from the kernel's arrays.
_NOT_FROM_KERNEL = {"scene", "settings", "energy", "wall_time", "final_state"}


def result_from_kernel(out: dict, scene: Scene, settings: RunSettings, wall_time: float,
                       energy: bool) -> Result:
    """Wrap the kernel's output dict ``out`` (one array per recorded field, plus the counters
    and ``final_state``) as a :class:`Result`; ``energy`` keeps the energy array."""
    fields = {f.name: out[_KERNEL_NAMES.get(f.name, f.name)]
              for f in dataclasses.fields(Result) if f.name not in _NOT_FROM_KERNEL}
    return Result(scene=scene, settings=settings, energy=out["energy"] if energy else None,
                  wall_time=wall_time, final_state=out.get("final_state"), **fields)
