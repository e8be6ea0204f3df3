"""Contact-force statistics a track engineer reads off a run, on plain arrays.

Inputs are the recorded time t [s] (uniform, increasing), the wheel position X [m] and the
contact force N [N] (N = 0 while the wheel is off the rail), and the static wheel load P0 [N].
Nothing here needs the kernel: :func:`force_statistics` works on any such arrays.

P1/P2 windows (after a discrete defect at X_d, reached at t_d by interpolating X(t)):
P1, the high-frequency peak of the wheel/rail contact resonance, is the maximum of N in
[t_d, t_d + T_1/2]; P2, the lower-frequency peak of the wheel and rail moving together on the
track, is the maximum in (t_d + T_1/2, t_d + T_2/2 + T_1/2]. T_1, T_2 [s] are the periods of
those two resonances; pass them from the scene (e.g. T_1 = 2 pi sqrt(M_red / k_contact)). The
defaults, T_1 = 1 ms (1000 Hz) and T_2 = 20 ms (50 Hz), are round values inside the usual
ranges of the two resonances (P1: several hundred Hz to above 1 kHz; P2: 30-100 Hz).

One-third-octave bands: IEC 61260-1 base 10, centres f_m = 1000 x 10^(k/10) Hz, edges
f_m x 10^(-+1/20). Band mean squares are sums of the one-sided FFT power of N - mean(N) over
the bins in [f_lo, f_hi) (Parseval); only bands with f_lo >= 1 / duration and f_hi <= Nyquist
are reported.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..base import validate as v
from ..base.bands import third_octave_bands

#: Default contact-resonance period T_1 [s] for the P1 window.
P1_PERIOD = 1e-3
#: Default wheel-on-track resonance period T_2 [s] for the P2 window.
P2_PERIOD = 20e-3


def _series(t, n):
    t = np.asarray(t, dtype=float)
    n = np.asarray(n, dtype=float)
    if t.ndim != 1 or n.shape != t.shape or t.size < 2:
        raise ValueError(f"t and N must be 1-d arrays of the same length >= 2, got shapes "
                         f"{t.shape} and {n.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(n))):
        raise ValueError("t and N must be finite")
    dt = np.diff(t)
    if np.any(dt <= 0.0) or np.ptp(dt) > 1e-6 * dt.mean():
        raise ValueError("t must be uniformly spaced and increasing [s]")
    return t, n, float(dt.mean())


def band_rms(t, n) -> tuple[np.ndarray, np.ndarray]:
    """RMS of N - mean(N) [N] in the one-third-octave bands that fit the record:
    (centres [Hz], rms [N]). A sine of amplitude A inside a band gives A / sqrt(2) there."""
    t, n, dt = _series(t, n)
    m = n.size
    spec = np.fft.rfft(n - n.mean())
    power = 2.0 * np.abs(spec) ** 2 / m**2  # one-sided mean square per bin
    power[0] = 0.0
    if m % 2 == 0:
        power[-1] *= 0.5  # the Nyquist bin is not doubled
    f = np.fft.rfftfreq(m, dt)
    duration = m * dt
    centres, edges = third_octave_bands(1.0 / duration, 0.5 / dt)
    rms = np.array([math.sqrt(power[(f >= lo) & (f < hi)].sum()) for lo, hi in edges])
    return centres, rms


def force_spectrum(t, n) -> tuple[np.ndarray, np.ndarray]:
    """Single-sided amplitude spectrum of N - mean(N): (f [Hz], |N|(f) [N]); a sine of
    amplitude A on a bin gives A (rectangular window, no padding)."""
    t, n, dt = _series(t, n)
    m = n.size
    amp = 2.0 * np.abs(np.fft.rfft(n - n.mean())) / m
    amp[0] = 0.0
    if m % 2 == 0:
        amp[-1] *= 0.5
    return np.fft.rfftfreq(m, dt), amp


def contact_loss(t, n, threshold: float = 0.0) -> tuple[float, np.ndarray]:
    """Total time without contact [s] and the intervals (start, end) [s], shape (k, 2).

    A sample is off contact when N <= ``threshold`` [N]. Each run of such samples counts from
    the midpoint before its first sample to the midpoint after its last (a run at the record's
    end is cut there), so the duration of a uniformly sampled loss is right to within one
    time step.
    """
    t, n, dt = _series(t, n)
    thr = v.number("threshold", threshold, low=0.0, unit="N")
    off = np.concatenate(([False], n <= thr, [False])).astype(np.int8)
    starts = np.flatnonzero(np.diff(off) == 1)  # first off sample of each run
    ends = np.flatnonzero(np.diff(off) == -1) - 1  # last off sample
    a = np.maximum(t[starts] - 0.5 * dt, t[0])
    b = np.minimum(t[ends] + 0.5 * dt, t[-1])
    intervals = np.column_stack((a, b))
    return float(np.sum(b - a)), intervals


def _arrival(t, x, x_defect: float) -> float:
    """Time [s] at which X(t) (increasing) reaches x_defect, by linear interpolation."""
    x = np.asarray(x, dtype=float)
    if x.shape != t.shape or np.any(np.diff(x) < 0.0):
        raise ValueError("x must be a non-decreasing array of the same length as t [m]")
    if not x[0] <= x_defect <= x[-1]:
        raise ValueError(f"defect_at = {x_defect} m is not passed in the run; allowed range "
                         f"[{x[0]}, {x[-1]}] m")
    return float(np.interp(x_defect, x, t))


def peak_forces(t, x, n, defect_at: float, *, p1_period: float = P1_PERIOD,
                p2_period: float = P2_PERIOD) -> tuple[float, float, float, float, float]:
    """(t_d, P1, t_P1, P2, t_P2) [s, N, s, N, s] after the defect at X = ``defect_at`` [m]:
    maxima of N in the P1 and P2 windows (module docstring). NaN where a window holds no
    sample (the record ends too early)."""
    t, n, _ = _series(t, n)
    t1 = v.positive("p1_period", p1_period, "s")
    t2 = v.number("p2_period", p2_period, low=t1, low_open=True, unit="s")
    td = _arrival(t, x, v.number("defect_at", defect_at, unit="m"))
    out = [td]
    for lo, hi, closed in ((td, td + 0.5 * t1, True), (td + 0.5 * t1, td + 0.5 * (t1 + t2),
                                                        False)):
        sel = ((t >= lo) if closed else (t > lo)) & (t <= hi)
        if not np.any(sel):
            out += [math.nan, math.nan]
            continue
        i = np.flatnonzero(sel)[np.argmax(n[sel])]
        out += [float(n[i]), float(t[i])]
    return tuple(out)


@dataclass(frozen=True)
class ForceStatistics:
    """Contact-force statistics of one run (see :func:`force_statistics`)."""

    max_force: float  #: max N [N]
    min_force: float  #: min N [N]
    dynamic_factor: float  #: max N / P0 [-]
    loss_duration: float  #: total time without contact [s]
    loss_intervals: np.ndarray  #: (k, 2) start/end of each loss [s]
    band_centres: np.ndarray  #: one-third-octave band centres [Hz]
    band_rms: np.ndarray  #: RMS of N - mean(N) per band [N]
    frequency: np.ndarray  #: spectrum frequencies [Hz]
    amplitude: np.ndarray  #: amplitude spectrum of N [N]
    defect_time: float = math.nan  #: t_d, time the wheel reaches the defect [s]
    p1: float = math.nan  #: P1 [N]
    p1_time: float = math.nan  #: [s]
    p2: float = math.nan  #: P2 [N]
    p2_time: float = math.nan  #: [s]

    def __repr__(self) -> str:
        lines = [
            (f"ForceStatistics: N in [{self.min_force / 1e3:.4g}, {self.max_force / 1e3:.4g}] kN,"
            f" dynamic factor {self.dynamic_factor:.4g}"),
            (f"  contact loss {self.loss_duration * 1e3:.4g} ms in"
            f" {len(self.loss_intervals)} interval(s)"),
        ]
        if not math.isnan(self.p1):
            lines.append(f"  P1 {self.p1 / 1e3:.4g} kN at {self.p1_time:.5g} s, "
                         f"P2 {self.p2 / 1e3:.4g} kN at {self.p2_time:.5g} s")
        bands = (f"{self.band_centres.size} one-third-octave bands "
                 f"({self.band_centres[0]:.3g}-{self.band_centres[-1]:.3g} Hz), "
                 if self.band_centres.size else "")
        lines.append(f"  {bands}spectrum of {self.frequency.size} bins")
        return "\n".join(lines)


def force_statistics(t, x, n, static_load: float, *, defect_at: float | None = None,
                     p1_period: float = P1_PERIOD, p2_period: float = P2_PERIOD,
                     loss_threshold: float = 0.0) -> ForceStatistics:
    """All statistics of the contact force N(t) [N] against the static load P0 =
    ``static_load`` [N]: extremes, dynamic factor max N / P0, contact loss, one-third-octave
    band RMS, amplitude spectrum, and with ``defect_at`` [m] the P1/P2 peaks."""
    t, n, _ = _series(t, n)
    p0 = v.positive("static_load", static_load, "N")
    loss, intervals = contact_loss(t, n, loss_threshold)
    centres, rms = band_rms(t, n)
    f, amp = force_spectrum(t, n)
    peaks = {}
    if defect_at is not None:
        td, p1, tp1, p2, tp2 = peak_forces(t, x, n, defect_at, p1_period=p1_period,
                                           p2_period=p2_period)
        peaks = {"defect_time": td, "p1": p1, "p1_time": tp1, "p2": p2, "p2_time": tp2}
    return ForceStatistics(
        max_force=float(n.max()), min_force=float(n.min()), dynamic_factor=float(n.max()) / p0,
        loss_duration=loss, loss_intervals=intervals, band_centres=centres, band_rms=rms,
        frequency=f, amplitude=amp, **peaks)


def result_statistics(result, *, defect_at: float | None = None, p1_period: float = P1_PERIOD,
                      p2_period: float = P2_PERIOD, loss_threshold: float = 0.0
                      ) -> ForceStatistics:
    """:func:`force_statistics` of a :class:`trackwheel.Result`: t, X_A = ``x_wheel`` and
    N = ``normal_force`` of the run against its scene's static load P0 = F + M g [N]."""
    for name in ("t", "x_wheel", "normal_force", "scene"):
        if not hasattr(result, name):
            raise TypeError(f"result must be a trackwheel.Result, got {type(result).__name__}")
    return force_statistics(result.t, result.x_wheel, result.normal_force,
                            result.scene.static_load, defect_at=defect_at, p1_period=p1_period,
                            p2_period=p2_period, loss_threshold=loss_threshold)


def defect_position(scene) -> float | None:
    """X [m] of the discrete rail defect whose P1/P2 peaks a run of ``scene`` shows: the middle
    of the first dipped joint of ``scene.irregularity`` (the cusp, where the slope changes by
    2 pi d / l and the wheel is thrown upward), or None if the profile holds no joint."""
    irr = getattr(scene, "irregularity", None)
    for part in () if irr is None else irr.parts:
        if getattr(part, "kind", None) == "dipped_joint":
            return part.at + 0.5 * part.length
    return None


def jenkins_p2(static_load: float, dip_angle: float, speed: float, unsprung_mass: float,
               track_mass: float, track_stiffness: float, track_damping: float) -> float:
    """Dipped-joint P2 force [N] by the empirical formula of Jenkins et al. (1974), for trends:

    P2 = P0 + 2 alpha v sqrt(M_u / (M_u + M_t)) [1 - C_t pi / (4 sqrt(K_t (M_u + M_t)))]
         sqrt(K_t M_u)

    P0 = ``static_load`` [N], 2 alpha = ``dip_angle`` the total joint dip angle [rad],
    v = ``speed`` [m/s], M_u = ``unsprung_mass`` [kg], and the track's equivalent mass M_t [kg],
    stiffness K_t [N/m] and damping C_t [N s/m] per wheel.
    """
    p0 = v.number("static_load", static_load, low=0.0, unit="N")
    a2 = v.number("dip_angle", dip_angle, low=0.0, unit="rad")
    sp = v.number("speed", speed, low=0.0, unit="m/s")
    mu = v.positive("unsprung_mass", unsprung_mass, "kg")
    mt = v.positive("track_mass", track_mass, "kg")
    kt = v.positive("track_stiffness", track_stiffness, "N/m")
    ct = v.number("track_damping", track_damping, low=0.0, unit="N s/m")
    damping = 1.0 - ct * math.pi / (4.0 * math.sqrt(kt * (mu + mt)))
    return p0 + a2 * sp * math.sqrt(mu / (mu + mt)) * damping * math.sqrt(kt * mu)


def seed_percentiles(df, columns, *, by="speed", q=(5.0, 50.0, 95.0)):
    """Percentiles over Monte Carlo realisations: for each value of ``by`` (a column, e.g. the
    speed, or a list of columns), the ``q`` percentiles [%] of each of ``columns`` over the
    rows (one per seed). Returns a pandas DataFrame indexed by ``by`` with columns
    (column, "p<q>"); numpy's linear interpolation between order statistics; NaN values
    (failed cases) are skipped."""
    import pandas as pd

    if not isinstance(df, pd.DataFrame):
        raise TypeError(f"df must be a pandas DataFrame, got {type(df).__name__}")
    cols = [columns] if isinstance(columns, str) else list(columns)
    keys = [by] if isinstance(by, str) else list(by)
    missing = [c for c in [*keys, *cols] if c not in df.columns]
    if missing:
        raise ValueError(f"columns {missing} are not in the table; it has {list(df.columns)}")
    qs = [v.number("q", x, low=0.0, high=100.0, unit="%") for x in np.atleast_1d(q)]
    out = {}
    for key, grp in df.groupby(by if isinstance(by, str) else keys, sort=True):
        row = {}
        for c in cols:
            vals = grp[c].to_numpy(float)
            vals = vals[np.isfinite(vals)]
            for x in qs:
                row[(c, f"p{x:g}")] = float(np.percentile(vals, x)) if vals.size else math.nan
        out[key] = row
    frame = pd.DataFrame.from_dict(out, orient="index")
    if isinstance(by, str):
        frame.index.name = by
    else:
        frame.index = pd.MultiIndex.from_tuples(frame.index, names=keys)
    return frame
