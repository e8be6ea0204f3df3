"""The settlement loop's results and their store (docs: Model § The settlement loop).

:class:`SettlementHistory` holds one entry per state of the bed, from the intact track (stage
0) to the last stage: the cycles and days so far, each settling sleeper's settlement and void,
and what the passages on that bed gave (peak ballast forces, wheel forces, the dynamic factor).
:meth:`SettlementHistory.frame` and :meth:`~SettlementHistory.stages` are its DataFrames.

The store is a directory: ``settle.json`` (the run's inputs and their hash) and one
``stage-NNNNN.json`` per state of the bed (the law's state, the passages so far, the passages'
forces on that bed), each written atomically; a run with the same inputs and store reads the
stages there and goes on from the last, bit for bit as if it had not stopped.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .passage import PassageForces
from .state import SettlementLaw, SettlementState

if TYPE_CHECKING:
    import pandas as pd

FORMAT = "trackwheel.settle.stage"
FORMAT_VERSION = 1


@dataclass(frozen=True)
class Stage:
    """One state of the bed: ``cycles`` [-] axle passes so far (of the loop's target count),
    ``passages`` (k,) whole passages of each traffic item so far, the law's ``state``, the
    ``voids`` (n,) [m] of the settling sleepers in this bed and ``forces`` (one
    :class:`PassageForces` per traffic item) of the passages on it."""

    index: int
    cycles: int
    passages: tuple[int, ...]
    state: SettlementState
    voids: np.ndarray
    forces: tuple[PassageForces, ...]

    def to_dict(self) -> dict:
        return {"index": self.index, "cycles": self.cycles, "passages": list(self.passages),
                "state": self.state.to_dict(), "voids": np.asarray(self.voids).tolist(),
                "forces": [f.to_dict() for f in self.forces]}

    @classmethod
    def from_dict(cls, d) -> Stage:
        return cls(int(d["index"]), int(d["cycles"]), tuple(int(p) for p in d["passages"]),
                   SettlementState.from_dict(d["state"]), np.asarray(d["voids"], dtype=float),
                   tuple(PassageForces.from_dict(f) for f in d["forces"]))


@dataclass(frozen=True, eq=False)
class SettlementHistory:
    """What :func:`trackwheel.settle` returns: the bed stage by stage.

    Arrays over the states of the bed (m + 1 of them: the intact bed, then after each of the m
    stages) and the n settling sleepers: ``sleepers`` (n,) X_j [m]; ``cycles`` (m+1,) [-] axle
    passes so far; ``days`` (m+1,) [day]; ``settlement`` (m+1, n) [m] (down positive);
    ``voids`` (m+1, n) [m] the gap g_j under each sleeper in that bed; ``peak_force``
    (m+1, n) [N] each sleeper's largest peak ballast force of the passages on that bed (max over
    the axles and items); ``wheel_max``, ``wheel_min`` (m+1, k) [N] each traffic item's
    largest and smallest wheel force; ``dynamic_factor`` (m+1,) [-] the largest wheel force
    over its static load. With ``feedback=False`` the passages run on the intact bed only and
    every row repeats its forces (the forces the stages used). ``support_stiffness`` (n,) [N/m]
    each sleeper's static support stiffness (pad and ballast in series); ``state`` the law's
    final :class:`SettlementState`; ``stage_list`` the stored stages.
    """

    sleepers: np.ndarray
    support_stiffness: np.ndarray
    cycles: np.ndarray
    days: np.ndarray
    settlement: np.ndarray
    voids: np.ndarray
    peak_force: np.ndarray
    wheel_max: np.ndarray
    wheel_min: np.ndarray
    dynamic_factor: np.ndarray
    state: SettlementState
    law: SettlementLaw
    feedback: bool
    item_labels: tuple[str, ...]
    stage_list: tuple[Stage, ...]
    static_deflection: float
    computed: int = 0

    @classmethod
    def build(cls, stages, sleepers, stiffness, days_per_cycle, law, feedback, labels,
              static_deflection, computed) -> SettlementHistory:
        peak = np.array([np.max([f.peaks.max(axis=0) for f in s.forces], axis=0)
                         for s in stages])
        wmax = np.array([[f.wheel_max.max() for f in s.forces] for s in stages])
        wmin = np.array([[f.wheel_min.min() for f in s.forces] for s in stages])
        factor = np.array([max(f.dynamic_factor for f in s.forces) for s in stages])
        cycles = np.array([s.cycles for s in stages], dtype=np.int64)
        return cls(np.asarray(sleepers, dtype=float), np.asarray(stiffness, dtype=float),
                   cycles, cycles * days_per_cycle,
                   np.array([s.state.settlement for s in stages]),
                   np.array([s.voids for s in stages]), peak, wmax, wmin, factor,
                   stages[-1].state, law, feedback, tuple(labels), tuple(stages),
                   float(static_deflection), computed)

    @property
    def n_stages(self) -> int:
        """The stages run (states of the bed minus one) [-]."""
        return len(self.stage_list) - 1

    @property
    def differential(self) -> np.ndarray:
        """(m+1,) [m] the largest minus the smallest settlement of each state."""
        return self.settlement.max(axis=1) - self.settlement.min(axis=1)

    def stages(self) -> pd.DataFrame:
        """One row per state of the bed: stage, cycles, days, the settlement's max, min and
        mean [m], the differential settlement [m], the largest void [m], the largest peak
        ballast force [N], the largest wheel force [N] and the dynamic factor [-]."""
        import pandas as pd

        return pd.DataFrame({
            "stage": np.arange(len(self.cycles)), "cycles": self.cycles, "days": self.days,
            "settlement_max_m": self.settlement.max(axis=1),
            "settlement_min_m": self.settlement.min(axis=1),
            "settlement_mean_m": self.settlement.mean(axis=1),
            "differential_m": self.differential, "void_max_m": self.voids.max(axis=1),
            "peak_ballast_force_max_N": self.peak_force.max(axis=1),
            "wheel_force_max_N": self.wheel_max.max(axis=1),
            "dynamic_factor": self.dynamic_factor})

    def frame(self) -> pd.DataFrame:
        """One row per state of the bed and sleeper (long form): stage, cycles, days, sleeper
        index, X [m], settlement [m], void [m], peak ballast force [N]."""
        import pandas as pd

        m, n = self.settlement.shape
        return pd.DataFrame({
            "stage": np.repeat(np.arange(m), n), "cycles": np.repeat(self.cycles, n),
            "days": np.repeat(self.days, n), "sleeper": np.tile(np.arange(n), m),
            "x_m": np.tile(self.sleepers, m), "settlement_m": self.settlement.ravel(),
            "void_m": self.voids.ravel(), "peak_ballast_force_N": self.peak_force.ravel()})

    def __repr__(self) -> str:
        return (f"SettlementHistory({self.n_stages} stages, {int(self.cycles[-1])} cycles, "
                f"{self.sleepers.size} sleepers, settlement {1e3 * self.settlement[-1].min():.3g}"
                f"..{1e3 * self.settlement[-1].max():.3g} mm, dynamic factor "
                f"{self.dynamic_factor[0]:.3f} -> {self.dynamic_factor[-1]:.3f})")


# ----------------------------------------------------------------------------------------------
# the store
def canonical(obj) -> bytes:
    """Canonical JSON (sorted keys, no spaces, floats by repr): what is hashed."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False).encode()


def open_store(store, inputs: dict) -> tuple[Path | None, list[Stage]]:
    """The store directory (created if missing, ``settle.json`` written) and the stages it
    holds for these ``inputs``: the sound ``stage-NNNNN.json`` from 0 on, up to the first
    missing or unsound one. ValueError if the store holds a run of other inputs."""
    if store is None:
        return None, []
    path = Path(os.fspath(store))
    if path.exists() and not path.is_dir():
        raise ValueError(f"store = {os.fspath(store)!r} exists and is not a directory")
    path.mkdir(parents=True, exist_ok=True)
    digest = hashlib.sha256(canonical(inputs)).hexdigest()
    meta = path / "settle.json"
    if meta.exists():
        try:
            old = json.loads(meta.read_bytes()).get("inputs_hash")
        except (OSError, ValueError):
            old = None
        if old != digest:
            raise ValueError(f"store = {os.fspath(store)!r} holds a settlement run of other "
                             "inputs (scene, traffic, law or settings); give another directory")
    else:
        write_json(meta, {"format": "trackwheel.settle", "inputs_hash": digest,
                          "inputs": inputs})
    stages = []
    while True:
        record = _read_stage(path / stage_name(len(stages)), digest)
        if record is None:
            break
        stages.append(record)
    return path, stages


def stage_name(index: int) -> str:
    return f"stage-{index:05d}.json"


def write_stage(store: Path | None, stage: Stage, inputs_hash: str) -> None:
    if store is None:
        return
    payload = {"format": FORMAT, "format_version": FORMAT_VERSION, "inputs_hash": inputs_hash,
               "stage": stage.to_dict()}
    payload["checksum"] = hashlib.sha256(canonical(payload)).hexdigest()
    write_json(store / stage_name(stage.index), payload)


def _read_stage(path: Path, digest: str) -> Stage | None:
    if not path.exists():
        return None
    try:
        payload = json.loads(path.read_bytes())
        checksum = payload.pop("checksum", None)
        if (payload.get("format") != FORMAT or payload.get("format_version") != FORMAT_VERSION
                or payload.get("inputs_hash") != digest
                or checksum != hashlib.sha256(canonical(payload)).hexdigest()):
            return None
        return Stage.from_dict(payload["stage"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def inputs_digest(inputs: dict) -> str:
    return hashlib.sha256(canonical(inputs)).hexdigest()


def write_json(path: Path, payload: dict) -> None:
    """Write ``payload`` atomically (a temporary file, flushed, renamed over the name)."""
    data = json.dumps(payload, sort_keys=True, allow_nan=False).encode()
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".json", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
