"""trackwheel: a railway wheel rolling at high speed over a flexible rail on elastic supports.

SI units everywhere (m, s, kg, N, Pa, Hz); speeds in m/s -- :func:`kmh` converts from km/h.
The physics is described in the documentation (docs: Model) and follows Kato et al. (2005).

Data flow one way: :class:`Scene` -> the C++ kernel (:func:`simulate`, :func:`static`,
:func:`eigen`) -> :class:`Result` -> :func:`analyse` -> ``trackwheel.plots``; the defaults
derived from a scene live in ``trackwheel.defaults``.
"""

from ._errors import DivergenceError
from ._version import __version__
from .analysis import Analysis, amplitude_spectrum, analyse, main_frequency
from .convergence import Convergence, ConvergenceWarning, converged
from .defaults import MeshWarning, StabilityWarning, default_settings, stability_limit
from .eigen import EigenResult, eigen
from .fidelity import adequacy, recommend
from .force_statistics import ForceStatistics, force_statistics
from .frequency import decay_rate, receptance
from .irregularity import Irregularity, Polygon, WheelFlat
from .periodic import (
    PeriodicResponse,
    RandomResponse,
    moving_receptance,
    periodic_response,
    random_response,
)
from .results import Result, RunSettings
from .scene import AbsorbingEnds, Contact, Rail, Scene, Supports, Wheel, Window, kmh
from .simulate import FIDELITY_LEVELS, simulate
from .vehicle import Bogie, CarBody, Vehicle
from .steady import SteadyState, steady_state
from .statics import QuasiStatic, StaticResult, linear_quasi_static, quasi_static, static
from .sweep import load_sweep, summarise_seeds, sweep
from . import spectra as spectra  # the module, re-exported (trackwheel.spectra.fra, ...)
from . import frequency as frequency  # the module (trackwheel.frequency.decay_rate_limit, ...)

__all__ = [
    "FIDELITY_LEVELS",
    "AbsorbingEnds",
    "Analysis",
    "Contact",
    "Convergence",
    "ConvergenceWarning",
    "DivergenceError",
    "EigenResult",
    "MeshWarning",
    "QuasiStatic",
    "Rail",
    "Result",
    "RunSettings",
    "Scene",
    "StabilityWarning",
    "StaticResult",
    "Supports",
    "Wheel",
    "Window",
    "SteadyState",
    "steady_state",
    "__version__",
    "adequacy",
    "amplitude_spectrum",
    "analyse",
    "converged",
    "default_settings",
    "eigen",
    "kmh",
    "linear_quasi_static",
    "load_sweep",
    "main_frequency",
    "quasi_static",
    "recommend",
    "simulate",
    "stability_limit",
    "static",
    "summarise_seeds",
    "sweep",
    "Irregularity",
    "Polygon",
    "WheelFlat",
    "ForceStatistics",
    "force_statistics",
    "Vehicle",
    "Bogie",
    "CarBody",
    "receptance",
    "decay_rate",
    "PeriodicResponse",
    "RandomResponse",
    "moving_receptance",
    "periodic_response",
    "random_response",
]
