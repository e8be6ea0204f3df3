"""The travelling window: a rail of whole sleeper bays that moves with the vehicle (docs: Model
§ The travelling window)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..base import validate as v
from ..base.limits import MAX_WINDOW_BAYS, ranges_doc


@dataclass(frozen=True)
class Window:
    """The travelling window (docs: Model § The travelling window): the rail is a fixed number of
    sleeper bays that travels with the wheels, so a run of any length costs the same per metre
    and the same memory.

    The window holds ``bays_behind`` whole bays behind the bay of the rearmost wheel, the bays
    the vehicle spans, and ``bays_ahead`` bays ahead of the leading wheel's bay; its rail length
    is :meth:`length` (a longer rail of whole bays adds bays ahead). When the rearmost wheel
    leaves its bay the state moves one bay back: the rear bay leaves, a fresh bay at rest under
    its own weight joins at the front. Needs a track periodic in its bay (equal supports every
    ``Supports.spacing``, ``Supports.positions`` not given) and, so that the rail's ends do not
    reflect, enough damping in the track (layered supports) or bays to let waves decay. Runs on
    every fidelity level, the full model with either integrator.

    The window's rail has absorbing end zones (:class:`AbsorbingEnds`) of about
    ``absorbing_length`` at each end (:meth:`zone_bays` whole bays) unless the scene's rail
    brings its own: they absorb the waves leaving the window and, on the full model, damp the
    rail's axial motion, which each shift knocks (without them the tangential force rings;
    docs: Model § The travelling window). ``absorbing_length=0`` leaves the rail's ends as they
    are.
    """

    bays_behind: int = 20  #: whole bays behind the rearmost wheel's bay [-], 1..1000
    bays_ahead: int = 20  #: whole bays ahead of the leading wheel's bay [-], 1..1000
    #: length of each absorbing end zone [m], >= 0 (8 bays of the ballasted preset)
    absorbing_length: float = 4.8

    def __post_init__(self):
        v.integer("Window.bays_behind", self.bays_behind, low=1, high=MAX_WINDOW_BAYS)
        v.integer("Window.bays_ahead", self.bays_ahead, low=1, high=MAX_WINDOW_BAYS)
        v.field("Window.absorbing_length", self.absorbing_length)

    def zone_bays(self, spacing: float) -> int:
        """Whole bays of ``spacing`` [m] in each absorbing end zone: ``absorbing_length``
        rounded up, at most ``bays_behind`` and ``bays_ahead`` (the zones stay off the
        vehicle's bays) [-]."""
        return min(math.ceil(self.absorbing_length / spacing - 1e-9), self.bays_behind,
                   self.bays_ahead)

    def n_bays(self, span: float, spacing: float) -> int:
        """Bays of the window for wheels spanning ``span`` [m] on bays of ``spacing`` [m]."""
        return self.bays_behind + 1 + math.ceil(span / spacing - 1e-9) + self.bays_ahead

    def length(self, span: float, spacing: float) -> float:
        """The window's rail length [m]: :meth:`n_bays` x ``spacing``."""
        return self.n_bays(span, spacing) * spacing



Window.__doc__ += ranges_doc("Window")
