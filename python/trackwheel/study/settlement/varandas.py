"""The load-history settlement law of Varandas, Hölscher and Silva (2014)
(docs: Model § Ballast settlement): a sleeper settles in a load cycle by an amount that depends
on the cycle's peak ballast force and on how many earlier cycles reached each force below it.

Sleeper j in cycle n with peak ballast force F_n settles by

    u_n = (gamma / M) int_0^{F_n} F^alpha (h_n(F) + 1)^(-beta) dF,
    M = F0^(alpha+1) / (alpha + 1) * Z(N0),   Z(N) = sum_{k=1}^{N} k^(-beta),

h_n(F) the number of earlier cycles whose peak reached F. At every force F the cycles that
reach it are the ones that raise h(F), each by one, so after any sequence of cycles

    S = (gamma / Z(N0)) int_0^inf d[(F/F0)^(alpha+1)] Z(H(F)),

H(F) the number of all cycles whose peak reached F: the settlement depends on the load
histogram only, not on the order of the cycles. The state is that histogram per sleeper: its
distinct peak levels and how many cycles had each. H is constant between two levels, so a step
of any number of cycles is a sum over the pieces between levels of the piece's weight
(F_hi/F0)^(alpha+1) - (F_lo/F0)^(alpha+1) times a partial sum sum_{h=H_old+1}^{H_old+dH}
h^(-beta) (:func:`~.power_sums.power_sum`): exact for a stage of 1e7 cycles at the cost of one.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ...base import validate as v
from .power_sums import MAX_EXPONENT, power_sum
from .state import SettlementLaw, SettlementState, whole


@dataclass(frozen=True)
class Varandas(SettlementLaw):
    """The load-history settlement law of Varandas et al. (2014), per sleeper.

    Defaults: ROSE's (Deltares' railway settlement tool), after Varandas et al. (2014),
    Proc. IMechE Part F 228(3), 242-259: alpha = 0.6, beta = 0.82, gamma = 10 mm, the
    settlement of the reference test of N0 = 10^6 cycles of F0 = 50 kN. A constant peak force
    F gives ``S_N = gamma (F/F0)^(1+alpha) Z(N) / Z(N0)``, Z(N) = sum_{n<=N} n^(-beta).

    ``level_rtol`` [-] keeps the history short when every cycle has a slightly different peak
    (cycle by cycle, or forces that change a little each stage): a new peak within
    ``level_rtol`` of an existing level of its sleeper counts at that level. Each peak then
    counts at a force within a factor (1 +- level_rtol) of its own, so the settlement stays
    within a factor (1 +- level_rtol)^(1+alpha) of the exact one (0.16 % at the default), and a
    sleeper keeps at most about ln(F_max/F_min) / level_rtol levels. 0 keeps every peak.
    """

    #: exponent of the force in the integrand [-], > -1
    alpha: float = 0.6
    #: decay of a force's settlement with the cycles that reached it before [-], in [0, 10]
    beta: float = 0.82
    #: settlement of the reference test [m]: N0 cycles of F0 on a fresh sleeper
    gamma: float = 0.01
    #: N0, cycles of the reference test [-]
    reference_cycles: int = 1_000_000
    #: F0, peak ballast force of the reference test [N]
    reference_force: float = 50e3
    #: relative tolerance within which a new peak counts at an existing level [-], in [0, 0.1]
    level_rtol: float = 1e-3

    name: ClassVar[str] = "varandas"

    def __post_init__(self):
        checked = {
            "alpha": v.number("alpha", self.alpha, low=-1.0, low_open=True, high=10.0),
            "beta": v.number("beta", self.beta, low=0.0, high=MAX_EXPONENT),
            "gamma": v.number("gamma", self.gamma, low=0.0, high=1.0, unit="m"),
            "reference_cycles": whole("reference_cycles", self.reference_cycles, low=1,
                                      high=10**12),
            "reference_force": v.number("reference_force", self.reference_force, low=0.0,
                                        low_open=True, high=1e7, unit="N"),
            "level_rtol": v.number("level_rtol", self.level_rtol, low=0.0, high=0.1),
        }
        for name, value in checked.items():
            object.__setattr__(self, name, value)

    @property
    def reference_sum(self) -> float:
        """Z(N0) = sum_{k=1}^{N0} k^(-beta) [-]: M_alpha_beta = F0^(alpha+1) Z(N0) /
        (alpha+1)."""
        return float(power_sum(self.beta, 1.0, float(self.reference_cycles)))

    def _history(self, n: int) -> dict:
        return {"levels": np.zeros((n, 0)), "counts": np.zeros((n, 0), dtype=np.int64)}

    def _constant_load(self, force, count):
        scale = self.gamma / self.reference_sum
        weight = (force / self.reference_force) ** (self.alpha + 1.0)
        return scale * (weight * power_sum(self.beta, 1.0, count))

    def _advance(self, state, force, count):
        levels, counts = state.history["levels"], state.history["counts"]
        n = state.n_sleepers
        new_levels, new_counts = force.T.copy(), count.T.copy()  # (n, k)
        empty = (new_levels == 0.0) | (new_counts == 0)  # leaves no mark on the histogram
        new_levels[empty], new_counts[empty] = 0.0, 0
        if self.level_rtol > 0.0 and levels.shape[1]:
            new_levels = self._snap(levels, new_levels)
        # the union of the old and the new levels, highest first; a batch's zero padding sinks
        # to the end, and of equal levels the first spans a piece of zero width
        union = np.concatenate([levels, new_levels], axis=1)
        order = np.argsort(-union, axis=1, kind="stable")
        union = np.take_along_axis(union, order, axis=1)
        old = np.take_along_axis(np.concatenate([counts, np.zeros_like(new_counts)], axis=1),
                                 order, axis=1)
        new = np.take_along_axis(np.concatenate([np.zeros_like(counts), new_counts], axis=1),
                                 order, axis=1)
        h_old = np.cumsum(old, axis=1)  # H(F) on the piece below each level, before
        h_new = np.cumsum(new, axis=1)  # and the cycles this step adds there
        scaled = (union / self.reference_force) ** (self.alpha + 1.0)
        weight = scaled - np.concatenate([scaled[:, 1:], np.zeros((n, 1))], axis=1)
        terms = np.zeros_like(weight)
        reached = h_new > 0  # the pieces this step's peaks reach (elsewhere nothing changes)
        terms[reached] = weight[reached] * power_sum(self.beta, h_old[reached] + 1.0,
                                                     h_new[reached])
        total = np.zeros(n)
        for column in terms.T:  # in order, so that padding columns add exact zeros
            total = total + column
        increment = (self.gamma / self.reference_sum) * total
        history = _histogram(union, old + new)
        return (SettlementState(self.name, state.settlement + increment,
                                state.cycles + count.sum(axis=0), history), increment)

    def _snap(self, levels: np.ndarray, new: np.ndarray) -> np.ndarray:
        """Each new peak moved to the nearest existing level of its sleeper if within
        ``level_rtol`` of it (one new column at a time: memory n x m)."""
        real = levels > 0.0
        out = new.copy()
        for i in range(new.shape[1]):
            peak = new[:, i:i + 1]
            distance = np.where(real, np.abs(levels - peak), np.inf)
            nearest = np.argmin(distance, axis=1)[:, None]
            close = (peak > 0.0) & (np.take_along_axis(distance, nearest, axis=1)
                                    <= self.level_rtol * peak)
            out[:, i:i + 1] = np.where(close, np.take_along_axis(levels, nearest, axis=1), peak)
        return out


def _histogram(levels: np.ndarray, counts: np.ndarray) -> dict:
    """Levels sorted highest first with their counts, equal levels merged, zeros dropped, as
    (n, width) arrays padded with zeros at the end."""
    n = levels.shape[0]
    valid = levels > 0.0
    start = valid.copy()
    start[:, 1:] &= levels[:, 1:] != levels[:, :-1]
    group = np.cumsum(start, axis=1) - 1
    width = int(start.sum(axis=1).max()) if n else 0
    rows, cols = np.nonzero(valid)
    out_levels = np.zeros((n, width))
    out_counts = np.zeros((n, width), dtype=np.int64)
    np.add.at(out_counts, (rows, group[rows, cols]), counts[rows, cols])
    out_levels[rows, group[rows, cols]] = levels[rows, cols]
    return {"levels": out_levels, "counts": out_counts}
