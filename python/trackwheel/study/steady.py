"""Steady state of a run over a track periodic in its sleeper bay.

Docs: Model § The travelling window.

Under a smooth periodic track the response of a wheel at constant speed v settles, once the
start-up transient has died, into a function of the position in the bay: periodic in X with
period d_s, in time with the sleeper-passing frequency f_s = v / d_s. :func:`steady_state`
finds where that holds (consecutive bays differ by less than a tolerance) and reports the
steady amplitude and the sleeper-passing harmonics k f_s.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..base import validate as v
from ..run.results import OUTPUT_FIELDS, Result

#: Samples per bay of the resampled signal [-]: the harmonics up to 64 f_s are resolved.
SAMPLES_PER_BAY = 128


@dataclass(frozen=True)
class SteadyState:
    """The steady, bay-periodic part of a run (see :func:`steady_state`)."""

    field: str  #: the output field measured (e.g. "normal_force")
    t_from: float  #: time the steady part starts [s] (start of the first steady bay)
    x_from: float  #: wheel position there [m] (a support position + k d_s)
    n_bays: int  #: whole bays in the steady part [-]
    bay_difference: float  #: largest difference of a steady bay from the last / scale [-]
    mean: float  #: mean of the field over the steady part [field's unit]
    amplitude: float  #: half the peak-to-peak of the mean bay [field's unit]
    sleeper_frequency: float  #: f_s = v / d_s [Hz]
    #: (k f_s [Hz], amplitude of harmonic k [field's unit]), k = 1 .. n_harmonics
    harmonics: tuple[np.ndarray, np.ndarray]
    bay_profile: np.ndarray  #: the mean bay, SAMPLES_PER_BAY values from x_from mod d_s


def _bays(result: Result, field: str) -> tuple[np.ndarray, float, float]:
    """(f resampled to SAMPLES_PER_BAY per bay, one bay per row; X of the first row [m]; d_s)."""
    d = result.scene.supports.spacing
    x = np.asarray(result.x_wheel, dtype=float)
    f = np.asarray(getattr(result, field), dtype=float)
    if x.ndim != 1 or f.ndim != 1:
        raise ValueError(f"result has {result.n_wheels} wheels: pass result.wheel(i)")
    x0 = (np.floor(x[0] / d) + 1.0) * d  # whole bays from the first support passed
    n = int(np.floor((x[-1] - x0) / d + 1e-9))
    if n < 3:
        raise ValueError(f"the run covers {n} whole bays of {d} m; steady_state needs at "
                         "least 3 (run longer)")
    xs = x0 + d * np.arange(n * SAMPLES_PER_BAY) / SAMPLES_PER_BAY
    return np.interp(xs, x, f).reshape(n, SAMPLES_PER_BAY), x0, d


def steady_state(result: Result, *, field: str = "normal_force", tol: float = 1e-3,
                 n_harmonics: int = 4) -> SteadyState:
    """The steady state of ``result`` in the sleeper bay.

    The field (one wheel: ``result.wheel(i)`` for a vehicle) is resampled at SAMPLES_PER_BAY
    points per bay d_s (linear interpolation in X between kept samples: keep several samples
    per bay). Bay j differs from the run's last bay by D_j = max |f_j - f_last| / scale,
    scale = max(|mean f|, peak-to-peak f) over the last bay (against the last bay rather than
    the previous one, so that a slow drift is not taken for a steady state). The steady part
    starts at the first bay from which every D_j < ``tol``; it must hold at least 3 bays. Over it: the mean bay (the average of its bays), its
    half peak-to-peak (the steady amplitude) and the amplitudes of its Fourier harmonics
    k = 1 .. ``n_harmonics`` at k f_s, f_s = v / d_s the sleeper-passing frequency.

    Raises ValueError if the run never settles within ``tol`` (run longer, or the track is
    not periodic: an irregularity) or covers fewer than 3 bays.
    """
    if not isinstance(result, Result):
        raise TypeError(f"result must be a trackwheel.Result, got {type(result).__name__}")
    fields = {name for name, *_ in OUTPUT_FIELDS}
    v.choice("field", field, fields)
    tol = v.number("tol", tol, low=0.0, low_open=True)
    n_harmonics = v.integer("n_harmonics", n_harmonics, low=1, high=SAMPLES_PER_BAY // 2)
    f, x0, d = _bays(result, field)
    last = f[-1]
    scale = max(abs(float(last.mean())), float(np.ptp(last)), np.finfo(float).tiny)
    diff = np.abs(f - last).max(axis=1) / scale  # D_j
    above = np.nonzero(diff >= tol)[0]
    first = 0 if above.size == 0 else int(above[-1]) + 1  # bay index from which all D < tol
    if first > f.shape[0] - 3:
        raise ValueError(f"{field} does not settle to a bay-periodic state within tol = {tol:g} "
                         f"(bay {f.shape[0] - 3} of {f.shape[0]} differs from the last by "
                         f"{diff[-3]:.3g} of the scale): run "
                         "longer, or check that the track is smooth and periodic")
    steady = f[first:]
    mean_bay = steady.mean(axis=0)
    coef = np.fft.rfft(mean_bay) / SAMPLES_PER_BAY
    k = np.arange(1, n_harmonics + 1)
    speed = float(result.settings.speed)
    x_from = x0 + first * d
    t_from = float(np.interp(x_from, result.x_wheel, result.t))
    return SteadyState(
        field=field, t_from=t_from, x_from=x_from, n_bays=steady.shape[0],
        bay_difference=float(diff[first:].max()),
        mean=float(steady.mean()), amplitude=0.5 * float(np.ptp(mean_bay)),
        sleeper_frequency=speed / d, harmonics=(k * speed / d, 2.0 * np.abs(coef[k])),
        bay_profile=mean_bay)


def from_time(result: Result, t_from: float) -> Result:
    """``result`` restricted to its samples at t >= ``t_from`` [s] (e.g.
    ``steady_state(result).t_from``)."""
    t_from = v.number("t_from", t_from, unit="s")
    keep = np.asarray(result.t) >= t_from
    if keep.sum() < 1:
        raise ValueError(f"t_from = {t_from} s is after the run's end {result.t[-1]:.6g} s")
    arrays = {name: getattr(result, name)[keep] for name, *_ in OUTPUT_FIELDS
              if getattr(result, name) is not None}
    for name in ("body_z", "body_phi"):
        if getattr(result, name) is not None:
            arrays[name] = getattr(result, name)[keep]
    return dataclasses.replace(result, **arrays)
