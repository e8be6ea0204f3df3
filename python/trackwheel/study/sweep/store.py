"""The sweep store: one JSON record per finished case, so that a sweep resumes (the format is
described in :mod:`trackwheel.study.sweep`).

Records of format 5 hold their row by the sweep table's column names (with units); records of
format 4, written before the support-force columns, are read with NaN there, and those of
format 3, written before the columns carried their units, also have their rows renamed, so an
older store keeps resuming; any other format is recomputed.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import json
import math
import os
import tempfile
import warnings
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..._version import __version__
from ...scene import Scene
from ..columns import COLUMNS, FLOAT_COLUMNS, SWEEP_COLUMNS, label, old_name
from .cases import frame

if TYPE_CHECKING:  # pandas is imported when a table is built: keeps `import trackwheel` light
    import pandas as pd

FORMAT = "trackwheel.sweep.case"
#: 2: the seed axis and the contact-force columns; 3: the vehicle's ``wheel`` column and
#: per-wheel ``wheels`` outputs; 4: the columns named with their units; 5: the support-force
#: columns. Older records than 3 are recomputed.
FORMAT_VERSION = 5
#: the columns format 5 added: NaN in the rows of older records
ADDED_IN_5 = tuple(label(n) for n in ("max_ballast_force", "max_ballast_force_x",
                                      "max_rail_seat_force"))
#: format 3's column names -> format 4's (the same rows otherwise)
RENAMED = {old_name(c): c.label for c in SWEEP_COLUMNS}


def jsonable(x):
    """Plain JSON values: numpy scalars to Python, NaN/inf to None, tuples to lists."""
    if isinstance(x, dict):
        return {str(k): jsonable(val) for k, val in x.items()}
    if isinstance(x, (list, tuple)):
        return [jsonable(val) for val in x]
    if isinstance(x, (bool, np.bool_)):
        return bool(x)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return float(x) if math.isfinite(x) else None
    if x is None or isinstance(x, str):
        return x
    raise TypeError(f"cannot store a value of type {type(x).__name__} ({x!r}) in a sweep record")


def canonical(obj) -> bytes:
    """The canonical JSON of ``obj`` (sorted keys, no spaces, floats by repr): what is hashed."""
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), allow_nan=False).encode()


def inputs(scene: Scene, speed: float, stiffness: float, kwargs: dict,
           seed: int | None = None) -> dict:
    """A case's inputs as stored and hashed: its scene, speed [m/s], support stiffness [N/m],
    seed, the simulate keywords and the version."""
    return jsonable({"scene": dataclasses.asdict(scene), "speed": speed,
                     "support_stiffness": stiffness, "seed": seed, "simulate": kwargs,
                     "version": __version__})


def inputs_hash(case_inputs: dict) -> str:
    """The SHA-256 of the canonical JSON of a case's inputs (its record's name)."""
    return hashlib.sha256(canonical(case_inputs)).hexdigest()


def open_store(store) -> Path | None:
    """The store directory [path] (created if missing), or None without one."""
    if store is None:
        return None
    store_dir = Path(os.fspath(store))
    if store_dir.exists() and not store_dir.is_dir():
        raise ValueError(f"store = {os.fspath(store)!r} exists and is not a directory")
    store_dir.mkdir(parents=True, exist_ok=True)
    return store_dir


def record_path(store: Path, h: str) -> Path:
    return store / f"case-{h[:24]}.json"


def write_record(store: Path, h: str, case_inputs: dict, row: dict) -> None:
    """Write a case's record atomically (a temporary file, flushed, renamed over the name)."""
    payload = {"format": FORMAT, "format_version": FORMAT_VERSION, "inputs_hash": h,
               "inputs": case_inputs, "row": jsonable(row)}
    payload["checksum"] = hashlib.sha256(canonical(payload)).hexdigest()
    data = json.dumps(payload, sort_keys=True, indent=1, allow_nan=False).encode()
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".json", dir=store)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, record_path(store, h))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def read_record(path: Path) -> tuple[dict | None, str]:
    """(payload, "") for a sound record (a format-3 row renamed to today's columns), (None,
    reason) otherwise."""
    try:
        payload = json.loads(path.read_bytes())
    except (OSError, ValueError) as exc:  # unreadable, truncated, not JSON, bad encoding
        return None, f"unreadable ({type(exc).__name__}: {exc})"
    if not isinstance(payload, dict) or payload.get("format") != FORMAT:
        return None, "not a trackwheel sweep record"
    version = payload.get("format_version")
    if version not in (3, 4, FORMAT_VERSION):
        return None, f"format version {version!r} != {FORMAT_VERSION}"
    checksum = payload.pop("checksum", None)
    if checksum != hashlib.sha256(canonical(payload)).hexdigest():
        return None, "checksum mismatch"
    case_inputs, row = payload.get("inputs"), payload.get("row")
    if not isinstance(case_inputs, dict) or not isinstance(row, dict):
        return None, "missing inputs or row"
    if payload.get("inputs_hash") != inputs_hash(case_inputs):
        return None, "inputs hash mismatch"
    if version == 3:
        payload["row"] = row = _renamed(row)
    if version in (3, 4):
        payload["row"] = row = _with_added(row)
    if set(row) - {"wheels"} != set(COLUMNS) - {label("worst")}:
        return None, "wrong columns"
    return payload, ""


def _with_added(row: dict) -> dict:
    """A row of format 3 or 4 with format 5's new columns (None: NaN, not computed then)."""
    out = {**row, **{c: row.get(c) for c in ADDED_IN_5}}
    if out.get("wheels"):
        out["wheels"] = [{**w, **{c: w.get(c) for c in ADDED_IN_5}} for w in out["wheels"]]
    return out


def _renamed(row: dict) -> dict:
    out = {RENAMED.get(k, k): val for k, val in row.items()}
    if out.get("wheels"):
        out["wheels"] = [{RENAMED.get(k, k): val for k, val in w.items()} for w in out["wheels"]]
    return out


def decode_row(row: dict) -> dict:
    """A stored row as the table holds it: None back to NaN in the float columns."""
    out = dict(row)
    for c in FLOAT_COLUMNS:
        if out[c] is None:
            out[c] = math.nan
    if out.get("wheels"):
        out["wheels"] = [{c: (math.nan if c in FLOAT_COLUMNS and val is None else val)
                          for c, val in w.items()} for w in out["wheels"]]
    return out


def stored_rows(store_dir: Path, cases, retry_errors: bool) -> list[dict | None]:
    """The stored row of each case (None: to compute): records of other inputs, or unsound
    ones, are reported (RuntimeWarning) and recomputed; failed cases too with
    ``retry_errors``. ``cases``: (.., inputs, hash) tuples."""
    rows: list[dict | None] = [None] * len(cases)
    for i, (*_, case_inputs, h) in enumerate(cases):
        path = record_path(store_dir, h)
        if not path.exists():
            continue
        payload, reason = read_record(path)
        if payload is not None and payload["inputs"] != case_inputs:
            payload, reason = None, "a record of other inputs"
        if payload is None:
            warnings.warn(f"sweep store {store_dir}: record {path.name} is {reason}; "
                          "recomputing it", RuntimeWarning, stacklevel=3)
            continue
        row = decode_row(payload["row"])
        if row[label("error")] and retry_errors:
            continue
        rows[i] = row
    return rows


def load_sweep(path) -> pd.DataFrame:
    """Load every sound record of a sweep store (``path``: the ``store=`` directory) into a
    DataFrame with the columns of :func:`sweep` (see :mod:`trackwheel.study.sweep` for the
    format), sorted by speed, support stiffness, seed and case hash. Records that fail their
    checks are left out with a ``RuntimeWarning`` naming them. A store may hold several sweeps
    (other settings, other versions): filter on the settings and ``version`` columns. Records
    written before the columns carried their units (format 3) are read with today's names."""
    store = Path(os.fspath(path))
    if not store.is_dir():
        raise ValueError(f"path = {os.fspath(path)!r} is not a sweep store directory")
    rows = []
    for p in sorted(store.glob("case-*.json")):
        payload, reason = read_record(p)
        if payload is None:
            warnings.warn(f"sweep store {store}: record {p.name} is {reason}; left out",
                          RuntimeWarning, stacklevel=2)
            continue
        rows.append(decode_row(payload["row"]))
    df = frame(rows)
    return df.sort_values([label(n) for n in ("speed", "support_stiffness", "seed", "case",
                                              "wheel")], ignore_index=True)
