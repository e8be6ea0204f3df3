"""The wheel: a rigid disc under its load, possibly out of round (docs: Model § Wheel)."""

from __future__ import annotations

from dataclasses import dataclass

from ..base import validate as v
from ..base.limits import ranges_doc
from ..excitation.wheel_defects import WHEEL_DEFECTS


@dataclass(frozen=True)
class Wheel:
    """The wheel: a rigid disc loaded by the car body (docs: Model § Wheel)."""

    mass: float = 10.0  #: M [kg]
    radius: float = 0.1  #: rho0, undeformed radius [m]
    load: float = 47040.0  #: F, vertical load on the centre (car body weight) [N]; M g is added
    inertia: float | None = None  #: J, polar moment of inertia [kg m^2]; None: M rho0^2 / 2
    youngs_modulus: float = 2.058e11  #: E of the wheel [Pa] (Hertz constant)
    poisson_ratio: float = 0.30  #: nu of the wheel [-]
    torque: float = 0.0  #: external torque on the wheel, positive in the rolling direction [N m]
    #: T_b, a friction brake on the rotation [N m]: -T_b sign(theta') while the wheel turns; the
    #: wheel locks (theta' = 0) when its spin reaches zero and stays locked while the torque
    #: needed to hold it, abs(T - rho lambda), is <= T_b (beyond adhesion, T_b > mu P rho0, it
    #: locks and slides). Full and ancf/* levels only (docs: Model § Rolling and slip)
    brake_torque: float = 0.0
    #: out-of-roundness, a tuple of :class:`~trackwheel.irregularity.WheelFlat` /
    #: :class:`~trackwheel.irregularity.Polygon` (docs: Model § Irregularities); () is a round wheel
    defects: tuple = ()

    def __post_init__(self):
        for name in ("mass", "radius", "load", "youngs_modulus", "poisson_ratio", "torque",
                     "brake_torque"):
            v.field(f"Wheel.{name}", getattr(self, name))
        if self.inertia is not None:
            v.field("Wheel.inertia", self.inertia)
        if not isinstance(self.defects, (tuple, list)):
            raise TypeError(f"Wheel.defects must be a tuple of WheelFlat/Polygon, "
                            f"got {type(self.defects).__name__}")
        for d in self.defects:
            if not isinstance(d, WHEEL_DEFECTS):
                raise TypeError(f"Wheel.defects must hold WheelFlat or Polygon values, "
                                f"got {type(d).__name__}")
            d.check(self.radius)
        object.__setattr__(self, "defects", tuple(self.defects))

    @property
    def polar_inertia(self) -> float:
        """J [kg m^2]: the given value, or a uniform disc M rho0^2 / 2."""
        return self.inertia if self.inertia is not None else 0.5 * self.mass * self.radius**2



Wheel.__doc__ += ranges_doc("Wheel")
