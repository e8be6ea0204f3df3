"""Argument checks shared by the public API: clear messages naming the parameter and range."""

from __future__ import annotations

import math
import numbers

import numpy as np

from .limits import MAX_ELEMENTS, RANGES


def number(name: str, value, *, low=None, high=None, low_open=False, high_open=False,
           unit: str = "") -> float:
    """Return ``value`` as a float after checking type, finiteness and range.

    Raises ``TypeError`` for non-numbers and ``ValueError`` naming ``name``, the value and the
    allowed range otherwise.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number{_bracketed(unit)}, "
                        f"got {type(value).__name__}")
    v = float(value)
    lo = "(" if low_open else "["
    hi = ")" if high_open else "]"
    rng = f"{lo}{'-inf' if low is None else low}, {'inf' if high is None else high}{hi}"
    if math.isnan(v) or math.isinf(v):
        raise ValueError(f"{name} = {value} is not finite; allowed range {rng}{_unit(unit)}")
    bad = (low is not None and (v < low or (low_open and v == low))) or (
        high is not None and (v > high or (high_open and v == high)))
    if bad:
        raise ValueError(f"{name} = {value!r} is outside the allowed range {rng}{_unit(unit)}")
    return v


def field(name: str, value, *, unit: str | None = None, hint: str = "",
          key: str | None = None) -> float:
    """``value`` checked against the plausible range of the parameter ``name``
    (:data:`trackwheel.base.limits.RANGES`, under ``key`` if given, e.g. a layered support's
    pad; ``unit`` overrides the range's, e.g. for a contact stiffness whose unit depends on the
    law; ``hint`` ends the message of a value above the range, e.g. the likely unit slip)."""
    r = RANGES[name if key is None else key]
    if unit is not None:
        r = r._replace(unit=unit)
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number{_bracketed(r.unit)}, "
                        f"got {type(value).__name__}")
    x = float(value)
    if not math.isfinite(x):
        raise ValueError(f"{name} = {value} is not finite; allowed range {r.text()}")
    if x < r.low or x > r.high or (r.low_open and x == r.low) or (r.high_open and x == r.high):
        shown = repr(x) if len(repr(x)) <= 12 else f"{x:.12g}"
        tail = f" ({hint})" if hint and x > r.high else ""
        raise ValueError(f"{name} = {shown} is outside the allowed range {r.text()}{tail}")
    return x


def positive(name: str, value, unit: str = "") -> float:
    return number(name, value, low=0.0, low_open=True, unit=unit)


def integer(name: str, value, *, low=None, high=None) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, got {type(value).__name__}")
    v = int(value)
    if (low is not None and v < low) or (high is not None and v > high):
        raise ValueError(f"{name} = {v} is outside the allowed range [{low}, {high}]")
    return v


def choice(name: str, value, allowed) -> str:
    try:
        ok = value in allowed
    except TypeError:  # unhashable, e.g. a list
        ok = False
    if not ok:
        raise ValueError(f"{name} = {value!r} is not one of {sorted(allowed)}")
    return value


def boolean(name: str, value) -> bool:
    """``value`` if it is a bool (or numpy bool); TypeError otherwise."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {type(value).__name__}")
    return bool(value)


def positions(name: str, values, low: float, high: float, unit: str = "m") -> np.ndarray:
    """1-d float array of finite values in [low, high]; a scalar becomes a length-1 array."""
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError) as exc:  # e.g. ragged nested sequences
        raise TypeError(f"{name} must be a number or a sequence of numbers [{unit}]") from exc
    if raw.dtype.kind not in "iuf" and not (raw.dtype.kind == "O" and raw.size == 0):
        raise TypeError(f"{name} must be a number or a sequence of real numbers [{unit}], "
                        f"got {type(values).__name__} of {raw.dtype}")
    arr = np.atleast_1d(raw.astype(float))
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name} must be a non-empty 1-d sequence [{unit}]")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or inf; allowed range [{low}, {high}] {unit}")
    if np.any(arr < low) or np.any(arr > high):
        bad = arr[(arr < low) | (arr > high)][0]
        raise ValueError(f"{name} = {bad} is outside the allowed range [{low}, {high}] {unit}")
    return arr


def n_elements(value, name: str = "n_elements", *, low: int = 1) -> int:
    """``value`` as a number of rail elements in [``low``, MAX_ELEMENTS] [-]: the one check of
    an element count (a Rail's, a call's ``n_elements``, a derived mesh's)."""
    return integer(name, value, low=low, high=MAX_ELEMENTS)


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def _bracketed(unit: str) -> str:
    return f" [{unit}]" if unit and unit != "-" else ""
