"""Settlement laws of the curve kind (docs: Model § Ballast settlement): the settlement after N
cycles of one constant load, S(N; F), a published curve whose coefficients scale with the peak
ballast force F; Sato (1995) and Shenton (1985).

A curve gives the settlement under one constant load only; under a load that varies from stage
to stage the laws accumulate by one of two rules (``hardening``):

- ``"strain"`` (the default; the "equivalent cycles" of accumulation models): the state is the
  settlement S itself. A stage of dN cycles at force F starts from the cycles N_eq that would
  have given S at F, S(N_eq; F) = S, and adds S(N_eq + dN; F) - S. After a heavier load a
  lighter one finds the bed already compacted (N_eq large, a small rate); after a lighter load
  a heavier one starts early on its own curve.
- ``"time"``: the state is the number of cycles N so far, whatever their loads; a stage adds
  S(N + dN; F) - S(N; F).

Both give the curve itself under a constant load. Several kinds of cycle in one call (rows of
``peak_force``) are applied in the order of the rows: the order matters for these laws (not for
Varandas'), by an amount that vanishes as the stages get shorter.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ...base import validate as v
from .state import SettlementLaw, SettlementState

#: Newton iterations of an inversion before it gives up (each stops at its own convergence:
#: quadratic, monotone, so a few tens in the worst case).
_MAX_NEWTON = 200
HARDENING = ("strain", "time")


class CurveLaw(SettlementLaw):
    """A settlement law given by a curve S(N; F), the settlement after N cycles of a constant
    peak ballast force F, and a ``hardening`` rule for a force that varies (module docstring).

    Subclasses give the curve's coefficients per sleeper from F (``_coefficients``), its rise
    S(N + dN; F) - S(N; F) (``_rise``) and its inverse in N (``_cycles_at``)."""

    def _check_common(self):
        for name, value in {
            "reference_force": v.number("reference_force", self.reference_force, low=0.0,
                                        low_open=True, high=1e7, unit="N"),
            "load_exponent": v.number("load_exponent", self.load_exponent, low=0.0,
                                      high=10.0),
            "hardening": v.choice("hardening", self.hardening, HARDENING),
        }.items():
            object.__setattr__(self, name, value)

    def _load_factor(self, force: np.ndarray, exponent: float) -> np.ndarray:
        return (force / self.reference_force) ** exponent

    def _constant_load(self, force, count):
        return self._rise(self._coefficients(force), np.zeros_like(count), count)

    def _advance(self, state, force, count):
        settlement = state.settlement
        cycles = state.cycles.astype(float)
        total = np.zeros(state.n_sleepers)
        for row, dn in zip(force, count.astype(float)):  # the rows in order
            coefficients = self._coefficients(row)
            start = cycles if self.hardening == "time" else self._cycles_at(coefficients,
                                                                            settlement)
            increment = self._rise(coefficients, start, dn)
            settlement = settlement + increment
            cycles = cycles + dn
            total = total + increment
        return (SettlementState(self.name, settlement, state.cycles + count.sum(axis=0)),
                total)


@dataclass(frozen=True)
class Sato(CurveLaw):
    """Sato (1995): ``S(N) = a (1 - exp(-b N)) + c N``, initial compaction then a linear rate.

    Sato, Y. (1995), Japanese studies on deterioration of ballasted track, Vehicle System
    Dynamics 24 (sup1), 197-208 (there y = gamma (1 - e^(-alpha x)) + beta x; here a, b, c). The
    coefficients hold at the peak ballast force ``reference_force`` F0 and scale with the peak
    force F of a cycle:
    ``c(F) = c (F/F0)^load_exponent`` (Sato's settlement rate grows with the load) and
    ``a(F) = a (F/F0)^compaction_exponent``; the default exponents 1 make the whole curve
    proportional to the load, so that an unloaded sleeper does not settle; 0 makes a term
    independent of the load. ``hardening``: how a varying load accumulates (module docstring).

    No defaults (a, b, c and F0 are required): the coefficients are fits to one site's or one
    test's settlement, and a default would need published values together with the peak
    ballast force under one sleeper at which they hold (or the track and load data to compute
    it). None of the sources consulted gives them in that form: of the reviews of Dahlberg
    (Railway track settlements - a literature review, SUPERTRACK report, Linkoping 2004) and
    Abadi et al. (2016, Procedia Engineering 143, 999-1006) only the openings, without
    coefficient values, were at hand, and ROSE (Deltares' settlement tool) takes Sato's three
    coefficients as required arguments, without a load dependence. Fit a, b, c to settlement
    against cycles measured at a known peak ballast force F0 (a box test, an instrumented
    sleeper).
    """

    #: a, initial compaction at F0 [m], in [0, 1]
    a: float
    #: b, its rate [1/cycle], >= 0
    b: float
    #: c, the linear settlement rate at F0 [m/cycle], in [0, 1]
    c: float
    #: F0, the peak ballast force at which a, c hold [N]
    reference_force: float
    #: exponent of F/F0 in c(F) [-], in [0, 10]
    load_exponent: float = 1.0
    #: exponent of F/F0 in a(F) [-], in [0, 10]
    compaction_exponent: float = 1.0
    #: "strain" (equivalent cycles) or "time" (cycles so far)
    hardening: str = "strain"

    name: ClassVar[str] = "sato"

    def __post_init__(self):
        for name, value in {
            "a": v.number("a", self.a, low=0.0, high=1.0, unit="m"),
            "b": v.number("b", self.b, low=0.0, unit="1/cycle"),
            "c": v.number("c", self.c, low=0.0, high=1.0, unit="m/cycle"),
            "compaction_exponent": v.number("compaction_exponent", self.compaction_exponent,
                                            low=0.0, high=10.0),
        }.items():
            object.__setattr__(self, name, value)
        self._check_common()

    def _coefficients(self, force):
        return (self.a * self._load_factor(force, self.compaction_exponent),
                self.c * self._load_factor(force, self.load_exponent))

    def _rise(self, coefficients, n, dn):
        """a(F) (e^(-bN) - e^(-b(N+dN))) + c(F) dN, without cancellation; 0 from N = inf."""
        a, c = coefficients
        with np.errstate(invalid="ignore"):
            compaction = a * np.exp(-self.b * n) * -np.expm1(-self.b * dn)
            linear = np.where(dn > 0.0, c * dn, 0.0)
        return np.where(np.isinf(n), 0.0, compaction + linear)

    def _cycles_at(self, coefficients, settlement):
        """N with S(N; F) = settlement: closed form without the linear term, else Newton from
        N = 0 (S is concave in N: the iterates rise monotonically to the root); inf where the
        curve never reaches it."""
        a, c = coefficients
        b = self.b
        y = settlement
        with np.errstate(divide="ignore", invalid="ignore"):
            saturating = np.where((y < a) & (b > 0.0), -np.log1p(-y / a) / b, np.inf)
        n = np.where(y == 0.0, 0.0, np.where(c > 0.0, 0.0, saturating))
        active = (y > 0.0) & (c > 0.0)
        for _ in range(_MAX_NEWTON):
            if not active.any():
                break
            with np.errstate(divide="ignore", invalid="ignore"):  # inactive: inf, 0 c
                value = -a * np.expm1(-b * n) + c * n
                slope = a * b * np.exp(-b * n) + c
                step = np.where(active, n + (y - value) / slope, n)
            moved = active & (step > n)
            n = np.where(moved, step, n)
            active = moved
        return n


@dataclass(frozen=True)
class Shenton(CurveLaw):
    """Shenton (1985): ``S(N) = k1 N^0.2 + k2 N``, with k1, k2 proportional to the load.

    Shenton, M. J. (1985), Ballast deformation and track deterioration, in Track Technology
    (Proc. Conf. Univ. Nottingham 1984), Thomas Telford, London, 253-265. k1 and k2 hold at the
    peak ballast force ``reference_force`` F0 and scale as ``(F/F0)^load_exponent`` (1:
    proportional to the load, as Shenton found; the first term dominates below about 10^6
    cycles). ``exponent`` is Shenton's 0.2. ``hardening``: how a varying load accumulates
    (module docstring).

    No defaults (k1, k2 and F0 are required), for the reason given under :class:`Sato`: k1 and
    k2 are fits to a line's or a test's measurements, and no source consulted gives values
    together with the peak ballast force per sleeper they hold at (ROSE's Shenton model also
    takes k1, k2 as required arguments). Fit them to settlement against cycles measured at a
    known peak ballast force F0.
    """

    #: k1, the settlement after the first cycle at F0 [m], in [0, 1]
    k1: float
    #: k2, the linear settlement rate at F0 [m/cycle], in [0, 1]
    k2: float
    #: F0, the peak ballast force at which k1, k2 hold [N]
    reference_force: float
    #: exponent of F/F0 in k1(F), k2(F) [-], in [0, 10]
    load_exponent: float = 1.0
    #: exponent of N in the first term [-], in (0, 1)
    exponent: float = 0.2
    #: "strain" (equivalent cycles) or "time" (cycles so far)
    hardening: str = "strain"

    name: ClassVar[str] = "shenton"

    def __post_init__(self):
        for name, value in {
            "k1": v.number("k1", self.k1, low=0.0, high=1.0, unit="m"),
            "k2": v.number("k2", self.k2, low=0.0, high=1.0, unit="m/cycle"),
            "exponent": v.number("exponent", self.exponent, low=0.0, high=1.0,
                                 low_open=True, high_open=True),
        }.items():
            object.__setattr__(self, name, value)
        self._check_common()

    def _coefficients(self, force):
        factor = self._load_factor(force, self.load_exponent)
        return self.k1 * factor, self.k2 * factor

    def _rise(self, coefficients, n, dn):
        """k1(F) ((N+dN)^e - N^e) + k2(F) dN, without cancellation; 0 from N = inf."""
        k1, k2 = coefficients
        e = self.exponent
        with np.errstate(divide="ignore", invalid="ignore"):
            power = np.where(n > 0.0, n ** e * np.expm1(e * np.log1p(dn / n)), dn ** e)
            linear = np.where(dn > 0.0, k2 * dn, 0.0)
        return np.where(np.isinf(n), 0.0, k1 * power + linear)

    def _cycles_at(self, coefficients, settlement):
        """N with S(N; F) = settlement, by Newton in t = N^e, where S = k1 t + k2 t^(1/e) is
        convex: from the upper bound min(S/k1, (S/k2)^e) the iterates fall monotonically to
        the root; inf where the curve is zero (no load) and S > 0."""
        k1, k2 = coefficients
        e = self.exponent
        y = settlement
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.minimum(np.where(k1 > 0.0, y / k1, np.inf),
                           np.where(k2 > 0.0, (y / k2) ** e, np.inf))
        active = (y > 0.0) & np.isfinite(t)
        t = np.where(y > 0.0, t, 0.0)
        for _ in range(_MAX_NEWTON):
            if not active.any():
                break
            with np.errstate(divide="ignore", invalid="ignore"):
                value = k1 * t + k2 * t ** (1.0 / e) - y
                slope = k1 + k2 / e * t ** (1.0 / e - 1.0)
                step = np.where(active, t - value / slope, t)
            moved = active & (step < t) & (step >= 0.0)
            t = np.where(moved, step, t)
            active = moved
        return t ** (1.0 / e)
