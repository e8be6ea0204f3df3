"""What every settlement law shares: the per-sleeper state it advances, the interface
(``initial_state``, ``advance``) and the checks of its inputs
(docs: Model § Ballast settlement).

A law is a frozen dataclass of its parameters; its state, a :class:`SettlementState`, holds
per sleeper the settlement so far, the load cycles so far and the law's own history (Varandas:
the load histogram). States are immutable: ``advance`` returns a new one, so a caller keeps any
earlier state to resume from, and ``to_dict``/``from_dict`` store one as plain JSON values.
"""

from __future__ import annotations

import abc
import dataclasses
import numbers
from collections.abc import Mapping
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ...base import validate as v
from ...base.limits import MAX_SUPPORTS

#: Most load cycles a sleeper may count [-]: whole numbers stay exact in double precision.
MAX_CYCLES = 2**53


def _frozen(array, dtype) -> np.ndarray:
    out = np.array(array, dtype=dtype, copy=True)
    out.flags.writeable = False
    return out


@dataclass(frozen=True, eq=False)
class SettlementState:
    """The state of a settlement law for n sleepers (immutable: ``advance`` returns a new one).

    ``law`` is the name of the law that made it (``"varandas"``, ``"sato"``, ``"shenton"``);
    ``settlement`` (n,) [m] the settlement of each sleeper so far (down positive, the amount
    the ballast bed under it has sunk); ``cycles`` (n,) [-] the load cycles (axle passes) each
    has seen; ``history`` the law's own arrays, each with the sleepers along its first axis and
    zero padding (Varandas: ``levels`` (n, m) [N], the distinct peak forces of the past cycles
    in descending order, and ``counts`` (n, m) [-], how many cycles had each).
    """

    law: str
    settlement: np.ndarray
    cycles: np.ndarray
    history: Mapping[str, np.ndarray] = dataclasses.field(default_factory=dict)

    def __post_init__(self):
        settlement = _frozen(self.settlement, float)
        cycles = _frozen(self.cycles, np.int64)
        if settlement.ndim != 1 or cycles.shape != settlement.shape:
            raise ValueError(f"settlement and cycles must be 1-d arrays of the same length, got "
                             f"shapes {settlement.shape} and {cycles.shape}")
        history = {}
        for name, array in self.history.items():
            array = _frozen(array, np.int64 if np.asarray(array).dtype.kind in "iu" else float)
            if array.shape[:1] != settlement.shape:
                raise ValueError(f"history {name!r} has shape {array.shape}: its first axis "
                                 f"must be the {settlement.size} sleepers")
            history[name] = array
        object.__setattr__(self, "settlement", settlement)
        object.__setattr__(self, "cycles", cycles)
        object.__setattr__(self, "history", history)

    @property
    def n_sleepers(self) -> int:
        """The number of sleepers [-]."""
        return int(self.settlement.size)

    def __len__(self) -> int:
        return self.n_sleepers

    def select(self, sleepers) -> SettlementState:
        """The state of some sleepers (an index, a slice, indices or a mask), as if they had
        been advanced alone: history columns that are padding for all of them are dropped."""
        index = np.arange(self.n_sleepers)[sleepers]
        index = np.atleast_1d(index)
        history = {name: a[index] for name, a in self.history.items()}
        widths = [a.shape[1] for a in history.values() if a.ndim == 2]
        if widths:
            used = np.zeros(widths[0], dtype=bool)
            for a in history.values():
                used |= np.any(a != 0, axis=0)
            keep = int(np.flatnonzero(used)[-1]) + 1 if used.any() else 0
            history = {name: a[:, :keep] if a.ndim == 2 else a for name, a in history.items()}
        return SettlementState(self.law, self.settlement[index], self.cycles[index], history)

    def equals(self, other: SettlementState) -> bool:
        """True if ``other`` is the same state bit for bit (same law, arrays and shapes)."""
        return (self.law == other.law and self.history.keys() == other.history.keys()
                and _same(self.settlement, other.settlement)
                and _same(self.cycles, other.cycles)
                and all(_same(a, other.history[k]) for k, a in self.history.items()))

    def to_dict(self) -> dict:
        """The state as plain JSON values (floats round-trip exactly through ``repr``)."""
        return {"law": self.law, "settlement": self.settlement.tolist(),
                "cycles": self.cycles.tolist(),
                "history": {name: {"shape": list(a.shape), "dtype": a.dtype.kind,
                                   "values": a.ravel().tolist()}
                            for name, a in self.history.items()}}

    @classmethod
    def from_dict(cls, data: Mapping) -> SettlementState:
        """The state that :meth:`to_dict` wrote."""
        history = {name: np.asarray(h["values"], dtype=np.int64 if h["dtype"] in "iu"
                                    else float).reshape(h["shape"])
                   for name, h in data.get("history", {}).items()}
        return cls(data["law"], np.asarray(data["settlement"], dtype=float),
                   np.asarray(data["cycles"], dtype=np.int64), history)


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


class SettlementLaw(abc.ABC):
    """A settlement law: how much each sleeper settles under load cycles of given peak ballast
    forces. Subclasses are frozen dataclasses of their parameters and implement ``_advance``
    (and ``_history`` for a history of their own)."""

    #: the law's name, stored with its states
    name: ClassVar[str] = ""

    def initial_state(self, n_sleepers: int) -> SettlementState:
        """The state of ``n_sleepers`` fresh sleepers: no settlement, no cycles, no history."""
        n = v.integer("n_sleepers", n_sleepers, low=1, high=MAX_SUPPORTS)
        return SettlementState(self.name, np.zeros(n), np.zeros(n, dtype=np.int64),
                               self._history(n))

    def advance(self, state: SettlementState, peak_force,
                cycles) -> tuple[SettlementState, np.ndarray]:
        """Advance every sleeper by ``cycles`` load cycles of peak ballast force ``peak_force``.

        ``peak_force`` [N] is (n,), one peak per sleeper, or (k, n): k kinds of cycle (the axles
        of a stage's traffic), each with its own peak per sleeper; compressive, >= 0.
        ``cycles`` [-] is how many cycles of each kind: a whole number, one per row (k,), or
        one per row and sleeper (the shape of ``peak_force``). Returns the new state and each
        sleeper's settlement increment (n,) [m], computed directly (not as a difference of
        totals, which would lose the small increments of a long history).
        """
        self._check_state(state)
        force, count = peak_inputs(peak_force, cycles, state.n_sleepers)
        if np.any(state.cycles + count.sum(axis=0) > MAX_CYCLES):
            raise ValueError(f"cycles: a sleeper would count more than {MAX_CYCLES} cycles, "
                             f"the most that stay exact")
        return self._advance(state, force, count)

    def constant_load(self, peak_force, cycles) -> np.ndarray:
        """The settlement [m] of fresh sleepers after ``cycles`` cycles of a constant peak
        ballast force ``peak_force`` [N] (broadcast together; a number for numbers): the law's
        closed form."""
        force = np.asarray(peak_force, dtype=float)
        count = np.asarray(cycles)
        force, count = np.broadcast_arrays(force, count)
        if force.ndim == 0:
            f, n = peak_inputs(force.reshape(1), count.reshape(1), 1)
        else:
            f, n = peak_inputs(force.ravel(), count.ravel(), force.size)
        return self._constant_load(f[0], n[0].astype(float)).reshape(force.shape)[()]

    def to_dict(self) -> dict:
        """The law's name and parameters as plain values (``law_from_dict`` reads them)."""
        return {"law": self.name, **dataclasses.asdict(self)}

    def _history(self, n: int) -> dict:
        return {}

    def _check_state(self, state):
        if not isinstance(state, SettlementState):
            raise TypeError(f"state must be a SettlementState, got {type(state).__name__}")
        if state.law != self.name:
            raise ValueError(f"state is a {state.law!r} state; this law is {self.name!r}")

    @abc.abstractmethod
    def _advance(self, state: SettlementState, force: np.ndarray,
                 count: np.ndarray) -> tuple[SettlementState, np.ndarray]:
        """The step itself on checked inputs: force (k, n) [N] and count (k, n) int64."""

    @abc.abstractmethod
    def _constant_load(self, force: np.ndarray, count: np.ndarray) -> np.ndarray:
        """The closed form on checked 1-d inputs: force [N], count [-] as floats."""


def peak_inputs(peak_force, cycles, n_sleepers: int) -> tuple[np.ndarray, np.ndarray]:
    """The peak forces as a (k, n) float array [N] and the cycles as a (k, n) int64 array,
    checked: forces finite and >= 0, cycles whole numbers in [0, MAX_CYCLES]."""
    force = np.asarray(peak_force, dtype=float) if _numeric(peak_force) else None
    if force is None or force.ndim not in (1, 2) or force.shape[-1] != n_sleepers:
        shape = "?" if force is None else force.shape
        raise ValueError(f"peak_force must be a real array of shape ({n_sleepers},) or "
                         f"(k, {n_sleepers}) [N], one peak per sleeper, got shape {shape}")
    force = np.atleast_2d(force)
    if not np.all(np.isfinite(force)) or np.any(force < 0.0):
        bad = force[~np.isfinite(force) | (force < 0.0)][0]
        raise ValueError(f"peak_force = {bad} is outside the allowed range [0, inf) N "
                         f"(a compressive peak ballast force)")
    if not _numeric(cycles):
        raise TypeError(f"cycles must be a whole number or an array of them, got "
                        f"{type(cycles).__name__}")
    raw = np.asarray(cycles)
    if raw.ndim == 1 and raw.shape[0] == force.shape[0] and np.ndim(peak_force) == 2:
        raw = raw[:, None]  # one count per row of a 2-d peak_force
    try:
        raw = np.broadcast_to(raw, force.shape)
    except ValueError:
        raise ValueError(f"cycles has shape {np.shape(cycles)}: give a number, one per row of "
                         f"peak_force ({force.shape[0]},) or one per peak {force.shape}") from None
    as_float = raw.astype(float)
    ok = np.isfinite(as_float) & (as_float >= 0) & (as_float <= MAX_CYCLES)
    ok &= as_float == np.floor(as_float)
    if not np.all(ok):
        bad = raw[~ok][0]
        raise ValueError(f"cycles = {bad} is not a whole number in the allowed range "
                         f"[0, {MAX_CYCLES}]")
    return force, as_float.astype(np.int64)


def _numeric(x) -> bool:
    if isinstance(x, (bool, np.bool_)):
        return False
    if isinstance(x, numbers.Real):
        return True
    try:
        kind = np.asarray(x).dtype.kind
    except (TypeError, ValueError):
        return False
    return kind in "iuf"



def whole(name: str, value, *, low: int, high: int) -> int:
    """``value`` as an int in [low, high]: an int, or a float with a whole value (1e6)."""
    if isinstance(value, (float, np.floating)) and float(value).is_integer():
        value = int(value)
    return v.integer(name, value, low=low, high=high)
