"""The supports under the rail: single springs, or layered pad, sleeper and ballast, each
property one value, one value per support or a function of X.

Docs: Model § Scene, § Layered supports, § Supports varying along the track.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Sequence
from dataclasses import dataclass, fields, replace
from functools import lru_cache

import numpy as np

from ..base import validate as v
from ..base.limits import MAX_SUPPORTS, ranges_doc
from ..base.units import check_stiffness_units
from ..excitation.profiles import derived_seed
from . import support_fields as sf
from .support_fields import PER_SUPPORT, Scatter, Transition, Voids

#: what a per-support field takes: one value, one value per support, or p(X) (X: array [m])
PerSupport = float | Sequence[float] | Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True, eq=False)
class SupportValues:
    """The supports' properties resolved at their positions X_j: one array per property, each
    (n,) and read-only (:meth:`Supports.values`)."""

    position: np.ndarray  #: X_j (n,) [m]
    stiffness: np.ndarray  #: k_s, or the pad's k_p, (n,) [N/m]
    damping: np.ndarray  #: c_s, or the pad's c_p, (n,) [N s/m]
    sleeper_mass: np.ndarray | None  #: m_s (n,) [kg]; None: single springs
    ballast_stiffness: np.ndarray | None  #: k_b (n,) [N/m]; None: single springs
    ballast_damping: np.ndarray  #: c_b (n,) [N s/m] (zeros for single springs)
    void: np.ndarray  #: g_j (n,) [m] (zeros without voids)
    ballast_tensionless: bool  #: every sleeper's ballast pushes only

    @property
    def layered(self) -> bool:
        """True for pad-sleeper-ballast supports."""
        return self.sleeper_mass is not None

    @property
    def static_stiffness(self) -> np.ndarray:
        """Static stiffness of each support (n,) [N/m]: k_s, or the pad and ballast in series,
        k_p k_b / (k_p + k_b)."""
        if not self.layered:
            return self.stiffness
        return self.stiffness * self.ballast_stiffness / (self.stiffness + self.ballast_stiffness)

    @property
    def unilateral(self) -> bool:
        """True if some sleeper's ballast pushes only (a void, or tensionless ballast)."""
        return self.ballast_tensionless or bool(np.any(self.void > 0.0))


@dataclass(frozen=True, repr=False)
class Supports:
    """Discrete elastic supports (rail pads/sleepers) under the rail (docs: Model § Scene, § Rail).

    By default ``n = round(L / spacing) - 1`` supports at ``spacing, 2 spacing, ...,
    L - spacing`` (nine for the paper's scene), between the two rigid end supports. Give
    ``positions`` to place them anywhere inside the rail, on or between nodes;
    ``positions=()`` leaves the rail simply supported at its ends only (a bare beam).

    Layered supports (docs: Model § Layered supports): give ``sleeper_mass`` and
    ``ballast_stiffness`` and each support becomes a rail pad (``stiffness``, ``damping``)
    between the rail and a sleeper of mass m_s, which rests on the ballast (k_b, c_b) on rigid
    ground; gravity pre-loads every layer. Without them (the default) each support is one
    spring and damper from the rail to the ground.

    A track that varies along X (docs: Model § Supports varying along the track): each
    property of a support (``stiffness``, ``damping``, ``sleeper_mass``, ``ballast_stiffness``,
    ``ballast_damping``, ``void``) is one value (every support the same), a sequence with one
    value per support (kept as a tuple of floats; support j at X_j = (j + 1) ``spacing``, or
    ``positions[j]``), or a function p(X) of the position X [m] (called with an array, returning
    one value per X). :meth:`values` resolves them at the supports, :meth:`value_at` at any X;
    both check every value against its range and name the support and its X. The presets
    :meth:`transition`, :meth:`hanging` and :meth:`scattered` build such fields from recipes
    (:class:`Transition`, :class:`Voids`, :class:`Scatter`), which compare, hash and print by
    value; any other function compares equal only to itself and prints by its name (a sweep
    tabulates it at the scene's supports). ``void`` (layered only, default 0) is the gap g_j
    between a sleeper and its ballast bed; ``ballast_tensionless`` makes every sleeper's
    ballast push only (not on the travelling window; docs:
    Model § Voids and unilateral ballast).
    """

    #: k_s, vertical stiffness of each support [N/m] (layered: pad k_p)
    stiffness: PerSupport = 140e6
    spacing: float = 0.5  #: d_s, support interval [m]
    damping: PerSupport = 0.0  #: c_s, viscous damping of each support [N s/m] (layered: pad c_p)
    positions: tuple[float, ...] | None = None  #: explicit positions X_j [m], or None
    #: m_s, the sleeper's share of one rail (half a sleeper) [kg]; None: single springs
    sleeper_mass: PerSupport | None = None
    ballast_stiffness: PerSupport | None = None  #: k_b, ballast under each sleeper [N/m]
    ballast_damping: PerSupport = 0.0  #: c_b, ballast damping under each sleeper [N s/m]
    #: g_j, the gap between each sleeper and its ballast bed [m], >= 0 (layered only)
    void: PerSupport = 0.0
    #: every sleeper's ballast pushes only, never pulls (layered only)
    ballast_tensionless: bool = False

    def __post_init__(self):
        for name in PER_SUPPORT:
            object.__setattr__(self, name, sf.stored(name, getattr(self, name)))
        if isinstance(self.stiffness, numbers.Real):
            v.field("Supports.stiffness", self.stiffness)
        v.positive("Supports.spacing", self.spacing, "m")
        if isinstance(self.damping, numbers.Real):
            v.field("Supports.damping", self.damping)
        if self.positions is not None:
            empty = isinstance(self.positions, (tuple, list)) and len(self.positions) == 0
            pos = () if empty else tuple(
                float(x) for x in v.positions("Supports.positions", self.positions,
                                              -math.inf, math.inf))
            object.__setattr__(self, "positions", pos)
        v.boolean("Supports.ballast_tensionless", self.ballast_tensionless)
        self._check_layers()
        for name in PER_SUPPORT:
            if isinstance(getattr(self, name), tuple):
                self._check_sequence(name)
        if isinstance(self.stiffness, numbers.Real):
            check_stiffness_units("Supports.stiffness", self.stiffness, stacklevel=4)
        if self.layered and isinstance(self.ballast_stiffness, numbers.Real):
            check_stiffness_units("Supports.ballast_stiffness", self.ballast_stiffness,
                                  stacklevel=4)

    def _check_layers(self):
        if self.sleeper_mass is None and self.ballast_stiffness is None:
            for name, zero in (("ballast_damping", 0.0), ("void", 0.0)):
                value = getattr(self, name)
                if not isinstance(value, numbers.Real) or value != zero:
                    raise ValueError(f"Supports.{name} = {sf.text(value)} {sf.UNITS[name]} "
                                     "needs a sleeper layer: give sleeper_mass and "
                                     "ballast_stiffness too")
            if self.ballast_tensionless:
                raise ValueError("Supports.ballast_tensionless = True needs a sleeper layer: "
                                 "give sleeper_mass and ballast_stiffness too")
            return
        if self.sleeper_mass is None or self.ballast_stiffness is None:
            raise ValueError("Supports.sleeper_mass and Supports.ballast_stiffness must be given "
                             "together (layered supports) or both be None (single springs); "
                             f"got sleeper_mass = {sf.text(self.sleeper_mass)}, "
                             f"ballast_stiffness = {sf.text(self.ballast_stiffness)}")
        if isinstance(self.stiffness, numbers.Real):
            v.field("Supports.stiffness", self.stiffness, key="Supports.stiffness.layered",
                    hint="the pad of layered supports")
        for name in ("sleeper_mass", "ballast_stiffness", "ballast_damping", "void"):
            if isinstance(getattr(self, name), numbers.Real):
                v.field(f"Supports.{name}", getattr(self, name))

    def _check_sequence(self, name: str):
        """Every value of the per-support sequence ``name`` in its range, naming the support
        and its X; as many values as explicit ``positions``. The units of a stiffness are
        checked on its softest value."""
        value = getattr(self, name)
        x = (np.asarray(self.positions[:len(value)]) if self.positions is not None
             else self.spacing * np.arange(1, len(value) + 1))
        if self.positions is not None and len(value) != len(self.positions):
            raise ValueError(f"Supports.{name} has {len(value)} values for "
                             f"{len(self.positions)} supports (Supports.positions); give one "
                             "value per support (or one value, or a function of X)")
        sf.check(name, np.asarray(value), x, layered=self.layered)
        if name in ("stiffness", "ballast_stiffness"):
            check_stiffness_units(f"Supports.{name}", min(value), stacklevel=5)

    # ------------------------------------------------------------------------------------------
    # the properties along X
    @property
    def layered(self) -> bool:
        """True for pad-sleeper-ballast supports (``sleeper_mass`` given)."""
        return self.sleeper_mass is not None

    @property
    def uniform(self) -> bool:
        """True when every per-support property is one value (every support the same)."""
        return all(not isinstance(getattr(self, name), tuple) and not callable(getattr(self, name))
                   for name in PER_SUPPORT)

    @property
    def unilateral(self) -> bool:
        """True if some sleeper's ballast may push only: ``ballast_tensionless``, or a void
        that is not the one value 0."""
        return self.ballast_tensionless or not (
            isinstance(self.void, numbers.Real) and self.void == 0.0)

    @property
    def n_random(self) -> int:
        """Number of scattered properties (:class:`Scatter`) that :meth:`reseeded` redraws."""
        return sum(isinstance(getattr(self, name), Scatter) for name in PER_SUPPORT)

    def one_value(self, what: str, names=PER_SUPPORT) -> None:
        """ValueError unless the properties ``names`` are each one value; ``what`` (the
        quantity or level that needs them so, and why) starts the message."""
        varying = [n for n in names
                   if isinstance(getattr(self, n), tuple) or callable(getattr(self, n))]
        if varying:
            verb = "varies" if len(varying) == 1 else "vary"
            raise ValueError(f"{what}; Supports.{', Supports.'.join(varying)} {verb} along X "
                             "here (give one value each)")

    @property
    def static_stiffness(self) -> float:
        """Static stiffness of one support [N/m]: k_s, or the pad and ballast in series,
        k_p k_b / (k_p + k_b). One value only where stiffness and ballast stiffness are;
        otherwise ``values(positions).static_stiffness`` gives each support's."""
        self.one_value("Supports.static_stiffness is one value only for supports that are the "
                       "same everywhere (Supports.values(positions).static_stiffness gives each "
                       "support's)", ("stiffness", "ballast_stiffness"))
        if not self.layered:
            return self.stiffness
        return self.stiffness * self.ballast_stiffness / (self.stiffness + self.ballast_stiffness)

    def values(self, positions) -> SupportValues:
        """Every property at the supports ``positions`` [m] (:meth:`resolve`): one read-only
        array each. A per-support sequence must have one value per position, a function's
        values are checked against the property's range (ValueError naming the support and
        its X). Cached per (supports, positions)."""
        pos = tuple(float(x) for x in np.atleast_1d(np.asarray(positions, dtype=float)))
        try:
            hash(self)
        except TypeError:  # a function that cannot be hashed: resolve without the cache
            return _resolve_values.__wrapped__(self, pos)
        return _resolve_values(self, pos)

    def value_at(self, name: str, x) -> np.ndarray:
        """The property ``name`` at any X [m] (an array of X's shape): the one value, the
        function's value, or for a per-support sequence the value of the support at X
        (ValueError if no support stands there). Checked against the property's range."""
        v.choice("name", name, PER_SUPPORT)
        value = getattr(self, name)
        if value is None:
            raise ValueError(f"Supports.{name} is None: single springs have no sleeper layer")
        x = np.asarray(x, dtype=float)
        if not isinstance(value, tuple):
            out = sf.evaluate(name, value, x)
            if callable(value):
                sf.check(name, out.ravel(), x.ravel(), layered=self.layered, indices=False)
            return out
        pos = (np.asarray(self.positions) if self.positions is not None
               else self.spacing * np.arange(1, len(value) + 1))
        dist = np.abs(pos[None, :] - x.reshape(-1, 1))
        j = dist.argmin(axis=1)
        off = dist[np.arange(j.size), j] > 1e-6
        if np.any(off):
            raise ValueError(f"Supports.{name} is given per support ({len(value)} values): "
                             f"X = {x.ravel()[off][0]:.6g} m is not one of its supports")
        return np.asarray(value)[j].reshape(x.shape)

    def check_at(self, positions, *, along_track: bool = False) -> SupportValues:
        """:meth:`values` at ``positions`` [m], the units of a stiffness given as a function
        checked on its softest value (a PlausibilityWarning), and every voided sleeper of a
        :class:`Voids` recipe on a support (ValueError otherwise): what a Scene checks.
        ``along_track``: the rail is a travelling window over a track with a sleeper every
        ``spacing`` (X = k spacing), and a void may stand at any of them."""
        vals = self.values(positions)
        if along_track and isinstance(self.void, Voids):
            for x in self.void.positions:
                if abs(x / self.spacing - round(x / self.spacing)) * self.spacing > 1e-6:
                    raise ValueError(f"Supports.void: no sleeper at X = {x:g} m for its void "
                                     f"(the track's sleepers stand every {self.spacing:g} m; "
                                     "Supports.hanging puts a void at one)")
            return vals
        for name in ("stiffness", "ballast_stiffness"):
            arr = getattr(vals, name)
            if callable(getattr(self, name)) and arr is not None and arr.size:
                check_stiffness_units(f"Supports.{name}", float(arr.min()), stacklevel=4)
        if isinstance(self.void, Voids):
            for x in self.void.positions:
                if not np.any(np.abs(vals.position - x) < 1e-6):
                    raise ValueError(f"Supports.void: no support at X = {x:g} m for its void "
                                     "(Supports.hanging puts a void at an existing sleeper)")
        return vals

    def resolve(self, length: float) -> tuple[float, ...]:
        """Support positions [m] on a rail of ``length`` [m]; checks they lie inside it."""
        if self.positions is not None:
            pos = self.positions
        else:
            if length / self.spacing > MAX_SUPPORTS + 1.5:
                raise ValueError(
                    f"Supports.spacing = {self.spacing} m puts more than {MAX_SUPPORTS} supports "
                    f"on a {length} m rail; allowed range [{length / (MAX_SUPPORTS + 1):.6g}, "
                    f"{length / 1.5:.6g}] m")
            n = int(round(length / self.spacing))
            if n < 2:
                raise ValueError(
                    f"Supports.spacing = {self.spacing} m leaves no support between the rail "
                    f"ends; allowed range (0, {length / 1.5:.6g}] m (or give positions=())")
            pos = tuple(self.spacing * j for j in range(1, n))
        for x in pos:
            if not 0.0 < x < length:
                raise ValueError(
                    f"Supports.positions: support at {x} m is outside the rail; "
                    f"allowed range (0, {length}) m")
        return pos

    def text(self, name: str, scale: float = 1.0, positions=None) -> str:
        """The property ``name`` for a label, times ``scale`` (e.g. 1e-6 for MN/m): "180" for
        one value, "90..180" over the supports ``positions`` [m] if it varies, "varies along
        X" without them."""
        value = getattr(self, name)
        if isinstance(value, numbers.Real):
            return f"{value * scale:g}"
        if positions is None:
            return "varies along X"
        arr = getattr(self.values(positions), name)
        return f"{arr.min() * scale:g}..{arr.max() * scale:g}"

    def __repr__(self) -> str:
        return "Supports(" + ", ".join(f"{f.name}={sf.text(getattr(self, f.name))}"
                                       for f in fields(self)) + ")"

    # ------------------------------------------------------------------------------------------
    # presets and generators
    def transition(self, at: float, *, ramp: float = 0.0, shape: str = "step",
                   **changes) -> Supports:
        """These supports with one or more properties changing at ``at`` [m] over a ramp of
        ``ramp`` [m] centred on it (:class:`Transition`; ``shape`` "step", "linear" or
        "cosine"), each given as ``name=(before, after)``::

            soft_to_stiff = Scene.ballasted_track().supports.transition(
                15.0, ramp=3.0, shape="cosine", ballast_stiffness=(50e6, 200e6))
        """
        if not changes:
            raise ValueError("Supports.transition needs at least one property=(before, after), "
                             f"e.g. ballast_stiffness=(50e6, 200e6); properties: {PER_SUPPORT}")
        new = {}
        for name, pair in changes.items():
            if name not in PER_SUPPORT:
                raise TypeError(f"Supports.transition got {name}=...; the properties are "
                                f"{', '.join(PER_SUPPORT)}")
            try:
                before, after = pair
            except (TypeError, ValueError):
                raise ValueError(f"Supports.transition: {name} = {pair!r} must be a pair "
                                 "(before, after)") from None
            new[name] = Transition(before, after, at, ramp, shape)
        return replace(self, **new)

    def hanging(self, at=None, *, gap, sleepers=None) -> Supports:
        """These (layered) supports with sleepers hanging over voids: the gap ``gap`` [m] (one
        value, or one per sleeper) under the sleeper nearest each X of ``at`` [m], or under the
        supports numbered ``sleepers`` (0-based; X_j = (j + 1) spacing or positions[j]). Adds
        to the voids of an earlier ``hanging`` (:class:`Voids`)."""
        if (at is None) == (sleepers is None):
            raise ValueError("Supports.hanging needs either at (X [m]) or sleepers (indices)")
        if at is not None:
            xs = [self._nearest(float(x)) for x in np.atleast_1d(v.positions(
                "at", at, -math.inf, math.inf))]
        else:
            js = [v.integer("sleepers", j, low=0, high=MAX_SUPPORTS)
                  for j in np.atleast_1d(np.asarray(sleepers)).tolist()]
            if self.positions is not None and max(js) >= len(self.positions):
                raise ValueError(f"sleepers = {max(js)} is outside the allowed range "
                                 f"[0, {len(self.positions) - 1}]")
            xs = [self.positions[j] if self.positions is not None else self.spacing * (j + 1)
                  for j in js]
        gaps = np.broadcast_to(np.asarray(gap, dtype=float), (len(xs),)).tolist()
        old = dict(zip(self.void.positions, self.void.gaps)) if isinstance(self.void, Voids) \
            else {}
        if not old and not (isinstance(self.void, numbers.Real) and self.void == 0.0):
            raise ValueError(f"Supports.hanging adds voids to void = 0 or to earlier voids of "
                             f"Supports.hanging; got void = {sf.text(self.void)}")
        old.update(zip(xs, gaps))
        return replace(self, void=Voids(tuple(old), tuple(old.values())))

    def _nearest(self, x: float) -> float:
        """X [m] of the support nearest ``x`` (on the grid of ``spacing`` without positions)."""
        if self.positions is not None:
            if not self.positions:
                raise ValueError("Supports.hanging: there are no supports (positions=())")
            return min(self.positions, key=lambda p: abs(p - x))
        return self.spacing * max(1, round(x / self.spacing))

    def scattered(self, cv: float, *, seed: int, mean: float | None = None,
                  property: str = "ballast_stiffness") -> Supports:
        """These supports with the property ``property`` scattered from sleeper to sleeper
        (:class:`Scatter`): lognormal with mean ``mean`` (None: the property's value here, one
        value or a :class:`Transition`) and coefficient of variation ``cv`` [-], drawn with
        ``seed`` and tied to each sleeper's absolute index round(X / spacing)."""
        v.choice("property", property, PER_SUPPORT)
        base = getattr(self, property) if mean is None else mean
        if base is None or isinstance(base, tuple) or (
                callable(base) and not isinstance(base, Transition)):
            raise ValueError(f"Supports.scattered: the mean of {property} must be one value or "
                             f"a Transition; got {sf.text(base)}")
        return replace(self, **{property: Scatter(base, cv, seed, self.spacing)})

    def reseeded(self, seed: int) -> Supports:
        """The same supports with every scattered property drawn afresh: realisation ``seed``
        (the first :class:`Scatter`, in the order of the fields, gets ``seed``, the k-th
        ``derived_seed(seed, k)``, as :meth:`trackwheel.Irregularity.reseeded` does)."""
        if self.n_random == 0:
            raise ValueError("Supports.reseeded: no property is scattered (build one with "
                             "Supports.scattered)")
        new, k = {}, 0
        for name in PER_SUPPORT:
            value = getattr(self, name)
            if isinstance(value, Scatter):
                new[name] = replace(value, seed=seed if k == 0 else derived_seed(seed, k))
                k += 1
        return replace(self, **new)

    def tabulated(self, positions) -> Supports:
        """These supports with every function of X that is not a recipe replaced by its values
        at ``positions`` [m] (a tuple per support): what the kernel sees on a fixed rail, in a
        form that pickles and is stored by value (the sweep's case scenes)."""
        funcs = {n: getattr(self, n) for n in PER_SUPPORT
                 if callable(getattr(self, n)) and not sf.is_recipe(getattr(self, n))}
        if not funcs:
            return self
        vals = self.values(positions)
        return replace(self, **{n: tuple(getattr(vals, n).tolist()) for n in funcs})


@lru_cache(maxsize=256)
def _resolve_values(supports: Supports, positions: tuple[float, ...]) -> SupportValues:
    x = np.array(positions, dtype=float)
    out = {}
    for name in PER_SUPPORT:
        value = getattr(supports, name)
        if value is None:
            out[name] = None
            continue
        arr = sf.evaluate(name, value, x)
        if callable(value):
            sf.check(name, arr, x, layered=supports.layered)
        arr.setflags(write=False)
        out[name] = arr
    x.setflags(write=False)
    return SupportValues(position=x, ballast_tensionless=supports.ballast_tensionless, **out)


Supports.__doc__ += ranges_doc("Supports")
