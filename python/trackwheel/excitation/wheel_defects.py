"""Wheel out-of-roundness: flats and polygonal wheels (docs: Model § Irregularities).

Sign convention: Delta rho(psi) [m] is the change of the wheel radius at wheel angle psi [rad],
measured on the wheel from a mark and advancing with the rolling angle theta; it is periodic in
2 pi. **Negative Delta rho is a flat.** Convention for the kernel: the mark (psi = 0) is the
wheel point in contact at rolling angle theta = 0, so the point in contact at theta is
psi = theta, and a defect at ``at_angle`` psi_f meets the rail at theta = psi_f + 2 pi k: every
2 pi rho0 of *rolled* distance. ``WheelFlat/Polygon.table(radius, n)`` sample a defect over one
revolution; the run layer (``trackwheel.run.profile``) turns the sum into the kernel's periodic
spline.

Like the rail-profile parts, each defect is a frozen, hashable, picklable dataclass of plain
numbers (its recipe).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..base import validate as v
from ..base.limits import ranges_doc


def _psi(psi, at: float) -> np.ndarray:
    """Angle from the defect centre, wrapped to [-pi, pi) [rad]."""
    p = np.asarray(psi, dtype=float)
    if not np.all(np.isfinite(p)):
        raise ValueError("psi must be finite [rad]")
    return np.mod(p - at + math.pi, 2.0 * math.pi) - math.pi


def _defect_table(defect, radius: float, n: int) -> tuple[float, float, np.ndarray]:
    n = v.integer("n", n, low=8, high=10_000_000)
    dpsi = 2.0 * math.pi / n
    return 0.0, dpsi, defect.delta_rho(dpsi * np.arange(n), radius)


@dataclass(frozen=True)
class WheelFlat:
    """A wheel flat of chord length L_f centred at wheel angle ``at_angle`` [rad].

    New flat (a chord): Delta rho = rho0 cos(phi_f) / cos(psi) - rho0 for |psi| <= phi_f =
    asin(L_f / (2 rho0)), 0 elsewhere; depth rho0 (1 - cos phi_f) ~ L_f^2 / (8 rho0).
    Rounded flat (``rounded=True``, Wu & Thompson 2002): with s = rho0 psi,
    Delta rho = -(d/2)(1 + cos(pi s / (L_f/2))) for |s| <= L_f/2, depth d = ``depth`` or, when
    None, L_f^2 / (16 rho0). psi is measured from ``at_angle`` and wrapped to [-pi, pi).
    """

    length: float  #: L_f, chord (new) or rounded length [m]
    rounded: bool = False
    at_angle: float = 0.0  #: wheel angle of the flat's centre [rad]
    depth: float | None = None  #: rounded flat's depth d [m]; None: L_f^2 / (16 rho0)
    kind: str = field(default="wheel_flat", init=False)

    def __post_init__(self):
        v.field("WheelFlat.length", self.length, hint="lengths are in m: 20 mm is 0.02")
        v.boolean("WheelFlat.rounded", self.rounded)
        v.number("WheelFlat.at_angle", self.at_angle, unit="rad")
        if self.depth is not None:
            if not self.rounded:
                raise ValueError("WheelFlat.depth is only for a rounded flat (rounded=True); "
                                 "a new flat's depth follows from its length")
            v.field("WheelFlat.depth", self.depth, hint="depths are in m: 1 mm is 1e-3")

    def check(self, radius: float) -> None:
        """Raise unless the flat fits a wheel of ``radius`` [m] (L_f < 2 rho0)."""
        r = v.positive("radius", radius, "m")
        if self.length >= 2.0 * r:
            raise ValueError(f"WheelFlat.length = {self.length} m must be shorter than the "
                             f"wheel's diameter; allowed range (0, {2.0 * r}) m")
        if self.depth is not None and self.depth >= r:
            raise ValueError(f"WheelFlat.depth = {self.depth} m must be smaller than the "
                             f"wheel's radius; allowed range (0, {r}) m")

    def _rounded(self, radius):
        d = self.depth if self.depth is not None else self.length**2 / (16.0 * radius)
        return d, 2.0 * math.pi / self.length  # s-wavenumber of cos(pi s / (L/2))

    def _terms(self, psi, radius, order: int) -> np.ndarray:
        self.check(radius)
        p = _psi(psi, self.at_angle)
        if self.rounded:
            d, k = self._rounded(radius)
            s = radius * p
            inside = np.abs(s) <= 0.5 * self.length
            c = (k * radius) ** order
            trig = (np.cos, lambda u: -np.sin(u), lambda u: -np.cos(u))[order]
            return np.where(inside, -0.5 * d * (order == 0) - 0.5 * d * c * trig(k * s), 0.0)
        phi = math.asin(self.length / (2.0 * radius))
        inside = np.abs(p) <= phi
        cp = np.cos(np.where(inside, p, 0.0))
        sp = np.sin(np.where(inside, p, 0.0))
        h = radius * math.cos(phi)
        val = (h / cp - radius, h * sp / cp**2, h * (1.0 + sp**2) / cp**3)[order]
        return np.where(inside, val, 0.0)

    def delta_rho(self, psi, radius: float) -> np.ndarray:
        """Delta rho [m] at wheel angle psi [rad] on a wheel of radius rho0 [m]."""
        return self._terms(psi, radius, 0)

    def delta_rho_dpsi(self, psi, radius: float) -> np.ndarray:
        """d Delta rho / d psi [m/rad]."""
        return self._terms(psi, radius, 1)

    def delta_rho_dpsi2(self, psi, radius: float) -> np.ndarray:
        """d^2 Delta rho / d psi^2 [m/rad^2] (a new flat's slope jumps at its edges)."""
        return self._terms(psi, radius, 2)

    def table(self, radius: float, n: int) -> tuple[float, float, np.ndarray]:
        """(psi0 = 0 [rad], dpsi = 2 pi / n [rad], Delta rho [m] at psi0 + i dpsi, i < n):
        one revolution, periodic (the value at 2 pi is the first one)."""
        return _defect_table(self, radius, n)


@dataclass(frozen=True)
class Polygon:
    """Polygonal (out-of-round) wheel: Delta rho = a cos(m psi + phase)."""

    order: int  #: m, harmonics per revolution [-] >= 1
    amplitude: float  #: a [m] >= 0
    phase: float = 0.0  #: [rad]
    kind: str = field(default="polygon", init=False)

    def __post_init__(self):
        v.integer("Polygon.order", self.order, low=1, high=10_000)
        v.field("Polygon.amplitude", self.amplitude, hint="amplitudes are in m: 0.1 mm is 1e-4")
        v.number("Polygon.phase", self.phase, unit="rad")

    def check(self, radius: float) -> None:
        """Raise unless the amplitude is smaller than the radius [m]."""
        r = v.positive("radius", radius, "m")
        if self.amplitude >= r:
            raise ValueError(f"Polygon.amplitude = {self.amplitude} m must be smaller than the "
                             f"wheel radius; allowed range [0, {r}) m")

    def _u(self, psi):
        p = np.asarray(psi, dtype=float)
        if not np.all(np.isfinite(p)):
            raise ValueError("psi must be finite [rad]")
        return self.order * p + self.phase

    def delta_rho(self, psi, radius: float) -> np.ndarray:
        """Delta rho [m] at wheel angle psi [rad] (``radius`` [m] only checked)."""
        self.check(radius)
        return self.amplitude * np.cos(self._u(psi))

    def delta_rho_dpsi(self, psi, radius: float) -> np.ndarray:
        """d Delta rho / d psi [m/rad]."""
        self.check(radius)
        return -self.amplitude * self.order * np.sin(self._u(psi))

    def delta_rho_dpsi2(self, psi, radius: float) -> np.ndarray:
        """d^2 Delta rho / d psi^2 [m/rad^2]."""
        self.check(radius)
        return -self.amplitude * self.order**2 * np.cos(self._u(psi))

    def table(self, radius: float, n: int) -> tuple[float, float, np.ndarray]:
        """(0, 2 pi / n, Delta rho at i 2 pi / n, i < n) [rad, rad, m], periodic."""
        return _defect_table(self, radius, n)


WheelFlat.__doc__ += ranges_doc("WheelFlat")
Polygon.__doc__ += ranges_doc("Polygon")

WHEEL_DEFECTS = (WheelFlat, Polygon)
