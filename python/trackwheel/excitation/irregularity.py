"""The rail profile r(X) [m] as a sum of parts, :class:`Irregularity`.

Docs: Model § Irregularities.

Build one with the classmethods (``random``, ``sine``, ``dipped_joint``, ``samples``) and
``+``; evaluate r, dr/dX and d^2r/dX^2 at any X [m]; sample it on a uniform grid (``grid``,
``table``, the contact-filtered ``table(..., half_width=a)``) or estimate its PSD (``psd``).
How the kernel receives it -- a cubic spline table, streamed over long runs -- is the run
layer's business (``trackwheel.run.profile``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..base import validate as v
from ..base.limits import MAX_SEED
from .contact_filter import contact_filter
from .profiles import PARTS, finite_x, DippedJoint, RandomProfile, SampledProfile, SineProfile, derived_seed
from .spectra import ChinaSpectrum, FRASpectrum, GermanSpectrum, ThirdOctaveSpectrum

_SPECTRA = (FRASpectrum, GermanSpectrum, ChinaSpectrum, ThirdOctaveSpectrum)
#: Default number of spectral-sum components per decade of Omega [-].
COMPONENTS_PER_DECADE = 100
#: Most samples of one uniform grid of the profile [-].
MAX_GRID_POINTS = 50_000_000


def grid_size(x_min: float, x_max: float, dx: float) -> int:
    """Points n = ceil((x_max - x_min) / dx) + 1 of the uniform grid on [x_min, x_max] with
    spacing <= dx [m] (checked: x_min < x_max, dx > 0, n <= MAX_GRID_POINTS)."""
    x_min = v.number("x_min", x_min, unit="m")
    x_max = v.number("x_max", x_max, low=x_min, low_open=True, unit="m")
    dx = v.positive("dx", dx, "m")
    n = math.ceil((x_max - x_min) / dx * (1 - 1e-12)) + 1
    if n > MAX_GRID_POINTS:
        raise ValueError(f"dx = {dx} m gives {n} points on [{x_min}, {x_max}] m; "
                         "allowed at most 5e7")
    return n


@dataclass(frozen=True)
class Irregularity:
    """A rail profile r(X) [m], positive = bump: a sum of parts (build with the classmethods
    and ``+``). Call it for r, ``.slope`` for dr/dX [-], ``.curvature`` for d^2r/dX^2 [1/m];
    all analytic (sampled data: from the interpolant) and vectorised over X [m]."""

    parts: tuple = ()

    def __post_init__(self):
        parts = tuple(self.parts)
        for p in parts:
            if not isinstance(p, PARTS):
                raise TypeError(f"Irregularity.parts must hold profile parts "
                                f"({', '.join(c.__name__ for c in PARTS)}), "
                                f"got {type(p).__name__}")
        object.__setattr__(self, "parts", parts)

    # constructors ------------------------------------------------------------------------
    @classmethod
    def random(cls, spectrum, *, seed: int, wavelengths: tuple[float, float] | None = None,
               n: int | None = None) -> Irregularity:
        """A random profile of one-sided PSD ``spectrum`` [m^2/(rad/m)] by the spectral sum
        (see :class:`RandomProfile`), generated over ``wavelengths`` = (lambda_min, lambda_max)
        [m] only (default: the spectrum's validity band, which the band must lie inside).
        ``n`` components (default 100 per decade of Omega, at least 32). Its variance is
        sum a_n^2 / 2 ~ integral of S over the band [m^2]."""
        if not isinstance(spectrum, _SPECTRA):
            raise TypeError(f"spectrum must be a trackwheel.spectra spectrum, "
                            f"got {type(spectrum).__name__}")
        seed = v.integer("seed", seed, low=0, high=MAX_SEED)
        w_lo, w_hi = spectrum.band
        valid = (2.0 * math.pi / w_hi, 2.0 * math.pi / w_lo)
        if wavelengths is None:
            wavelengths = valid
        lam = v.positions("wavelengths", wavelengths, 0.0, math.inf)
        if lam.size != 2 or not 0.0 < lam[0] < lam[1]:
            shown = ", ".join(f"{x:g}" for x in lam)
            raise ValueError(f"wavelengths = ({shown}) m must be (lambda_min, lambda_max) "
                             "with 0 < lambda_min < lambda_max [m]")
        tol = 1e-9 * valid[1]
        if lam[0] < valid[0] * (1 - 1e-9) or lam[1] > valid[1] + tol:
            raise ValueError(f"wavelengths = ({lam[0]:g}, {lam[1]:g}) m is outside the validity "
                             f"band of {spectrum.name}: allowed range "
                             f"[{valid[0]:.6g}, {valid[1]:.6g}] m")
        if n is None:
            n = max(32, math.ceil(COMPONENTS_PER_DECADE * math.log10(lam[1] / lam[0])))
        n = v.integer("n", n, low=1, high=1_000_000)
        band = (float(lam[0]), float(lam[1]))
        return cls((RandomProfile(spectrum, seed, band, n),))

    @classmethod
    def sine(cls, wavelength: float, amplitude: float, phase: float = 0.0) -> Irregularity:
        """Sine corrugation r = a sin(2 pi X / lambda + phase): ``wavelength`` lambda [m],
        ``amplitude`` a [m], ``phase`` [rad], in the ranges of :class:`SineProfile` (and a
        slope 2 pi a / lambda of at most ``MAX_PROFILE_SLOPE``)."""
        return cls((SineProfile(wavelength, amplitude, phase),))

    @classmethod
    def dipped_joint(cls, depth: float, length: float, at: float) -> Irregularity:
        """Dipped joint (Kabo form, :class:`DippedJoint`): ``depth`` d [m] (the surface goes to
        r = -d), ``length`` l [m], starting at X = ``at`` [m], in the ranges of
        :class:`DippedJoint` (and a slope pi d / l of at most ``MAX_PROFILE_SLOPE``)."""
        return cls((DippedJoint(depth, length, at),))

    @classmethod
    def samples(cls, x, r, method: str = "cubic") -> Irregularity:
        """Measured profile: r [m] at strictly increasing x [m] (at least 4 points),
        interpolated by ``method`` "cubic" (CubicSpline) or "pchip"; X outside the samples
        raises a ValueError naming the covered range."""
        xa = v.positions("Irregularity.samples.x", x, -math.inf, math.inf)
        ra = v.positions("Irregularity.samples.r", r, -math.inf, math.inf)
        return cls((SampledProfile(tuple(xa.tolist()), tuple(ra.tolist()), method),))

    # realisations ----------------------------------------------------------------------------
    @property
    def n_random(self) -> int:
        """Number of random parts (:class:`RandomProfile`) [-]."""
        return sum(isinstance(p, RandomProfile) for p in self.parts)

    def reseeded(self, seed: int) -> Irregularity:
        """The same profile with every random part drawn afresh: realisation ``seed`` of the
        ensemble (the Monte Carlo axis of :func:`trackwheel.sweep`).

        The first random part gets ``seed`` itself, so ``Irregularity.random(S, seed=s)`` and
        ``Irregularity.random(S, seed=0).reseeded(s)`` are the same profile; random part k >= 1
        (in the order of ``parts``) gets ``derived_seed(seed, k)``, so the parts stay
        independent of each other. Deterministic parts (sines, joints, samples) are kept. Raises
        ValueError if the profile has no random part (nothing to re-seed)."""
        seed = v.integer("seed", seed, low=0, high=MAX_SEED)
        if self.n_random == 0:
            raise ValueError("Irregularity.reseeded: the profile has no random part to re-seed "
                             "(build one with Irregularity.random)")
        parts, k = [], 0
        for p in self.parts:
            if isinstance(p, RandomProfile):
                p = replace(p, seed=seed if k == 0 else derived_seed(seed, k))
                k += 1
            parts.append(p)
        return Irregularity(tuple(parts))

    # algebra and evaluation ------------------------------------------------------------------
    def __add__(self, other):
        if not isinstance(other, Irregularity):
            return NotImplemented
        return Irregularity(self.parts + other.parts)

    def __radd__(self, other):
        # sum([...]) starts from 0: a smooth rail
        if isinstance(other, int) and other == 0:
            return self
        return NotImplemented

    def _sum(self, x, method: str) -> np.ndarray:
        xa = finite_x(x)
        out = np.zeros(xa.shape)
        for p in self.parts:
            out = out + getattr(p, method)(xa)
        return out

    def __call__(self, x) -> np.ndarray:
        """r(X) [m] at X [m] (array of X's shape)."""
        return self._sum(x, "value")

    def slope(self, x) -> np.ndarray:
        """dr/dX [-] at X [m]."""
        return self._sum(x, "slope")

    def curvature(self, x) -> np.ndarray:
        """d^2 r/dX^2 [1/m] at X [m]."""
        return self._sum(x, "curvature")

    def __repr__(self) -> str:
        return "Irregularity(" + " + ".join(repr(p) for p in self.parts) + ")"

    # sampling ------------------------------------------------------------------------------
    def grid(self, x_min: float, x_max: float, dx: float) -> np.ndarray:
        """Uniform X [m] from x_min to x_max inclusive, spacing <= dx (n = ceil(span/dx) + 1)."""
        return np.linspace(x_min, x_max, grid_size(x_min, x_max, dx))

    def table(self, x_min: float, x_max: float, dx: float, *, half_width: float | None = None
              ) -> tuple[float, float, np.ndarray]:
        """(x0 [m], dx [m], r [m]) on the uniform grid :meth:`grid`: x_i = x0 + i dx, i = 0..n-1,
        with dx = (x_max - x_min)/(n - 1) <= the requested dx. This is how the kernel receives
        the profile (it interpolates cubically between the samples).

        ``half_width`` a [m] (e.g. :func:`contact_half_width`): the values are the contact-
        filtered profile (:func:`contact_filter`), computed from samples on the grid extended
        by a on both sides, so every returned value averages the whole patch."""
        x = self.grid(x_min, x_max, dx)
        h = float(x[1] - x[0])
        if half_width is None:
            return float(x[0]), h, self(x)
        a = v.positive("half_width", half_width, "m")
        k = math.ceil(a / h * (1 - 1e-12)) + 1
        xe = x[0] + h * np.arange(-k, x.size + k)
        xf, rf = contact_filter(xe, self(xe), a)
        first = int(np.searchsorted(xf, x[0] - 0.5 * h))
        return float(x[0]), h, rf[first:first + x.size]

    def shortest_wavelength(self) -> float:
        """The shortest wavelength [m] the profile holds, to judge the contact filter
        (:func:`filter_matters`): lambda_min of a random part, a sine's wavelength, a joint's
        length (its cusp has content at all shorter wavelengths, falling like lambda^2), and
        twice the finest spacing of sampled data (their Nyquist wavelength); inf if empty."""
        out = math.inf
        for p in self.parts:
            if isinstance(p, RandomProfile):
                out = min(out, p.wavelengths[0])
            elif isinstance(p, SineProfile):
                out = min(out, p.wavelength)
            elif isinstance(p, DippedJoint):
                out = min(out, p.length)
            else:
                out = min(out, 2.0 * float(np.min(np.diff(p.x))))
        return out

    def psd(self, x_min: float, x_max: float, dx: float, *, nperseg: int | None = None
            ) -> tuple[np.ndarray, np.ndarray]:
        """Welch estimate of the one-sided PSD of r sampled on :meth:`grid`: (Omega [rad/m],
        S [m^2/(rad/m)]), Omega > 0. scipy.signal.welch (Hann window, 50 % overlap, mean
        removed per segment) gives S_f [m^2/(1/m)] over f = 1/lambda; S = S_f / (2 pi) at
        Omega = 2 pi f keeps the variance. ``nperseg`` default: 1/8 of the samples."""
        from scipy.signal import welch

        x = self.grid(x_min, x_max, dx)
        h = x[1] - x[0]
        if nperseg is None:
            nperseg = max(16, x.size // 8)
        nperseg = v.integer("nperseg", nperseg, low=16, high=x.size)
        f, s = welch(self(x), fs=1.0 / h, window="hann", nperseg=nperseg)
        return 2.0 * math.pi * f[1:], s[1:] / (2.0 * math.pi)

