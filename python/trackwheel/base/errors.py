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
