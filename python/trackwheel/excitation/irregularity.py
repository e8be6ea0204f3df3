"""Rail profiles and wheel out-of-roundness: the excitation (docs: Model § Irregularities).

Sign conventions
----------------
- Rail profile r(X) [m]: height of the running surface above the rail's centre line at track
  coordinate X [m]; **positive r is a bump**, so a dipped joint is negative. The profile is
  fixed to the track.
- Wheel out-of-roundness Delta rho(psi) [m]: change of the wheel radius at wheel angle psi
  [rad], measured on the wheel from a mark and advancing with the rolling angle theta; it is
  periodic in 2 pi. **Negative Delta rho is a flat.** Convention for the kernel: the mark
  (psi = 0) is the wheel point in contact at rolling angle theta = 0, so the point in contact at
  theta is psi = theta, and a defect at ``at_angle`` psi_f meets the rail at
  theta = psi_f + 2 pi k: every 2 pi rho0 of *rolled* distance.

Every object here is a frozen, hashable, picklable dataclass whose fields are plain numbers,
strings and tuples (the recipe, never sampled arrays of a generated profile), so
``dataclasses.asdict`` of a scene that carries one is JSON-able and stable: the sweep store's
case hash accounts for it, and the same recipe gives bit-identical values in any process.

How the kernel receives them: ``Irregularity.table(x_min, x_max, dx)`` and
``WheelFlat/Polygon.table(radius, n)`` sample them on uniform grids for cubic interpolation.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np

from . import _validate as v
from .spectra import ChinaSpectrum, FRASpectrum, GermanSpectrum, ThirdOctaveSpectrum

_SPECTRA = (FRASpectrum, GermanSpectrum, ChinaSpectrum, ThirdOctaveSpectrum)
#: Default number of spectral-sum components per decade of Omega [-].
COMPONENTS_PER_DECADE = 100
_CHUNK = 2048  # X values evaluated at once (bounds the (chunk, n) work array)
#: :meth:`Irregularity.spline_table` fits the spline this many intervals at a time [-], each
#: chunk extended by SPLINE_OVERLAP knots at both sides [-]
SPLINE_CHUNK = 1 << 16
SPLINE_OVERLAP = 40


def _x(x) -> np.ndarray:
    a = np.asarray(x, dtype=float)
    if not np.all(np.isfinite(a)):
        raise ValueError("X must be finite [m]")
    return a


def derived_seed(seed: int, k: int) -> int:
    """Seed [-] of random part k >= 1 in realisation ``seed`` (:meth:`Irregularity.reseeded`):
    the first 63 bits of ``numpy.random.SeedSequence([seed, k])``'s first 64-bit word. NumPy
    fixes SeedSequence's output across versions and platforms, and distinct (seed, k) pairs
    give unrelated streams, so no two parts of one realisation, nor the same part of two
    realisations, share a generator."""
    word = np.random.SeedSequence([int(seed), int(k)]).generate_state(1, np.uint64)[0]
    return int(word) & (2**63 - 1)


# ---------------------------------------------------------------------------------------------
# rail-profile components
@dataclass(frozen=True)
class RandomProfile:
    """r(X) = sum_n a_n cos(Omega_n X + phi_n), a_n = sqrt(2 S(Omega_n) dOmega_n) (§10).

    Omega grid: the band [Omega_lo, Omega_hi] = [2 pi / lambda_max, 2 pi / lambda_min] is cut
    into ``n`` log-spaced sub-bands of width dOmega_n, and Omega_n is drawn uniformly inside
    sub-band n. Log spacing gives every octave the same number of components (spectra fall
    like Omega^-2..-4 over decades); the random sub-band frequencies make the sum aperiodic
    (a uniform grid would repeat every 2 pi / dOmega) and make the expected variance exactly
    the integral of S over the band (stratified sampling: E[S(Omega_n)] dOmega_n =
    integral of S over sub-band n). phi_n uniform on [0, 2 pi). Omega_n then phi_n are drawn
    from ``numpy.random.default_rng(seed)``.
    """

    spectrum: object  #: a trackwheel.spectra spectrum
    seed: int  #: seed of numpy.random.default_rng [-]
    wavelengths: tuple[float, float]  #: (lambda_min, lambda_max) generated [m]
    n: int  #: number of components [-]
    kind: str = field(default="random", init=False)

    @property
    def omega_band(self) -> tuple[float, float]:
        """(Omega_lo, Omega_hi) [rad/m] generated."""
        return (2.0 * math.pi / self.wavelengths[1], 2.0 * math.pi / self.wavelengths[0])

    def components(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(Omega_n [rad/m], a_n [m], phi_n [rad]), each shape (n,)."""
        return _components(self)

    def _sum(self, x, power: int, trig) -> np.ndarray:
        w, a, ph = self.components()
        coef = a * w**power
        x = _x(x)
        flat = x.ravel()
        out = np.empty(flat.size)
        for i in range(0, flat.size, _CHUNK):
            xs = flat[i:i + _CHUNK]
            out[i:i + _CHUNK] = (coef * trig(np.multiply.outer(xs, w) + ph)).sum(axis=1)
        return out.reshape(x.shape)

    def value(self, x) -> np.ndarray:
        return self._sum(x, 0, np.cos)

    def slope(self, x) -> np.ndarray:
        return -self._sum(x, 1, np.sin)

    def curvature(self, x) -> np.ndarray:
        return -self._sum(x, 2, np.cos)

    def __repr__(self) -> str:
        return (f"RandomProfile({self.spectrum.name!r}, seed={self.seed}, "
                f"wavelengths={self.wavelengths} m, n={self.n})")


@lru_cache(maxsize=256)
def _components(p: RandomProfile):
    rng = np.random.default_rng(p.seed)
    lo, hi = p.omega_band
    edges = np.geomspace(lo, hi, p.n + 1)
    width = np.diff(edges)
    omega = edges[:-1] + width * rng.random(p.n)
    phase = 2.0 * math.pi * rng.random(p.n)
    amp = np.sqrt(2.0 * p.spectrum(omega) * width)
    for arr in (omega, amp, phase):
        arr.flags.writeable = False  # cached: shared by every caller
    return omega, amp, phase


@dataclass(frozen=True)
class SineProfile:
    """Sine corrugation r = a sin(2 pi X / lambda + phase)."""

    wavelength: float  #: lambda [m]
    amplitude: float  #: a [m]
    phase: float = 0.0  #: [rad]
    kind: str = field(default="sine", init=False)

    def _arg(self, x):
        return 2.0 * math.pi * _x(x) / self.wavelength + self.phase

    def value(self, x):
        return self.amplitude * np.sin(self._arg(x))

    def slope(self, x):
        return self.amplitude * (2.0 * math.pi / self.wavelength) * np.cos(self._arg(x))

    def curvature(self, x):
        return -self.amplitude * (2.0 * math.pi / self.wavelength) ** 2 * np.sin(self._arg(x))


@dataclass(frozen=True)
class DippedJoint:
    """Dipped joint or weld (Kabo 2006), xi = X - at:
    r = -d (1 - cos(pi xi / l)) for 0 <= xi <= l/2, -d (1 + cos(pi xi / l)) for l/2 < xi <= l,
    0 elsewhere: a V-shaped dip of depth d (r = -d at the middle, a cusp with slope -+pi d / l).
    """

    depth: float  #: d > 0 [m]; the surface goes down to -d
    length: float  #: l [m]
    at: float  #: X_j, start of the joint [m]
    kind: str = field(default="dipped_joint", init=False)

    def _parts(self, x):
        xi = _x(x) - self.at
        k = math.pi / self.length
        inside = (xi >= 0.0) & (xi <= self.length)
        first = xi <= 0.5 * self.length
        sign = np.where(first, -1.0, 1.0)  # 1 -/+ cos
        return xi, k, inside, sign

    def value(self, x):
        xi, k, inside, sign = self._parts(x)
        return np.where(inside, -self.depth * (1.0 + sign * np.cos(k * xi)), 0.0)

    def slope(self, x):
        xi, k, inside, sign = self._parts(x)
        return np.where(inside, self.depth * k * sign * np.sin(k * xi), 0.0)

    def curvature(self, x):
        xi, k, inside, sign = self._parts(x)
        return np.where(inside, self.depth * k**2 * sign * np.cos(k * xi), 0.0)


@dataclass(frozen=True)
class SampledProfile:
    """Measured r at points x, interpolated (``method`` "cubic": scipy CubicSpline, not-a-knot;
    "pchip": scipy PchipInterpolator, no overshoot). Evaluating outside [x[0], x[-1]] raises."""

    x: tuple[float, ...]  #: sample positions, strictly increasing [m]
    r: tuple[float, ...]  #: r at x [m]
    method: str = "cubic"
    kind: str = field(default="samples", init=False)

    def _spline(self, x, nu: int):
        xa = _x(x)
        lo, hi = self.x[0], self.x[-1]
        if xa.size and (xa.min() < lo or xa.max() > hi):
            raise ValueError(f"Irregularity.samples covers X in [{lo}, {hi}] m; the profile was "
                             f"asked for X in [{xa.min()}, {xa.max()}] m (outside the samples)")
        return _interpolant(self)(xa, nu)

    def value(self, x):
        return self._spline(x, 0)

    def slope(self, x):
        return self._spline(x, 1)

    def curvature(self, x):
        return self._spline(x, 2)

    def __repr__(self) -> str:
        digest = hashlib.sha256(np.asarray(self.x + self.r).tobytes()).hexdigest()[:12]
        return (f"SampledProfile({len(self.x)} samples on [{self.x[0]}, {self.x[-1]}] m, "
                f"method={self.method!r}, sha256={digest})")


@lru_cache(maxsize=32)
def _interpolant(p: SampledProfile):
    from scipy.interpolate import CubicSpline, PchipInterpolator

    cls = CubicSpline if p.method == "cubic" else PchipInterpolator
    return cls(np.asarray(p.x), np.asarray(p.r))


_PARTS = (RandomProfile, SineProfile, DippedJoint, SampledProfile)


# ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Irregularity:
    """A rail profile r(X) [m], positive = bump: a sum of parts (build with the classmethods
    and ``+``). Call it for r, ``.slope`` for dr/dX [-], ``.curvature`` for d^2r/dX^2 [1/m];
    all analytic (sampled data: from the interpolant) and vectorised over X [m]."""

    parts: tuple = ()

    def __post_init__(self):
        parts = tuple(self.parts)
        for p in parts:
            if not isinstance(p, _PARTS):
                raise TypeError(f"Irregularity.parts must hold profile parts "
                                f"({', '.join(c.__name__ for c in _PARTS)}), "
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
        seed = v.integer("seed", seed, low=0, high=2**63 - 1)
        w_lo, w_hi = spectrum.band
        valid = (2.0 * math.pi / w_hi, 2.0 * math.pi / w_lo)
        if wavelengths is None:
            wavelengths = valid
        lam = v.positions("wavelengths", wavelengths, 0.0, math.inf)
        if lam.size != 2 or not 0.0 < lam[0] < lam[1]:
            raise ValueError(f"wavelengths = {tuple(lam)} must be (lambda_min, lambda_max) "
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
        """Sine corrugation r = a sin(2 pi X / lambda + phase): ``wavelength`` [m] > 0,
        ``amplitude`` a [m] >= 0, ``phase`` [rad]."""
        return cls((SineProfile(v.positive("wavelength", wavelength, "m"),
                                v.number("amplitude", amplitude, low=0.0, unit="m"),
                                v.number("phase", phase, unit="rad")),))

    @classmethod
    def dipped_joint(cls, depth: float, length: float, at: float) -> Irregularity:
        """Dipped joint (Kabo form, :class:`DippedJoint`): ``depth`` d > 0 [m] (the surface
        goes to r = -d), ``length`` l > 0 [m], starting at X = ``at`` [m]."""
        return cls((DippedJoint(v.positive("depth", depth, "m"),
                                v.positive("length", length, "m"),
                                v.number("at", at, unit="m")),))

    @classmethod
    def samples(cls, x, r, method: str = "cubic") -> Irregularity:
        """Measured profile: r [m] at strictly increasing x [m] (at least 4 points),
        interpolated by ``method`` "cubic" (CubicSpline) or "pchip"; X outside the samples
        raises a ValueError naming the covered range."""
        xa = v.positions("x", x, -math.inf, math.inf)
        ra = v.positions("r", r, -math.inf, math.inf)
        if xa.size != ra.size:
            raise ValueError(f"x ({xa.size}) and r ({ra.size}) must have the same length")
        if xa.size < 4:
            raise ValueError(f"x has {xa.size} samples; at least 4 are needed")
        if np.any(np.diff(xa) <= 0.0):
            raise ValueError("x must be strictly increasing [m]")
        v.choice("method", method, {"cubic", "pchip"})
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
        seed = v.integer("seed", seed, low=0, high=2**63 - 1)
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
        xa = _x(x)
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
        return np.linspace(x_min, x_max, self._grid_size(x_min, x_max, dx))

    @staticmethod
    def _grid_size(x_min: float, x_max: float, dx: float) -> int:
        x_min = v.number("x_min", x_min, unit="m")
        x_max = v.number("x_max", x_max, low=x_min, low_open=True, unit="m")
        dx = v.positive("dx", dx, "m")
        n = math.ceil((x_max - x_min) / dx * (1 - 1e-12)) + 1
        if n > 50_000_000:
            raise ValueError(f"dx = {dx} m gives {n} points on [{x_min}, {x_max}] m; "
                             "allowed at most 5e7")
        return n

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

    def spline_table(self, x_min: float, x_max: float, dx: float, *,
                     chunk: int = SPLINE_CHUNK) -> tuple[float, float, np.ndarray, float, float]:
        """The kernel's rail profile: the not-a-knot cubic spline through the samples of
        :meth:`table` (unfiltered) at the knots X_i = x0 + i h, as (x0 [m], h [m], c, worst
        curvature [1/m], its X [m]) with c of shape (4, n - 1) holding scipy's PPoly
        coefficients (highest power first) of each interval, and the largest r'' of the spline
        at its knots (where a cubic's r'' is extreme on a grid this fine) and where it is.
        Assembled from :meth:`spline_chunks`."""
        x0, h, n = self.spline_grid(x_min, x_max, dx)
        c = np.empty((4, n - 1))
        worst, at = -math.inf, x0
        for i0, cc, w, x in self.spline_chunks(x_min, x_max, dx, chunk=chunk):
            c[:, i0:i0 + cc.shape[1]] = cc
            if w > worst:
                worst, at = w, x
        return x0, h, c, worst, at

    def spline_grid(self, x_min: float, x_max: float, dx: float) -> tuple[float, float, int]:
        """(x0 [m], h [m], n) of :meth:`spline_table`'s knots X_i = x0 + i h, i < n."""
        n = self._grid_size(x_min, x_max, dx)
        x_min, x_max = float(x_min), float(x_max)
        return x_min, (x_min + (x_max - x_min) / (n - 1)) - x_min, n

    def spline_chunks(self, x_min: float, x_max: float, dx: float, *,
                      chunk: int = SPLINE_CHUNK):
        """:meth:`spline_table` ``chunk`` intervals at a time, for building the table without
        holding more than one chunk: yields (i0, c, worst [1/m], its X [m]) per chunk, c of
        shape (4, m) the coefficients of intervals i0..i0 + m - 1, worst the largest r'' at the
        chunk's knots (and at the last knot, in the last chunk).

        Each chunk's spline is fitted on the chunk extended by SPLINE_OVERLAP knots at both
        sides (not-a-knot at the profile's true ends). A cubic spline's dependence on a far
        sample decays by a factor 2 - sqrt(3) = 0.27 per knot (the tridiagonal system's
        decay), 0.27^40 < 1e-22 over the overlap, so the chunks join to round-off of the one
        spline through all samples; with a single chunk it is that spline, bit for bit. The
        samples are those of :meth:`table`, bit for bit (the same grid X_i = x_min + i
        (x_max - x_min)/(n - 1))."""
        from scipy.interpolate import CubicSpline

        x_min, h, n = self.spline_grid(x_min, x_max, dx)
        step = (float(x_max) - x_min) / (n - 1)
        chunk = v.integer("chunk", chunk, low=1)
        for i0 in range(0, n - 1, chunk):
            i1 = min(i0 + chunk, n - 1)  # intervals [i0, i1), knots i0..i1
            j0, j1 = max(0, i0 - SPLINE_OVERLAP), min(n, i1 + 1 + SPLINE_OVERLAP)
            idx = np.arange(j0, j1)
            xs = idx * step + x_min  # np.linspace's arithmetic, its last value exact
            if j1 == n:
                xs[-1] = x_max
            knots = x_min + h * idx
            spline = CubicSpline(knots, self(xs))
            c = spline.c[:, i0 - j0:i1 - j0]
            # r'' at a knot is 2 c_2 of its interval, at the last knot the last interval's end
            k = int(np.argmax(c[1]))
            worst, at = float(2.0 * c[1, k]), float(knots[i0 - j0 + k])
            if i1 == n - 1:
                end = float(spline(knots[-1], 2))
                if end > worst:
                    worst, at = end, float(knots[-1])
            yield i0, c, worst, at
            del spline, c  # one chunk's spline alive at a time

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


# ---------------------------------------------------------------------------------------------
# contact filter
def hertz_half_width(load: float, radius: float, effective_modulus: float,
                     contact_length: float | None = None) -> float:
    """Half-length a [m] of the Hertz contact patch along the track (Johnson 1985, ch. 4).

    ``contact_length=None``: circular contact of a sphere of radius R on a flat, the geometry
    of trackwheel's Hertz constant C_H = 4/3 E* sqrt(R): a = (3 P R / (4 E*))^(1/3)
    (Johnson eq. 4.22). With a ``contact_length`` b [m]: line contact of a cylinder,
    a = sqrt(4 P R / (pi b E*)) (Johnson eq. 4.43). P = ``load`` [N], R = ``radius`` [m],
    E* = ``effective_modulus`` [Pa] (1/E* = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2).
    """
    p = v.positive("load", load, "N")
    r = v.positive("radius", radius, "m")
    e = v.positive("effective_modulus", effective_modulus, "Pa")
    if contact_length is None:
        return (3.0 * p * r / (4.0 * e)) ** (1.0 / 3.0)
    b = v.positive("contact_length", contact_length, "m")
    return math.sqrt(4.0 * p * r / (math.pi * b * e))


def contact_half_width(scene) -> float:
    """Hertz half-length a [m] of the static contact patch of a :class:`trackwheel.Scene`:
    :func:`hertz_half_width` at P = F + M g, R = rho0, the scene's E* (circular contact, the
    geometry of its Hertz constant)."""
    return hertz_half_width(scene.static_load, scene.wheel.radius, scene.effective_modulus)


def contact_filter(x, r, half_width: float) -> tuple[np.ndarray, np.ndarray]:
    """Patch-length average of a sampled profile (docs: Model § Irregularities, the 1D form):
    r_f(X) = (1 / 2a) integral_{X-a}^{X+a} r dX', a = ``half_width`` [m].

    ``x`` [m] uniform, increasing; ``r`` [m]. The integral is the trapezoid rule on the samples
    (exact for r linear between samples). Returns (x_f, r_f) at the samples whose whole window
    lies inside [x[0], x[-1]].
    """
    xa = v.positions("x", x, -math.inf, math.inf)
    ra = v.positions("r", r, -math.inf, math.inf)
    a = v.positive("half_width", half_width, "m")
    if xa.size != ra.size or xa.size < 2:
        raise ValueError("x and r must have the same length, at least 2")
    h = np.diff(xa)
    if np.any(h <= 0.0) or np.ptp(h) > 1e-9 * h.mean():
        raise ValueError("x must be uniformly spaced and increasing [m]")
    if 2.0 * a > xa[-1] - xa[0]:
        raise ValueError(f"half_width = {a} m: the window 2a is longer than the samples "
                         f"({xa[-1] - xa[0]} m)")
    cum = np.concatenate(([0.0], np.cumsum(0.5 * (ra[1:] + ra[:-1]) * h)))
    keep = (xa - a >= xa[0]) & (xa + a <= xa[-1])
    xf = xa[keep]
    # the primitive is piecewise quadratic: interpolate it exactly within the cell
    return xf, (_primitive(xa, ra, cum, xf + a) - _primitive(xa, ra, cum, xf - a)) / (2.0 * a)


def _primitive(x, r, cum, xq):
    """integral_{x0}^{xq} of the piecewise-linear interpolant of r."""
    i = np.clip(np.searchsorted(x, xq, side="right") - 1, 0, x.size - 2)
    t = xq - x[i]
    slope = (r[i + 1] - r[i]) / (x[i + 1] - x[i])
    return cum[i] + r[i] * t + 0.5 * slope * t**2


def filter_attenuation(wavelength, half_width: float) -> np.ndarray:
    """Transfer function of the patch average at ``wavelength`` [m]:
    H = sin(Omega a) / (Omega a), Omega = 2 pi / lambda, a = ``half_width`` [m] (H = 1: no
    effect; it changes sign past its first zero at lambda = 2a)."""
    lam = v.positions("wavelength", wavelength, 0.0, math.inf)
    a = v.positive("half_width", half_width, "m")
    if np.any(lam <= 0.0):
        raise ValueError("wavelength must be > 0 m")
    return np.sinc(2.0 * a / lam)  # np.sinc(u) = sin(pi u)/(pi u), pi u = Omega a


def filter_matters(shortest_wavelength: float, half_width: float, threshold_db: float = 1.0
                   ) -> bool:
    """True when the patch average attenuates the shortest wavelength in the profile by more
    than ``threshold_db`` [dB] (-20 log10 |H| > threshold): then the contact filter should be
    used. The attenuation grows monotonically with 1/lambda up to the first zero (lambda = 2a)."""
    thr = v.positive("threshold_db", threshold_db, "dB")
    lam = v.positive("shortest_wavelength", shortest_wavelength, "m")
    if lam <= 2.0 * v.positive("half_width", half_width, "m"):
        return True
    h = abs(float(filter_attenuation(lam, half_width)[0]))
    return -20.0 * math.log10(h) > thr


# ---------------------------------------------------------------------------------------------
# wheel out-of-roundness
def _psi(psi, at: float) -> np.ndarray:
    """Angle from the defect centre, wrapped to [-pi, pi) [rad]."""
    p = np.asarray(psi, dtype=float)
    if not np.all(np.isfinite(p)):
        raise ValueError("psi must be finite [rad]")
    return np.mod(p - at + math.pi, 2.0 * math.pi) - math.pi


def _defect_table(defect, radius: float, n: int) -> tuple[float, float, np.ndarray]:
    n = v.integer("n", n, low=8, high=10_000_000)
    dpsi = 2.0 * math.pi / n
    return 0.0, dpsi, defect.delta_rho(dpsi * np.arange(n), radius)


@dataclass(frozen=True)
class WheelFlat:
    """A wheel flat of chord length L_f centred at wheel angle ``at_angle`` [rad].

    New flat (a chord): Delta rho = rho0 cos(phi_f) / cos(psi) - rho0 for |psi| <= phi_f =
    asin(L_f / (2 rho0)), 0 elsewhere; depth rho0 (1 - cos phi_f) ~ L_f^2 / (8 rho0).
    Rounded flat (``rounded=True``, Wu & Thompson 2002): with s = rho0 psi,
    Delta rho = -(d/2)(1 + cos(pi s / (L_f/2))) for |s| <= L_f/2, depth d = ``depth`` or, when
    None, L_f^2 / (16 rho0). psi is measured from ``at_angle`` and wrapped to [-pi, pi).
    """

    length: float  #: L_f, chord (new) or rounded length [m]
    rounded: bool = False
    at_angle: float = 0.0  #: wheel angle of the flat's centre [rad]
    depth: float | None = None  #: rounded flat's depth d [m]; None: L_f^2 / (16 rho0)
    kind: str = field(default="wheel_flat", init=False)

    def __post_init__(self):
        v.positive("WheelFlat.length", self.length, "m")
        v.boolean("WheelFlat.rounded", self.rounded)
        v.number("WheelFlat.at_angle", self.at_angle, unit="rad")
        if self.depth is not None:
            if not self.rounded:
                raise ValueError("WheelFlat.depth is only for a rounded flat (rounded=True); "
                                 "a new flat's depth follows from its length")
            v.positive("WheelFlat.depth", self.depth, "m")

    def check(self, radius: float) -> None:
        """Raise unless the flat fits a wheel of ``radius`` [m] (L_f < 2 rho0)."""
        r = v.positive("radius", radius, "m")
        if self.length >= 2.0 * r:
            raise ValueError(f"WheelFlat.length = {self.length} m must be shorter than the "
                             f"wheel's diameter; allowed range (0, {2.0 * r}) m")

    def _rounded(self, radius):
        d = self.depth if self.depth is not None else self.length**2 / (16.0 * radius)
        return d, 2.0 * math.pi / self.length  # s-wavenumber of cos(pi s / (L/2))

    def _terms(self, psi, radius, order: int) -> np.ndarray:
        self.check(radius)
        p = _psi(psi, self.at_angle)
        if self.rounded:
            d, k = self._rounded(radius)
            s = radius * p
            inside = np.abs(s) <= 0.5 * self.length
            c = (k * radius) ** order
            trig = (np.cos, lambda u: -np.sin(u), lambda u: -np.cos(u))[order]
            return np.where(inside, -0.5 * d * (order == 0) - 0.5 * d * c * trig(k * s), 0.0)
        phi = math.asin(self.length / (2.0 * radius))
        inside = np.abs(p) <= phi
        cp = np.cos(np.where(inside, p, 0.0))
        sp = np.sin(np.where(inside, p, 0.0))
        h = radius * math.cos(phi)
        val = (h / cp - radius, h * sp / cp**2, h * (1.0 + sp**2) / cp**3)[order]
        return np.where(inside, val, 0.0)

    def delta_rho(self, psi, radius: float) -> np.ndarray:
        """Delta rho [m] at wheel angle psi [rad] on a wheel of radius rho0 [m]."""
        return self._terms(psi, radius, 0)

    def delta_rho_dpsi(self, psi, radius: float) -> np.ndarray:
        """d Delta rho / d psi [m/rad]."""
        return self._terms(psi, radius, 1)

    def delta_rho_dpsi2(self, psi, radius: float) -> np.ndarray:
        """d^2 Delta rho / d psi^2 [m/rad^2] (a new flat's slope jumps at its edges)."""
        return self._terms(psi, radius, 2)

    def table(self, radius: float, n: int) -> tuple[float, float, np.ndarray]:
        """(psi0 = 0 [rad], dpsi = 2 pi / n [rad], Delta rho [m] at psi0 + i dpsi, i < n):
        one revolution, periodic (the value at 2 pi is the first one)."""
        return _defect_table(self, radius, n)


@dataclass(frozen=True)
class Polygon:
    """Polygonal (out-of-round) wheel: Delta rho = a cos(m psi + phase)."""

    order: int  #: m, harmonics per revolution [-] >= 1
    amplitude: float  #: a [m] >= 0
    phase: float = 0.0  #: [rad]
    kind: str = field(default="polygon", init=False)

    def __post_init__(self):
        v.integer("Polygon.order", self.order, low=1, high=10_000)
        v.number("Polygon.amplitude", self.amplitude, low=0.0, unit="m")
        v.number("Polygon.phase", self.phase, unit="rad")

    def check(self, radius: float) -> None:
        """Raise unless the amplitude is smaller than the radius [m]."""
        r = v.positive("radius", radius, "m")
        if self.amplitude >= r:
            raise ValueError(f"Polygon.amplitude = {self.amplitude} m must be smaller than the "
                             f"wheel radius; allowed range [0, {r}) m")

    def _u(self, psi):
        p = np.asarray(psi, dtype=float)
        if not np.all(np.isfinite(p)):
            raise ValueError("psi must be finite [rad]")
        return self.order * p + self.phase

    def delta_rho(self, psi, radius: float) -> np.ndarray:
        """Delta rho [m] at wheel angle psi [rad] (``radius`` [m] only checked)."""
        self.check(radius)
        return self.amplitude * np.cos(self._u(psi))

    def delta_rho_dpsi(self, psi, radius: float) -> np.ndarray:
        """d Delta rho / d psi [m/rad]."""
        self.check(radius)
        return -self.amplitude * self.order * np.sin(self._u(psi))

    def delta_rho_dpsi2(self, psi, radius: float) -> np.ndarray:
        """d^2 Delta rho / d psi^2 [m/rad^2]."""
        self.check(radius)
        return -self.amplitude * self.order**2 * np.cos(self._u(psi))

    def table(self, radius: float, n: int) -> tuple[float, float, np.ndarray]:
        """(0, 2 pi / n, Delta rho at i 2 pi / n, i < n) [rad, rad, m], periodic."""
        return _defect_table(self, radius, n)


WHEEL_DEFECTS = (WheelFlat, Polygon)
