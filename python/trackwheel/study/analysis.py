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
from functools import lru_cache

import numpy as np
from numpy.polynomial import chebyshev

from ..base import validate as v
from ..base.fields import dataclass_fields, generated_doc
from .columns import ANALYSIS_FIELDS, OUTPUTS
from .force_statistics import (  # ForceStatistics: the annotation of Analysis.forces
    P1_PERIOD,
    P2_PERIOD,
    ForceStatistics,  # noqa: F401
    result_statistics,
)
from ..run.results import Result
from ..scene import Scene
from ..run.statics import linear_quasi_static, quasi_static
from .steady import from_time, steady_state

__all__ = [
    "QS_DEGREE",
    "ZERO_PADDING",
    "Analysis",
    "amplitude_spectrum",
    "analyse",
    "main_frequency",
]

#: Degree of the polynomial that represents the quasi-static line inside each rail element.
#: With the wheel at X, the static contact-point displacement is, to within the geometric
#: nonlinearity, N(X)^T K^-1 N(X) P with cubic Hermite shape functions N: a polynomial of degree
#: 6 in X inside an element, with kinks in its derivatives only at the nodes (the support springs
#: enter K, not N). So y_qs is solved at the QS_DEGREE + 1 Chebyshev-Lobatto points of each
#: element the run crosses (the end points shared with the neighbours: QS_DEGREE static solves
#: per element) and interpolated by the element's Chebyshev series. Measured against direct
#: static solves: < 2e-13 m for the paper's scene with 20 elements and < 1e-15 m with 80, i.e.
#: below 1e-8 of the static deflection (7e-5 m) and 1e-7 of the smallest dynamic amplitude of
#: Fig. 7 (1.2e-6 m at 50 km/h); a cubic on a 5 mm grid costs 7 (20 elements) or 1.5 (80) times
#: as many solves for an error of 2e-11 m. Each analysis reports an estimate of its own error,
#: |c_7| + |c_8| of the Chebyshev coefficients (``Analysis.y_qs_error``, ~1e-12 m here).
QS_DEGREE = 8
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


# --------------------------------------------------------------------------------------------
# quasi-static line
@lru_cache(maxsize=128)
def _qs_series(scene: Scene, n_elements: int, e0: int, e1: int, linear: bool):
    """Chebyshev series of y_qs on each element e0 .. e1-1 of the mesh: of the ANCF model or
    (``linear``) of the linear track in all its coordinates.

    Returns (coefficients (QS_DEGREE + 1, e1 - e0) [m], error estimate [m]). Cached per (scene,
    mesh, element range): the same range is always solved the same way (one warm-started
    sweep), so the line is bit-identical whichever process or earlier analysis computed it.
    """
    n = QS_DEGREE
    le = scene.rail.length / n_elements
    t = -np.cos(np.pi * np.arange(n + 1) / n)  # Chebyshev-Lobatto points on [-1, 1]
    n_el = e1 - e0
    x = ((np.arange(e0, e1)[:, None] + 0.5 * (t[None, :-1] + 1.0)) * le).ravel()
    x = np.minimum(np.append(x, e1 * le), scene.rail.length)
    if linear:
        y = linear_quasi_static(scene, x, n_elements=n_elements)
    else:
        y = quasi_static(scene, x, n_elements=n_elements).y_contact
    values = y[np.arange(n_el)[:, None] * n + np.arange(n + 1)[None, :]]  # (n_el, n + 1)
    coef = np.linalg.solve(chebyshev.chebvander(t, n), values.T)  # (n + 1, n_el)
    coef.setflags(write=False)
    return coef, float(np.max(np.abs(coef[-2]) + np.abs(coef[-1])))


def _in_window(scene: Scene, x: np.ndarray) -> np.ndarray:
    """X [m] as the rail coordinate of a fixed rail, or on a travelling window the same place
    in its bay in the window's middle bay (the quasi-static line of the periodic track)."""
    if scene.window is None:
        return x
    d = scene.supports.spacing
    middle = round(scene.rail.length / d) // 2
    return middle * d + np.mod(x, d)


def _quasi_static_line(scene: Scene, n_elements: int, x: np.ndarray, linear: bool = False):
    """y_qs at the wheel positions x [m] and the estimate of its error [m]."""
    x = _in_window(scene, x)
    le = scene.rail.length / n_elements
    e0 = max(0, min(n_elements - 1, math.floor(float(x.min()) / le)))
    e1 = max(e0 + 1, min(n_elements, math.ceil(float(x.max()) / le)))
    coef, err = _qs_series(scene, n_elements, e0, e1, linear)
    k = np.clip(np.floor(x / le).astype(np.int64) - e0, 0, e1 - e0 - 1)
    t = np.clip(2.0 * (x / le - (k + e0)) - 1.0, -1.0, 1.0)
    return chebyshev.chebval(t, coef[:, k], tensor=False), err


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
                f"{self.loss_duration * 1e3:.3g} ms" + self._peaks_text())

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
            steady: bool = False) -> Analysis:
    """Measure the contact-point vibration of a :func:`trackwheel.simulate` run (docs: Model §
    Outputs).

    The quasi-static line is solved with the run's scene and mesh (``result.settings
    .n_elements``) and the run's model: the ANCF statics (:func:`trackwheel.quasi_static`) for
    the full and ``ancf/*`` levels, the linear track's own statics in all its coordinates
    (:func:`trackwheel.linear_quasi_static`) for the ``linear/*`` levels, so that every
    run starts at d = 0 (a modal run with its truncation error of the static deflection: that
    error is the modal level's, and d shows it). It is solved at 8 Chebyshev points
    per element crossed (cached per scene, mesh, model and range) and interpolated by each element's degree-8 Chebyshev series (see
    :data:`QS_DEGREE`): the error (< 2e-13 m for the paper's scene, ``Analysis.y_qs_error``
    estimates it for any scene) is negligible against the dynamic part. The spectrum and main
    frequency are those of :func:`main_frequency` on d(t) (``n_fft`` as there); the sampling
    interval is ``dt x output_every``.

    The contact-force statistics (``Analysis.forces``, see
    :mod:`trackwheel.force_statistics`) are taken against the static load P0 = F + M g [N]:
    ``dynamic_factor`` = max N / P0, contact loss where N <= 0, the RMS of N - mean(N) in each
    one-third-octave band the record resolves. With ``defect_at`` X_d [m] (e.g. the middle of
    a dipped joint, :func:`trackwheel.force_statistics.defect_position`) also P1, the maximum
    of N in [t_d, t_d + T_1/2], and P2, the maximum in (t_d + T_1/2, t_d + (T_1 + T_2)/2], with
    t_d the time the wheel centre reaches X_d and T_1 = ``p1_period``, T_2 = ``p2_period`` [s].

    A vehicle with several wheels is measured one wheel at a time: ``wheel`` = i analyses
    ``result.wheel(i)``, wheel i alone under its static load of the weight distribution
    (its quasi-static line is that wheel's alone; the neighbours' static deflection is part
    of its dynamic part d).

    ``t_from`` [s] measures only the samples from that time on; ``steady=True`` from the start
    of the steady state in the sleeper bay (:func:`trackwheel.steady_state` of the contact
    force: the start-up transient left out). On a travelling window (``scene.window``) the
    quasi-static line is the periodic track's: solved in the window's middle bay at the wheel's
    position in its bay.

    Raises ValueError if the run kept fewer than 4 samples, if ``defect_at`` is not passed
    in the run, or if the run has several wheels and ``wheel`` is not given.
    """
    if not isinstance(result, Result):
        raise TypeError(f"result must be a trackwheel.Result, got {type(result).__name__}")
    if wheel is not None:
        result = result.wheel(wheel)
    elif result.n_wheels > 1:
        raise ValueError(f"result has {result.n_wheels} wheels: give wheel = 0 .. "
                         f"{result.n_wheels - 1} (one Analysis per wheel)")
    if steady:
        if t_from is not None:
            raise ValueError("give t_from or steady=True, not both")
        t_from = steady_state(result).t_from
    if t_from is not None:
        result = from_time(result, t_from)
    n = result.t.size
    if n < 4:
        raise ValueError(f"result has {n} samples; the analysis needs at least 4 "
                         "(lower output_every or run longer)")
    s = result.settings
    dt = float(s.dt) * int(s.output_every)
    x = np.asarray(result.x_wheel, dtype=float)
    linear = s.fidelity.startswith("linear/")
    y_qs, qs_err = _quasi_static_line(result.scene, int(s.n_elements), x, linear)
    d = result.y_contact - y_qs
    i_max = int(np.argmax(np.abs(d)))
    nf = _n_fft(n_fft, n)
    freqs, amps = amplitude_spectrum(d, dt, n_fft=nf)
    resolution = 1.0 / (n * dt)
    f_main = _peak(freqs, amps, resolution, 0.5 / dt)
    N = result.normal_force
    forces = result_statistics(result, defect_at=defect_at, p1_period=p1_period,
                               p2_period=p2_period)
    return Analysis(
        t=result.t, x_wheel=x, y_contact=result.y_contact, y_qs=y_qs, dynamic=d,
        amplitude=float(abs(d[i_max])), amplitude_time=float(result.t[i_max]),
        main_frequency=f_main, frequency_resolution=resolution, spectrum=(freqs, amps),
        n_fft=nf,
        y_qs_error=qs_err, normal_force=N, min_contact_force=float(N.min()),
        max_contact_force=float(N.max()), lost_contact=result.lost_contact,
        acc_contact=result.acc_contact, acc_A=result.acc_A, acc_B=result.acc_B,
        acc_C=result.acc_C, acc_D=result.acc_D, acc_E=result.acc_E, forces=forces)
