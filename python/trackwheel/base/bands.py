"""Frequency bands shared by every layer: the one-third-octave bands of IEC 61260-1 (base 10)."""

from __future__ import annotations

import math

import numpy as np

from . import validate as v


def third_octave_bands(f_min: float, f_max: float) -> tuple[np.ndarray, np.ndarray]:
    """(centres [Hz], edges [Hz] shape (n, 2)) of the IEC 61260-1 base-10 one-third-octave
    bands lying wholly inside [f_min, f_max] [Hz]."""
    f_min = v.positive("f_min", f_min, "Hz")
    f_max = v.number("f_max", f_max, low=f_min, low_open=True, unit="Hz")
    half = 10.0 ** 0.05
    k_lo = math.ceil(10.0 * math.log10(f_min * half / 1000.0) - 1e-9)
    k_hi = math.floor(10.0 * math.log10(f_max / half / 1000.0) + 1e-9)
    centres = 1000.0 * 10.0 ** (np.arange(k_lo, k_hi + 1) / 10.0)
    return centres, np.column_stack((centres / half, centres * half))
