"""What the kernel returns, as tables defined once: :class:`RunSettings` (the settings a run
used), :class:`Result` (a run) and the static solution's fields.

- :data:`OUTPUT_FIELDS`: the kernel's output table, one row per recorded array (defined once in
  ``cpp/output.cpp``): Result's array fields, their documentation and the output-size estimate;
  :func:`result_from_kernel` is the only place that turns the kernel's dict into a Result.
  Adding an output is one row in C++. :data:`SUPPORT_FIELDS` are the same table's per-support
  rows (recorded on request), :data:`ENVELOPE_FIELDS` the fields of each support's envelope
  along the track (:meth:`Result.sleeper_envelope`).
- :data:`SETTINGS_FIELDS`: RunSettings' fields with their units (the sweep tables' settings
  columns take theirs from here).
- :data:`STATIC_FIELDS`: the fields of a static solution (``trackwheel.static``,
  ``quasi_static``, the vehicle's static state), with the kernel's key of each;
  :func:`static_from_kernel` reads them from the kernel's dict.
"""

from __future__ import annotations

import dataclasses
from dataclasses import field

import numpy as np

from .. import _core
from ..base.fields import Quantity, dataclass_fields, generated_doc
from ..scene import Scene

__all__ = ["ENVELOPE_FIELDS", "OUTPUT_FIELDS", "SETTINGS_FIELDS", "STATIC_FIELDS",
           "SUPPORT_FIELDS", "Result", "RunSettings", "result_from_kernel", "sample_bytes",
           "static_from_kernel"]

#: The kernel's output table, one row per recorded field: (name, unit, doc, per_wheel, dtype).
OUTPUT_FIELDS: tuple[tuple[str, str, str, bool, str], ...] = tuple(
    tuple(f) for f in _core.OUTPUT_FIELDS)
#: The output table's per-support rows (name, unit, doc): float64 arrays (n_samples,
#: n_supports) over the rail's supports, recorded with ``simulate(..., support_forces=True)``.
SUPPORT_FIELDS: tuple[tuple[str, str, str], ...] = tuple(tuple(f) for f in _core.SUPPORT_FIELDS)
#: The fields of each support's envelope along the track (name, unit, doc), one entry per
#: support the run saw: the columns of :meth:`Result.sleeper_envelope`.
ENVELOPE_FIELDS: tuple[tuple[str, str, str], ...] = tuple(
    tuple(f) for f in _core.ENVELOPE_FIELDS)

#: The settings a run used, after its defaults were resolved: the fields of RunSettings.
SETTINGS_FIELDS: tuple[Quantity, ...] = (
    Quantity("integrator", "", '"generalized_alpha" or "explicit"', "str"),
    Quantity("dt", "s", "time step", "float"),
    Quantity("n_elements", "", "rail elements", "int"),
    Quantity("speed", "m/s", "forward speed v", "float"),
    Quantity("x_start", "m", "wheel-centre start X_0", "float"),
    Quantity("t_end", "s", "simulated time, steps x dt", "float"),
    Quantity("output_every", "", "one kept sample every this many steps", "int"),
    Quantity("rho_inf", "-", "generalized-alpha spectral radius at infinite frequency", "float"),
    Quantity("baumgarte", "1/s", "Baumgarte alpha of the explicit scheme (0: off)", "float"),
    Quantity("rolling", "", "rolling constraint with slip (False: frictionless, or a linear "
             "level)", "bool"),
    Quantity("start", "", '"static" or "sudden"', "str"),
    Quantity("drop_height", "m", "height the wheel was lifted above its start", "float"),
    Quantity("fidelity", "", "model level, one of trackwheel.FIDELITY_LEVELS", "str",
             default="full"),
    Quantity("n_modes", "", "modes of the linear levels' modal path (None: all coordinates)",
             "int | None", default=None),
)

#: The fields of a static solution with the wheel at rest, and the kernel's key of each
#: (``static_solve``'s dict): every static result class is built from this table.
STATIC_FIELDS: tuple[Quantity, ...] = (
    Quantity("y_wheel", "m", "Y_A, wheel-centre height"),
    Quantity("contact_s", "m", "s*, rail coordinate of the contact point"),
    Quantity("y_contact", "m", "y_B = y(s*), rail displacement under the wheel (negative = "
             "down)"),
    Quantity("normal_force", "N", "N, the contact force (equals the static wheel load)"),
    Quantity("iterations", "", "Newton iterations", "int"),
    Quantity("rail_coordinates", "", "ANCF coordinates e, (4 (n_e + 1),) [m, m, -, -]",
             "np.ndarray"),
    Quantity("sleeper_z", "m", "layered supports: sleeper heights z_j (negative = down), one "
             "per support; else empty", "np.ndarray", factory=lambda: np.empty(0)),
    Quantity("ballast_force", "N", "layered supports: ballast force under each sleeper, "
             "-k_b z_j, or k_b max(0, -z_j - g_j) over a void or on tensionless ballast (positive "
             "= compression); their sum is the wheel loads plus the weight of rail and sleepers "
             "on them; else empty", "np.ndarray",
             factory=lambda: np.empty(0)),
)
#: the kernel's key of a static field where it differs from the field's name
_STATIC_KEYS = {"rail_coordinates": "e"}


def static_from_kernel(d: dict, names) -> dict:
    """The static fields ``names`` (names of :data:`STATIC_FIELDS`) read from the kernel's
    ``static_solve`` dict ``d``: the arrays as numpy arrays, the scalars as they are."""
    kinds = {q.name: q.kind for q in STATIC_FIELDS}
    out = {}
    for name in names:
        value = d[_STATIC_KEYS.get(name, name)]
        out[name] = np.asarray(value) if kinds[name] == "np.ndarray" else value
    return out


class _SettingsMethods:
    """Derived views of :class:`RunSettings`."""

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


RunSettings = dataclasses.make_dataclass(
    "RunSettings", dataclass_fields(SETTINGS_FIELDS), bases=(_SettingsMethods,), frozen=True,
    namespace={"__module__": __name__, "__doc__": generated_doc(
        "The settings a :func:`trackwheel.simulate` run used, after defaults were resolved "
        "(item access, ``settings[\"dt\"]``, works too):", SETTINGS_FIELDS)})


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
        return _intervals(self.t, ~self.in_contact)

    @property
    def sliding(self) -> np.ndarray:
        """Boolean mask of samples where the wheel slides on the rail, |lambda| = mu N
        (``slip_state`` 2): a brake or torque beyond adhesion, or a violent impact."""
        return self.slip_state == 2

    @property
    def locked(self) -> np.ndarray:
        """Boolean mask of samples where the wheel touches the rail and does not turn: a brake
        beyond adhesion (``Wheel.brake_torque`` > mu P rho0) has locked it, and it slides. Not
        turning is a rim speed |theta'| rho0 below LOCKED_RIM_SPEED (the kernel's lock leaves
        denormal spins, ~1e-323 rad/s, for a few steps)."""
        rim = np.abs(self.thetadot) * self.scene.wheel.radius
        return self.in_contact & (rim < LOCKED_RIM_SPEED)

    def sliding_intervals(self) -> list[tuple[float, float]]:
        """[(t_start, t_end), ...] of the kept samples where the wheel slides [s]."""
        return _intervals(self.t, self.sliding)

    def locked_intervals(self) -> list[tuple[float, float]]:
        """[(t_start, t_end), ...] of the kept samples where the wheel is locked [s]."""
        return _intervals(self.t, self.locked)

    @property
    def n_wheels(self) -> int:
        """Wheels in the run (per-wheel arrays are 2-D when there are several)."""
        return 1 if self.x_wheel.ndim == 1 else self.x_wheel.shape[1]

    def wheel(self, i: int):
        """Wheel ``i``'s view as a one-wheel run: every per-wheel array reduced to that wheel's
        (n_samples,) column, ``scene`` the single-wheel scene of that wheel under its static
        load of the vehicle's weight distribution, and ``settings.x_start`` that wheel's start.
        The view is a single wheel: :func:`trackwheel.analyse` of it measures against that
        wheel alone on the track; ``analyse(result, wheel=i)`` measures the wheel against its
        quasi-static line with the whole vehicle on the track (and the stretch the vehicle
        runs clear of the rail's ends)."""
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

    def sleeper_envelope(self):
        """Each support's envelope along the track (docs: Model § Outputs) as a pandas
        DataFrame, one row per support the run saw in the order of X (on a travelling window
        every sleeper that passed through it), the extremes over the kept samples while the
        support was in the rail; forces in N with compression positive, displacements in m up
        positive, times in s (``df.attrs["units"]`` maps each column to its unit; the columns
        are :data:`ENVELOPE_FIELDS`, listed below).

        ``contact_time`` counts the kept samples whose ballast force is > 0 (intact ballast:
        every sample unless the sleeper lifts off a tensionless bed; a sleeper over a void:
        the time it carries load), each standing for ``output_every`` x ``dt``; so does
        ``observed_time`` for every sample the support was in the rail. Single-spring supports
        report the spring's force as both forces and a zero displacement.

        Columns:
        """
        import pandas as pd

        df = pd.DataFrame({name: np.asarray(self.support_envelope[name])
                           for name, _u, _d in ENVELOPE_FIELDS})
        df.attrs["units"] = {name: unit for name, unit, _d in ENVELOPE_FIELDS}
        return df

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
        ] + _slide_lines(self))


_ResultMethods.sleeper_envelope.__doc__ += "\n" + "\n".join(
    f"        - ``{n}`` [{u}]: {d}" for n, u, d in ENVELOPE_FIELDS) + "\n"


#: Rim speed |theta'| rho0 [m/s] below which a wheel counts as locked (Result.locked): a
#: nanometre per second, far below any rolling or braking wheel's.
LOCKED_RIM_SPEED = 1e-9


def _intervals(t: np.ndarray, mask: np.ndarray) -> list[tuple[float, float]]:
    """[(first, last), ...] times [s] of the runs of True in ``mask`` (one wheel's)."""
    on = np.concatenate(([False], mask, [False]))
    edges = np.flatnonzero(np.diff(on.astype(np.int8)))
    return [(float(t[i]), float(t[j - 1])) for i, j in zip(edges[::2], edges[1::2])]


def _slide_lines(r) -> list[str]:
    """The repr's line on sliding and locking, if the wheel slid (sample counts x the sample
    spacing; every wheel of a vehicle together)."""
    if r.t.size < 2 or not np.any(r.sliding):
        return []
    dt = float(r.t[1] - r.t[0])
    lock = np.any(r.locked, axis=-1) if r.locked.ndim > 1 else r.locked
    slide = np.any(r.sliding, axis=-1) if r.sliding.ndim > 1 else r.sliding
    return [f"  slid: {slide.sum() * dt * 1e3:.4g} ms (|lambda| = mu N), locked "
            f"(theta' = 0): {lock.sum() * dt * 1e3:.4g} ms"]


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
              "then car body (None without bodies; z = 0 where every spring is unstretched).", "",
              "Per-support arrays (:data:`SUPPORT_FIELDS`), (n_samples, n_supports) over the",
              "rail's supports in the order of X, recorded with",
              "``simulate(..., support_forces=True)`` on a fixed rail (else None):", ""]
    for name, unit, doc in SUPPORT_FIELDS:
        lines.append(f"- ``{name}`` [{unit}]: {doc}")
    lines += ["", "``support_envelope``: each support's envelope along the track, {name: array}",
              "over :data:`ENVELOPE_FIELDS` (also on a travelling window, one entry per sleeper",
              "that passed): :meth:`sleeper_envelope` as a DataFrame.", "",
              "``ballast_events``: a unilateral ballast's open/closed changes over the run",
              "(voids, tensionless ballast; 0 otherwise); ``ballast_contact_time`` [s]: each",
              "sleeper's time on its ballast (None without sleepers; on a travelling window one",
              "entry per sleeper the run met, the rows of :meth:`sleeper_envelope`, each",
              "counting its time in the window)."]
    return "\n".join(lines)


Result = dataclasses.make_dataclass(
    "Result",
    [("scene", Scene), ("settings", RunSettings),
     *[(f[0], "np.ndarray | None" if f[0] == "energy" else "np.ndarray") for f in OUTPUT_FIELDS],
     ("steps", int), ("newton_iterations", int), ("state_changes", int),
     ("stability_limit", float), ("wall_time", float),
     ("final_state", object, field(repr=False)),
     ("body_z", "np.ndarray | None", field(default=None, repr=False)),
     ("body_phi", "np.ndarray | None", field(default=None, repr=False)),
     *[(f[0], "np.ndarray | None", field(default=None, repr=False)) for f in SUPPORT_FIELDS],
     ("support_envelope", "dict | None", field(default=None, repr=False)),
     ("ballast_events", int, field(default=0)),
     ("ballast_contact_time", "np.ndarray | None", field(default=None, repr=False))],
    bases=(_ResultMethods,), frozen=True, repr=False,
    namespace={"__doc__": _result_doc(), "__module__": __name__})


def sample_bytes(energy: bool, n_supports: int = 0) -> int:
    """Bytes one kept sample of a one-wheel run takes, from the output table, with the
    per-support fields of ``n_supports`` recorded supports."""
    return sum(4 if dtype.startswith("int") else 8 for name, _u, _d, _w, dtype in OUTPUT_FIELDS
               if energy or name != "energy") + 8 * len(SUPPORT_FIELDS) * n_supports


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
    for name, _unit, _doc in SUPPORT_FIELDS:
        arrays[name] = out.get(name)
    env = out.get("support_envelope")
    arrays["support_envelope"] = None if env is None else {
        name: np.asarray(env[name]) for name, _u, _d in ENVELOPE_FIELDS}
    return Result(scene=scene, settings=settings, **arrays, steps=out["steps"],
                  newton_iterations=out["newton_iterations"], state_changes=out["state_changes"],
                  stability_limit=out["stability_limit"], wall_time=wall_time,
                  final_state=out.get("final_state"),
                  ballast_events=int(out.get("ballast_events", 0)),
                  ballast_contact_time=(out["ballast_contact_time"]
                                        if len(out.get("ballast_contact_time", ())) else None))
