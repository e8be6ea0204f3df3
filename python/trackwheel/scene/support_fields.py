"""Support properties along X: one field of :class:`~trackwheel.Supports` as one value, one
value per support or a function p(X), resolved and checked at the supports; the recipes the
presets build (:class:`Transition`, :class:`Scatter`, :class:`Voids`).

Docs: Model § Supports varying along the track.

A recipe is a frozen dataclass of plain numbers and tuples that is also a function of X, like
the parts of a rail profile: it compares and hashes by value, prints as its own constructor, and
``dataclasses.asdict`` of a scene that carries one is plain JSON (its ``kind`` names it), so the
sweep store keys a case by the recipe. Any other function of X is kept as it is given (equal
only to itself, printed by its name); the sweep tabulates it at the scene's supports.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ..base import validate as v
from ..base.limits import MAX_SEED, RANGES

#: the fields of Supports that describe one support, in the order of SupportParams
PER_SUPPORT = ("stiffness", "damping", "sleeper_mass", "ballast_stiffness", "ballast_damping",
               "void")
#: the unit of each per-support field
UNITS = {"stiffness": "N/m", "damping": "N s/m", "sleeper_mass": "kg", "ballast_stiffness": "N/m",
         "ballast_damping": "N s/m", "void": "m"}
#: the shapes s(xi) of a transition (docs: Model § Supports varying along the track)
SHAPES = ("step", "linear", "cosine")

#: sleepers per block of standard normal draws of a scattered bed (:func:`bed_normals`)
_BLOCK = 1024
#: how close [m] an X must be to a voided sleeper's position to be that sleeper
_SAME_SLEEPER = 1e-6


def stored(name: str, value):
    """``value`` of the Supports field ``name`` as the dataclass keeps it: None, a callable and
    a plain number as given, anything else as a tuple of floats (one per support). TypeError
    for what is none of these."""
    if value is None or callable(value):
        return value
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
        return value
    if isinstance(value, (str, bytes, bool, np.bool_)):
        raise TypeError(_kinds(name, type(value).__name__))
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(_kinds(name, type(value).__name__)) from None
    if arr.ndim == 0:
        return float(arr)
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"Supports.{name} must be one value, a non-empty 1-d sequence (one "
                         f"value per support) or a function of X; got shape {arr.shape}")
    return tuple(float(x) for x in arr)


def _kinds(name: str, got: str) -> str:
    return (f"Supports.{name} must be a real number [{UNITS[name]}], a sequence of them (one per "
            f"support) or a function p(X) of the position X [m]; got {got}")


def range_key(name: str, layered: bool) -> str:
    """The RANGES key of the field ``name`` (a layered support's pad has its own range)."""
    return "Supports.stiffness.layered" if name == "stiffness" and layered else f"Supports.{name}"


def check(name: str, values: np.ndarray, positions: np.ndarray, *, layered: bool,
          indices: bool = True) -> None:
    """ValueError naming the first support (index, if ``indices``, and X) whose value of the
    field ``name`` is not finite or outside its plausible range."""
    r = RANGES[range_key(name, layered)]
    with np.errstate(invalid="ignore"):
        bad = ~np.isfinite(values) | (values < r.low) | (values > r.high)
        if r.low_open:
            bad |= values == r.low
        if r.high_open:
            bad |= values == r.high
    if not bad.any():
        return
    j = int(np.argmax(bad))
    where = f" at support {j} (X = {positions[j]:.6g} m)" if indices else (
        f" at X = {positions[j]:.6g} m")
    hint = "the pad of layered supports" if name == "stiffness" and layered else ""
    v.field(f"Supports.{name}{where}", float(values[j]), key=range_key(name, layered), hint=hint)


def evaluate(name: str, value, positions: np.ndarray, n_given: int | None = None) -> np.ndarray:
    """The field ``name`` (one value, a tuple or a function of X) at ``positions`` [m], as a
    float array of their shape. A tuple must have one value per support (``n_given`` the
    number of supports; ValueError naming both lengths)."""
    if callable(value):
        out = np.asarray(value(positions.copy()), dtype=float)
        try:
            return np.array(np.broadcast_to(out, positions.shape), dtype=float)
        except ValueError:
            raise ValueError(f"Supports.{name}: the function of X returned shape {out.shape} "
                             f"for {positions.size} positions; it must return one value per X "
                             "(an array of X's shape)") from None
    if isinstance(value, tuple):
        n = positions.size if n_given is None else n_given
        if len(value) != n:
            raise ValueError(f"Supports.{name} has {len(value)} values for {n} supports; give "
                             "one value per support (or one value, or a function of X)")
        return np.array(value, dtype=float)
    return np.full(positions.shape, float(value))


# ----------------------------------------------------------------------------------------------
# recipes: functions of X that are also their own description
@dataclass(frozen=True)
class Transition:
    """A transition of one support property at ``at`` over the ramp length ``ramp``
    (docs: Model § Supports varying along the track):

        p(X) = (1 - s(xi)) before + s(xi) after,   xi = (X - at) / ramp,

    step s = H(xi) (1/2 at X = at exactly, ``ramp`` = 0), linear s = clip(xi + 1/2, 0, 1),
    cosine s = (1 - cos(pi clip(xi + 1/2, 0, 1))) / 2: the ramp is centred on ``at``, from
    at - ramp/2 to at + ramp/2. Written as (1 - s) p1 + s p2 so that the values off the ramp are
    exactly ``before`` and ``after``. ``ramp`` = 0 is a step whatever the ``shape``; a step has
    no ramp.
    """

    before: float  #: p1, the value for X < at - ramp/2 [the property's unit]
    after: float  #: p2, the value for X > at + ramp/2
    at: float  #: X0, the middle of the transition [m]
    ramp: float = 0.0  #: L_r, the ramp's length [m], >= 0
    shape: str = "step"  #: s: "step", "linear" or "cosine"
    kind: str = field(default="transition", init=False, repr=False)

    def __post_init__(self):
        for name in ("before", "after", "at"):
            v.number(f"Transition.{name}", getattr(self, name))
        v.number("Transition.ramp", self.ramp, low=0.0, unit="m")
        v.choice("Transition.shape", self.shape, SHAPES)
        if self.shape == "step" and self.ramp > 0.0:
            raise ValueError(f"Transition.ramp = {self.ramp:g} m with shape 'step': a step has "
                             "no ramp; give shape='linear' or 'cosine' (or ramp=0)")

    def blend(self, x) -> np.ndarray:
        """s(xi) in [0, 1] at X [m]."""
        x = np.asarray(x, dtype=float)
        if self.ramp == 0.0:
            return np.where(x > self.at, 1.0, np.where(x < self.at, 0.0, 0.5))
        t = np.clip((x - self.at) / self.ramp + 0.5, 0.0, 1.0)
        return t if self.shape == "linear" else 0.5 * (1.0 - np.cos(math.pi * t))

    def __call__(self, x) -> np.ndarray:
        s = self.blend(x)
        return (1.0 - s) * self.before + s * self.after


@lru_cache(maxsize=256)
def _block(seed: int, block: int) -> np.ndarray:
    """The standard normals of the sleepers ``block * _BLOCK`` .. ``(block + 1) * _BLOCK - 1``:
    a Generator on ``SeedSequence(seed, spawn_key=(b,))`` (the b-th child the seed would spawn,
    b = 2 block for block >= 0, -2 block - 1 below), so any sleeper's draw is found without
    drawing those before it."""
    key = 2 * block if block >= 0 else -2 * block - 1
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(key,)))
    out = rng.standard_normal(_BLOCK)
    out.setflags(write=False)
    return out


def bed_normals(seed: int, index) -> np.ndarray:
    """xi_j ~ N(0, 1) of the sleepers with absolute indices ``index`` (j = round(X / d)): fixed
    by (seed, j) alone, so a longer rail or a travelling window sees the same bed where it
    overlaps another."""
    j = np.asarray(index, dtype=np.int64)
    blocks, within = np.divmod(j, _BLOCK)
    out = np.empty(j.shape)
    for b in np.unique(blocks):
        sel = blocks == b
        out[sel] = _block(int(seed), int(b))[within[sel]]
    return out


@dataclass(frozen=True)
class Scatter:
    """A scattered bed (docs: Model § Supports varying along the track): lognormal per sleeper,

        p_j = mean(X_j) exp(sigma xi_j - sigma^2 / 2),   sigma^2 = ln(1 + cv^2),

    with mean ``mean`` and coefficient of variation ``cv`` (the lognormal's own: E[p_j] = mean,
    std[p_j] = cv mean), xi_j standard normal from numpy's Generator seeded by ``seed`` and tied
    to the sleeper's absolute index j = floor(X / spacing + 1/2) (:func:`bed_normals`). At any X
    it is the value of the sleeper nearest X on the grid of ``spacing``.
    """

    mean: float | Transition  #: the mean value, or a transition of it [the property's unit]
    cv: float  #: coefficient of variation [-], >= 0
    seed: int  #: seed of the sleepers' standard normals [-]
    spacing: float  #: the sleeper grid d [m] that numbers the sleepers
    kind: str = field(default="scatter", init=False, repr=False)

    def __post_init__(self):
        if not isinstance(self.mean, Transition):
            v.number("Scatter.mean", self.mean)
        v.number("Scatter.cv", self.cv, low=0.0, high=10.0)
        v.integer("Scatter.seed", self.seed, low=0, high=MAX_SEED)
        v.positive("Scatter.spacing", self.spacing, "m")

    @property
    def sigma(self) -> float:
        """sigma = sqrt(ln(1 + cv^2)) [-]."""
        return math.sqrt(math.log1p(self.cv * self.cv))

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        mean = self.mean(x) if callable(self.mean) else np.full(x.shape, float(self.mean))
        s = self.sigma
        xi = bed_normals(self.seed, np.floor(x / self.spacing + 0.5))
        return mean * np.exp(s * xi - 0.5 * s * s)


@dataclass(frozen=True)
class Voids:
    """Hanging sleepers (docs: Model § Supports varying along the track): the gap ``gaps[k]``
    [m] under the sleeper at ``positions[k]`` [m], none elsewhere (g(X) = 0 at any other X)."""

    positions: tuple[float, ...]  #: X of each voided sleeper [m]
    gaps: tuple[float, ...]  #: g >= 0 under each [m]
    kind: str = field(default="voids", init=False, repr=False)

    def __post_init__(self):
        pos = tuple(float(x) for x in np.atleast_1d(v.positions(
            "Voids.positions", self.positions, -math.inf, math.inf)))
        gaps = tuple(float(g) for g in np.atleast_1d(v.positions(
            "Voids.gaps", self.gaps, 0.0, RANGES["Supports.void"].high)))
        if len(gaps) != len(pos):
            raise ValueError(f"Voids.gaps has {len(gaps)} values for {len(pos)} positions")
        if len(set(pos)) != len(pos):
            raise ValueError(f"Voids.positions names a sleeper twice: {pos}")
        object.__setattr__(self, "positions", pos)
        object.__setattr__(self, "gaps", gaps)

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        out = np.zeros(x.shape)
        for p, g in zip(self.positions, self.gaps):
            out[np.abs(x - p) < _SAME_SLEEPER] = g
        return out


#: the recipes by kind
RECIPES = {"transition": Transition, "scatter": Scatter, "voids": Voids}


def is_recipe(value) -> bool:
    return isinstance(value, tuple(RECIPES.values()))


def text(value) -> str:
    """A field's value as printed by ``repr(Supports(...))``: a function of X by its qualified
    name (no memory address, so that the text is stable)."""
    if callable(value) and not is_recipe(value):
        name = getattr(value, "__qualname__", type(value).__qualname__)
        return f"<function {getattr(value, '__module__', '?')}.{name}>"
    return repr(value)


__all__ = ["PER_SUPPORT", "RECIPES", "SHAPES", "UNITS", "Scatter", "Transition", "Voids",
           "bed_normals", "check", "evaluate", "is_recipe", "range_key", "stored", "text"]
