"""The excitation: rail profiles (random from spectra, sines, dipped joints, measured samples),
the contact filter and wheel out-of-roundness (docs: Model § Irregularities).

Layer 1: it knows the base layer only. The scene carries these recipes (``Scene.irregularity``,
``Wheel.defects``); the run layer turns them into the kernel's spline tables.

- :mod:`.spectra` -- published irregularity spectra (one-sided PSDs in SI units);
- :mod:`.profiles` -- the parts of a rail profile; :mod:`.irregularity` -- their sum,
  :class:`Irregularity`, with sampling and a Welch PSD;
- :mod:`.contact_filter` -- the profile averaged over the Hertz contact patch;
- :mod:`.wheel_defects` -- wheel flats and polygonal wheels.

This package is also ``trackwheel.irregularity`` (the module path of the flat layout).
"""

from . import spectra
from .contact_filter import (
    contact_filter,
    contact_half_width,
    filter_attenuation,
    filter_matters,
    hertz_half_width,
)
from .irregularity import COMPONENTS_PER_DECADE, Irregularity, grid_size
from .profiles import PARTS, DippedJoint, RandomProfile, SampledProfile, SineProfile, derived_seed
from .wheel_defects import WHEEL_DEFECTS, Polygon, WheelFlat

__all__ = [
    "COMPONENTS_PER_DECADE",
    "PARTS",
    "WHEEL_DEFECTS",
    "DippedJoint",
    "Irregularity",
    "Polygon",
    "RandomProfile",
    "SampledProfile",
    "SineProfile",
    "WheelFlat",
    "contact_filter",
    "contact_half_width",
    "derived_seed",
    "filter_attenuation",
    "filter_matters",
    "grid_size",
    "hertz_half_width",
    "spectra",
]
