"""Exceptions raised by trackwheel."""

from __future__ import annotations


class DivergenceError(RuntimeError):
    """A simulation stopped because its solution diverged.

    Attributes: ``time`` [s] and ``step`` where it happened, and ``cause``, the likely reason
    (for example "time step 2e-05 s is above the explicit stability limit of about 1.3e-05 s").
    """

    def __init__(self, message: str, time: float = float("nan"), step: int = -1,
                 cause: str = ""):
        super().__init__(message)
        self.time = time
        self.step = step
        self.cause = cause

    def __reduce__(self):  # picklable across process pools
        return (type(self), (str(self), self.time, self.step, self.cause))


class PlausibilityWarning(UserWarning):
    """A value inside its allowed range but outside what a railway has: most likely a slip of
    units (a speed in km/h given as m/s, a stiffness in MN/m given as N/m). The message names
    the parameter and the likely slip. Where the value is meant, silence it with
    ``warnings.filterwarnings("ignore", category=trackwheel.PlausibilityWarning)``."""


class FailedCasesWarning(UserWarning):
    """Some cases of a sweep failed (each is a row of the table with its ``error``): the
    message gives their number and the first error."""


class SweepFailedError(RuntimeError):
    """Every case of a sweep failed: the message gives the first error; ``table`` is the sweep
    table with every case's error (the failed cases are in the store too)."""

    def __init__(self, message: str, table=None):
        super().__init__(message)
        self.table = table

    def __reduce__(self):  # picklable across process pools
        return (type(self), (str(self), self.table))
