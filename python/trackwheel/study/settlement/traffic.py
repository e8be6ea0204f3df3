"""The traffic that settles the ballast: one or more kinds of passage (a vehicle or a wheel
load at a speed) and how often each runs (docs: Model § The settlement loop).

A :class:`TrafficItem` is one kind of passage: the scene's own wheel or vehicle (or another
vehicle, or the single wheel under another load) at a forward speed, ``per_day`` passages a
day. Each passage is one load cycle per axle (per wheel on the modelled rail) for every sleeper
it runs over. :class:`Traffic` is the mix; :meth:`Traffic.passages` shares a number of axle
passes out among the items in proportion to their axle passes a day, in whole passages.
"""

from __future__ import annotations

import numbers
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from ...base import validate as v
from ...base.limits import MAX_SPEED
from ...scene import Scene, Vehicle


@dataclass(frozen=True)
class TrafficItem:
    """One kind of passage over the track.

    ``speed`` [m/s] the forward speed (``trackwheel.kmh`` converts); ``per_day`` [1/day] how
    many such passages run a day (any time unit will do: the history's ``days`` count that
    unit); ``vehicle`` a :class:`~trackwheel.Vehicle` to run instead of the scene's own (None:
    the scene's); ``wheel_load`` F [N] the static load on the scene's single wheel instead of
    ``Scene.wheel.load`` (not with a vehicle); ``name`` a label for tables and plots.
    """

    speed: float  #: forward speed v [m/s], (0, MAX_SPEED]
    per_day: float = 1.0  #: passages a day [1/day], > 0
    vehicle: Vehicle | None = None  #: the vehicle of these passages (None: the scene's)
    wheel_load: float | None = None  #: F on the scene's single wheel [N] (None: the scene's)
    name: str = ""  #: a label

    def __post_init__(self):
        object.__setattr__(self, "speed", v.number("TrafficItem.speed", self.speed, low=0.0,
                                                   low_open=True, high=MAX_SPEED, unit="m/s"))
        object.__setattr__(self, "per_day", v.number("TrafficItem.per_day", self.per_day,
                                                     low=0.0, low_open=True, high=1e9,
                                                     unit="1/day"))
        if self.vehicle is not None and not isinstance(self.vehicle, Vehicle):
            raise TypeError(f"TrafficItem.vehicle must be a trackwheel.Vehicle or None, got "
                            f"{type(self.vehicle).__name__}")
        if self.wheel_load is not None:
            if self.vehicle is not None:
                raise ValueError("TrafficItem.wheel_load is the single wheel's load: give it "
                                 "or a vehicle, not both")
            object.__setattr__(self, "wheel_load", v.number(
                "TrafficItem.wheel_load", self.wheel_load, low=0.0, high=1e7, unit="N"))
        if not isinstance(self.name, str):
            raise TypeError(f"TrafficItem.name must be a str, got {type(self.name).__name__}")

    def scene(self, base: Scene) -> Scene:
        """``base`` with this item's vehicle or wheel load."""
        if self.vehicle is not None:
            return replace(base, vehicle=self.vehicle)
        if self.wheel_load is not None:
            return replace(base, vehicle=None, wheel=replace(base.wheel, load=self.wheel_load))
        return base

    def axles(self, base: Scene) -> int:
        """Load cycles a passage gives each sleeper: the wheels on the modelled rail [-]."""
        return len(self.scene(base).active_vehicle.wheels)

    def label(self, index: int) -> str:
        """``name``, or "item <index>"."""
        return self.name or f"item {index}"


@dataclass(frozen=True)
class Traffic:
    """The traffic mix: one or more :class:`TrafficItem` (``Traffic.of`` builds one from an
    item, a sequence of items or a speed [m/s])."""

    items: tuple[TrafficItem, ...]

    def __post_init__(self):
        items = tuple(self.items)
        if not items:
            raise ValueError("traffic is empty: give at least one TrafficItem")
        for i, item in enumerate(items):
            if not isinstance(item, TrafficItem):
                raise TypeError(f"traffic item {i} must be a TrafficItem, got "
                                f"{type(item).__name__}")
        object.__setattr__(self, "items", items)

    @classmethod
    def of(cls, traffic) -> Traffic:
        """A Traffic from a Traffic, a TrafficItem, a sequence of them, or a speed [m/s] (one
        passage a day of the scene's own wheel or vehicle)."""
        if isinstance(traffic, Traffic):
            return traffic
        if isinstance(traffic, TrafficItem):
            return cls((traffic,))
        if isinstance(traffic, numbers.Real) and not isinstance(traffic, bool):
            return cls((TrafficItem(speed=float(traffic)),))
        if isinstance(traffic, Sequence) and not isinstance(traffic, str):
            return cls(tuple(traffic))
        raise TypeError(f"traffic must be a Traffic, a TrafficItem, a sequence of them or a "
                        f"speed [m/s]; got {type(traffic).__name__}")

    def __len__(self) -> int:
        return len(self.items)

    def axles(self, base: Scene) -> np.ndarray:
        """Axles (wheels on the rail) per passage of each item, (k,) [-]."""
        return np.array([item.axles(base) for item in self.items], dtype=np.int64)

    def axle_rate(self, base: Scene) -> float:
        """Axle passes a day over each sleeper, sum of per_day x axles [1/day]."""
        return float(sum(item.per_day * a for item, a in zip(self.items, self.axles(base))))

    def passages(self, base: Scene, cycles: int) -> np.ndarray:
        """The whole passages of each item, (k,) int, when the traffic has run ``cycles`` axle
        passes: item i's share per_day_i / sum(per_day x axles) of them, rounded half up. A
        function of the total alone, so stages that end at the same total agree, and the
        passages of a stage are the difference of two calls."""
        rate = self.axle_rate(base)
        share = np.array([item.per_day for item in self.items]) / rate
        return np.floor(share * float(cycles) + 0.5).astype(np.int64)

    def days(self, base: Scene, cycles) -> np.ndarray:
        """The days [day] the traffic takes to run ``cycles`` axle passes."""
        return np.asarray(cycles, dtype=float) / self.axle_rate(base)

    def to_dict(self) -> list[dict]:
        """The items as plain values (a vehicle as its dataclass fields)."""
        import dataclasses

        return [{"speed": item.speed, "per_day": item.per_day,
                 "vehicle": None if item.vehicle is None else dataclasses.asdict(item.vehicle),
                 "wheel_load": item.wheel_load, "name": item.name} for item in self.items]

