"""trackwheel: a railway wheel rolling at high speed over a flexible rail on elastic supports.

SI units everywhere (m, s, kg, N, Pa, Hz); speeds in m/s -- :func:`kmh` converts from km/h.
The physics is described in the documentation (docs: Model) and follows Kato et al. (2005).

Data flow one way, one layer per subpackage (docs: Development):
``base`` (limits, units, checks) -> ``excitation`` (rail profiles, spectra, wheel defects) ->
``scene`` (:class:`Scene`) -> ``run`` (the C++ kernel: :func:`simulate`, :func:`static`,
:func:`eigen`, :func:`receptance` -> :class:`Result`) -> ``study`` (:func:`analyse`,
:func:`sweep`, :func:`adequacy`, ...) -> ``plots`` -> ``reproduce`` -> ``cli``.
"""

import importlib as _importlib
import sys as _sys

from ._version import __version__
from .base.errors import (
    DivergenceError,
    FailedCasesWarning,
    PlausibilityWarning,
    SweepFailedError,
)
from .base.units import kmh
from .excitation import Irregularity, Polygon, WheelFlat
from .excitation import spectra as spectra  # the module (trackwheel.spectra.fra, ...)
from .run.defaults import MeshWarning, StabilityWarning, default_settings, stability_limit
from .run.eigen import EigenResult, eigen
from .run.frequency import decay_rate, receptance
from .run.periodic import (
    PeriodicResponse,
    RandomResponse,
    moving_receptance,
    periodic_response,
    random_response,
)
from .run.results import Result, RunSettings
from .run.simulate import FIDELITY_LEVELS, TIME_DOMAIN_LEVELS, simulate
from .run.statics import QuasiStatic, StaticResult, linear_quasi_static, quasi_static, static
from .scene import (
    AbsorbingEnds,
    Bogie,
    CarBody,
    Contact,
    Rail,
    Scatter,
    Scene,
    SupportValues,
    Supports,
    Transition,
    Vehicle,
    Voids,
    Wheel,
    Window,
)
from .study.analysis import Analysis, amplitude_spectrum, analyse, main_frequency
from .study.convergence import Convergence, ConvergenceWarning, converged
from .study.fidelity import adequacy, recommend
from .study.settlement import settle
from .study.force_statistics import ForceStatistics, force_statistics
from .study.steady import SteadyState, steady_state
from .study.sweep import load_sweep, summarise_seeds, sweep

#: The module paths of the flat layout and the modules they are now: ``import
#: trackwheel.simulate`` (or ``from trackwheel.eigen import rail_frequencies``) keeps working,
#: and gives the module itself (the same object: its names, its monkeypatchable globals).
#: ``trackwheel.scene``, ``.plots``, ``.reproduce`` and ``.cli`` are packages at their old paths.
#: ``trackwheel.settlement`` (the settlement laws) is a short path of the same kind.
FLAT_MODULES = {
    "irregularity": "excitation",
    "spectra": "excitation.spectra",
    "vehicle": "scene.vehicle",
    "defaults": "run.defaults",
    "results": "run.results",
    "simulate": "run.simulate",
    "statics": "run.statics",
    "eigen": "run.eigen",
    "frequency": "run.frequency",
    "analysis": "study.analysis",
    "steady": "study.steady",
    "force_statistics": "study.force_statistics",
    "convergence": "study.convergence",
    "fidelity": "study.fidelity",
    "sweep": "study.sweep",
    "settlement": "study.settlement",
}
for _old, _new in FLAT_MODULES.items():
    _module = _importlib.import_module(f"{__name__}.{_new}")
    _sys.modules[f"{__name__}.{_old}"] = _module
    # the attribute too, unless a public function of the same name holds it (trackwheel.eigen,
    # .simulate, .sweep, .force_statistics are the functions, as they always were)
    globals().setdefault(_old, _module)
del _old, _new, _module

__all__ = [
    "FIDELITY_LEVELS",
    "TIME_DOMAIN_LEVELS",
    "AbsorbingEnds",
    "Analysis",
    "Contact",
    "Convergence",
    "ConvergenceWarning",
    "DivergenceError",
    "FailedCasesWarning",
    "PlausibilityWarning",
    "SweepFailedError",
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
    "SupportValues",
    "Transition",
    "Scatter",
    "Voids",
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
    "settle",
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
