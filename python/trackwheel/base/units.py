"""Unit conversions at the boundary: trackwheel computes in SI units (m, s, kg, N, Pa, Hz)."""

from __future__ import annotations

import warnings

from . import validate as v
from .errors import PlausibilityWarning
from .limits import RECORD_SPEED, SOFTEST_SUPPORT


def kmh(speed_kmh: float) -> float:
    """Convert a speed from km/h to m/s (``kmh(300)`` -> 83.33 m/s)."""
    return v.number("speed_kmh", speed_kmh, low=0.0, unit="km/h") / 3.6


def check_speed_units(speed: float, name: str = "speed", stacklevel: int = 3) -> None:
    """Warn (:class:`PlausibilityWarning`) if ``speed`` [m/s] is above the wheel-on-rail record
    (``RECORD_SPEED``, 574.8 km/h): most likely a speed in km/h given in m/s."""
    if speed > RECORD_SPEED:
        warnings.warn(
            f"{name} = {speed:g} m/s is {speed * 3.6:g} km/h, faster than any train has run on "
            f"rails ({RECORD_SPEED * 3.6:g} km/h); speeds are in m/s: did you mean "
            f"tw.kmh({speed:g}) = {speed / 3.6:.4g} m/s?", PlausibilityWarning,
            stacklevel=stacklevel)


def check_stiffness_units(name: str, stiffness: float, stacklevel: int = 3) -> None:
    """Warn (:class:`PlausibilityWarning`) if a support, pad or ballast ``stiffness`` [N/m] is
    below ``SOFTEST_SUPPORT`` (10 kN/m): most likely MN/m (or kN/m) given in N/m."""
    if stiffness >= SOFTEST_SUPPORT:
        return
    guess = next((f"{stiffness:g} {unit} is {stiffness * f:.4g} N/m"
                  for unit, f in (("MN/m", 1e6), ("kN/m", 1e3))
                  if 1e6 <= stiffness * f <= 1e10), None)
    hint = f" ({guess}: did you mean that?)" if guess else ""
    warnings.warn(
        f"{name} = {stiffness:g} N/m is a thousand times softer than any track (rail pads "
        f"and ballast: about 1e7 to 1e9 N/m); stiffnesses are in N/m{hint}", PlausibilityWarning,
        stacklevel=stacklevel)
