"""One passage of the settlement loop: a traffic item run over the (settled) track, and what the
loop takes from it, every settling sleeper's peak ballast force per axle
(docs: Model § The settlement loop).

:class:`PassageTask` is everything one passage needs, a plain picklable value, so that the
passages of a stage run on any ``concurrent.futures.Executor``; :func:`run_passage` runs one and
returns a :class:`PassageForces`. Two ways to run it (``PassageTask.fidelity``):

- a time-domain level of :func:`trackwheel.simulate` (``"linear/hertz"``, ..., ``"full"``): the
  dynamic passage at the item's speed; each sleeper's peak ballast force per axle
  (:func:`peak_ballast_forces`): one wheel, the run's envelope along the track
  (``Result.support_envelope``, on a fixed rail or a travelling window); several axles, the
  per-support ballast-force histories of a fixed rail (``simulate(..., support_forces=True)``),
  each sample given to the axle nearest the sleeper;
- ``"static"``: the wheel (or each wheel of the vehicle in turn) standing still right above
  each sleeper, the peak the static ballast force under it: the fixed-load estimate of linear
  spring tools, without inertia (no dynamic factor).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ...run import statics
from ...run.defaults import default_settings
from ...run.results import sample_bytes
from ...run.simulate import TIME_DOMAIN_LEVELS, simulate
from ...scene import Scene
from ...scene.support_fields import Voids

#: the passage that stands the wheels still above each sleeper (no time integration)
STATIC_LEVEL = "static"
#: every way :func:`run_passage` runs a passage
PASSAGE_LEVELS = TIME_DOMAIN_LEVELS + (STATIC_LEVEL,)
#: the travel of the wheels between two kept samples of a dynamic passage, a fraction of the
#: sleeper spacing [-]: the peak's relative error from sampling is about (dx / L)^2 / 8 for a
#: force bump of length L ~ d_s, 3e-6 at d_s / 200 (a few time steps at 200 km/h)
SAMPLE_TRAVEL = 1.0 / 200.0
#: the most memory the per-support histories of a several-axle passage may take [bytes]: a
#: longer rail keeps fewer samples (output_every grows) rather than more memory
HISTORY_BYTES = 256 * 2**20


@dataclass(frozen=True)
class PassageTask:
    """One passage: the ``scene`` (the traffic item's vehicle on the track as given), the
    ``voids`` of the settled bed (None: the scene's own): (N,) [m] one per support of a fixed
    rail, or on a travelling window the :class:`~trackwheel.scene.support_fields.Voids` at the
    track's sleepers (:func:`bed_voids`), the forward
    ``speed`` [m/s], the ``fidelity`` (:data:`PASSAGE_LEVELS`), the reference point's start and
    end ``x_start``, ``x_end`` [m] (resolved), the settling sleepers' positions ``sleepers``
    [m] and the other :func:`trackwheel.simulate` keywords ``simulate_kwargs``."""

    scene: Scene
    voids: tuple[float, ...] | Voids | None
    speed: float
    fidelity: str
    x_start: float
    x_end: float
    sleepers: tuple[float, ...]
    simulate_kwargs: dict = field(default_factory=dict)

    def bed(self) -> Scene:
        """The scene on the settled bed: ``Supports.void`` the ``voids``."""
        if self.voids is None:
            return self.scene
        return replace(self.scene, supports=replace(self.scene.supports, void=self.voids))


@dataclass(frozen=True)
class PassageForces:
    """What the loop takes from a passage: ``peaks`` (n_axles, n_sleepers) [N] each settling
    sleeper's peak ballast force (compression positive, >= 0) per axle, rear axle first;
    ``wheel_max``, ``wheel_min`` (n_axles,) [N] each wheel's largest and smallest contact force
    over the passage; ``static_load`` (n_axles,) [N] each wheel's static load (the dynamic
    factor is wheel_max / static_load)."""

    peaks: np.ndarray
    wheel_max: np.ndarray
    wheel_min: np.ndarray
    static_load: np.ndarray

    def __post_init__(self):
        peaks = np.atleast_2d(np.asarray(self.peaks, dtype=float))
        object.__setattr__(self, "peaks", np.maximum(peaks, 0.0))
        for name in ("wheel_max", "wheel_min", "static_load"):
            arr = np.atleast_1d(np.asarray(getattr(self, name), dtype=float))
            if arr.shape != (peaks.shape[0],):
                raise ValueError(f"PassageForces.{name} has shape {arr.shape}: one value per "
                                 f"axle ({peaks.shape[0]},)")
            object.__setattr__(self, name, arr)

    @property
    def dynamic_factor(self) -> float:
        """The largest wheel force over its static load, max over the axles [-]."""
        return float(np.max(self.wheel_max / self.static_load))

    def to_dict(self) -> dict:
        return {"peaks": self.peaks.tolist(), "wheel_max": self.wheel_max.tolist(),
                "wheel_min": self.wheel_min.tolist(), "static_load": self.static_load.tolist()}

    @classmethod
    def from_dict(cls, data) -> PassageForces:
        return cls(np.asarray(data["peaks"], dtype=float), np.asarray(data["wheel_max"]),
                   np.asarray(data["wheel_min"]), np.asarray(data["static_load"]))


def run_passage(task: PassageTask) -> PassageForces:
    """Run one passage (in any process: the default passage of :func:`trackwheel.settle`)."""
    scene = task.bed()
    loads = np.asarray(scene.active_vehicle.static_loads(scene.gravity), dtype=float)
    sleepers = np.asarray(task.sleepers, dtype=float)
    if task.fidelity == STATIC_LEVEL:
        peaks = static_peaks(scene, sleepers)
        return PassageForces(peaks, loads, loads, loads)
    several = loads.size > 1
    kwargs = dict(task.simulate_kwargs)
    kwargs.setdefault("output_every", passage_output_every(task, several))
    result = simulate(scene, task.speed, fidelity=task.fidelity, x_start=task.x_start,
                      x_end=task.x_end, progress=False, support_forces=several, **kwargs)
    force = np.asarray(result.normal_force, dtype=float).reshape(len(result.t), -1)
    return PassageForces(peak_ballast_forces(result, scene, sleepers), force.max(axis=0),
                         force.min(axis=0), loads)


def track_supports(scene: Scene, x_range) -> np.ndarray:
    """X [m] of every support the passages meet: the rail's on a fixed rail; on a travelling
    window each sleeper of the track (X = k d) it can cover over the runs, from a window's
    length (and a bay) behind the earliest start ``x_range`` (start, end) [m] pairs of the
    reference point to one ahead of the latest end, the vehicle's span included."""
    if scene.window is None:
        return np.asarray(scene.support_positions, dtype=float)
    d = scene.supports.spacing
    rear, front = scene.active_vehicle.span
    reach = scene.rail.length + d
    lo = min(x0 for x0, _ in x_range) + rear - reach
    hi = max(x1 for _, x1 in x_range) + front + reach
    return d * np.arange(math.floor(lo / d), math.ceil(hi / d) + 1)


def bed_voids(scene: Scene, supports: np.ndarray, voids: np.ndarray):
    """The ``PassageTask.voids`` of a bed with the gaps ``voids`` (N,) [m] under the supports
    at ``supports`` (N,) [m] (:func:`track_supports`): the tuple of gaps on a fixed rail; on a
    travelling window (which takes a void as a function of X, the sleepers it meets streaming
    in) the :class:`~trackwheel.scene.support_fields.Voids` at those sleepers."""
    if scene.window is None:
        return tuple(np.asarray(voids, dtype=float).tolist())
    return Voids(tuple(np.asarray(supports, dtype=float).tolist()),
                 tuple(np.asarray(voids, dtype=float).tolist()))


def passage_output_every(task: PassageTask, several: bool) -> int:
    """The passage's ``output_every``: a kept sample every SAMPLE_TRAVEL x d_s of travel (the
    envelope and the histories resolve each sleeper's peak), or, for several axles (the
    per-support histories, 24 bytes per support and sample), as many samples as fit in
    HISTORY_BYTES if fewer."""
    scene = task.scene
    dt = task.simulate_kwargs.get("dt")
    if dt is None:
        dt = default_settings(scene)["dt"]
    travel = max(task.speed * float(dt), 1e-300)
    every = max(1, int(SAMPLE_TRAVEL * scene.supports.spacing / travel))
    if several:
        n_steps = (task.x_end - task.x_start) / travel
        per_sample = (sample_bytes(False) * len(scene.active_vehicle.positions)
                      + sample_bytes(False, len(scene.support_positions)) - sample_bytes(False))
        every = max(every, math.ceil(n_steps * per_sample / HISTORY_BYTES))
    return every


def peak_ballast_forces(result, scene: Scene, sleepers) -> np.ndarray:
    """Each sleeper's peak ballast force per axle in a passage, (n_axles, n_sleepers) [N]
    (compression positive): of the kept samples in which axle i is the axle nearest sleeper j,
    the largest ballast force on sleeper j. ``sleepers``: the sleepers' positions X_j [m].

    One axle: the run's envelope along the track (``result.support_envelope``, every run keeps
    it, on a travelling window too). Several: the per-support histories
    (``result.ballast_force``, a run with ``support_forces=True`` on a fixed rail); a run
    without them raises a ValueError naming the way out.
    """
    sleepers = np.asarray(sleepers, dtype=float)
    offsets = np.asarray(scene.active_vehicle.positions, dtype=float)
    if offsets.size == 1:
        env = result.support_envelope
        columns = _columns(np.asarray(env["x"], dtype=float), sleepers)
        return np.asarray(env["ballast_force_max"], dtype=float)[columns][None, :]
    history = getattr(result, "ballast_force", None)
    if history is None:
        raise ValueError("the per-axle peaks of a several-axle vehicle need the per-support "
                         "ballast forces: simulate(..., support_forces=True) on a fixed rail")
    columns = _columns(np.asarray(scene.support_positions, dtype=float), sleepers)
    x_wheels = np.asarray(result.x_wheel, dtype=float).reshape(len(result.t), -1)
    x_ref = x_wheels[:, 0] - offsets[0]
    return axle_peaks(x_ref, offsets, sleepers, np.asarray(history, dtype=float)[:, columns])


def axle_peaks(x_ref: np.ndarray, offsets: np.ndarray, sleepers: np.ndarray,
               force: np.ndarray) -> np.ndarray:
    """(n_axles, n_sleepers): of the samples (rows of ``force`` (T, n_sleepers) [N], the
    vehicle's reference point at ``x_ref`` (T,) [m]) in which axle i (at x_ref + offsets[i])
    is the axle nearest sleeper j (at ``sleepers[j]``), the largest force; 0 where axle i is
    never the nearest."""
    n_axles = offsets.size
    out = np.zeros((n_axles, sleepers.size))
    if n_axles == 1:
        out[0] = force.max(axis=0, initial=0.0)
        return out
    distance = np.abs(x_ref[:, None, None] + offsets[None, :, None] - sleepers[None, None, :])
    nearest = np.argmin(distance, axis=1)  # (T, n_sleepers)
    for i in range(n_axles):
        out[i] = np.where(nearest == i, force, 0.0).max(axis=0, initial=0.0)
    return out


def static_peaks(scene: Scene, sleepers: np.ndarray) -> np.ndarray:
    """(n_axles, n_sleepers) [N]: the static ballast force on sleeper j with axle i standing
    right above it (the vehicle's reference point at X_j - x_i), the others where they fall."""
    positions = np.asarray(scene.support_positions, dtype=float)
    columns = _columns(positions, sleepers)
    veh = scene.active_vehicle
    offsets = np.asarray(veh.positions, dtype=float)
    out = np.zeros((offsets.size, sleepers.size))
    for i, p in enumerate(offsets):
        for j, x in enumerate(sleepers):
            if scene.vehicle is None:
                force = statics.static(scene, float(x)).ballast_force
            else:
                force = statics.vehicle_static(scene, float(x - p)).ballast_force
            out[i, j] = max(float(np.asarray(force)[columns[j]]), 0.0)
    return out


def _columns(positions: np.ndarray, sleepers: np.ndarray) -> np.ndarray:
    """The support index of each sleeper X (ValueError if one stands on no support)."""
    if positions.size == 0:
        raise ValueError("the scene has no supports to settle")
    idx = np.argmin(np.abs(positions[None, :] - sleepers[:, None]), axis=1)
    off = np.abs(positions[idx] - sleepers) > 1e-6
    if np.any(off):
        raise ValueError(f"the settling sleeper at X = {sleepers[off][0]:.6g} m stands on no "
                         "support of the scene")
    return idx
