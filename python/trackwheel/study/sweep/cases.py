"""One case of a sweep: its scene, its run and analysis as a table row, and the rows as the
sweep's DataFrame (columns: :data:`trackwheel.study.columns.SWEEP_COLUMNS`).

:func:`run_case` runs in the workers (a top-level function of picklable arguments).
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import time
import warnings

import numpy as np

from ...base.errors import DivergenceError, PlausibilityWarning
from ...run.simulate import PERIODIC_LEVEL, simulate
from ...scene import Scene
from ..analysis import analyse
from ..columns import COLUMNS, FLOAT_COLUMNS, SETTINGS_COLUMNS, SWEEP_COLUMNS, label
from ..force_statistics import defect_position
from . import periodic

#: simulate's keyword arguments and their defaults (what a sweep passes on)
SIMULATE_PARAMS = {name: p.default for name, p in inspect.signature(simulate).parameters.items()
                   if p.kind is inspect.Parameter.KEYWORD_ONLY}


def case_scene(scene: Scene, stiffness: float | None, seed: int | None = None) -> Scene:
    """``scene`` with the support stiffness ``stiffness`` [N/m] (None: the scene's own), a
    support property given as a function of X tabulated at the supports (so the case pickles
    and is stored by value) and, with a ``seed``, its irregularity's random parts and its
    scattered supports drawn afresh (:meth:`trackwheel.Irregularity.reseeded`,
    :meth:`trackwheel.Supports.reseeded`)."""
    supports = scene.supports
    with warnings.catch_warnings():  # the sweep warns once about implausible stiffnesses
        warnings.simplefilter("ignore", PlausibilityWarning)
        if stiffness is not None:
            supports = dataclasses.replace(supports, stiffness=stiffness)
    if scene.window is None:
        supports = supports.tabulated(scene.support_positions)
    if seed is not None and supports.n_random:
        supports = supports.reseeded(seed)
    irr = scene.irregularity
    if seed is not None and irr is not None and irr.n_random:
        irr = irr.reseeded(seed)
    if supports is scene.supports and irr is scene.irregularity:
        return scene
    with warnings.catch_warnings():  # the sweep warns once about implausible stiffnesses
        warnings.simplefilter("ignore", PlausibilityWarning)
        return dataclasses.replace(scene, supports=supports, irregularity=irr)


def error_row(scene: Scene, kwargs: dict, message: str, wall: float) -> dict:
    """The row of a failed case: NaN outputs, the settings asked for (None/NaN where
    simulate would resolve them), the ``error`` message and the time to failure [s]."""
    row = {c: math.nan for c in FLOAT_COLUMNS}
    row.update({label(n): None for n in ("lost_contact", "wheel", "output_every", "steps")})
    row.update({SETTINGS_COLUMNS[n]: None for n in ("integrator", "rolling", "start",
                                                    "fidelity", "n_modes")})
    row[SETTINGS_COLUMNS["n_elements"]] = scene.rail.n_elements
    for name, column in SETTINGS_COLUMNS.items():
        given = kwargs.get(name, SIMULATE_PARAMS.get(name))
        if given is not None:
            row[column] = given
    if kwargs.get("x_end") is not None:
        row[label("x_end")] = kwargs["x_end"]
    row.update({label("error"): message, label("wall_time"): wall})
    return row


def wheel_outputs(r, scene: Scene) -> list[dict]:
    """The analysed outputs (:data:`~trackwheel.study.columns.OUTPUTS`) of each wheel of run
    ``r``, by column (P1/P2 for a wheel that passes the scene's dipped joint)."""
    out = []
    for i in range(r.n_wheels):
        ri = r.wheel(i)
        x_d = defect_position(scene)
        if x_d is not None and not ri.x_wheel[0] <= x_d <= ri.x_wheel[-1]:
            x_d = None  # this wheel does not reach the joint: no P1/P2
        # analysed as a wheel of the vehicle (its quasi-static line with the whole vehicle)
        wheel = i if r.n_wheels > 1 else None
        out.append(analyse(r, wheel=wheel, defect_at=x_d).outputs())
    return out


def run_case(scene: Scene, speed: float, kwargs: dict) -> dict:
    """Simulate and analyse one case; DivergenceError, ValueError and the kernel's RuntimeError
    (a failed static solve) become an error row. A vehicle's case row holds its worst wheel's
    outputs and, under ``wheels``, every wheel's (the table has one row per wheel). At the
    periodic level, the steady state's row (:mod:`.periodic`)."""
    if kwargs.get("fidelity") == PERIODIC_LEVEL:
        return periodic.run_case(scene, speed, kwargs)
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():  # the sweep warns once about implausible speeds
            warnings.simplefilter("ignore", PlausibilityWarning)
            r = simulate(scene, speed, progress=False, **kwargs)
        wheels = wheel_outputs(r, scene)
    except (DivergenceError, ValueError, RuntimeError) as exc:
        # RuntimeError: the kernel's static solve at the start failed (e.g. a load that pushes
        # the rail off its supports) -- a property of the case, like a divergence
        return error_row(scene, kwargs, f"{type(exc).__name__}: {exc}",
                         time.perf_counter() - t0)
    s = r.settings
    row = {column: getattr(s, name) for name, column in SETTINGS_COLUMNS.items()}
    worst = int(np.argmax([w[label("amplitude")] for w in wheels]))
    row.update(wheels[worst])
    row.update({label("wheel"): worst, label("error"): "", label("wall_time"): r.wall_time,
                label("steps"): r.steps})
    row[label("x_end")] = s.x_end
    if len(wheels) > 1:
        row["wheels"] = wheels
    return row


def long_rows(rows: list[dict]) -> list[dict]:
    """One row per wheel: a vehicle case's row repeated with each wheel's outputs, ``wheel``
    its index and ``worst`` on the worst one (a single wheel: wheel 0, worst)."""
    out = []
    for row in rows:
        per_wheel = row.get("wheels")
        base = {k: val for k, val in row.items() if k != "wheels"}
        worst = base.get("wheel")
        if not per_wheel:
            out.append(dict(base, worst=None if worst is None else True))
            continue
        for i, w in enumerate(per_wheel):
            out.append(dict(base, **w, wheel=i, worst=i == worst))
    return out


def frame(rows: list[dict]):
    """The sweep table of case rows: one row per case and wheel, the columns of
    :data:`~trackwheel.study.columns.SWEEP_COLUMNS` in order with their dtypes."""
    import pandas as pd

    df = pd.DataFrame.from_records(long_rows(rows), columns=list(COLUMNS))
    for c in SWEEP_COLUMNS:
        if c.dtype is not None:
            df[c.label] = df[c.label].astype(c.dtype)
    return df


__all__ = ["SIMULATE_PARAMS", "case_scene", "error_row", "frame", "long_rows",
           "run_case", "wheel_outputs"]
