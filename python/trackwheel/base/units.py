"""Unit conversions at the boundary: trackwheel computes in SI units (m, s, kg, N, Pa, Hz)."""

from __future__ import annotations

from . import validate as v


def kmh(speed_kmh: float) -> float:
    """Convert a speed from km/h to m/s (``kmh(300)`` -> 83.33 m/s)."""
    return v.number("speed_kmh", speed_kmh, low=0.0, unit="km/h") / 3.6
