"""The sweep itself: the arguments checked, the cases listed (speed x support stiffness x seed),
those in the store read, the others run (serially, on our pool or on any executor), every
finished case stored as it comes back, and the rows returned as the sweep table."""

from __future__ import annotations

import itertools
import warnings
from concurrent.futures import Executor
from typing import TYPE_CHECKING

import numpy as np

from ..._version import __version__
from ...base import validate as v
from ...base.errors import FailedCasesWarning, SweepFailedError
from ...base.units import check_speed_units, check_stiffness_units
from ...base.limits import MAX_SEED
from ...scene import Scene
from ..columns import SPEED_KMH, SWEEP_COLUMNS, doc_table, label, periodic_doc_table
from ..fidelity import adequacy
from ...run.simulate import PERIODIC_LEVEL
from . import cases, periodic, pool
from . import store as store_module  # sweep's argument `store` is the directory

if TYPE_CHECKING:  # pandas is imported when a table is built: keeps `import trackwheel` light
    import pandas as pd


def sweep(scene: Scene, speed, support_stiffness=None, *, seeds=None,
          executor: Executor | None = None,
          max_workers: int | None = None, store=None, progress: bool = True,
          retry_errors: bool = False, fidelity_tol: float = 0.005,
          **simulate_kwargs) -> pd.DataFrame:
    """Run ``simulate`` + ``analyse`` for every (speed, support stiffness) pair.

    Parameters
    ----------
    scene : the base Scene; each case replaces ``scene.supports.stiffness`` (and with
        ``seeds`` the random parts of ``scene.irregularity`` and the scattered properties of
        ``scene.supports``). A support property given as a function of X (not a recipe such
        as :class:`trackwheel.Transition`) enters each case as its values at the supports.
    speed : forward speed(s) v > 0 [m/s] (a number or a sequence; ``kmh`` converts).
    support_stiffness : support stiffness(es) k_s > 0 [N/m], each one value for every support
        (it replaces a stiffness that varies along X); default the scene's (a stiffness that
        varies along X is kept, its ``support_stiffness`` column NaN).
    seeds : realisations of the random irregularity and the scattered bed (integers >= 0), or
        None (default: the scene as given, ``seed`` column <NA>). Seed s runs the scene with
        ``scene.irregularity.reseeded(s)``: its first random part drawn with seed s, the others
        with seeds derived from s (:func:`trackwheel.irregularity.derived_seed`), the
        deterministic parts unchanged; and with ``scene.supports.reseeded(s)`` (the same rule
        over its :class:`trackwheel.Scatter` properties). Summarise the rows with
        :func:`summarise_seeds`.
    executor : any ``concurrent.futures.Executor`` to run the cases on, e.g.
        ``distributed.Client(...).get_executor()`` for a Dask cluster (not shut down here).
        Default: a process pool of ``max_workers`` processes (default ``os.cpu_count()``);
        ``max_workers=1`` runs the cases one after the other in this process.
    store : directory [path] to keep each finished case in (created if missing); re-running
        the same sweep with the same store skips the cases already there. See
        :mod:`trackwheel.study.sweep` for the format and :func:`load_sweep` to read it.
    progress : show a progress bar over the cases (``tqdm.auto``: the notebook widget in
        Jupyter). ``simulate``'s own bar is always off in a sweep.
    retry_errors : recompute stored cases that failed (DivergenceError, ValueError).
    fidelity_tol : with ``fidelity="auto"``: the tolerance handed to
        :func:`trackwheel.adequacy` (relative, on amplitude, main frequency, peak force).
    **simulate_kwargs : passed to every :func:`trackwheel.simulate` call (integrator, dt,
        n_elements, x_start, x_end, fidelity, ...). ``fidelity="auto"`` first runs
        :func:`trackwheel.adequacy` on one sample case -- the highest speed on the softest
        supports, the most dynamic corner of the sweep -- and sweeps at the cheapest level
        within ``fidelity_tol`` of the full model; the choice is in the ``fidelity`` column and
        ``df.attrs["fidelity_auto"]`` (chosen level, sample case, the adequacy table).
        ``fidelity="periodic/linear"`` (:data:`trackwheel.FIDELITY_LEVELS`' least detailed)
        takes each case's steady state from :func:`trackwheel.periodic_response` in
        milliseconds, in this process (a pool costs more than it saves; an ``executor``
        given is used); the columns it fills are listed below, and the other simulate
        keywords, which it has no use for, are refused (chosen by ``"auto"``, it ignores
        them). A case it refuses (contact loss, an undamped track, a random profile, ...)
        is an error row like a diverged one.

    Returns
    -------
    pandas.DataFrame with one row per case, the Cartesian product in order (speed major, then
    stiffness, seed minor), the columns below (each named with its unit): the settings used,
    the outputs of :func:`trackwheel.analyse` and its contact-force statistics
    (``dynamic_factor``, ``loss_duration_s``, ``force_rms_N``, and ``p1_N``/``p2_N`` with their
    times when the scene holds a dipped joint that the run passes: the peaks after the joint's
    middle, :func:`trackwheel.force_statistics.defect_position`). ``df.attrs`` holds
    ``computed`` (cases run by this call) and ``from_store`` (cases read from the store).
    Results do not depend on the executor or the number of workers (each case is a
    deterministic, independent run).

    Raises
    ------
    ValueError, TypeError : bad arguments (empty, non-positive, NaN or duplicate values,
        unknown simulate keywords, seeds without a random irregularity, a support stiffness
        the scene refuses), before anything runs.
    SweepFailedError : every case failed (DivergenceError, ValueError or the kernel's
        RuntimeError, each stored as a failed case); the message gives the first error, the
        exception's ``table`` the whole table.
    Any exception other than DivergenceError/ValueError/RuntimeError from a case, and
    KeyboardInterrupt: re-raised after the finished cases are stored.

    Warns
    -----
    FailedCasesWarning : some cases failed: their number and the first error (the rows carry
        each case's ``error``).
    PlausibilityWarning : a speed above the wheel-on-rail record or a support stiffness below
        1 MN/m (a likely slip of units), once per value.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    speeds = _values("speed", speed, "m/s")
    stiffs = _stiffness_axis(scene, support_stiffness)
    seed_axis = _seeds(seeds, scene)
    kwargs = _simulate_kwargs(simulate_kwargs)
    auto = None
    if kwargs.get("fidelity") == PERIODIC_LEVEL:
        periodic.check_keywords(kwargs)
    if kwargs.get("fidelity") == "auto":
        auto = _auto_fidelity(scene, speeds, stiffs, kwargs, fidelity_tol)
        kwargs["fidelity"] = auto["chosen"]
    workers = _workers(executor, max_workers)
    if not isinstance(progress, bool) or not isinstance(retry_errors, bool):
        raise TypeError("progress and retry_errors must be True or False")
    store_dir = store_module.open_store(store)

    for sp in speeds.tolist():  # once here, not once per case
        check_speed_units(sp, stacklevel=3)
    for k in stiffs:
        if k is not None:
            check_stiffness_units("support_stiffness", k, stacklevel=3)
    case_list = []  # (speed, stiffness, seed, case scene, inputs, hash)
    for sp, k, seed in itertools.product(speeds.tolist(), stiffs, seed_axis):
        try:
            cs = cases.case_scene(scene, k, seed)
        except ValueError as exc:  # e.g. a support so soft that the track sags metres
            if k is None:
                raise
            raise ValueError(f"support_stiffness = {k:g} N/m: {exc}") from None
        inputs = store_module.inputs(cs, sp, k, kwargs, seed)
        case_list.append((sp, k, seed, cs, inputs, store_module.inputs_hash(inputs)))
    rows = ([None] * len(case_list) if store_dir is None
            else store_module.stored_rows(store_dir, case_list, retry_errors))
    todo = [i for i, r in enumerate(rows) if r is None]
    _compute(case_list, rows, todo, kwargs, store_dir, executor, workers, progress)
    df = cases.frame(rows)
    df.attrs.update(computed=len(todo), from_store=len(case_list) - len(todo))
    if auto is not None:
        df.attrs["fidelity_auto"] = auto
    _report_failures(df)
    return df


def _report_failures(df) -> None:
    """Warn (FailedCasesWarning) with the number of failed cases and the first error; raise
    SweepFailedError, the table attached, if every case failed."""
    error = label("error")
    failed = df[df[error].fillna("") != ""]
    if failed.empty:
        return
    import pandas as pd

    first = failed.iloc[0]
    seed = first[label("seed")]
    where = (f"v = {first[label('speed')]:.4g} m/s, k_s = "
             f"{first[label('support_stiffness')]:.4g} N/m"
             + ("" if pd.isna(seed) else f", seed {seed}"))
    text = f"the first ({where}): {first[error]}"
    if len(failed) == len(df):
        raise SweepFailedError(f"every case of the sweep failed ({len(df)}); {text}", df)
    warnings.warn(f"{len(failed)} of {len(df)} cases of the sweep failed (rows with an error); "
                  f"{text}", FailedCasesWarning, stacklevel=3)


def _compute(case_list, rows, todo, kwargs, store_dir, executor, workers, progress) -> None:
    """Run the cases ``todo`` (serially, on our pool or on ``executor``), each row completed
    with its case's axes and stored as it comes back, into ``rows``."""
    from tqdm.auto import tqdm

    bar = tqdm(total=len(case_list), initial=len(case_list) - len(todo), unit="case",
               desc=f"sweep [{kwargs['fidelity']}]" if "fidelity" in kwargs else "sweep",
               disable=not progress)

    def finish(i: int, row: dict) -> None:
        sp, k, seed, _, inputs, h = case_list[i]
        row = dict(row)
        row.update({label("speed"): sp, SPEED_KMH.label: sp * 3.6, label("support_stiffness"): k,
                    label("seed"): seed, label("version"): __version__, label("case"): h})
        if store_dir is not None:
            store_module.write_record(store_dir, h, inputs, row)
            row = store_module.decode_row(store_module.jsonable(row))  # what a re-run reads
        rows[i] = row
        bar.update(1)

    # the periodic level's cases take milliseconds: a pool would cost more than it saves
    serial = workers == 1 or len(todo) == 1 or kwargs.get("fidelity") == PERIODIC_LEVEL
    try:
        if todo and executor is None and serial:
            for i in todo:
                finish(i, cases.run_case(case_list[i][3], case_list[i][0], kwargs))
        elif todo:
            if executor is None:
                with pool.make_pool(min(workers, len(todo))) as ex:
                    pool.run_parallel(ex, True, todo, case_list, kwargs, finish)
            else:
                pool.run_parallel(executor, False, todo, case_list, kwargs, finish)
    finally:
        bar.close()


def _auto_fidelity(scene: Scene, speeds, stiffs, kwargs: dict, tol) -> dict:
    """``fidelity="auto"``: the cheapest level adequate within ``tol`` on the sweep's most
    dynamic case (the highest speed on the softest supports), with that case and the table."""
    tol = v.number("fidelity_tol", tol, low=0.0, low_open=True)
    sample_v = float(np.max(speeds))
    sample_k = None if stiffs == [None] else float(np.min(stiffs))
    rest = {key: val for key, val in kwargs.items() if key != "fidelity"}
    table = adequacy(cases.case_scene(scene, sample_k), speeds=[sample_v], tol=tol, **rest)
    return {"chosen": table.attrs["recommended"], "sample_speed": sample_v,
            "sample_support_stiffness": sample_k, "tol": tol,
            "table": table.to_dict("records")}


def _simulate_kwargs(simulate_kwargs: dict) -> dict:
    """The simulate keywords, checked: known to simulate and storable (plain JSON values)."""
    unknown = sorted(set(simulate_kwargs) - set(cases.SIMULATE_PARAMS))
    if unknown:
        raise TypeError(f"sweep got unknown simulate keyword(s) {unknown}; allowed: "
                        f"{sorted(set(cases.SIMULATE_PARAMS) - {'progress'})}")
    kwargs = dict(simulate_kwargs)
    store_module.jsonable(kwargs)  # the store hashes them: plain numbers, strings, bools, None
    return kwargs


def _workers(executor, max_workers) -> int:
    if executor is not None and not isinstance(executor, Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor, "
                        f"got {type(executor).__name__}")
    if executor is not None and max_workers is not None:
        raise ValueError("give executor or max_workers, not both")
    return pool.default_workers() if max_workers is None else v.integer(
        "max_workers", max_workers, low=1, high=4096)


def _stiffness_axis(scene: Scene, support_stiffness) -> list:
    """The support stiffness axis [N/m]: the values given, else the scene's one value, or
    [None] (the scene's own supports) for a stiffness that varies along X."""
    if support_stiffness is None:
        k = scene.supports.stiffness
        if isinstance(k, tuple) or callable(k):
            return [None]
        support_stiffness = k
    return _values("support_stiffness", support_stiffness, "N/m").tolist()


def _values(name: str, values, unit: str) -> np.ndarray:
    try:
        arr = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a number or a sequence of numbers [{unit}]") from exc
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a number or a 1-d sequence [{unit}], "
                         f"got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"{name} is empty: give at least one value in (0, inf) {unit}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or inf; allowed range (0, inf) {unit}")
    if np.any(arr <= 0.0):
        raise ValueError(f"{name} = {float(arr[arr <= 0.0][0])!r} is outside the allowed range "
                         f"(0, inf) {unit}")
    if np.unique(arr).size != arr.size:
        raise ValueError(f"{name} contains duplicate values: {arr.tolist()}")
    return arr



def _seeds(seeds, scene: Scene) -> list[int | None]:
    """The seed axis: [None] without one, else the validated seeds (non-negative integers)."""
    if seeds is None:
        return [None]
    if isinstance(seeds, (int, np.integer)):
        seeds = [seeds]
    try:
        out = [v.integer("seeds", s, low=0, high=MAX_SEED) for s in seeds]
    except TypeError as exc:
        raise TypeError("seeds must be a sequence of integers >= 0 (or None)") from exc
    if not out:
        raise ValueError("seeds is empty: give at least one integer >= 0 (or None)")
    if len(set(out)) != len(out):
        raise ValueError(f"seeds contains duplicate values: {out}")
    if (scene.irregularity is None or scene.irregularity.n_random == 0) and (
            scene.supports.n_random == 0):
        raise ValueError("seeds: the scene has no random part to re-seed; give "
                         "scene.irregularity = Irregularity.random(...) (+ other parts) or "
                         "scattered supports (Supports.scattered)")
    return out



sweep.__doc__ += "\n    Columns\n    -------\n" + "\n".join(
    "    " + line for line in doc_table(SWEEP_COLUMNS).splitlines()) + "\n"
_PERIODIC_TITLE = 'At the periodic level (``fidelity="periodic/linear"``)'
sweep.__doc__ += (f"\n    {_PERIODIC_TITLE}\n    {'-' * len(_PERIODIC_TITLE)}\n" + "\n".join(
    "    " + line for line in periodic_doc_table().splitlines()) + "\n")
