"""The contact force under a random rail profile, straight from its spectrum.

Docs: Model § The periodic level ("Random profiles").

A Gaussian profile of one-sided spatial PSD S(Omega) [m^2/(rad/m)] is, under a wheel at
speed v, the temporal process of one-sided PSD S_f(f) = (2 pi / v) S(2 pi f / v) [m^2/Hz]. Its
harmonic at f drives, through the periodic track, the force harmonics H_p(f) [N/m] at
f + p f_s (f_s = v / d, the periodic level's harmonic balance for a unit profile harmonic). The
force is then the sleeper-passing part s(theta) (deterministic, at the bay phase theta) plus a
zero-mean Gaussian part whose variance at phase theta is

    sigma^2(theta) = integral S_f(f) |sum_p H_p(f) e^{i p theta}|^2 df,

and whose spectrum, averaged over the phase (the force is cyclostationary), is
S_N(f') = sum_p |H_p(f)|^2 S_f(f) at f' = |f + p f_s|. One-third-octave band RMS integrate
S_N over the band (plus the sleeper-passing lines inside it); the force at a random instant is
the mixture over theta of normal laws N(P + s(theta), sigma^2(theta)), whose quantiles are the
dynamic-factor percentiles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...base import validate as v
from ...base.limits import MAX_SPEED
from ...base.bands import third_octave_bands
from ...excitation import contact_half_width, filter_attenuation
from ...scene import Scene
from ...excitation.spectra import ChinaSpectrum, FRASpectrum, GermanSpectrum, ThirdOctaveSpectrum
from .wheel import fidelity_of, wheel_of
from .balance import DEFAULT_RTOL, balance, periodic_track
from .outputs import PHASES
from .response import check_applies, periodic_response

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["DEFAULT_PERCENTILES", "RandomResponse", "random_response"]

_SPECTRA = (FRASpectrum, GermanSpectrum, ChinaSpectrum, ThirdOctaveSpectrum)
#: Percentiles [%] of the dynamic factor N / P reported by default
DEFAULT_PERCENTILES = (1.0, 5.0, 50.0, 95.0, 99.0, 99.9)
#: Profile frequencies per decade of the default grid [-]
PER_DECADE = 120


@dataclass(frozen=True)
class RandomResponse:
    """The contact force of :func:`random_response` (docs: Model § The periodic level)."""

    scene: Scene
    speed: float  #: v [m/s]
    spectrum: object  #: the profile's spectrum
    wavelengths: tuple[float, float]  #: (lambda_min, lambda_max) of the profile [m]
    static_load: float  #: P [N]
    #: the force's PSD averaged over the bay phase: frequency_hz, psd_n2_per_hz [N^2/Hz]
    #: (the random part; the sleeper-passing lines are in ``sleeper_passing``)
    psd: pd.DataFrame
    #: one-third-octave bands (IEC 61260-1, base 10): centre_hz, lower_hz, upper_hz,
    #: rms_random_n, rms_sleeper_n, rms_n (both together) [N]
    band_rms: pd.DataFrame
    #: percentile [%], force_n [N], dynamic_factor [-] of N at a random instant (Gaussian)
    percentiles: pd.DataFrame
    sigma: float  #: standard deviation of the random part, averaged over the phase [N]
    loss_probability: float  #: P(N <= 0) under the Gaussian law [-]
    #: the sleeper-passing harmonics of the smooth track (PeriodicResponse.force_harmonics)
    sleeper_passing: pd.DataFrame

    @property
    def rms(self) -> float:
        """RMS of N - P [N]: the random part and the sleeper passing together."""
        sp = self.sleeper_passing.amplitude_n.to_numpy()
        return math.sqrt(self.sigma**2 + 0.5 * float(np.sum(sp**2)))

    def __repr__(self) -> str:
        return (f"RandomResponse({getattr(self.spectrum, 'name', self.spectrum)} at "
                f"{self.speed * 3.6:.4g} km/h: sigma {self.sigma:.4g} N "
                f"({self.sigma / self.static_load:.3g} P), P(N <= 0) = "
                f"{self.loss_probability:.3g})")


def random_response(scene: Scene, speed: float, spectrum, *,
                    wavelengths: tuple[float, float] | None = None, n_harmonics: int = 2,
                    fidelity: str | None = None, percentiles=DEFAULT_PERCENTILES,
                    per_decade: int = PER_DECADE, rtol: float = DEFAULT_RTOL,
                    max_loss_probability: float = 1e-3, linearisation_tol: float = 0.02
                    ) -> RandomResponse:
    """The contact force of the scene's wheel at ``speed`` [m/s] over a Gaussian rail profile
    of one-sided PSD ``spectrum`` (a ``trackwheel.spectra`` spectrum, [m^2/(rad/m)]) on the
    periodic track, without realisations (module docstring): its PSD, its one-third-octave
    band RMS and the dynamic-factor percentiles.

    ``wavelengths`` = (lambda_min, lambda_max) [m]: the profile's band (default the spectrum's
    validity band; ``Irregularity.random`` generates the same band). ``n_harmonics``: side
    bands kept on each side (the balance keeps two more). ``per_decade``: profile frequencies
    per decade (log-spaced; the PSD and the band integrals are piecewise linear between them,
    a one-third-octave spectrum's band edges are nodes). ``percentiles`` [%] in (0, 100).
    The scene's own irregularity is ignored (the profile is the spectrum's). Raises ValueError
    where the periodic level does not apply (``periodic_response``), and when the Gaussian
    law gives the contact a probability of opening above ``max_loss_probability``: the linear
    result then does not describe the tail it predicts, or ("linear/hertz") when 3 sigma of the
    force swing the Hertz law beyond ``linearisation_tol`` (``periodic_response``)."""
    if not isinstance(spectrum, _SPECTRA):
        raise TypeError(f"spectrum must be a trackwheel.spectra spectrum, got "
                        f"{type(spectrum).__name__}")
    fidelity = fidelity_of(scene, fidelity)
    track = periodic_track(scene)
    speed = v.number("speed", speed, low=0.0, high=MAX_SPEED, low_open=True, unit="m/s")
    n_out = v.integer("n_harmonics", n_harmonics, low=0, high=16)
    per_decade = v.integer("per_decade", per_decade, low=10, high=10_000)
    max_loss = v.number("max_loss_probability", max_loss_probability, low=0.0, high=1.0)
    qs = v.positions("percentiles", percentiles, 0.0, 100.0, unit="%")
    if np.any((qs <= 0.0) | (qs >= 100.0)):
        raise ValueError("percentiles must lie in (0, 100) %")
    lam = _band(spectrum, wavelengths)
    wheel = wheel_of(scene, fidelity)
    P = wheel.load
    from .response import HARMONIC_MARGIN

    n = n_out + HARMONIC_MARGIN
    d = track.bay
    fs = speed / d
    # the smooth track's sleeper passing (deterministic)
    smooth = periodic_response(scene, speed, irregularity=_smooth(), fidelity=fidelity,
                               rtol=rtol, linearisation_tol=1e9)
    sp = smooth.force_harmonics
    # profile frequencies: log grid plus the spectrum's discontinuities
    f = _grid(spectrum, lam, speed, per_decade)
    a_patch = contact_half_width(scene) if scene.contact.patch_filter else None
    lam_f = speed / f
    gain = 1.0 if a_patch is None else filter_attenuation(lam_f, a_patch) ** 2
    s_f = 2.0 * math.pi / speed * spectrum(2.0 * math.pi * f / speed) * gain  # [m^2/Hz]
    H = np.empty((f.size, 2 * n + 1), complex)  # force per unit profile harmonic [N/m]
    rhs = np.zeros(2 * n + 1, complex)
    rhs[n] = 1.0
    for i, fi in enumerate(f):
        H[i] = balance(track, wheel, fidelity, speed, 2.0 * math.pi * fi, n, rhs,
                        rtol=rtol).N
    H = H[:, n - n_out:n + n_out + 1]
    p = np.arange(-n_out, n_out + 1)
    g = np.abs(H) ** 2 * s_f[:, None]  # density of harmonic p at f + p f_s [N^2/Hz]
    # variance at the bay phase theta: sigma^2(theta) = int S_f |sum_p H_p e^{i p theta}|^2
    theta = 2.0 * math.pi * np.arange(PHASES) / PHASES
    env = np.abs(H @ np.exp(1j * np.multiply.outer(p, theta))) ** 2 * s_f[:, None]
    var_theta = _trapezoid(env, f)
    # the sleeper passing at theta (t = theta / (2 pi f_s))
    base = smooth.force(theta / (2.0 * math.pi * fs)) - P
    psd = _psd_table(f, g, p, fs)
    bands = _band_table(f, g, p, fs, sp)
    quant, loss = _percentiles(P, base, np.sqrt(var_theta), qs)
    if loss > max_loss:
        raise ValueError(
            f"the Gaussian force opens the contact with probability {loss:.3g} > "
            f"max_loss_probability = {max_loss:g}: the linear result does not describe the "
            "contact losses it predicts; use simulate over realisations (Irregularity.random) "
            "with fidelity 'linear/hertz' or 'full'")
    if fidelity == "linear/hertz":  # the Hertz law's linearisation over +-3 sigma
        swing = float(np.max(np.abs(base))) + 3.0 * math.sqrt(float(var_theta.max()))
        check_applies(fidelity, P, P - swing, P + swing, linearisation_tol, loss=False)
    import pandas as pd

    return RandomResponse(
        scene=scene, speed=speed, spectrum=spectrum, wavelengths=lam, static_load=P,
        psd=psd, band_rms=bands,
        percentiles=pd.DataFrame({"percentile": qs, "force_n": quant,
                                  "dynamic_factor": quant / P}),
        sigma=math.sqrt(float(var_theta.mean())), loss_probability=loss,
        sleeper_passing=sp)


def _smooth():
    from ...excitation import Irregularity

    return Irregularity()


def _band(spectrum, wavelengths) -> tuple[float, float]:
    lo, hi = spectrum.band
    valid = (2.0 * math.pi / hi, 2.0 * math.pi / lo)
    if wavelengths is None:
        return valid
    lam = v.positions("wavelengths", wavelengths, 0.0, math.inf)
    if lam.size != 2 or not 0.0 < lam[0] < lam[1]:
        raise ValueError(f"wavelengths = {tuple(lam)} must be (lambda_min, lambda_max) with "
                         "0 < lambda_min < lambda_max [m]")
    if lam[0] < valid[0] * (1 - 1e-9) or lam[1] > valid[1] * (1 + 1e-9):
        raise ValueError(f"wavelengths = ({lam[0]:g}, {lam[1]:g}) m is outside the validity "
                         f"band of {spectrum.name}: allowed range [{valid[0]:.6g}, "
                         f"{valid[1]:.6g}] m")
    return float(lam[0]), float(lam[1])


def _grid(spectrum, lam, speed, per_decade) -> np.ndarray:
    """Profile frequencies [Hz] from v / lambda_max to v / lambda_min: log-spaced, with the
    spectrum's discontinuities (a one-third-octave spectrum's band edges) as nodes (twice,
    just inside each side)."""
    # just inside the band: a spectrum that ends there (a one-third-octave one) is zero at
    # its outer edge
    f_lo, f_hi = speed / lam[1] * (1 + 1e-9), speed / lam[0] * (1 - 1e-9)
    m = max(8, math.ceil(per_decade * math.log10(f_hi / f_lo)))
    f = np.geomspace(f_lo, f_hi, m + 1)
    if isinstance(spectrum, ThirdOctaveSpectrum):
        e = spectrum.edges() * speed / (2.0 * math.pi)
        e = e[(e > f_lo) & (e < f_hi)]
        f = np.union1d(f, np.concatenate((e * (1 - 1e-9), e * (1 + 1e-9))))
    return f


def _trapezoid(y, x):
    """Trapezoid rule of y (n, ...) over x (n,)."""
    dx = np.diff(x)
    return (0.5 * (y[1:] + y[:-1]) * dx.reshape((-1,) + (1,) * (y.ndim - 1))).sum(axis=0)


def _psd_table(f, g, p, fs) -> pd.DataFrame:
    """S_N(f') on the union of the shifted grids, summing the harmonics' densities
    (each linear between its nodes, zero outside its band), folded to f' > 0."""
    import pandas as pd

    pieces = [(np.abs(f + q * fs), g[:, j]) for j, q in enumerate(p)]
    grid = np.unique(np.concatenate([x for x, _ in pieces]))
    grid = grid[grid > 0.0]
    total = np.zeros(grid.size)
    for x, y in pieces:
        order = np.argsort(x)
        xs, ys = x[order], y[order]
        inside = (grid >= xs[0]) & (grid <= xs[-1])
        total[inside] += np.interp(grid[inside], xs, ys)
    return pd.DataFrame({"frequency_hz": grid, "psd_n2_per_hz": total})


def _band_table(f, g, p, fs, sp) -> pd.DataFrame:
    """The one-third-octave bands that the response covers, with the exact integrals of the
    piecewise-linear densities over each band and the sleeper-passing lines inside it."""
    import pandas as pd

    lo = max(float(np.min(np.abs(f[:, None] + p[None, :] * fs))), 1e-3)
    hi = float(np.max(np.abs(f[:, None] + p[None, :] * fs)))
    lines_f = sp.frequency_hz.to_numpy()
    lines_a = sp.amplitude_n.to_numpy()
    centres, edges = third_octave_bands(lo, max(hi, lo * 1.3))
    rand = np.zeros(centres.size)
    for j, q in enumerate(p):
        x = f + q * fs
        if np.all(x > 0) or np.all(x < 0):
            xs, ys = (x, g[:, j]) if x[0] > 0 else (-x[::-1], g[::-1, j])
            rand += [_integral(xs, ys, a, b) for a, b in edges]
        else:  # a side band crossing f' = 0: fold the negative part
            neg = x < 0
            rand += [_integral(x[~neg], g[~neg, j], a, b) for a, b in edges]
            rand += [_integral(-x[neg][::-1], g[neg, j][::-1], a, b) for a, b in edges]
    line = np.array([0.5 * float(np.sum(lines_a[(lines_f >= a) & (lines_f < b)] ** 2))
                     for a, b in edges])
    return pd.DataFrame({"centre_hz": centres, "lower_hz": edges[:, 0], "upper_hz": edges[:, 1],
                         "rms_random_n": np.sqrt(rand), "rms_sleeper_n": np.sqrt(line),
                         "rms_n": np.sqrt(rand + line)})


def _integral(x, y, a, b) -> float:
    """Integral over [a, b] of the piecewise-linear interpolant of y(x) (x increasing), zero
    outside [x[0], x[-1]]."""
    a, b = max(a, x[0]), min(b, x[-1])
    if b <= a or x.size < 2:
        return 0.0
    inside = (x > a) & (x < b)
    xs = np.concatenate(([a], x[inside], [b]))
    ys = np.interp(xs, x, y)
    return float(np.sum(0.5 * (ys[1:] + ys[:-1]) * np.diff(xs)))


def _percentiles(P, base, sigma, qs) -> tuple[np.ndarray, float]:
    """Quantiles [N] of the mixture over the phase of N(P + base, sigma^2) at ``qs`` [%], and
    P(N <= 0)."""
    from scipy.optimize import brentq
    from scipy.special import ndtr

    sigma = np.maximum(sigma, 1e-300)

    def cdf(x):
        return float(np.mean(ndtr((x - P - base) / sigma)))

    lo = P + float(base.min()) - 40.0 * float(sigma.max())
    hi = P + float(base.max()) + 40.0 * float(sigma.max())
    out = np.array([brentq(lambda x, q=q: cdf(x) - q / 100.0, lo, hi, xtol=1e-9 * P)
                    for q in qs])
    return out, cdf(0.0)
