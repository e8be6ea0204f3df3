"""Parameter sweeps over speed, support stiffness and random realisations, in parallel,
resumable (issues 5, 13).

``sweep(scene, speed=[...], support_stiffness=[...], seeds=[...], **simulate_kwargs)`` runs
``simulate(case_scene, v, **simulate_kwargs)`` and :func:`trackwheel.analyse` for every
(speed, support stiffness, seed) case and returns one table row per case and wheel (long
format: a vehicle's case has one row per wheel, ``wheel`` its index, ``worst`` True on the wheel
with the largest amplitude, so ``df[df.worst]`` is one row per case; a single wheel is wheel 0);
:func:`summarise_seeds` turns the rows of a Monte Carlo sweep into percentiles per speed.

Seeds (the realisation axis): with ``seeds=[s, ...]`` the case scene's irregularity is
``scene.irregularity.reseeded(s)`` (:meth:`trackwheel.Irregularity.reseeded`): its first random
part is drawn with seed s, random part k >= 1 with ``derived_seed(s, k)``, deterministic parts
(sines, joints, measured samples) are kept. The reseeded profile is part of the case scene, so
it is in the inputs hash: each realisation is its own record and a re-run resumes.

Store format (``store=DIR``)
----------------------------
One JSON file per finished case, ``DIR/case-<h>.json`` where ``<h>`` is the first 24 hex digits
of the case's *inputs hash*: the SHA-256 of the canonical JSON (sorted keys, no spaces, floats
written with ``repr`` so they round-trip exactly) of ::

    {"scene": dataclasses.asdict(case scene),   # support stiffness and seed already applied
     "speed": v [m/s], "support_stiffness": k [N/m], "seed": s or None,
     "simulate": {the simulate keyword arguments given to sweep},
     "version": trackwheel.__version__}

The file holds ``{"format": "trackwheel.sweep.case", "format_version": 3, "inputs_hash": <full
hash>, "inputs": {...}, "row": {column: value}, "checksum": <SHA-256 of the canonical JSON of
everything but the checksum>}``; NaN and inf are written as ``null``. Each record is written to
a temporary file in the same directory, flushed to disk and renamed over the final name
(``os.replace``, atomic on POSIX and Windows), by the process that runs the sweep, as soon as
its case completes; so an interrupted sweep (Ctrl-C, a crashed worker, a killed machine) leaves
only complete records. On a re-run a record is used only if it parses, its checksum matches and
its inputs equal the case's; anything else is reported (``RuntimeWarning``) and recomputed.
Leftover temporary files (``.tmp-*``) are ignored. :func:`load_sweep` reads a store back into
a DataFrame (checking every record); plain pandas reads it too:
``pd.DataFrame([json.load(open(p))["row"] for p in Path(DIR).glob("case-*.json")])``.

Parallel runs: by default a ``ProcessPoolExecutor`` over the available cores, started with the
``forkserver`` method (``spawn`` where there is none) -- never ``fork``, which is unsafe in a
parent running threads (Jupyter, progress bars, Dask). Its workers import the main module, so a
*script* must call ``sweep`` under ``if __name__ == "__main__":`` (notebooks, the ``trackwheel``
command and ``max_workers=1`` need nothing). Records are written by the calling process as the
cases come back, so any executor works, local or remote.

Failed cases: a case whose run diverges (:class:`trackwheel.DivergenceError`), is rejected
(``ValueError``, e.g. a speed above simulate's range) or cannot start (``RuntimeError``: the
static solve at the start failed) becomes a row with its message in
``error`` and NaN outputs, and the sweep carries on. Such rows are stored too: they are
deterministic (same inputs, same version, same failure), so re-running a sweep does not retry
them unless ``retry_errors=True``. Any other exception is a bug or an interruption: the sweep
stops, keeps (and stores) every case that finished, and re-raises.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import inspect
import itertools
import json
import math
import multiprocessing
import os
import tempfile
import time
import warnings
from concurrent.futures import FIRST_COMPLETED, Executor, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from . import _validate as v
from ._errors import DivergenceError
from ._version import __version__
from .analysis import analyse
from .fidelity import adequacy
from .force_statistics import defect_position, seed_percentiles
from .scene import Scene
from .simulate import simulate

if TYPE_CHECKING:  # pandas is imported when a table is built: keeps `import trackwheel` light
    import pandas as pd

__all__ = ["COLUMNS", "load_sweep", "summarise_seeds", "sweep"]

FORMAT = "trackwheel.sweep.case"
#: 2: the seed axis and the contact-force columns (issue 13); 3: the vehicle's ``wheel``
#: column and per-wheel ``wheels`` outputs (issue 15). Older records are recomputed.
FORMAT_VERSION = 3

#: Table columns, in order. Outputs are NaN (and ``lost_contact`` <NA>) for failed cases.
COLUMNS = (
    "speed",  # v [m/s]
    "speed_kmh",  # v [km/h]
    "support_stiffness",  # k_s [N/m]
    "seed",  # realisation of the random irregularity (<NA> without a seeds axis)
    "wheel",  # the wheel this row measures (0 for a single wheel; <NA> for failed cases)
    "worst",  # True on the case's worst wheel (largest amplitude): one such row per case
    "amplitude",  # max |d| [m] (analyse)
    "main_frequency",  # [Hz]
    "frequency_resolution",  # 1/(N dt) [Hz]
    "min_contact_force",  # [N]
    "max_contact_force",  # [N]
    "lost_contact",  # bool
    # contact-force statistics (analyse(...).forces, trackwheel.force_statistics)
    "dynamic_factor",  # max N / P0, P0 = F + M g [-]
    "loss_duration",  # total time without contact [s]
    "force_rms",  # RMS of N - mean(N) over the record [N]
    "p1", "p1_time",  # P1 peak after the scene's dipped joint [N], its time [s] (NaN: none)
    "p2", "p2_time",  # P2 peak [N], its time [s]
    "error",  # "" if the case ran, else "DivergenceError: ..." / "ValueError: ..."
    "wall_time",  # simulate's wall time [s] (time to failure for failed cases)
    # settings used (from Result.settings; for failed cases the requested or default ones)
    "integrator", "dt", "n_elements", "x_start", "x_end", "t_end", "output_every", "rho_inf",
    "baumgarte", "rolling", "start", "drop_height", "fidelity", "n_modes",
    "steps",  # time steps taken
    "version",  # trackwheel version that computed the row
    "case",  # inputs hash (the store's record name)
)
_FLOAT = ("speed", "speed_kmh", "support_stiffness", "amplitude", "main_frequency",
          "frequency_resolution", "min_contact_force", "max_contact_force", "dynamic_factor",
          "loss_duration", "force_rms", "p1", "p1_time", "p2", "p2_time", "wall_time", "dt",
          "x_start", "x_end", "t_end", "rho_inf", "baumgarte", "drop_height")
#: force-statistics columns :func:`summarise_seeds` summarises by default
SEED_COLUMNS = ("max_contact_force", "min_contact_force", "dynamic_factor", "loss_duration",
                "force_rms")
_SETTINGS = ("integrator", "dt", "n_elements", "x_start", "t_end", "output_every", "rho_inf",
             "baumgarte", "rolling", "start", "drop_height", "fidelity", "n_modes")
_SIMULATE_PARAMS = {name: p.default for name, p in inspect.signature(simulate).parameters.items()
                    if p.kind is inspect.Parameter.KEYWORD_ONLY}


# --------------------------------------------------------------------------------------------
# one case (runs in the workers: top level, picklable arguments)
def _case_scene(scene: Scene, stiffness: float, seed: int | None = None) -> Scene:
    scene = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports,
                                                                    stiffness=stiffness))
    if seed is None:
        return scene
    return dataclasses.replace(scene, irregularity=scene.irregularity.reseeded(seed))


def _error_row(scene: Scene, speed: float, kwargs: dict, message: str, wall: float) -> dict:
    row = {c: math.nan for c in _FLOAT}
    row.update(lost_contact=None, wheel=None, n_elements=scene.rail.n_elements,
               output_every=None, steps=None, integrator=None, rolling=None, start=None, fidelity=None,
               n_modes=None)
    for name in _SETTINGS:  # what was asked for; None/NaN where simulate resolves it
        given = kwargs.get(name, _SIMULATE_PARAMS.get(name))
        if given is not None:
            row[name] = given
    if kwargs.get("x_end") is not None:
        row["x_end"] = kwargs["x_end"]
    row.update(error=message, wall_time=wall)
    return row


def _wheel_outputs(r, scene: Scene) -> list[dict]:
    """The analysed outputs of each wheel of run ``r`` (P1/P2 for a wheel that passes the
    scene's dipped joint)."""
    out = []
    for i in range(r.n_wheels):
        ri = r.wheel(i)
        x_d = defect_position(scene)
        if x_d is not None and not ri.x_wheel[0] <= x_d <= ri.x_wheel[-1]:
            x_d = None  # this wheel does not reach the joint: no P1/P2
        a = analyse(ri, defect_at=x_d)
        out.append(dict(
            amplitude=a.amplitude, main_frequency=a.main_frequency,
            frequency_resolution=a.frequency_resolution, min_contact_force=a.min_contact_force,
            max_contact_force=a.max_contact_force, lost_contact=a.lost_contact,
            dynamic_factor=a.dynamic_factor, loss_duration=a.loss_duration,
            force_rms=float(np.std(ri.normal_force)), p1=a.forces.p1, p1_time=a.forces.p1_time,
            p2=a.forces.p2, p2_time=a.forces.p2_time))
    return out


def _run_case(scene: Scene, speed: float, kwargs: dict) -> dict:
    """Simulate and analyse one case; DivergenceError, ValueError and the kernel's RuntimeError
    (a failed static solve) become an error row. A vehicle's case row holds its worst wheel's
    outputs and, under ``wheels``, every wheel's (the table has one row per wheel)."""
    t0 = time.perf_counter()
    try:
        r = simulate(scene, speed, progress=False, **kwargs)
        wheels = _wheel_outputs(r, scene)
    except (DivergenceError, ValueError, RuntimeError) as exc:
        # RuntimeError: the kernel's static solve at the start failed (e.g. a load that pushes
        # the rail off its supports) -- a property of the case, like a divergence
        return _error_row(scene, speed, kwargs, f"{type(exc).__name__}: {exc}",
                          time.perf_counter() - t0)
    s = r.settings
    row = {name: getattr(s, name) for name in _SETTINGS}
    worst = int(np.argmax([w["amplitude"] for w in wheels]))
    row.update(wheels[worst], wheel=worst, error="", wall_time=r.wall_time, x_end=s.x_end,
               steps=r.steps)
    if len(wheels) > 1:
        row["wheels"] = wheels
    return row


# --------------------------------------------------------------------------------------------
# store
def _jsonable(x):
    """Plain JSON values: numpy scalars to Python, NaN/inf to None, tuples to lists."""
    if isinstance(x, dict):
        return {str(k): _jsonable(val) for k, val in x.items()}
    if isinstance(x, (list, tuple)):
        return [_jsonable(val) for val in x]
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if x is None or isinstance(x, str):
        return x
    raise TypeError(f"cannot store a value of type {type(x).__name__} ({x!r}) in a sweep record")


def _canonical(obj) -> bytes:
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False).encode()


def _inputs(scene: Scene, speed: float, stiffness: float, kwargs: dict,
            seed: int | None = None) -> dict:
    return _jsonable({"scene": dataclasses.asdict(scene), "speed": speed,
                      "support_stiffness": stiffness, "seed": seed, "simulate": kwargs,
                      "version": __version__})


def _record_path(store: Path, inputs_hash: str) -> Path:
    return store / f"case-{inputs_hash[:24]}.json"


def _write_record(store: Path, inputs_hash: str, inputs: dict, row: dict) -> None:
    payload = {"format": FORMAT, "format_version": FORMAT_VERSION, "inputs_hash": inputs_hash,
               "inputs": inputs, "row": _jsonable(row)}
    payload["checksum"] = hashlib.sha256(_canonical(payload)).hexdigest()
    data = json.dumps(payload, sort_keys=True, indent=1, allow_nan=False).encode()
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".json", dir=store)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, _record_path(store, inputs_hash))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _read_record(path: Path) -> tuple[dict | None, str]:
    """(payload, "") for a sound record, (None, reason) otherwise."""
    try:
        payload = json.loads(path.read_bytes())
    except (OSError, ValueError) as exc:  # unreadable, truncated, not JSON, bad encoding
        return None, f"unreadable ({type(exc).__name__}: {exc})"
    if not isinstance(payload, dict) or payload.get("format") != FORMAT:
        return None, "not a trackwheel sweep record"
    if payload.get("format_version") != FORMAT_VERSION:
        return None, f"format version {payload.get('format_version')!r} != {FORMAT_VERSION}"
    checksum = payload.pop("checksum", None)
    if checksum != hashlib.sha256(_canonical(payload)).hexdigest():
        return None, "checksum mismatch"
    inputs, row = payload.get("inputs"), payload.get("row")
    if not isinstance(inputs, dict) or not isinstance(row, dict):
        return None, "missing inputs or row"
    if payload.get("inputs_hash") != hashlib.sha256(_canonical(inputs)).hexdigest():
        return None, "inputs hash mismatch"
    if set(row) - {"wheels"} != set(COLUMNS) - {"worst"}:
        return None, "wrong columns"
    return payload, ""


def _decode_row(row: dict) -> dict:
    out = dict(row)
    for c in _FLOAT:
        if out[c] is None:
            out[c] = math.nan
    if out.get("wheels"):
        out["wheels"] = [{c: (math.nan if c in _FLOAT and val is None else val)
                          for c, val in w.items()} for w in out["wheels"]]
    return out


def _long(rows: list[dict]) -> list[dict]:
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


def _frame(rows: list[dict]):
    import pandas as pd

    df = pd.DataFrame.from_records(_long(rows), columns=list(COLUMNS))
    for c in _FLOAT:
        df[c] = df[c].astype("float64")
    df["lost_contact"] = df["lost_contact"].astype("boolean")
    df["worst"] = df["worst"].astype("boolean")
    for c in ("seed", "wheel", "n_elements", "output_every", "steps"):
        df[c] = df[c].astype("Int64")
    df["error"] = df["error"].astype(str)
    return df


def load_sweep(path) -> pd.DataFrame:
    """Load every sound record of a sweep store (``path``: the ``store=`` directory) into a
    DataFrame with the columns of :func:`sweep` (see the module docstring for the format),
    sorted by speed, support stiffness, seed and case hash. Records that fail their checks are left
    out with a ``RuntimeWarning`` naming them. A store may hold several sweeps (other settings,
    other versions): filter on the settings and ``version`` columns."""
    store = Path(os.fspath(path))
    if not store.is_dir():
        raise ValueError(f"path = {os.fspath(path)!r} is not a sweep store directory")
    rows = []
    for p in sorted(store.glob("case-*.json")):
        payload, reason = _read_record(p)
        if payload is None:
            warnings.warn(f"sweep store {store}: record {p.name} is {reason}; left out",
                          RuntimeWarning, stacklevel=2)
            continue
        rows.append(_decode_row(payload["row"]))
    df = _frame(rows)
    return df.sort_values(["speed", "support_stiffness", "seed", "case", "wheel"],
                          ignore_index=True)


# --------------------------------------------------------------------------------------------
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


def _default_workers() -> int:
    """The cores this process may run on (os.cpu_count() where affinity is unknown)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return os.cpu_count() or 1


def _pool(workers: int) -> ProcessPoolExecutor:
    # forkserver (POSIX) or spawn: never fork a parent that may run threads (progress bars,
    # Jupyter, Dask); the workers import trackwheel afresh and run _run_case by name.
    if "forkserver" in multiprocessing.get_all_start_methods():
        ctx = multiprocessing.get_context("forkserver")
        # The server (started once per session) imports trackwheel once; the workers of every
        # sweep fork from it ready to run: ~0.1 s instead of ~0.5-1 s per pool. "__main__" is
        # the default preload. No effect if the server already runs.
        ctx.set_forkserver_preload(["__main__", "trackwheel.sweep"])
    else:
        ctx = multiprocessing.get_context("spawn")
    return ProcessPoolExecutor(max_workers=workers, mp_context=ctx)


def _terminate(pool: ProcessPoolExecutor) -> None:
    """Stop our own pool's worker processes now (after Ctrl-C: their cases are abandoned)."""
    terminate = getattr(pool, "terminate_workers", None)  # Python >= 3.14
    if terminate is not None:
        terminate()
        return
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for proc in procs:  # our own workers, by handle
        with contextlib.suppress(OSError):
            proc.terminate()
    for proc in procs:
        proc.join(timeout=5.0)


def _seeds(seeds, scene: Scene) -> list[int | None]:
    """The seed axis: [None] without one, else the validated seeds (non-negative integers)."""
    if seeds is None:
        return [None]
    if isinstance(seeds, (int, np.integer)):
        seeds = [seeds]
    try:
        out = [v.integer("seeds", s, low=0, high=2**63 - 1) for s in seeds]
    except TypeError as exc:
        raise TypeError("seeds must be a sequence of integers >= 0 (or None)") from exc
    if not out:
        raise ValueError("seeds is empty: give at least one integer >= 0 (or None)")
    if len(set(out)) != len(out):
        raise ValueError(f"seeds contains duplicate values: {out}")
    if scene.irregularity is None or scene.irregularity.n_random == 0:
        raise ValueError("seeds: the scene's irregularity has no random part to re-seed; "
                         "give scene.irregularity = Irregularity.random(...) (+ other parts)")
    return out


def sweep(scene: Scene, speed, support_stiffness=None, *, seeds=None,
          executor: Executor | None = None,
          max_workers: int | None = None, store=None, progress: bool = True,
          retry_errors: bool = False, fidelity_tol: float = 0.005,
          **simulate_kwargs) -> pd.DataFrame:
    """Run ``simulate`` + ``analyse`` for every (speed, support stiffness) pair.

    Parameters
    ----------
    scene : the base Scene; each case replaces ``scene.supports.stiffness`` (and with
        ``seeds`` the random parts of ``scene.irregularity``).
    speed : forward speed(s) v > 0 [m/s] (a number or a sequence; ``kmh`` converts).
    support_stiffness : support stiffness(es) k_s > 0 [N/m]; default the scene's.
    seeds : realisations of the random irregularity (integers >= 0), or None (default: the
        scene as given, ``seed`` column <NA>). Seed s runs the scene with
        ``scene.irregularity.reseeded(s)``: its first random part drawn with seed s, the others
        with seeds derived from s (:func:`trackwheel.irregularity.derived_seed`), the
        deterministic parts unchanged. Summarise the rows with :func:`summarise_seeds`.
    executor : any ``concurrent.futures.Executor`` to run the cases on, e.g.
        ``distributed.Client(...).get_executor()`` for a Dask cluster (not shut down here).
        Default: a process pool of ``max_workers`` processes (default ``os.cpu_count()``);
        ``max_workers=1`` runs the cases one after the other in this process.
    store : directory [path] to keep each finished case in (created if missing); re-running
        the same sweep with the same store skips the cases already there. See the module
        docstring for the format and :func:`load_sweep` to read it.
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

    Returns
    -------
    pandas.DataFrame with one row per case, the Cartesian product in order (speed major, then
    stiffness, seed minor), columns :data:`COLUMNS`: the settings used, the outputs of
    :func:`trackwheel.analyse` and its contact-force statistics (``dynamic_factor``,
    ``loss_duration``, ``force_rms``, and ``p1``/``p2`` with their times when the scene holds
    a dipped joint that the run passes: the peaks after the joint's middle,
    :func:`trackwheel.force_statistics.defect_position`). ``df.attrs`` holds ``computed`` (cases run by
    this call) and ``from_store`` (cases read from the store). Results do not depend on the
    executor or the number of workers (each case is a deterministic, independent run).

    Raises
    ------
    ValueError, TypeError : bad arguments (empty, non-positive, NaN or duplicate values,
        unknown simulate keywords, seeds without a random irregularity), before anything runs.
    Any exception other than DivergenceError/ValueError/RuntimeError from a case, and
    KeyboardInterrupt: re-raised after the finished cases are stored.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    speeds = _values("speed", speed, "m/s")
    stiffs = _values("support_stiffness",
                     scene.supports.stiffness if support_stiffness is None else support_stiffness,
                     "N/m")
    seed_axis = _seeds(seeds, scene)
    unknown = sorted(set(simulate_kwargs) - set(_SIMULATE_PARAMS))
    if unknown:
        raise TypeError(f"sweep got unknown simulate keyword(s) {unknown}; allowed: "
                        f"{sorted(set(_SIMULATE_PARAMS) - {'progress'})}")
    kwargs = dict(simulate_kwargs)
    _jsonable(kwargs)  # the store hashes them: plain numbers, strings, bools, None
    auto = None
    if kwargs.get("fidelity") == "auto":
        fidelity_tol = v.number("fidelity_tol", fidelity_tol, low=0.0, low_open=True)
        sample_v, sample_k = float(np.max(speeds)), float(np.min(stiffs))
        rest = {key: val for key, val in kwargs.items() if key != "fidelity"}
        table = adequacy(_case_scene(scene, sample_k), speeds=[sample_v], tol=fidelity_tol,
                         **rest)
        kwargs["fidelity"] = table.attrs["recommended"]
        auto = {"chosen": kwargs["fidelity"], "sample_speed": sample_v,
                    "sample_support_stiffness": sample_k, "tol": fidelity_tol,
                    "table": table.to_dict("records")}
    if executor is not None and not isinstance(executor, Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor, "
                        f"got {type(executor).__name__}")
    if executor is not None and max_workers is not None:
        raise ValueError("give executor or max_workers, not both")
    workers = _default_workers() if max_workers is None else v.integer(
        "max_workers", max_workers, low=1, high=4096)
    if not isinstance(progress, bool) or not isinstance(retry_errors, bool):
        raise TypeError("progress and retry_errors must be True or False")
    store_dir = None
    if store is not None:
        store_dir = Path(os.fspath(store))
        if store_dir.exists() and not store_dir.is_dir():
            raise ValueError(f"store = {os.fspath(store)!r} exists and is not a directory")
        store_dir.mkdir(parents=True, exist_ok=True)

    cases = []  # (speed, stiffness, seed, case scene, inputs, hash)
    for sp, k, seed in itertools.product(speeds.tolist(), stiffs.tolist(), seed_axis):
        cs = _case_scene(scene, k, seed)
        inputs = _inputs(cs, sp, k, kwargs, seed)
        cases.append((sp, k, seed, cs, inputs, hashlib.sha256(_canonical(inputs)).hexdigest()))

    rows: list[dict | None] = [None] * len(cases)
    if store_dir is not None:
        for i, (*_, inputs, h) in enumerate(cases):
            path = _record_path(store_dir, h)
            if not path.exists():
                continue
            payload, reason = _read_record(path)
            if payload is not None and payload["inputs"] != inputs:
                payload, reason = None, "a record of other inputs"
            if payload is None:
                warnings.warn(f"sweep store {store_dir}: record {path.name} is {reason}; "
                              "recomputing it", RuntimeWarning, stacklevel=2)
                continue
            row = _decode_row(payload["row"])
            if row["error"] and retry_errors:
                continue
            rows[i] = row
    todo = [i for i, r in enumerate(rows) if r is None]
    n_stored = len(cases) - len(todo)

    from tqdm.auto import tqdm

    bar = tqdm(total=len(cases), initial=n_stored, unit="case",
               desc=f"sweep [{kwargs['fidelity']}]" if "fidelity" in kwargs else "sweep",
               disable=not progress)

    def finish(i: int, row: dict) -> None:
        sp, k, seed, _, inputs, h = cases[i]
        row = dict(row, speed=sp, speed_kmh=sp * 3.6, support_stiffness=k, seed=seed,
                   version=__version__, case=h)
        if store_dir is not None:
            _write_record(store_dir, h, inputs, row)
            row = _decode_row(_jsonable(row))  # exactly what a re-run reads back
        rows[i] = row
        bar.update(1)

    try:
        if todo and executor is None and (workers == 1 or len(todo) == 1):
            for i in todo:
                finish(i, _run_case(cases[i][3], cases[i][0], kwargs))
        elif todo:
            if executor is None:
                with _pool(min(workers, len(todo))) as ex:
                    _run_parallel(ex, True, todo, cases, kwargs, finish)
            else:
                _run_parallel(executor, False, todo, cases, kwargs, finish)
    finally:
        bar.close()

    df = _frame(rows)
    df.attrs.update(computed=len(todo), from_store=n_stored)
    if auto is not None:
        df.attrs["fidelity_auto"] = auto
    return df


def _run_parallel(ex, own, todo, cases, kwargs, finish) -> None:
    pending = {ex.submit(_run_case, cases[i][3], cases[i][0], kwargs): i for i in todo}
    try:
        while pending:
            done, _ = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                i = pending.pop(fut)
                finish(i, fut.result())
    except KeyboardInterrupt:
        for fut in pending:
            fut.cancel()
        for fut in [f for f in pending if f.done() and not f.cancelled()]:
            if fut.exception() is None:  # finished meanwhile: keep it
                finish(pending[fut], fut.result())
        if own:
            _terminate(ex)
        raise
    except BaseException as exc:
        # a case raised something unexpected: keep every case that still finishes, then raise
        if own and isinstance(exc, BrokenProcessPool) and hasattr(exc, "add_note"):
            exc.add_note("trackwheel.sweep: a worker process died. Run from a script, the "
                         "sweep must sit under `if __name__ == \"__main__\":` (the workers "
                         "import the main module); max_workers=1 runs without workers.")
        for fut in pending:
            fut.cancel()
        running = [f for f in pending if not f.cancelled()]
        wait(running)
        for fut in running:
            if fut.exception() is None:
                finish(pending[fut], fut.result())
        raise


def summarise_seeds(df: pd.DataFrame, columns=SEED_COLUMNS, *, by="speed",
                    q=(5.0, 50.0, 95.0)) -> pd.DataFrame:
    """Percentiles over the realisations of a :func:`sweep` with ``seeds``: for each speed (or
    each value of ``by``, a column or a list of columns), the ``q`` percentiles [%] of
    ``columns`` (default :data:`SEED_COLUMNS`: max and min contact force [N], dynamic
    factor [-], contact-loss duration [s], force RMS [N]) over the rows, failed rows left out.

    Returns a DataFrame indexed by ``by`` with columns (column, "p<q>") and ``n_seeds`` (the
    rows that ran). Raises ValueError if a group mixes several support stiffnesses (pass
    ``by=["speed", "support_stiffness"]``) or the table has no ``seed`` values.
    """
    import pandas as pd

    if not isinstance(df, pd.DataFrame):
        raise TypeError(f"df must be a pandas DataFrame, got {type(df).__name__}")
    keys = [by] if isinstance(by, str) else list(by)
    if "seed" not in df.columns or df["seed"].isna().all():
        raise ValueError("df has no seed values: summarise the table of sweep(..., seeds=[...])")
    if "support_stiffness" in df.columns and "support_stiffness" not in keys:
        mixed = df.groupby(keys)["support_stiffness"].nunique()
        if (mixed > 1).any():
            raise ValueError(f"the rows of one {'/'.join(keys)} hold several support "
                             "stiffnesses; pass by=[..., 'support_stiffness'] or filter the table")
    # a table read back from CSV has NaN, not "", where no error was written
    ok = df[df["error"].isna() | (df["error"] == "")] if "error" in df.columns else df
    out = seed_percentiles(ok, columns, by=by, q=q)
    out[("n_seeds", "")] = ok.groupby(by if isinstance(by, str) else keys).size()
    return out
