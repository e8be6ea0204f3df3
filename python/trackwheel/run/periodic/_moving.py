"""The moving-load receptance matrix of the periodic track (docs: Model § The periodic level).

A force exp(i w_m t) [N] (upward on the rail) moving at speed v along the infinite periodic
track of bay d drives the rail under it at the frequencies w_m + p w_s (w_s = 2 pi v / d); with
w_m = Omega + m w_s the rail's displacement harmonic p per force harmonic m is

    A_pm = (1 / 2 pi) integral dk exp(i k Delta) I_pm(k),
    I_pm(k) = d delta_pm h_m + c h_p h_m,   h_q = 1 / (d D(k_q, w')),   c = -d s / (1 + s S),

all at the track-frame frequency w' = Omega - k v, k_q = k + 2 pi q / d, s = s(w') and
S = S(k, w') (``_track``); Delta is the distance from the force to the point where the rail
is read (0: under the force). The free rail's waves (poles of h_m, on the real axis for the
undamped rail) cancel between the two terms; I is analytic on the real axis except near the
zeros of 1 + s S, the track's Bloch waves at w' (lightly damped ones make narrow peaks).

The kernel (cpp/periodic.cpp) integrates over the whole real k axis: [-K, K]
(K = 2 pi (n + 4) / d for harmonics |p| <= n) in panels of half a Brillouin zone, the tails k = +-K / u over u in (0, 1] (the integrand falls
like 1/k^4, Timoshenko 1/k^2, so it stays bounded in u). The zeros k_c of 1 + s S near the
real axis are found first (secant iterations from the minima of |1 + s S| on a scan and from the free
rail's poles along the line) and their pole terms rho_c h(k_c) h(k_c)^T / (k - k_c),
rho_c = -d s / (1 + s S)'(k_c), are subtracted in the panels near them and added back
exactly (log((b - k_c) / (a - k_c))), so what the 15-point Gauss-Kronrod rule integrates is
smooth. Panels whose Kronrod and embedded 7-point Gauss results differ by more than the
tolerance are bisected (error proxies: the diagonal and the column m = 0). ``_Line`` is the integrand in numpy, the kernel's reference in the tests.
"""

from __future__ import annotations

import math

import numpy as np

from ... import _core
from ._track import PeriodicTrack

#: Zones beyond the highest harmonic in the central part of the k axis [-] (the kernel's
#: kExtraZones)
EXTRA_ZONES = 4
#: |s h_m| above which the diagonal is formed without cancellation (``_Line.parts``) [-]
CANCELLATION = 1e3


class QuadratureError(RuntimeError):
    """The kernel's k quadrature did not reach its tolerance (a nearly undamped wave)."""


class _Line:
    """The integrand along the line w' = Omega - k v for harmonics ``shifts``."""

    def __init__(self, track: PeriodicTrack, speed: float, omega: float, shifts: np.ndarray):
        self.track, self.speed, self.omega, self.shifts = track, speed, omega, shifts
        self.dk = 2.0 * math.pi / track.bay * shifts

    def _off_static(self, k):
        """k moved by a relative 1e-12 where w' = Omega - k v is exactly 0: the lattice sum's
        partial fractions are singular there, the integrand is not (a removable point)."""
        k = np.asarray(k)
        at = (self.omega - k * self.speed) == 0.0
        if self.speed > 0.0 and np.any(at):
            k = np.where(at, k * (1.0 + 1e-12) + 1e-12, k)
        return k

    def den(self, k):
        """1 + s S at k (real or complex) [-]."""
        k = self._off_static(k)
        w = self.omega - k * self.speed
        return 1.0 + self.track.support_stiffness(w) * self.track.lattice_sum(k, w)

    def parts(self, k):
        """(h (n, M) [1/N], c (n,) [N], diag (n, M) [m/N]) at real k (n,): off the diagonal
        I_pm = c h_p h_m, on it diag_m = d h_m + c h_m^2 [m/N]. Where |s h_m| is large (near
        the free rail's pole of h_m, or the static point w' = 0) the two terms of diag_m
        nearly cancel, so there it is d h_m (1 + s S_m') / (1 + s S) with S_m' the lattice
        sum without term m (``lattice_sum_excluding``)."""
        tr, d = self.track, self.track.bay
        k = self._off_static(k)
        w = self.omega - k * self.speed
        s = tr.support_stiffness(w)
        h = tr.inverse_stiffness(k[:, None] + self.dk[None, :], w[:, None]) / d
        den = 1.0 + s * tr.lattice_sum(k, w)
        c = -d * s / den
        diag = d * h + c[:, None] * h * h
        i, m = np.nonzero(np.abs(s[:, None] * h) > CANCELLATION)
        if i.size:
            excl = tr.lattice_sum_excluding(k[i], w[i], self.shifts[m])
            diag[i, m] = d * h[i, m] * (1.0 + s[i] * excl) / den[i]
        return h, c, diag

    def den_slope(self, k, step):
        """d(1 + s S)/dk by the fourth-order central difference with ``step`` [rad/m]."""
        f = [self.den(k + j * step) for j in (-2, -1, 1, 2)]
        return (f[0] - 8.0 * f[1] + 8.0 * f[2] - f[3]) / (12.0 * step)


def receptance_matrix(track: PeriodicTrack, speed: float, omega: float, n: int, *,
                      offsets=(0.0,), rtol: float = 1e-8) -> np.ndarray:
    """A (n_offsets, 2n+1, 2n+1) [m/N]: the moving-load receptance matrix of the module
    docstring for harmonics p, m = -n..n at ``speed`` v [m/s] (>= 0) and base frequency
    ``omega`` [rad/s] (v > 0 or omega != 0), read at each of ``offsets`` Delta [m] from the
    force; converged to ``rtol`` of its largest entry. Computed in the C++ kernel
    (cpp/periodic.cpp, GIL released)."""
    try:
        return _core.periodic_receptance_matrix(kernel_params(track), float(speed),
                                                float(omega), int(n),
                                                [float(x) for x in np.atleast_1d(offsets)],
                                                float(rtol))
    except RuntimeError as exc:
        raise QuadratureError(str(exc)) from None


def kernel_params(track: PeriodicTrack):
    """The kernel's PeriodicTrackParams of ``track``."""
    p = _core.PeriodicTrackParams()
    p.bay, p.EI, p.mass = track.bay, track.bending_stiffness, track.mass_per_length
    p.shear = track.shear_stiffness if track.timoshenko else 0.0
    p.rotary = track.rotary_inertia if track.timoshenko else 0.0
    p.pad_stiffness, p.pad_damping = track.pad_stiffness, track.pad_damping
    p.sleeper_mass = track.sleeper_mass
    p.ballast_stiffness, p.ballast_damping = track.ballast_stiffness, track.ballast_damping
    return p
