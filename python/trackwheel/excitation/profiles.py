"""The parts of a rail profile r(X) [m] (docs: Model § Irregularities): a random profile from a
spectrum, a sine corrugation, a dipped joint and measured samples.

Sign convention: r(X) is the height of the running surface above the rail's centre line at
track coordinate X [m]; **positive r is a bump**, so a dipped joint is negative. The profile
is fixed to the track.

Every part is a frozen, hashable, picklable dataclass whose fields are plain numbers, strings
and tuples (the recipe, never sampled arrays of a generated profile), so ``dataclasses.asdict``
of a scene that carries one is JSON-able and stable: the sweep store's case hash accounts for
it, and the same recipe gives bit-identical values in any process. Each part evaluates
``value``, ``slope`` and ``curvature`` at X [m]; :class:`~trackwheel.Irregularity` sums them.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ..base import validate as v
from ..base.limits import MAX_PROFILE_SLOPE, MIN_SAMPLE_SPACING, ranges_doc

#: the hint of a length given in mm where metres are meant
_IN_METRES = "rail profiles are in m: 1 mm is 1e-3"

_CHUNK = 2048  # X values evaluated at once (bounds the (chunk, n) work array)


def finite_x(x) -> np.ndarray:
    """X [m] as a float array, checked finite."""
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
        x = finite_x(x)
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

    def __post_init__(self):
        lam = v.field("Irregularity.sine.wavelength", self.wavelength)
        a = v.field("Irregularity.sine.amplitude", self.amplitude, hint=_IN_METRES)
        v.number("Irregularity.sine.phase", self.phase, unit="rad")
        check_slope("Irregularity.sine", 2.0 * math.pi * a / lam,
                    f"amplitude {a:g} m on wavelength {lam:g} m", "2 pi a / lambda",
                    "a longer wavelength or a smaller amplitude")

    def _arg(self, x):
        return 2.0 * math.pi * finite_x(x) / self.wavelength + self.phase

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

    def __post_init__(self):
        d = v.field("Irregularity.dipped_joint.depth", self.depth, hint=_IN_METRES)
        length = v.field("Irregularity.dipped_joint.length", self.length)
        v.number("Irregularity.dipped_joint.at", self.at, unit="m")
        check_slope("Irregularity.dipped_joint", math.pi * d / length,
                    f"depth {d:g} m over length {length:g} m", "pi d / l",
                    "a longer joint or a shallower dip")

    def _parts(self, x):
        xi = finite_x(x) - self.at
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

    def __post_init__(self):
        xa = v.positions("Irregularity.samples.x", self.x, -math.inf, math.inf)
        ra = v.positions("Irregularity.samples.r", self.r, -math.inf, math.inf)
        for value in (xa.min(), xa.max()):
            v.field("Irregularity.samples.x", float(value))
        for value in (ra.min(), ra.max()):
            v.field("Irregularity.samples.r", float(value), hint=_IN_METRES)
        if xa.size != ra.size:
            raise ValueError(f"Irregularity.samples: x ({xa.size}) and r ({ra.size}) must have "
                             "the same length")
        if xa.size < 4:
            raise ValueError(f"Irregularity.samples.x has {xa.size} samples; at least 4 are "
                             "needed")
        gaps = np.diff(xa)
        if np.any(gaps <= 0.0):
            raise ValueError("Irregularity.samples.x must be strictly increasing [m]")
        if gaps.min() < MIN_SAMPLE_SPACING:
            raise ValueError(f"Irregularity.samples.x: samples {gaps.min():.3g} m apart; "
                             f"allowed at least {MIN_SAMPLE_SPACING:g} m apart")
        v.choice("Irregularity.samples.method", self.method, {"cubic", "pchip"})

    def _spline(self, x, nu: int):
        xa = finite_x(x)
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


def check_slope(name: str, slope: float, what: str, formula: str, advice: str) -> None:
    """ValueError unless a profile's steepest slope ``slope`` [-] is at most
    MAX_PROFILE_SLOPE."""
    if slope > MAX_PROFILE_SLOPE:
        raise ValueError(f"{name}: {what} rises at a slope of {slope:.3g} ({formula}); allowed "
                         f"at most {MAX_PROFILE_SLOPE:g}: {advice} (amplitudes and depths are "
                         "in m: 1 mm is 1e-3)")


SineProfile.__doc__ += ranges_doc("Irregularity.sine")
DippedJoint.__doc__ += ranges_doc("Irregularity.dipped_joint")
SampledProfile.__doc__ += ranges_doc("Irregularity.samples") + (
    f"    and the samples at least MIN_SAMPLE_SPACING = {MIN_SAMPLE_SPACING:g} m apart.\n")

#: the rail-profile part types an Irregularity may hold
PARTS = (RandomProfile, SineProfile, DippedJoint, SampledProfile)
