"""The contact filter: the rail profile the wheel sees, averaged over its contact patch
(docs: Model § Irregularities, the 1D form)."""

from __future__ import annotations

import math

import numpy as np

from ..base import validate as v


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
    # uniform to round-off: a grid x0 + i h far from 0 (tens of metres) in steps of microns
    # carries spacing errors of a few eps |x|, more than 1e-9 h
    if np.any(h <= 0.0) or np.ptp(h) > 1e-9 * h.mean() + 16.0 * np.finfo(float).eps * float(
            np.max(np.abs(xa))):
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

