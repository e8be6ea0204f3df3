"""The supports under the rail: single springs, or layered pad, sleeper and ballast (docs: Model
§ Scene, § Layered supports)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..base import validate as v
from ..base.units import check_stiffness_units
from ..base.limits import MAX_SUPPORTS, ranges_doc


@dataclass(frozen=True)
class Supports:
    """Discrete elastic supports (rail pads/sleepers) under the rail (docs: Model § Scene, § Rail).

    By default ``n = round(L / spacing) - 1`` equal supports at ``spacing, 2 spacing, ...,
    L - spacing`` (nine for the paper's scene), between the two rigid end supports. Give
    ``positions`` to place them anywhere inside the rail, on or between nodes;
    ``positions=()`` leaves the rail simply supported at its ends only (a bare beam).

    Layered supports (docs: Model § Layered supports): give ``sleeper_mass`` and
    ``ballast_stiffness`` and each support becomes a rail pad (``stiffness``, ``damping``)
    between the rail and a sleeper of mass m_s, which rests on the ballast (k_b, c_b) on rigid
    ground; gravity pre-loads every layer. Without them (the default) each support is one
    spring and damper from the rail to the ground.
    """

    stiffness: float = 140e6  #: k_s, vertical stiffness of each support [N/m] (layered: pad k_p)
    spacing: float = 0.5  #: d_s, support interval [m]
    damping: float = 0.0  #: c_s, viscous damping of each support [N s/m] (layered: pad c_p)
    positions: tuple[float, ...] | None = None  #: explicit positions X_j [m], or None
    #: m_s, the sleeper's share of one rail (half a sleeper) [kg]; None: single springs
    sleeper_mass: float | None = None
    ballast_stiffness: float | None = None  #: k_b, ballast under each sleeper [N/m]
    ballast_damping: float = 0.0  #: c_b, ballast damping under each sleeper [N s/m]

    def __post_init__(self):
        v.field("Supports.stiffness", self.stiffness)
        v.positive("Supports.spacing", self.spacing, "m")
        v.field("Supports.damping", self.damping)
        self._check_layers()
        check_stiffness_units("Supports.stiffness", self.stiffness, stacklevel=4)
        if self.layered:
            check_stiffness_units("Supports.ballast_stiffness", self.ballast_stiffness,
                                  stacklevel=4)
        if self.positions is not None:
            empty = isinstance(self.positions, (tuple, list)) and len(self.positions) == 0
            pos = () if empty else tuple(
                float(x) for x in v.positions("Supports.positions", self.positions,
                                              -math.inf, math.inf))
            object.__setattr__(self, "positions", pos)

    def _check_layers(self):
        if self.sleeper_mass is None and self.ballast_stiffness is None:
            if self.ballast_damping != 0.0:
                raise ValueError(f"Supports.ballast_damping = {self.ballast_damping} N s/m needs "
                                 "a sleeper layer: give sleeper_mass and ballast_stiffness too")
            return
        if self.sleeper_mass is None or self.ballast_stiffness is None:
            raise ValueError("Supports.sleeper_mass and Supports.ballast_stiffness must be given "
                             "together (layered supports) or both be None (single springs); "
                             f"got sleeper_mass = {self.sleeper_mass}, ballast_stiffness = "
                             f"{self.ballast_stiffness}")
        v.field("Supports.stiffness", self.stiffness, key="Supports.stiffness.layered",
                hint="the pad of layered supports")
        v.field("Supports.sleeper_mass", self.sleeper_mass)
        v.field("Supports.ballast_stiffness", self.ballast_stiffness)
        v.field("Supports.ballast_damping", self.ballast_damping)

    @property
    def layered(self) -> bool:
        """True for pad-sleeper-ballast supports (``sleeper_mass`` given)."""
        return self.sleeper_mass is not None

    @property
    def static_stiffness(self) -> float:
        """Static stiffness of one support [N/m]: k_s, or the pad and ballast in series,
        k_p k_b / (k_p + k_b)."""
        if not self.layered:
            return self.stiffness
        return self.stiffness * self.ballast_stiffness / (self.stiffness + self.ballast_stiffness)

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



Supports.__doc__ += ranges_doc("Supports")
