"""Steady state of a run over a track periodic in its sleeper bay.

Docs: Model § The travelling window.

Under a smooth periodic track the response of a wheel at constant speed v settles, once the
start-up transient has died, into a function of the position in the bay: periodic in X with
period d_s, in time with the sleeper-passing frequency f_s = v / d_s. :func:`steady_state`
finds where that holds (the bays' bay-periodic content, their sleeper-passing harmonics up to
the scene's highest frequency of interest, differs from the last bay's by less than a
tolerance) and reports the steady amplitude and the sleeper-passing harmonics k f_s.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..base import validate as v
from ..run.defaults import highest_frequency
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
    #: largest difference of a steady bay from the reference (the mean of the last bays) /
    #: scale, both low-passed to the harmonics up to ``f_cut`` [-]
    bay_difference: float
    #: the largest change from one reference bay to the next / scale, low-passed alike: the
    #: run's stationary bay-to-bay scatter, its part that is not bay-periodic (e.g. a shear
    #: rail's node-crossing ripple) [-]
    scatter: float
    f_cut: float  #: the low-pass of the comparison [Hz]: harmonics k f_s <= f_cut kept
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
                 n_harmonics: int = 4, f_cut: float | None = None) -> SteadyState:
    """The steady state of ``result`` in the sleeper bay.

    The field (one wheel: ``result.wheel(i)`` for a vehicle) is resampled at SAMPLES_PER_BAY
    points per bay d_s (linear interpolation in X between kept samples: keep several samples
    per bay). What is compared is each bay's content below ``f_cut`` [Hz]: its Fourier
    harmonics k f_s (f_s = v / d_s, the sleeper-passing frequency) with k f_s <= ``f_cut``,
    by default the scene's highest frequency of interest
    (:func:`trackwheel.run.defaults.highest_frequency`: 1.42 kHz on the ballasted track,
    1.07 kHz with its Timoshenko rail), above which a run with the derived step resolves
    nothing physical (20 steps per period there; the sampled shape of a shear rail's sharp
    node-crossing kicks differs in every bay there, as the steps fall differently in each).

    The reference is the mean of the last quarter of the bays (at least 3): the best estimate
    of the steady bay, a slow drift still showing against it. Bay j differs from it by
    D_j = max |lp(f_j - ref)| / scale, scale = max(|mean f|, peak-to-peak f) over the
    reference. What changes from each reference bay to the next (the same measure of f_j -
    f_(j-1), its largest over the reference: ``scatter``) is the run's stationary scatter: on a
    shear rail without a consistent moving contact, a ripple near the pinned-pinned frequency
    whose phase differs in every bay (5e-3 of the load at 200-300 km/h and 8 elements per
    bay), which no bay sheds, so no tolerance below it could be met; a drift adds only its
    change per bay, so it is still caught. A bay is steady when D_j < max(``tol``, 2 x scatter):
    within ``tol`` = 1e-3 of the force (the static load, for the contact force; a tenth of
    the 1 % the derived mesh and step hold the headline outputs to, so that what is left of
    the transient is below the discretisation's own error), or, where the run scatters more
    than that, within twice its own scatter (a transient smaller than the scatter cannot be
    told from it, and changes the mean bay by less than scatter / sqrt(n_bays)). The steady
    part starts at the first bay from which every bay is steady; it must hold at least 3
    bays.

    Over the steady part: the mean bay (the average of its bays, unfiltered: the average
    removes what is not bay-periodic), its half peak-to-peak (the steady amplitude) and the
    amplitudes of its Fourier harmonics k = 1 .. ``n_harmonics`` at k f_s.

    Raises ValueError if the run never settles (run longer, or the track is not periodic: an
    irregularity) or covers fewer than 3 bays.
    """
    if not isinstance(result, Result):
        raise TypeError(f"result must be a trackwheel.Result, got {type(result).__name__}")
    fields = {name for name, *_ in OUTPUT_FIELDS}
    v.choice("field", field, fields)
    tol = v.number("tol", tol, low=0.0, low_open=True)
    n_harmonics = v.integer("n_harmonics", n_harmonics, low=1, high=SAMPLES_PER_BAY // 2)
    f, x0, d = _bays(result, field)
    speed = float(result.settings.speed)
    f_s = speed / d
    f_cut = highest_frequency(result.scene) if f_cut is None else v.number(
        "f_cut", f_cut, low=0.0, low_open=True, unit="Hz")
    k_cut = min(int(f_cut / f_s + 1e-9), SAMPLES_PER_BAY // 2) if f_s > 0.0 else 0
    n_ref = max(3, f.shape[0] // 4)
    ref = f[-n_ref:].mean(axis=0)
    scale = max(abs(float(ref.mean())), float(np.ptp(ref)), np.finfo(float).tiny)
    def lowpass_max(g):  # max over the bay of g's content below f_cut, over the scale
        spec = np.fft.rfft(g, axis=1)
        spec[:, k_cut + 1:] = 0.0
        return np.abs(np.fft.irfft(spec, SAMPLES_PER_BAY, axis=1)).max(axis=1) / scale

    diff = lowpass_max(f - ref)  # D_j
    # what changes from one reference bay to the next (a drift adds only its step per bay)
    scatter = float(lowpass_max(np.diff(f[-n_ref - 1:], axis=0)).max())
    limit = max(tol, 2.0 * scatter)
    above = np.nonzero(diff >= limit)[0]
    first = 0 if above.size == 0 else int(above[-1]) + 1  # bay index from which all D < limit
    if first > f.shape[0] - 3:
        raise ValueError(f"{field} does not settle to a bay-periodic state within tol = {tol:g} "
                         f"(bay {f.shape[0] - 3} of {f.shape[0]} differs from the last bays' "
                         f"mean by {diff[-3]:.3g} of the scale below {f_cut:.4g} Hz): run "
                         "longer, or check that the track is smooth and periodic")
    steady = f[first:]
    mean_bay = steady.mean(axis=0)
    coef = np.fft.rfft(mean_bay) / SAMPLES_PER_BAY
    k = np.arange(1, n_harmonics + 1)
    x_from = x0 + first * d
    t_from = float(np.interp(x_from, result.x_wheel, result.t))
    return SteadyState(
        field=field, t_from=t_from, x_from=x_from, n_bays=steady.shape[0],
        bay_difference=float(diff[first:].max()), scatter=scatter, f_cut=float(f_cut),
        mean=float(steady.mean()), amplitude=0.5 * float(np.ptp(mean_bay)),
        sleeper_frequency=f_s, harmonics=(k * f_s, 2.0 * np.abs(coef[k])),
        bay_profile=mean_bay)


def from_time(result: Result, t_from: float) -> Result:
    """``result`` restricted to its samples at t >= ``t_from`` [s] (e.g.
    ``steady_state(result).t_from``)."""
    t_from = v.number("t_from", t_from, unit="s")
    keep = np.asarray(result.t) >= t_from
    if keep.sum() < 1:
        raise ValueError(f"t_from = {t_from} s is after the run's end {result.t[-1]:.6g} s")
    return samples(result, keep)


def samples(result: Result, keep: np.ndarray) -> Result:
    """``result`` restricted to the samples where the boolean mask ``keep`` (n_samples,) is
    True (every recorded array, the bodies' too)."""
    arrays = {name: getattr(result, name)[keep] for name, *_ in OUTPUT_FIELDS
              if getattr(result, name) is not None}
    for name in ("body_z", "body_phi"):
        if getattr(result, name) is not None:
            arrays[name] = getattr(result, name)[keep]
    return dataclasses.replace(result, **arrays)
