"""The planar vehicle: wheels, bogie frames and a car body on suspensions.

Specification: docs: Model § The vehicle.

One rail carries half of everything: each :class:`~trackwheel.Wheel` is half a wheelset, a
:class:`Bogie` half a bogie frame, the :class:`CarBody` half the car body, and each suspension
the springs and dampers on one side. Positions ``x`` [m] are measured along the vehicle in the
direction of travel from its reference point, which :func:`trackwheel.simulate` places at
``x_start`` (the presets put the rear wheel there).

Each body has a vertical displacement z (up) and a small pitch phi (positive: the front rises);
a point at x on a body of centre x_b is at height z + (x - x_b) phi. A primary suspension
(k_1, c_1) joins each wheel centre to its bogie, a secondary one (k_2, c_2) each bogie centre
(its pivot) to the car body. The weights are distributed by the lever rule (each bogie on two
wheels and the car on two pivots is statically determinate), which sets every wheel's static
load; a wheel in a bogie then has no constant ``load`` of its own: the suspension carries it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..base import validate as v
from ..base.limits import RANGES, ranges_doc
from .wheel import Wheel


@dataclass(frozen=True)
class Bogie:
    """Half a bogie frame on one rail, resting on its wheels through primary suspensions."""

    wheels: tuple[int, ...]  #: indices into ``Vehicle.wheels`` (one or two)
    centre: float  #: x of the frame's centre of mass and pivot along the vehicle [m]
    mass: float = 1750.0  #: M_b [kg]
    #: J_b about the centre [kg m^2]; None for a frame on one wheel under its centre, which
    #: no moment can pitch
    pitch_inertia: float | None = 861.0
    primary_stiffness: float = 1.173e6  #: k_1 per wheel [N/m]
    primary_damping: float = 19.6e3  #: c_1 per wheel [N s/m]
    #: constant vertical force on the pivot when no car body rests on it (its share of the car
    #: body's weight, or 0) [N]
    load: float = 0.0

    def __post_init__(self):
        if not isinstance(self.wheels, (tuple, list)) or not 1 <= len(self.wheels) <= 2:
            raise ValueError(f"Bogie.wheels must list one or two wheel indices, got "
                             f"{self.wheels!r}")
        object.__setattr__(self, "wheels", tuple(
            v.integer("Bogie.wheels", w, low=0) for w in self.wheels))
        for name in ("centre", "mass", "primary_stiffness", "primary_damping", "load"):
            v.field(f"Bogie.{name}", getattr(self, name))
        if self.pitch_inertia is None:
            if len(self.wheels) != 1:
                raise ValueError("Bogie.pitch_inertia = None is only for a frame on one "
                                 "wheel (under its centre, nothing pitches it); a frame on "
                                 "two wheels needs its pitch inertia > 0 kg m^2")
        else:
            v.field("Bogie.pitch_inertia", self.pitch_inertia)


@dataclass(frozen=True)
class CarBody:
    """Half a car body on one rail, resting on the pivots of two bogies through secondary
    suspensions (or, for a quarter car, a share of it on the pivot of one bogie)."""

    #: x of the centre of mass along the vehicle [m], between the pivots (on one bogie: at
    #: its pivot)
    centre: float
    mass: float = 17250.0  #: M_c [kg]
    #: J_c about the centre [kg m^2]; None for a body on one bogie (the quarter car), which no
    #: moment can pitch
    pitch_inertia: float | None = 7.802e5
    secondary_stiffness: float = 0.61e6  #: k_2 per bogie [N/m]
    secondary_damping: float = 9.8e3  #: c_2 per bogie [N s/m]

    def __post_init__(self):
        for name in ("centre", "mass", "secondary_stiffness", "secondary_damping"):
            v.field(f"CarBody.{name}", getattr(self, name))
        if self.pitch_inertia is not None:
            v.field("CarBody.pitch_inertia", self.pitch_inertia)


#: Huo & Dai (2019), "Formulation of a linearized model for vehicle-track interactions", Shock
#: and Vibration 2019, 2015465, Table 1: a Chinese high-speed car (CRH type). Masses and
#: inertias are the whole bodies'; per rail they are halved, the suspensions are per side.
HUO_DAI_2019 = dict(car_mass=34500.0, car_pitch_inertia=1560400.0, bogie_mass=3500.0,
                    bogie_pitch_inertia=1722.0, wheelset_mass=2200.0, k1=1.173e6, c1=19.6e3,
                    k2=0.61e6, c2=9.8e3, half_bogie_distance=8.75, half_wheelbase=1.25,
                    wheel_radius=0.43)


def _high_speed_wheel() -> Wheel:
    """Half a wheelset of the Huo & Dai (2019) car: mass 1100 kg, radius 0.43 m, no load of its
    own (the suspension carries the body's weight)."""
    p = HUO_DAI_2019
    return Wheel(mass=0.5 * p["wheelset_mass"], radius=p["wheel_radius"], load=0.0)


@dataclass(frozen=True)
class Vehicle:
    """Wheels along a vehicle, optionally with bogie frames and a car body on suspensions.

    ``Vehicle()`` is the paper's single wheel under its constant load (Part I).
    """

    wheels: tuple[Wheel, ...] = field(default_factory=lambda: (Wheel(),))
    positions: tuple[float, ...] = (0.0,)  #: x of each wheel centre along the vehicle [m]
    bogies: tuple[Bogie, ...] = ()
    car: CarBody | None = None

    def __post_init__(self):
        if not isinstance(self.wheels, (tuple, list)) or not self.wheels:
            raise ValueError("Vehicle.wheels must be a non-empty tuple of trackwheel.Wheel")
        for w in self.wheels:
            if not isinstance(w, Wheel):
                raise TypeError(f"Vehicle.wheels must hold trackwheel.Wheel values, got "
                                f"{type(w).__name__}")
        object.__setattr__(self, "wheels", tuple(self.wheels))
        pos = tuple(v.field("Vehicle.positions", x) for x in self.positions)
        object.__setattr__(self, "positions", pos)
        if len(pos) != len(self.wheels):
            raise ValueError(f"Vehicle.positions has {len(pos)} entries for "
                             f"{len(self.wheels)} wheels; give one x [m] per wheel")
        self._check_spacing()
        object.__setattr__(self, "bogies", tuple(self.bogies))
        self._check_bogies()
        self._check_car()

    def _check_spacing(self):
        for i in range(1, len(self.positions)):
            gap = self.positions[i] - self.positions[i - 1]
            need = self.wheels[i].radius + self.wheels[i - 1].radius
            if gap < need:
                raise ValueError(
                    f"Vehicle.positions: wheels {i - 1} and {i} are {gap:.4g} m apart, so they "
                    f"overlap; allowed: increasing positions at least the sum of the radii "
                    f"({need:.4g} m) apart")

    def _check_bogies(self):
        seen: set[int] = set()
        for j, b in enumerate(self.bogies):
            if not isinstance(b, Bogie):
                raise TypeError(f"Vehicle.bogies must hold Bogie values, got {type(b).__name__}")
            for w in b.wheels:
                if w >= len(self.wheels):
                    raise ValueError(f"Vehicle.bogies[{j}].wheels: wheel {w} does not exist; "
                                     f"allowed range [0, {len(self.wheels) - 1}]")
                if w in seen:
                    raise ValueError(f"Vehicle.bogies[{j}].wheels: wheel {w} is already in "
                                     "another bogie; each wheel rests under one bogie")
                seen.add(w)
            xs = [self.positions[w] for w in b.wheels]
            inside = (min(xs) < b.centre < max(xs)) if len(xs) == 2 else b.centre == xs[0]
            if not inside:
                raise ValueError(
                    f"Vehicle.bogies[{j}].centre = {b.centre} m: its wheels at {xs} m are "
                    f"outside the bogie; allowed: the centre strictly between its two wheels "
                    f"(one wheel: at the wheel)")

    def _check_car(self):
        if self.car is None:
            return
        if not isinstance(self.car, CarBody):
            raise TypeError(f"Vehicle.car must be a CarBody or None, got "
                            f"{type(self.car).__name__}")
        if len(self.bogies) not in (1, 2):
            raise ValueError(f"Vehicle.car rests on two bogies (a quarter car: on one); the "
                             f"vehicle has {len(self.bogies)}")
        if len(self.bogies) == 1:
            x = self.bogies[0].centre
            if self.car.centre != x:
                raise ValueError(f"CarBody.centre = {self.car.centre} m: a car body on one "
                                 f"bogie rests on its pivot; allowed: {x} m")
            if self.car.pitch_inertia is not None:
                raise ValueError("CarBody.pitch_inertia must be None for a car body on one "
                                 "bogie (the pivot under its centre cannot pitch it)")
        else:
            a, b = sorted(bg.centre for bg in self.bogies)
            if not a < self.car.centre < b:
                raise ValueError(f"CarBody.centre = {self.car.centre} m must lie between the "
                                 f"bogie pivots; allowed range ({a}, {b}) m")
            if self.car.pitch_inertia is None:
                raise ValueError("CarBody.pitch_inertia = None is only for a car body on one "
                                 "bogie; on two it needs its pitch inertia > 0 kg m^2")
        for j, bg in enumerate(self.bogies):
            if bg.load != 0.0:
                raise ValueError(f"Vehicle.bogies[{j}].load must be 0 N under a car body "
                                 "(the car body's weight reaches the pivot)")

    # presets ------------------------------------------------------------------------------
    @classmethod
    def single_wheel(cls, wheel: Wheel | None = None) -> "Vehicle":
        """One wheel under its constant load (Part I; default: the paper's wheel)."""
        return cls(wheels=(Wheel() if wheel is None else wheel,), positions=(0.0,))

    @classmethod
    def bogie(cls, wheelbase: float = 2.5, wheel: Wheel | None = None,
              load: float | None = None) -> "Vehicle":
        """Half a bogie of the Huo & Dai (2019) high-speed car (``HUO_DAI_2019``) on two wheels
        ``wheelbase`` [m] apart (rear wheel at x = 0; at least the wheels' diameter, at most
        1000 m), carrying ``load`` [N] on its pivot (default: its share of the half car body's
        weight, M_c g / 4 with g = 9.8 m/s^2)."""
        p = HUO_DAI_2019
        w = _high_speed_wheel() if wheel is None else wheel
        if not isinstance(w, Wheel):
            raise TypeError(f"wheel must be a trackwheel.Wheel or None, got {type(w).__name__}")
        # the two wheels must not overlap; beyond 1000 m they leave Vehicle.positions' range
        wb = v.number("wheelbase", wheelbase, low=2.0 * w.radius, high=RANGES[
            "Vehicle.positions"].high, unit="m")
        share = 0.25 * p["car_mass"] * 9.8 if load is None else v.number(
            "load", load, low=0.0, unit="N")
        return cls(wheels=(w, w), positions=(0.0, wb),
                   bogies=(_huo_dai_bogie((0, 1), 0.5 * wb, share),))

    @classmethod
    def half_car(cls, wheel: Wheel | None = None) -> "Vehicle":
        """Half the Huo & Dai (2019) high-speed car on one rail (``HUO_DAI_2019``): four half
        wheelsets of 1100 kg, two half bogie frames (1750 kg, 861 kg m^2, wheelbase 2.5 m,
        k_1 = 1.173 MN/m, c_1 = 19.6 kN s/m per wheel), half a car body (17250 kg,
        7.802e5 kg m^2, pivots 17.5 m apart, k_2 = 0.61 MN/m, c_2 = 9.8 kN s/m per bogie).
        The rear wheel is at x = 0."""
        p = HUO_DAI_2019
        w = _high_speed_wheel() if wheel is None else wheel
        lt, lc = p["half_wheelbase"], p["half_bogie_distance"]
        rear, front = lt, lt + 2 * lc
        pos = (0.0, 2 * lt, 2 * lc, 2 * lc + 2 * lt)
        car = CarBody(centre=0.5 * (rear + front), mass=0.5 * p["car_mass"],
                      pitch_inertia=0.5 * p["car_pitch_inertia"], secondary_stiffness=p["k2"],
                      secondary_damping=p["c2"])
        return cls(wheels=(w,) * 4, positions=pos,
                   bogies=(_huo_dai_bogie((0, 1), rear, 0.0), _huo_dai_bogie((2, 3), front, 0.0)),
                   car=car)

    @classmethod
    def quarter_car(cls, wheel: Wheel | None = None, *, bogie_mass: float | None = None,
                    body_mass: float | None = None, primary_stiffness: float | None = None,
                    primary_damping: float | None = None,
                    secondary_stiffness: float | None = None,
                    secondary_damping: float | None = None) -> "Vehicle":
        """A quarter car: one wheel, its share of a bogie frame on the primary suspension and
        its share of the car body on the secondary suspension, stacked above the wheel (x = 0):
        wheel - k_1, c_1 - bogie M_b - k_2, c_2 - body M_c.

        The static wheel load is the weight of all three, P = (M_w + M_b + M_c) g: set it
        through the masses (for a load P at gravity g, ``body_mass = P / g - M_b - M_w``). No
        moment acts on the bodies (every spring is under their centres), so they do not pitch
        and need no pitch inertia. Defaults: one wheel's share of the Huo & Dai (2019) car
        (``HUO_DAI_2019``): wheel 1100 kg (half a wheelset), M_b = 875 kg (a quarter of the
        bogie frame), M_c = 4312.5 kg (an eighth of the car body), k_1 = 1.173 MN/m and
        c_1 = 19.6 kN s/m (the half car's per wheel), k_2 = 0.305 MN/m and c_2 = 4.9 kN s/m
        (the half car's per bogie side, shared by its two wheels): P = 61.6 kN at 9.8 m/s^2,
        the load of each wheel of :meth:`bogie` and :meth:`half_car`. Masses [kg],
        stiffnesses [N/m], dampings [N s/m]; each None takes its default."""
        p = HUO_DAI_2019
        w = _high_speed_wheel() if wheel is None else wheel

        def value(x, default):
            return default if x is None else x

        bogie = Bogie(wheels=(0,), centre=0.0, mass=value(bogie_mass, 0.25 * p["bogie_mass"]),
                      pitch_inertia=None,
                      primary_stiffness=value(primary_stiffness, p["k1"]),
                      primary_damping=value(primary_damping, p["c1"]))
        car = CarBody(centre=0.0, mass=value(body_mass, p["car_mass"] / 8.0),
                      pitch_inertia=None,
                      secondary_stiffness=value(secondary_stiffness, 0.5 * p["k2"]),
                      secondary_damping=value(secondary_damping, 0.5 * p["c2"]))
        return cls(wheels=(w,), positions=(0.0,), bogies=(bogie,), car=car)

    # derived ------------------------------------------------------------------------------
    @property
    def n_wheels(self) -> int:
        return len(self.wheels)

    @property
    def n_bodies(self) -> int:
        """Bodies with (z, phi): the bogies, then the car body."""
        return len(self.bogies) + (self.car is not None)

    @property
    def unpitched(self) -> tuple[bool, ...]:
        """For each body (the bogies, then the car body): True if it cannot pitch (its pitch
        inertia None: every spring acts under its centre, so no moment reaches it)."""
        bodies = [*self.bogies, *(() if self.car is None else (self.car,))]
        return tuple(b.pitch_inertia is None for b in bodies)

    @property
    def span(self) -> tuple[float, float]:
        """(x of the rearmost wheel, x of the leading wheel) [m]."""
        return self.positions[0], self.positions[-1]

    def bogie_of(self, wheel: int) -> int | None:
        """Index of the bogie wheel ``wheel`` rests under, or None."""
        for j, b in enumerate(self.bogies):
            if wheel in b.wheels:
                return j
        return None

    def pivot_loads(self, gravity: float) -> tuple[float, ...]:
        """Vertical force on each bogie's pivot [N]: the car body's weight by the lever rule,
        or the bogie's constant ``load``."""
        if self.car is None:
            return tuple(b.load for b in self.bogies)
        if len(self.bogies) == 1:
            return (self.car.mass * gravity,)
        x1, x2 = (b.centre for b in self.bogies)
        W = self.car.mass * gravity
        return (W * (x2 - self.car.centre) / (x2 - x1), W * (self.car.centre - x1) / (x2 - x1))

    def static_loads(self, gravity: float) -> tuple[float, ...]:
        """Static wheel loads P_w = (share of the bogie's weight and pivot force) + M_w g [N]
        (a wheel outside every bogie: its own F + M g)."""
        loads = [w.load + w.mass * gravity for w in self.wheels]
        for b, F in zip(self.bogies, self.pivot_loads(gravity)):
            total = b.mass * gravity + F
            if len(b.wheels) == 1:
                shares = (total,)
            else:
                xi, xk = (self.positions[w] for w in b.wheels)
                shares = (total * (xk - b.centre) / (xk - xi), total * (b.centre - xi) / (xk - xi))
            for w, s in zip(b.wheels, shares):
                loads[w] = s + self.wheels[w].mass * gravity
        return tuple(loads)


def _huo_dai_bogie(wheels, centre, load) -> Bogie:
    p = HUO_DAI_2019
    return Bogie(wheels=wheels, centre=centre, mass=0.5 * p["bogie_mass"],
                 pitch_inertia=0.5 * p["bogie_pitch_inertia"], primary_stiffness=p["k1"],
                 primary_damping=p["c1"], load=load)


def rigid_track_frequencies(vehicle: Vehicle) -> dict[str, float]:
    """Closed-form bounce and pitch frequencies [Hz] of the bodies on rigidly held wheels,
    undamped: a bogie bounces at sqrt(sum k_1 / M_b) / 2 pi and pitches at
    sqrt(sum k_1 a_i^2 / J_b) / 2 pi; the car body on its secondary springs (the bogies held)
    at sqrt(n k_2 / M_c) (n its bogies) and sqrt(k_2 (a_1^2 + a_2^2) / J_c). Keys
    'bogie{j}_bounce', 'bogie{j}_pitch', 'car_bounce', 'car_pitch' (no pitch key for a body
    that cannot pitch: one on a single support under its centre)."""
    out = {}
    for j, b in enumerate(vehicle.bogies):
        arms = [vehicle.positions[w] - b.centre for w in b.wheels]
        k = b.primary_stiffness
        out[f"bogie{j}_bounce"] = math.sqrt(k * len(arms) / b.mass) / (2 * math.pi)
        if b.pitch_inertia is not None:
            out[f"bogie{j}_pitch"] = math.sqrt(k * sum(a * a for a in arms)
                                               / b.pitch_inertia) / (2 * math.pi)
    if vehicle.car is not None:
        c = vehicle.car
        arms = [b.centre - c.centre for b in vehicle.bogies]
        k = c.secondary_stiffness
        out["car_bounce"] = math.sqrt(len(arms) * k / c.mass) / (2 * math.pi)
        if c.pitch_inertia is not None:
            out["car_pitch"] = math.sqrt(k * sum(a * a for a in arms)
                                         / c.pitch_inertia) / (2 * math.pi)
    return out


Vehicle.__doc__ += ranges_doc("Vehicle")
Bogie.__doc__ += ranges_doc("Bogie")
CarBody.__doc__ += ranges_doc("CarBody")
