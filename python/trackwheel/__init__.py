"""trackwheel: a railway wheel rolling at high speed over a flexible rail on elastic supports.

SI units everywhere (m, s, kg, N, Pa, Hz); speeds in m/s -- :func:`kmh` converts from km/h.
The physics is specified in MODEL.md and follows Kato et al. (2005).
"""

from ._version import __version__
from .scene import Contact, Rail, Scene, Supports, Wheel, kmh
from .statics import QuasiStatic, StaticResult, quasi_static, static
from .eigen import EigenResult, eigen
from ._errors import DivergenceError
from .simulate import Result, simulate
from .convergence import (Convergence, ConvergenceWarning, StabilityWarning, converged,
                          default_settings, stability_limit)
from .analysis import Analysis, amplitude_spectrum, analyse, main_frequency
from .sweep import load_sweep, sweep
from .fidelity import adequacy, recommend
from .simulate import FIDELITY_LEVELS
from . import spectra
from .irregularity import Irregularity, Polygon, WheelFlat
from .force_statistics import ForceStatistics, force_statistics

__all__ = [
    "FIDELITY_LEVELS",
    "adequacy",
    "recommend",
    "Analysis",
    "amplitude_spectrum",
    "analyse",
    "main_frequency",
    "load_sweep",
    "sweep",
    "Contact",
    "Convergence",
    "ConvergenceWarning",
    "StabilityWarning",
    "converged",
    "default_settings",
    "stability_limit",
    "DivergenceError",
    "Result",
    "simulate",
    "EigenResult",
    "QuasiStatic",
    "Rail",
    "Scene",
    "StaticResult",
    "Supports",
    "Wheel",
    "__version__",
    "eigen",
    "kmh",
    "quasi_static",
    "static",
    "spectra",
    "Irregularity",
    "Polygon",
    "WheelFlat",
    "ForceStatistics",
    "force_statistics",
]
