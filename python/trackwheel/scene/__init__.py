"""The scene: what is simulated, as frozen dataclasses in SI units (docs: Model § Scene).

Layer 2: it knows the base layer and the excitation it carries. One module per part:

- :mod:`.rail` -- :class:`Rail` and its :class:`AbsorbingEnds`;
- :mod:`.supports` -- :class:`Supports` (single springs, or pad, sleeper and ballast layers),
  each property one value, one per support or a function of X; :mod:`.support_fields` -- the
  recipes of such functions (:class:`Transition`, :class:`Scatter`, :class:`Voids`);
- :mod:`.wheel` -- :class:`Wheel`; :mod:`.contact` -- :class:`Contact`;
- :mod:`.window` -- the travelling :class:`Window`;
- :mod:`.vehicle` -- :class:`Vehicle` with its :class:`Bogie` frames and :class:`CarBody`;
- :mod:`.scene` -- :class:`Scene`, which holds them all, with the presets
  ``Scene.kato2005()`` and ``Scene.ballasted_track()``.

Every value is validated on construction, so a scene that exists is a scene the kernel can
run; nothing here imports the compiled kernel.
"""

from ..base.limits import GAUSS_RANGE, MAX_ELEMENTS, MAX_SUPPORTS
from ..base.units import kmh
from .contact import Contact
from .rail import (
    ABSORBING_ATTENUATION,
    ABSORBING_AXIAL_ATTENUATION,
    ABSORBING_AXIAL_MIN_FREQUENCY,
    ABSORBING_MAX_FREQUENCY,
    AbsorbingEnds,
    Rail,
)
from .scene import GRAVITY, Scene
from .support_fields import Scatter, Transition, Voids
from .supports import SupportValues, Supports
from .vehicle import Bogie, CarBody, Vehicle
from .wheel import Wheel
from .window import Window

__all__ = [
    "ABSORBING_ATTENUATION",
    "ABSORBING_AXIAL_ATTENUATION",
    "ABSORBING_AXIAL_MIN_FREQUENCY",
    "ABSORBING_MAX_FREQUENCY",
    "GAUSS_RANGE",
    "GRAVITY",
    "MAX_ELEMENTS",
    "MAX_SUPPORTS",
    "AbsorbingEnds",
    "Bogie",
    "CarBody",
    "Contact",
    "Rail",
    "Scatter",
    "Scene",
    "SupportValues",
    "Supports",
    "Transition",
    "Vehicle",
    "Voids",
    "Wheel",
    "Window",
    "kmh",
]
