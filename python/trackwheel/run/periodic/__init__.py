"""The periodic level: the steady response of a wheel on the linear track periodic in its
sleeper bay, in the frequency domain (docs: Model § The periodic level)."""

from .response import (
    DEFAULT_HARMONICS,
    PERIODIC_FIDELITIES,
    PeriodicResponse,
    moving_receptance,
    periodic_response,
    periodic_track,
)

__all__ = ["DEFAULT_HARMONICS", "PERIODIC_FIDELITIES", "PeriodicResponse", "moving_receptance",
           "periodic_response", "periodic_track"]
from .spectral import DEFAULT_PERCENTILES, RandomResponse, random_response  # noqa: E402

__all__ += ["DEFAULT_PERCENTILES", "RandomResponse", "random_response"]
