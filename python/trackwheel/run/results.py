"""What a run returns: :class:`RunSettings` (the settings it used) and :class:`Result`.

The kernel returns a dict of named arrays, one per row of its output table
(:data:`OUTPUT_FIELDS`, defined once in ``cpp/output.cpp``): that table defines Result's array
fields, their documentation and the output-size estimate, and :func:`result_from_kernel` is the
only place that turns the dict into a :class:`Result`. Adding an output is one row in C++.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import numpy as np

from . import _core
from .scene import Scene

__all__ = ["OUTPUT_FIELDS", "Result", "RunSettings", "result_from_kernel", "sample_bytes"]

#: The kernel's output table, one row per recorded field: (name, unit, doc, per_wheel, dtype).
OUTPUT_FIELDS: tuple[tuple[str, str, str, bool, str], ...] = tuple(
    tuple(f) for f in _core.OUTPUT_FIELDS)


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
        free = np.concatenate(([False], ~self.in_contact, [False]))
        edges = np.flatnonzero(np.diff(free.astype(np.int8)))
        return [(float(self.t[i]), float(self.t[j - 1])) for i, j in zip(edges[::2], edges[1::2])]

    @property
    def n_wheels(self) -> int:
        """Wheels in the run (per-wheel arrays are 2-D when there are several)."""
        return 1 if self.x_wheel.ndim == 1 else self.x_wheel.shape[1]

    def wheel(self, i: int):
        """Wheel ``i``'s view as a one-wheel run: every per-wheel array reduced to that wheel's
        (n_samples,) column, ``scene`` the single-wheel scene of that wheel under its static
        load of the vehicle's weight distribution (so :func:`trackwheel.analyse` measures its
        quasi-static line and force statistics against that wheel alone under that load), and
        ``settings.x_start`` that wheel's start."""
        n = self.n_wheels
        if not (isinstance(i, (int, np.integer)) and not isinstance(i, bool) and 0 <= i < n):
            raise ValueError(f"wheel = {i!r} must be an integer in [0, {n - 1}]")
        if n == 1:
            return self
        cols = {name: getattr(self, name)[:, i]
                for name, _u, _d, per_wheel, _t in OUTPUT_FIELDS if per_wheel}
        sc = self.scene
        veh = sc.active_vehicle
        w = veh.wheels[i]
        load = veh.static_loads(sc.gravity)[i] - w.mass * sc.gravity
        scene = dataclasses.replace(sc, vehicle=None, wheel=dataclasses.replace(w, load=load))
        settings = dataclasses.replace(self.settings,
                                       x_start=self.settings.x_start + veh.positions[i])
        return dataclasses.replace(self, scene=scene, settings=settings, **cols)

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


def _result_doc() -> str:
    lines = ["Output of :func:`trackwheel.simulate`, one entry per kept sample (every",
             "``output_every`` steps).", "",
             "Array fields (from the kernel's output table :data:`OUTPUT_FIELDS`), each of shape",
             "(n_samples,) for one wheel, the per-wheel ones (n_samples, n_wheels) for a vehicle",
             "with several wheels (``result.wheel(i)`` is wheel i's one-wheel view), in SI units:",
             ""]
    for name, unit, doc, _per_wheel, dtype in OUTPUT_FIELDS:
        kind = "int" if dtype.startswith("int") else (f"[{unit}]" if unit else "[-]")
        lines.append(f"- ``{name}`` {kind}: {doc}")
    lines += ["", "``energy`` is None unless ``simulate(..., energy=True)``. Accelerations converge",
              "more slowly in dt than displacements with generalized-alpha (its algorithmic",
              "accelerations lag): ``acc_contact`` is about 5 % RMS off at 1e-5 s and 0.5 % at",
              "1e-6 s for the paper's scene at 300 km/h, so use dt <= 1e-6 s for Fig. 8-type",
              "acceleration studies.", "",
              "Other fields: ``scene``, ``settings`` (:class:`RunSettings`), ``steps``,",
              "``newton_iterations`` (generalized-alpha), ``state_changes`` (slip/contact",
              "switches), ``stability_limit`` (predicted explicit RK4 limit at the start) [s],",
              "``wall_time`` [s], ``final_state`` (kernel state at the end, for restarts),",
              "``body_z`` [m] and ``body_phi`` [rad] (n_samples, n_bodies): the vehicle's bogies",
              "then car body (None without bodies; z = 0 where every spring is unstretched)."]
    return "\n".join(lines)


Result = dataclasses.make_dataclass(
    "Result",
    [("scene", Scene), ("settings", RunSettings),
     *[(f[0], "np.ndarray | None" if f[0] == "energy" else "np.ndarray") for f in OUTPUT_FIELDS],
     ("steps", int), ("newton_iterations", int), ("state_changes", int),
     ("stability_limit", float), ("wall_time", float),
     ("final_state", object, field(repr=False)),
     ("body_z", "np.ndarray | None", field(default=None, repr=False)),
     ("body_phi", "np.ndarray | None", field(default=None, repr=False))],
    bases=(_ResultMethods,), frozen=True, repr=False,
    namespace={"__doc__": _result_doc(), "__module__": __name__})


def sample_bytes(energy: bool) -> int:
    """Bytes one kept sample of a one-wheel run takes, from the output table."""
    return sum(4 if dtype.startswith("int") else 8 for name, _u, _d, _w, dtype in OUTPUT_FIELDS
               if energy or name != "energy")


def result_from_kernel(out: dict, scene: Scene, settings: RunSettings, wall_time: float,
                       energy: bool) -> Result:
    """Wrap the kernel's output dict ``out`` (one array per row of :data:`OUTPUT_FIELDS`, plus
    the counters and ``final_state``) as a :class:`Result`; ``energy`` keeps the energy array.
    One wheel: the per-wheel (n_samples, 1) columns become (n_samples,); several wheels keep
    (n_samples, n_wheels). The vehicle's bodies: ``body_z``, ``body_phi`` (n_samples, n_bodies),
    None without bodies."""
    one = out["x_wheel"].shape[1] == 1
    arrays = {name: (out[name][:, 0] if per_wheel and one else out[name])
              for name, _unit, _doc, per_wheel, _dtype in OUTPUT_FIELDS}
    nb = out["body_z"].shape[1] if "body_z" in out else 0
    arrays["body_z"] = out["body_z"] if nb else None
    arrays["body_phi"] = out["body_phi"] if nb else None
    if not energy:
        arrays["energy"] = None
    return Result(scene=scene, settings=settings, **arrays, steps=out["steps"],
                  newton_iterations=out["newton_iterations"], state_changes=out["state_changes"],
                  stability_limit=out["stability_limit"], wall_time=wall_time,
                  final_state=out.get("final_state"))
