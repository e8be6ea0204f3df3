"""The periodic level's cases of a sweep (``fidelity="periodic/linear"``): each case's row from
:func:`trackwheel.periodic_response`, in milliseconds.

The row is the steady state on the infinite periodic track in the frequency domain (docs:
Model § The periodic level).

What the row holds (:data:`trackwheel.study.columns.PERIODIC_OUTPUTS` says it per column): the
outputs of the steady state -- max |d| over it, the frequency of d's largest line, the force's
extremes over all phases, the dynamic factor max N / P, the RMS of N - P; ``lost_contact``
False and ``loss_duration`` 0 (a steady state that would lose contact is refused) -- and NaN
where the periodic level has no counterpart: the frequency resolution of a record, P1/P2 after
a joint (joints are refused), the time-domain settings (integrator, step, mesh, passage).
A case the periodic level refuses (contact loss, a non-periodic or undamped track, several
wheels, a random or discrete profile, the Hertz law beyond its linearisation) is an error row
with the reason, like a diverged time-domain case.
"""

from __future__ import annotations

import math
import time

from ...run.periodic import periodic_response
from ...run.simulate import PERIODIC_LEVEL
from ...scene import Scene
from ..columns import FLOAT_COLUMNS, SETTINGS_COLUMNS, label

__all__ = ["TIME_DOMAIN_KEYWORDS", "check_keywords", "run_case"]

#: simulate's keywords that a periodic case has no use for: the time integration, the mesh, the
#: passage and the start (given with fidelity="periodic/linear" they are refused)
TIME_DOMAIN_KEYWORDS = ("integrator", "dt", "n_elements", "x_start", "x_end", "distance",
                        "duration", "output_every", "rho_inf", "baumgarte", "rolling", "start",
                        "drop_height", "energy", "n_modes", "max_newton", "newton_tol")


def check_keywords(kwargs: dict) -> None:
    """Refuse time-domain settings given with ``fidelity="periodic/linear"``."""
    given = sorted(k for k in kwargs if k not in ("fidelity", "progress"))
    if given:
        raise ValueError(
            f"sweep: {', '.join(given)} do(es) not apply to fidelity={PERIODIC_LEVEL!r}: the "
            "steady state in the frequency domain has no time step, mesh, passage or start; "
            "give only the speeds, support stiffnesses and the scene")


def _empty_row() -> dict:
    row = {c: math.nan for c in FLOAT_COLUMNS}
    row.update({column: None for column in SETTINGS_COLUMNS.values()})
    row.update({label(n): None for n in ("lost_contact", "output_every", "steps")})
    row[SETTINGS_COLUMNS["fidelity"]] = PERIODIC_LEVEL
    return row


def run_case(scene: Scene, speed: float, kwargs: dict) -> dict:
    """One case at the periodic level: its steady outputs by column, or an error row
    (``ValueError``: the level does not apply; ``RuntimeError``: its wavenumber quadrature did
    not converge) with the time to failure. ``kwargs`` (the sweep's simulate keywords) are not
    used: with ``fidelity="auto"`` they served the adequacy runs that chose this level."""
    t0 = time.perf_counter()
    row = _empty_row()
    try:
        outputs = periodic_response(scene, speed).outputs()
    except (ValueError, RuntimeError) as exc:
        row.update({label("error"): f"{type(exc).__name__}: {exc}",
                    label("wall_time"): time.perf_counter() - t0})
        return row
    row.update({label(name): value for name, value in outputs.items()})
    row.update({label("wheel"): 0, label("error"): "",
                label("wall_time"): time.perf_counter() - t0})
    return row
