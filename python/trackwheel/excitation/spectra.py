"""Published rail-irregularity spectra as one-sided PSDs in SI units (docs: Model § Irregularities).

Every spectrum here is a frozen, picklable value that is called with the spatial angular
frequency Omega = 2 pi / lambda [rad/m] and returns S(Omega) [m^2/(rad/m)], **one-sided**:
the variance of the profile is ``integral_0^inf S(Omega) dOmega`` [m^2]. Each carries its
validity band ``band = (Omega_min, Omega_max)`` [rad/m] and a ``name``; outside the band it is
still evaluated (the formula extends), but :meth:`trackwheel.Irregularity.random` refuses to
generate outside it.

Conversions, written out (the formulas are given as published, in their own units):

- US FRA (``fra``): S [cm^2/(rad/m)] x 1e-4 -> [m^2/(rad/m)].
- German high speed (``german``): published in m^2/(rad/m) already.
- China TB/T 3352-2014 (``china_hsr``): S(f) [mm^2/(1/m)] over f = 1/lambda [1/m]; the same
  variance over Omega = 2 pi f needs S(Omega) dOmega = S(f) df, so
  S(Omega) = S(f = Omega / 2 pi) x 1e-6 / (2 pi).
- One-third-octave roughness levels (``third_octave``, ``iso3095``): band level
  L = 10 log10(r_rms^2 / r_0^2) [dB re r_0 = 1 um] is a band variance
  r_rms^2 = 1e-12 x 10^(L/10) [m^2], spread uniformly over the band's Omega width:
  S = r_rms^2 / (Omega_hi - Omega_lo) inside the band.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..base import validate as v

# FRA (Garg & Dukkipati 1984, Table 2.2 form, vertical profile): A_v [cm^2 rad/m] per class.
_FRA_AV = {1: 1.2107, 2: 1.0181, 3: 0.6816, 4: 0.5376, 5: 0.2095, 6: 0.0339}
_FRA_K = 0.25  # [-]
_FRA_OMEGA_C = 0.8245  # [rad/m]
# Garg & Dukkipati give the FRA spectra for wavelengths 1.524-304.8 m (5-1000 ft).
_FRA_LAMBDA = (1.524, 304.8)  # [m]

_GERMAN_AV = {"low": 4.032e-7, "high": 1.080e-6}  # [m rad]
_GERMAN_OMEGA_C = 0.8246  # [rad/m]
_GERMAN_OMEGA_R = 0.0206  # [rad/m]
# The German formula is a fit without published hard limits; trackwheel accepts 1-300 m,
# the range over which it is used in the high-speed literature.
_GERMAN_LAMBDA = (1.0, 300.0)  # [m]

# TB/T 3352-2014, ballastless track, vertical profile: S(f) = A / f^n [mm^2/(1/m)],
# f in [0.005, 0.5] 1/m, pieces split at these spatial frequencies [1/m].
_CHINA_SPLITS = (0.0187, 0.0474, 0.1533)
_CHINA_A = (1.0544e-5, 3.5588e-3, 1.9784e-2, 3.9488e-4)
_CHINA_N = (3.3891, 1.9271, 1.3643, 3.4516)
_CHINA_F = (0.005, 0.5)  # [1/m]

# ISO 3095:2013 rail-roughness limit: one-third-octave levels [dB re 1 um] at wavelengths [cm].
_ISO_LAMBDA_CM = (40, 31.5, 25, 20, 16, 12.5, 10, 8, 6.3, 5, 4, 3.15, 2.5, 2, 1.6, 1.25, 1, 0.8,
                  0.63, 0.5, 0.4, 0.315)
_ISO_LEVELS = (17.1, 15.0, 13.0, 11.0, 9.0, 7.0, 4.9, 2.9, 0.9, -1.1, -3.2, -5.0, -5.6, -6.2,
               -6.8, -7.4, -8.0, -8.6, -9.2, -9.8, -10.4, -11.0)

#: Ratio of a one-third-octave band's upper to its centre frequency (IEC 61260-1, base 10).
THIRD_OCTAVE_HALF = 10.0 ** 0.05


def _omega(omega) -> np.ndarray:
    w = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w <= 0.0):
        raise ValueError("Omega must be finite and > 0 rad/m; allowed range (0, inf) rad/m")
    return w


def _band(lambdas) -> tuple[float, float]:
    return (2.0 * math.pi / lambdas[1], 2.0 * math.pi / lambdas[0])


@dataclass(frozen=True)
class FRASpectrum:
    """US FRA vertical-profile spectrum (Garg & Dukkipati 1984), one-sided.

    S(Omega) = k A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)) [cm^2/(rad/m)], with
    k = 0.25, Omega_c = 0.8245 rad/m and A_v [cm^2 rad/m] = 1.2107, 1.0181, 0.6816, 0.5376,
    0.2095, 0.0339 for classes 1..6 (class 6 the best track); returned x 1e-4 in m^2/(rad/m).
    Taken as one-sided (variance = integral over Omega > 0), as Garg & Dukkipati use it; other
    published versions differ by factors 2 pi or 4. Valid for lambda = 1.524-304.8 m.
    """

    track_class: int  #: FRA track class, 1 (worst) .. 6 (best) [-]
    kind: str = field(default="fra", init=False)

    def __post_init__(self):
        v.integer("track_class", self.track_class, low=1, high=6)

    @property
    def name(self) -> str:
        return f"FRA class {self.track_class}"

    @property
    def band(self) -> tuple[float, float]:
        """(Omega_min, Omega_max) [rad/m] of validity."""
        return _band(_FRA_LAMBDA)

    def __call__(self, omega) -> np.ndarray:
        """S(Omega) [m^2/(rad/m)] at Omega [rad/m]."""
        w = _omega(omega)
        wc2 = _FRA_OMEGA_C**2
        return 1e-4 * _FRA_K * _FRA_AV[self.track_class] * wc2 / (w**2 * (w**2 + wc2))


@dataclass(frozen=True)
class GermanSpectrum:
    """German high-speed vertical-profile spectrum, one-sided, published in SI.

    S(Omega) = A_v Omega_c^2 / ((Omega^2 + Omega_r^2)(Omega^2 + Omega_c^2)) [m^2/(rad/m)],
    Omega_c = 0.8246 rad/m, Omega_r = 0.0206 rad/m, A_v = 4.032e-7 m rad ("low" disturbance)
    or 1.080e-6 m rad ("high"). Accepted band lambda = 1-300 m (trackwheel's choice: the fit
    has no published hard limits).
    """

    level: str  #: "low" or "high" disturbance
    kind: str = field(default="german", init=False)

    def __post_init__(self):
        v.choice("level", self.level, set(_GERMAN_AV))

    @property
    def name(self) -> str:
        return f"German high-speed, {self.level} disturbance"

    @property
    def band(self) -> tuple[float, float]:
        return _band(_GERMAN_LAMBDA)

    def __call__(self, omega) -> np.ndarray:
        """S(Omega) [m^2/(rad/m)] at Omega [rad/m]."""
        w = _omega(omega)
        wc2, wr2 = _GERMAN_OMEGA_C**2, _GERMAN_OMEGA_R**2
        return _GERMAN_AV[self.level] * wc2 / ((w**2 + wr2) * (w**2 + wc2))


@dataclass(frozen=True)
class ChinaSpectrum:
    """China high-speed ballastless track, vertical profile (TB/T 3352-2014), one-sided.

    S(f) = A / f^n [mm^2/(1/m)] over f = 1/lambda in [0.005, 0.5] 1/m, in four pieces split at
    f = 0.0187, 0.0474, 0.1533 1/m with A = 1.0544e-5, 3.5588e-3, 1.9784e-2, 3.9488e-4 and
    n = 3.3891, 1.9271, 1.3643, 3.4516. Returned as S(Omega) = S(Omega / 2 pi) x 1e-6 / (2 pi)
    [m^2/(rad/m)] (same variance over Omega = 2 pi f).
    """

    kind: str = field(default="china_hsr", init=False)

    @property
    def name(self) -> str:
        return "China HSR ballastless (TB/T 3352-2014)"

    @property
    def band(self) -> tuple[float, float]:
        return (2.0 * math.pi * _CHINA_F[0], 2.0 * math.pi * _CHINA_F[1])

    def __call__(self, omega) -> np.ndarray:
        """S(Omega) [m^2/(rad/m)] at Omega [rad/m]."""
        f = _omega(omega) / (2.0 * math.pi)
        piece = np.searchsorted(np.asarray(_CHINA_SPLITS), f, side="right")
        a = np.asarray(_CHINA_A)[piece]
        n = np.asarray(_CHINA_N)[piece]
        return a / f**n * 1e-6 / (2.0 * math.pi)


@dataclass(frozen=True)
class ThirdOctaveSpectrum:
    """A roughness spectrum given as one-third-octave band levels, one-sided, piecewise constant.

    ``levels_db[i]`` is L_i = 10 log10(r_rms,i^2 / r_0^2) [dB re r_0 = 1 um] of the band centred
    on wavelength ``wavelengths[i]`` [m]. The bands tile the Omega axis: an inner edge is the
    geometric mean of neighbouring centres Omega_i = 2 pi / lambda_i, the outer edges are
    Omega_centre x 10^(+-1/20) (IEC 61260-1 base-10 one-third octave). In band i
    S = 1e-12 x 10^(L_i/10) / (Omega_hi,i - Omega_lo,i) [m^2/(rad/m)], so the band's variance is
    exactly its level; outside the bands S = 0.
    """

    wavelengths: tuple[float, ...]  #: band-centre wavelengths [m], any order
    levels_db: tuple[float, ...]  #: band levels [dB re 1 um]
    label: str = "one-third-octave spectrum"
    kind: str = field(default="third_octave", init=False)

    def __post_init__(self):
        lam = v.positions("wavelengths", self.wavelengths, 0.0, math.inf)
        lev = v.positions("levels_db", self.levels_db, -math.inf, math.inf, unit="dB")
        if lam.size != lev.size:
            raise ValueError(f"wavelengths ({lam.size}) and levels_db ({lev.size}) must have "
                             "the same length")
        if np.any(lam <= 0.0):
            raise ValueError("wavelengths must be > 0 m; allowed range (0, inf) m")
        order = np.argsort(-lam)  # increasing Omega
        if np.any(np.diff(lam[order]) == 0.0):
            raise ValueError("wavelengths must be distinct")
        object.__setattr__(self, "wavelengths", tuple(float(x) for x in lam[order]))
        object.__setattr__(self, "levels_db", tuple(float(x) for x in lev[order]))

    @property
    def name(self) -> str:
        return self.label

    def edges(self) -> np.ndarray:
        """Band edges Omega [rad/m], increasing, shape (n_bands + 1,)."""
        c = 2.0 * math.pi / np.asarray(self.wavelengths)
        inner = np.sqrt(c[:-1] * c[1:])
        return np.concatenate(([c[0] / THIRD_OCTAVE_HALF], inner, [c[-1] * THIRD_OCTAVE_HALF]))

    @property
    def band(self) -> tuple[float, float]:
        e = self.edges()
        return (float(e[0]), float(e[-1]))

    def __call__(self, omega) -> np.ndarray:
        """S(Omega) [m^2/(rad/m)] at Omega [rad/m]; 0 outside the bands."""
        w = _omega(omega)
        e = self.edges()
        density = 1e-12 * 10.0 ** (np.asarray(self.levels_db) / 10.0) / np.diff(e)
        i = np.searchsorted(e, w, side="right") - 1
        inside = (i >= 0) & (i < density.size)
        return np.where(inside, density[np.clip(i, 0, density.size - 1)], 0.0)


def fra(track_class: int) -> FRASpectrum:
    """US FRA vertical-profile spectrum of class 1..6 (see :class:`FRASpectrum`)."""
    return FRASpectrum(track_class)


def german(level: str) -> GermanSpectrum:
    """German high-speed spectrum, ``level`` = "low" or "high" (see :class:`GermanSpectrum`)."""
    return GermanSpectrum(level)


def china_hsr() -> ChinaSpectrum:
    """China high-speed ballastless spectrum, TB/T 3352-2014 (see :class:`ChinaSpectrum`)."""
    return ChinaSpectrum()


def third_octave(wavelengths, levels_db, label: str = "one-third-octave spectrum"
                 ) -> ThirdOctaveSpectrum:
    """A user roughness spectrum from one-third-octave levels [dB re 1 um] at band-centre
    wavelengths [m] (see :class:`ThirdOctaveSpectrum`)."""
    return ThirdOctaveSpectrum(tuple(np.atleast_1d(np.asarray(wavelengths, dtype=float))),
                               tuple(np.atleast_1d(np.asarray(levels_db, dtype=float))), label)


def iso3095() -> ThirdOctaveSpectrum:
    """ISO 3095:2013 rail-roughness limit spectrum: one-third-octave levels [dB re 1 um] from
    17.1 dB at lambda = 40 cm to -11.0 dB at 0.315 cm (docs: Model § Irregularities), as a
    :class:`ThirdOctaveSpectrum` (valid lambda ~ 0.28-45 cm)."""
    return third_octave([x / 100.0 for x in _ISO_LAMBDA_CM], _ISO_LEVELS,
                        "ISO 3095:2013 limit")
