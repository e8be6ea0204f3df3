"""Post-processing of a run: the dynamic part of the contact-point displacement, its amplitude and
main frequency, and the acceleration terms (docs: Model § Outputs).

``analyse(result)`` measures the vibration the paper plots in Figs. 6-8:

- the quasi-static line y_qs(X) [m] -- the static contact-point displacement with the wheel
  resting at X, from :func:`trackwheel.quasi_static` with the run's own scene and mesh;
- the dynamic part d(t) = y_B(t) - y_qs(X_A(t)) [m] and its amplitude max |d| [m];
- the main frequency [Hz]: the peak of the amplitude spectrum of d(t) (mean removed, Hann window,
  zero padding, parabolic interpolation of the log magnitude), reported with the frequency
  resolution 1/(N dt) of the record.

- the contact-force statistics of :mod:`trackwheel.force_statistics` (``Analysis.forces``):
  max and min N, the dynamic factor max N / P0 against the static load P0 = F + M g, the
  contact-loss intervals and duration, the RMS of N in one-third-octave bands, the amplitude
  spectrum of N, and with ``defect_at`` the P1/P2 peaks after a discrete defect.

The lower-level :func:`amplitude_spectrum` and :func:`main_frequency` work on any uniformly
sampled signal. Everything is vectorised numpy.
"""

from __future__ import annotations

import math
import dataclasses

import numpy as np

from ..base import validate as v
from ..base.fields import dataclass_fields, generated_doc
from .columns import ANALYSIS_FIELDS, OUTPUTS
from .force_statistics import (  # ForceStatistics: the annotation of Analysis.forces
    P1_PERIOD,
    P2_PERIOD,
    ForceStatistics,  # noqa: F401
    result_statistics,
)
from ..run.stretch import measured_stretch
from ..run.results import Result
from .static_line import QS_DEGREE, quasi_static_line, vehicle_quasi_static_line
from .steady import from_time, samples, steady_state

__all__ = [
    "QS_DEGREE",
    "ZERO_PADDING",
    "Analysis",
    "amplitude_spectrum",
    "analyse",
    "main_frequency",
]

#: The FFT length is the smallest power of two >= ZERO_PADDING x the record length.
ZERO_PADDING = 8


# --------------------------------------------------------------------------------------------
# spectra
def _signal(name, signal) -> np.ndarray:
    try:
        x = np.asarray(signal, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be a 1-d sequence of numbers") from exc
    if x.ndim != 1 or x.size < 4:
        raise ValueError(f"{name} must be a 1-d array of at least 4 samples, "
                         f"got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError(f"{name} contains NaN or inf")
    return x


def _n_fft(n_fft, n: int) -> int:
    if n_fft is None:
        return 1 << math.ceil(math.log2(ZERO_PADDING * n))
    return v.integer("n_fft", n_fft, low=n)


def amplitude_spectrum(signal, dt: float, *, n_fft: int | None = None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """One-sided amplitude spectrum of a uniformly sampled ``signal`` (sample spacing ``dt`` [s]).

    The mean is removed, a Hann window applied, and the record zero-padded to ``n_fft`` points
    (default: the smallest power of two >= 8 N). Amplitudes are scaled by the window's coherent
    gain, 2 |X_k| / sum(w) (|X_0| / sum(w) at 0 Hz), so that a sine of amplitude A lying on a
    bin shows a peak of height A, in the signal's units; between bins the peak is lower by the
    Hann scalloping loss (at most 0.25 % with the default 8x padding: a tone 1/16 bin off).

    Returns ``(freqs, amplitudes)``, each of shape (n_fft // 2 + 1,), freqs in [Hz]. The
    zero-padded bins are 1/(n_fft dt) apart, but the resolution -- the spacing at which two
    tones can be told apart -- stays about 1/(N dt) (two bins for the Hann main-lobe half width).
    """
    x = _signal("signal", signal)
    dt = v.positive("dt", dt, "s")
    nf = _n_fft(n_fft, x.size)
    w = np.hanning(x.size)
    spec = np.abs(np.fft.rfft((x - x.mean()) * w, nf)) * (2.0 / w.sum())
    spec[0] *= 0.5
    if nf % 2 == 0:
        spec[-1] *= 0.5
    return np.fft.rfftfreq(nf, dt), spec


def _peak(freqs: np.ndarray, amps: np.ndarray, f_min: float, f_max: float) -> float:
    """Frequency of the largest interior local maximum of ``amps`` with f_min <= f <= f_max,
    refined by a parabola through the logarithms of the three bins around it (exact for a
    Gaussian peak; the Hann main lobe is close to one). NaN if there is no such maximum."""
    a = amps
    inner = np.arange(1, a.size - 1)
    ok = (a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:]) & (freqs[1:-1] >= f_min) & (freqs[1:-1] <= f_max)
    if not np.any(ok):
        return math.nan
    k = int(inner[ok][np.argmax(a[1:-1][ok])])
    with np.errstate(divide="ignore"):
        lm, l0, lp = np.log(a[k - 1:k + 2])
    denom = lm - 2.0 * l0 + lp
    shift = 0.5 * (lm - lp) / denom if np.isfinite(denom) and denom < 0.0 else 0.0
    return float(freqs[k] + shift * (freqs[1] - freqs[0]))


def main_frequency(signal, dt: float, *, n_fft: int | None = None, f_min: float | None = None,
                   f_max: float | None = None) -> float:
    """Main (dominant) frequency [Hz] of a uniformly sampled ``signal`` (spacing ``dt`` [s]).

    The largest peak of :func:`amplitude_spectrum` (mean removed, Hann window, zero padding to
    ``n_fft``, default the smallest power of two >= 8 N), refined by parabolic interpolation of
    the log magnitude over the three bins around it. Only peaks with ``f_min <= f <= f_max`` are
    considered; ``f_min`` defaults to the resolution 1/(N dt): a period longer than the record
    is not an oscillation the record resolves (this also skips the window's 0 Hz lobe left by a
    slow trend), ``f_max`` to the Nyquist frequency.

    Accuracy (tests/test_analysis.py): for a pure tone at least 5 resolution bins from 0 Hz the
    error is below 1e-3 of the resolution 1/(N dt) (the remaining bias is the leakage of the
    negative-frequency image); two tones 6 bins apart with amplitude ratio 2 shift the stronger
    one's estimate by less than 2e-3 bins. Returns NaN if the spectrum has no peak in range.
    """
    x = _signal("signal", signal)
    dt = v.positive("dt", dt, "s")
    fmin = 1.0 / (x.size * dt) if f_min is None else v.number("f_min", f_min, low=0.0,
                                                                  unit="Hz")
    fmax = 0.5 / dt if f_max is None else v.number("f_max", f_max, low=fmin, unit="Hz")
    freqs, amps = amplitude_spectrum(x, dt, n_fft=n_fft)
    return _peak(freqs, amps, fmin, fmax)


def _measured(result: Result, wheel: int, measure, defect_at) -> tuple[float, float] | None:
    """The X range [m] of wheel ``wheel``'s centre to measure, or None for every sample."""
    if isinstance(measure, str):
        v.choice("measure", measure, {"default", "run"})
        if measure == "run":
            return None
        s = result.settings
        stretch = measured_stretch(result.scene, float(s.speed), float(s.x_start),
                                   float(s.x_end))
        if stretch is None:
            return None
        offset = result.scene.active_vehicle.positions[wheel] if result.n_wheels > 1 else 0.0
        lo, hi = stretch[0] + offset, stretch[1] + offset
        if defect_at is not None and not lo <= defect_at <= hi:
            return None  # the defect's P1/P2 need the run around it
        return lo, hi
    try:
        lo, hi = (float(x) for x in measure)
    except (TypeError, ValueError):
        raise ValueError(f"measure = {measure!r}: allowed 'default', 'run' or (x_from, x_to) "
                         "[m]") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise ValueError(f"measure = ({lo}, {hi}) m: allowed x_from < x_to, both finite")
    return lo, hi


# --------------------------------------------------------------------------------------------
class _AnalysisMethods:
    """Derived views of an :class:`Analysis`."""

    def __repr__(self) -> str:
        return (f"<trackwheel.Analysis: {self.t.size} samples, "
                f"X = {self.x_wheel[0]:.4g} -> {self.x_wheel[-1]:.4g} m>\n"
                f"  amplitude max|d| = {self.amplitude:.4g} m at t = {self.amplitude_time:.4g} s, "
                f"main frequency {self.main_frequency:.1f} Hz "
                f"(resolution {self.frequency_resolution:.2g} Hz)\n"
                f"  contact force {self.min_contact_force:.6g}..{self.max_contact_force:.6g} N, "
                f"lost contact: {'yes' if self.lost_contact else 'no'}\n"
                f"  dynamic factor {self.dynamic_factor:.4g}, contact loss "
                f"{self.loss_duration * 1e3:.3g} ms" + self._peaks_text()
                + (f"\n  slid {self.slide_duration * 1e3:.4g} ms (|lambda| = mu N), locked "
                   f"{self.locked_duration * 1e3:.4g} ms" if self.slide_duration > 0 else ""))

    def _peaks_text(self) -> str:
        f = self.forces
        if math.isnan(f.defect_time):
            return ""
        return f", P1 {f.p1:.5g} N, P2 {f.p2:.5g} N"

    @property
    def dynamic_factor(self) -> float:
        """max N / P0 [-], P0 = F + M g the static wheel load."""
        return self.forces.dynamic_factor

    @property
    def loss_duration(self) -> float:
        """Total time without contact [s] (0 if the wheel kept contact)."""
        return self.forces.loss_duration

    @property
    def force_rms(self) -> float:
        """RMS of N - mean(N) over the record [N]."""
        return float(np.std(self.normal_force))

    @property
    def p1(self) -> float:
        """P1 [N] after the defect given to :func:`analyse` (NaN: none)."""
        return self.forces.p1

    @property
    def p1_time(self) -> float:
        """Time of P1 [s]."""
        return self.forces.p1_time

    @property
    def p2(self) -> float:
        """P2 [N] after the defect given to :func:`analyse` (NaN: none)."""
        return self.forces.p2

    @property
    def p2_time(self) -> float:
        """Time of P2 [s]."""
        return self.forces.p2_time

    @property
    def sample_spacing(self) -> float:
        """dt of the record [s] (time step x output_every)."""
        return float(self.t[1] - self.t[0])

    def outputs(self) -> dict:
        """The scalar outputs (:data:`trackwheel.study.columns.OUTPUTS`) by column name, the
        row a sweep table holds for this wheel."""
        return {q.label: getattr(self, q.name) for q in OUTPUTS}


_FIELD_NAMES = {q.name for q in ANALYSIS_FIELDS}
Analysis = dataclasses.make_dataclass(
    "Analysis", dataclass_fields(ANALYSIS_FIELDS), bases=(_AnalysisMethods,), frozen=True,
    eq=False, repr=False, namespace={"__module__": __name__, "__doc__": "\n".join([
        generated_doc("The measured vibration of one run (docs: Model § Outputs), from "
                      ":func:`analyse`. Fields:", ANALYSIS_FIELDS), "",
        "Derived outputs (properties):", "",
        *(f"- {q.describe()}" for q in OUTPUTS if q.name not in _FIELD_NAMES)])})


def analyse(result: Result, *, n_fft: int | None = None, defect_at: float | None = None,
            p1_period: float = P1_PERIOD, p2_period: float = P2_PERIOD,
            wheel: int | None = None, t_from: float | None = None,
            steady: bool = False, measure="default") -> Analysis:
    """Measure the contact-point vibration of a :func:`trackwheel.simulate` run (docs: Model §
    Outputs).

    **What is measured** (``measure``; ``Analysis.x_range`` says which X range it was):
    ``"default"`` the part of the run that neither the rail's rigid ends nor the start-up
    transient dominate (:func:`trackwheel.run.defaults.measured_stretch`: from one decay
    length of the wheel's bounce on the track after the start, while every wheel is at least
    :func:`~trackwheel.run.defaults.end_clearance` from both rail ends), or the whole run where
    the rail is too short for such a stretch -- the paper's 5 m rail, measured whole as the
    paper does -- or where it would leave out the ``defect_at`` given; ``"run"`` every sample;
    ``(x_from, x_to)`` [m] the samples with the wheel's centre in that range. ``t_from`` [s]
    measures the samples from that time on instead, ``steady=True`` from the start of the
    steady state in the sleeper bay (:func:`trackwheel.steady_state` of the contact force).

    The quasi-static line is solved with the run's scene and mesh (``result.settings
    .n_elements``) and the run's model: the ANCF statics (:func:`trackwheel.quasi_static`) for
    the full and ``ancf/*`` levels, the linear track's own statics in all its coordinates
    (:func:`trackwheel.linear_quasi_static`) for the ``linear/*`` levels, so that every
    run starts at d = 0 (a modal run with its truncation error of the static deflection: that
    error is the modal level's, and d shows it). It is solved at 8 Chebyshev points
    per element crossed (cached per scene, mesh, model and range) and interpolated by each
    element's degree-8 Chebyshev series (see :data:`QS_DEGREE`): the error (< 2e-13 m for the
    paper's scene, ``Analysis.y_qs_error`` estimates it for any scene) is negligible against
    the dynamic part. Its cost grows as the passage, not as passage x rail: the linear
    track's line from the band of K^-1, the full level's on a long fixed rail bay by bay on
    pieces of the rail (:mod:`trackwheel.study.static_line`). The spectrum and main frequency are those of :func:`main_frequency` on
    d(t) (``n_fft`` as there); the sampling interval is ``dt x output_every``.

    The contact-force statistics (``Analysis.forces``, see
    :mod:`trackwheel.force_statistics`) are taken against the static load P0 = F + M g [N]:
    ``dynamic_factor`` = max N / P0, contact loss where N <= 0, the RMS of N - mean(N) in each
    one-third-octave band the record resolves. With ``defect_at`` X_d [m] (e.g. the middle of
    a dipped joint, :func:`trackwheel.force_statistics.defect_position`) also P1, the maximum
    of N in [t_d, t_d + T_1/2], and P2, the maximum in (t_d + T_1/2, t_d + (T_1 + T_2)/2], with
    t_d the time the wheel centre reaches X_d and T_1 = ``p1_period``, T_2 = ``p2_period`` [s].

    A vehicle with several wheels is measured one wheel at a time: ``wheel`` = i analyses
    wheel i under its static load of the weight distribution. Its quasi-static line is its own
    static displacement with the whole vehicle resting on the track (every wheel under its
    lever-rule load, solved where any wheel crosses a node and interpolated between), so its
    d starts at 0 as a single wheel's does, and the neighbours' static deflection is not
    counted as dynamic.

    On a travelling window (``scene.window``) the quasi-static line is the window's own: over a
    periodic track solved in the window's bay ``bays_behind`` (where the run holds the rear
    wheel) at the wheel's (the vehicle's) position in its bay; over supports that vary along X
    (one wheel) bay by bay on the window's rail as the run has it there.

    Raises ValueError if fewer than 4 samples are measured, if ``defect_at`` is not passed
    in them, if the run has several wheels and ``wheel`` is not given, or for a bad
    ``measure`` (or one given with ``t_from`` / ``steady``).
    """
    if not isinstance(result, Result):
        raise TypeError(f"result must be a trackwheel.Result, got {type(result).__name__}")
    if wheel is not None:
        one = result.wheel(wheel)
    elif result.n_wheels > 1:
        raise ValueError(f"result has {result.n_wheels} wheels: give wheel = 0 .. "
                         f"{result.n_wheels - 1} (one Analysis per wheel)")
    else:
        one = result
    i = 0 if wheel is None else int(wheel)
    if steady and t_from is not None:
        raise ValueError("give t_from or steady=True, not both")
    if (steady or t_from is not None) and not (isinstance(measure, str)
                                              and measure == "default"):
        raise ValueError("give measure or t_from / steady=True, not both")
    if steady:
        t_from = steady_state(one).t_from
    if t_from is not None:
        one = from_time(one, t_from)
    else:
        stretch = _measured(result, i, measure, defect_at)
        if stretch is not None:
            x = np.asarray(one.x_wheel, dtype=float)
            tiny = 1e-9 * max(1.0, abs(stretch[1]))
            one = samples(one, (x >= stretch[0] - tiny) & (x <= stretch[1] + tiny))
    n = one.t.size
    if n < 4:
        raise ValueError(f"result has {n} samples in the measured part; the analysis needs at "
                         "least 4 (lower output_every, run longer, or widen measure)")
    s = one.settings
    dt = float(s.dt) * int(s.output_every)
    x = np.asarray(one.x_wheel, dtype=float)
    linear = s.fidelity.startswith("linear/")
    if result.n_wheels > 1:
        offset = result.scene.active_vehicle.positions[i]
        y_qs, qs_err = vehicle_quasi_static_line(result.scene, int(s.n_elements), x - offset,
                                                 i, linear)
    else:
        y_qs, qs_err = quasi_static_line(one.scene, int(s.n_elements), x, linear)
    d = one.y_contact - y_qs
    i_max = int(np.argmax(np.abs(d)))
    nf = _n_fft(n_fft, n)
    freqs, amps = amplitude_spectrum(d, dt, n_fft=nf)
    resolution = 1.0 / (n * dt)
    f_main = _peak(freqs, amps, resolution, 0.5 / dt)
    N = one.normal_force
    forces = result_statistics(one, defect_at=defect_at, p1_period=p1_period,
                               p2_period=p2_period)
    return Analysis(
        t=one.t, x_wheel=x, x_range=(float(x[0]), float(x[-1])), y_contact=one.y_contact,
        y_qs=y_qs, dynamic=d,
        amplitude=float(abs(d[i_max])), amplitude_time=float(one.t[i_max]),
        main_frequency=f_main, frequency_resolution=resolution, spectrum=(freqs, amps),
        n_fft=nf,
        y_qs_error=qs_err, normal_force=N, min_contact_force=float(N.min()),
        max_contact_force=float(N.max()), lost_contact=one.lost_contact,
        acc_contact=one.acc_contact, acc_A=one.acc_A, acc_B=one.acc_B,
        acc_C=one.acc_C, acc_D=one.acc_D, acc_E=one.acc_E,
        slide_duration=float(np.sum(one.sliding)) * dt,
        locked_duration=float(np.sum(one.locked)) * dt, forces=forces,
        **support_peaks(result, float(x[0]), float(x[-1])))


def support_peaks(result: Result, x_from: float, x_to: float) -> dict:
    """The largest ballast and rail-seat forces [N] over the run at the supports standing in
    [x_from, x_to] [m] (the wheel's measured stretch: the start-up and the rail's ends left
    out as they are for the wheel), and the X [m] of the ballast's; NaN where no support
    stands there. From the run's envelope along the track (``Result.support_envelope``),
    which every run keeps, on a fixed rail and on a travelling window alike."""
    env = result.support_envelope
    nan = {"max_ballast_force": math.nan, "max_ballast_force_x": math.nan,
           "max_rail_seat_force": math.nan}
    if env is None:
        return nan
    X = np.asarray(env["x"], dtype=float)
    tiny = 1e-9 * max(1.0, abs(x_to))
    inside = np.flatnonzero((X >= x_from - tiny) & (X <= x_to + tiny))
    if inside.size == 0:
        return nan
    fb = np.asarray(env["ballast_force_max"], dtype=float)[inside]
    k = int(np.argmax(fb))
    return {"max_ballast_force": float(fb[k]), "max_ballast_force_x": float(X[inside[k]]),
            "max_rail_seat_force": float(np.max(np.asarray(env["rail_seat_force_max"],
                                                           dtype=float)[inside]))}
