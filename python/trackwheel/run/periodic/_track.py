"""The infinite periodic track in the wavenumber-frequency domain.

Docs: Model § The periodic level.

Everything here is exact for the continuous beam: no mesh. Conventions: time dependence
exp(+i w t), space dependence exp(+i k X); w [rad/s] is the frequency in the track's frame, k
[rad/m] the wavenumber; displacements and forces upward positive.

- Free rail: a travelling distributed force F exp(i(k X + w t)) [N/m] drives the free,
  undamped rail to W exp(i(k X + w t)) with W = F / D(k, w). Euler-Bernoulli:
  D = EI k^4 - m w^2. Timoshenko (shear stiffness kappa G A, rotary inertia rho I):
  D = kappa G A k^2 (EI k^2 - rho I w^2) / (EI k^2 + kappa G A - rho I w^2) - m w^2.
- Supports every d at X_j = j d: point springs of dynamic stiffness s(w) on the rail's
  deflection (single: k_s + i w c_s; pad-sleeper-ballast: s_p (s_b - m_s w^2) /
  (s_p + s_b - m_s w^2), s_p = k_p + i w c_p, s_b = k_b + i w c_b).
- Lattice sum S(k, w) = (1/d) sum_q 1 / D(k_q, w), k_q = k + 2 pi q / d: the deflection at a
  support of the free rail under the row of unit point forces exp(i k j d) at the supports.
  In closed form from the partial fractions 1/D = sum_r c_r / (k^2 - a_r^2) and
  sum_q 1 / (k_q^2 - a^2) = (d / 4a) [cot((k - a) d/2) - cot((k + a) d/2)].
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: |z| below which g(z) = cot z - 1/z is evaluated by its Taylor series [-]
_SERIES_LIMIT = 0.3
#: Taylor coefficients of -g(z) = sum_n b_n z^(2n-1), b_n = 2^(2n) |B_2n| / (2n)! (Bernoulli
#: numbers B_2n), n = 1..7
_COT_SERIES = (1.0 / 3.0, 1.0 / 45.0, 2.0 / 945.0, 1.0 / 4725.0, 2.0 / 93555.0,
               1382.0 / 638512875.0, 4.0 / 18243225.0)


@dataclass(frozen=True)
class PeriodicTrack:
    """The linear track of one bay, as the periodic level needs it (SI units)."""

    bay: float  #: d, support spacing [m]
    bending_stiffness: float  #: EI [N m^2]
    mass_per_length: float  #: m = rho A [kg/m]
    #: kappa G A [N]; inf: Euler-Bernoulli
    shear_stiffness: float = math.inf
    rotary_inertia: float = 0.0  #: rho I [kg m] (Timoshenko only)
    pad_stiffness: float = 0.0  #: k_s or k_p [N/m]
    pad_damping: float = 0.0  #: c_s or c_p [N s/m]
    sleeper_mass: float = 0.0  #: m_s [kg]; 0: single supports
    ballast_stiffness: float = 0.0  #: k_b [N/m]
    ballast_damping: float = 0.0  #: c_b [N s/m]

    @property
    def timoshenko(self) -> bool:
        return math.isfinite(self.shear_stiffness)

    @property
    def layered(self) -> bool:
        return self.sleeper_mass > 0.0

    # the free rail ------------------------------------------------------------------------
    def dynamic_stiffness(self, k, w) -> np.ndarray:
        """D(k, w) [N/m^2] of the free rail (module docstring); broadcasts k [rad/m] and w
        [rad/s], real or complex. Timoshenko: inf where the rotation equation's coefficient
        EI k^2 + kappa G A - rho I w^2 vanishes."""
        return 1.0 / self.inverse_stiffness(k, w)

    def inverse_stiffness(self, k, w) -> np.ndarray:
        """1 / D(k, w) [m^2/N] (complex), finite where D is infinite (Timoshenko)."""
        k = np.asarray(k)
        w2 = np.asarray(w) ** 2
        EI, m = self.bending_stiffness, self.mass_per_length
        if not self.timoshenko:
            return 1.0 / (EI * k**4 - m * w2 + 0j)
        G, J = self.shear_stiffness, self.rotary_inertia
        k2 = k * k
        quartic = G * EI * k2 * k2 - (G * J + m * EI) * w2 * k2 - m * w2 * (G - J * w2)
        return (EI * k2 + G - J * w2) / (quartic + 0j)

    def partial_fractions(self, w):
        """(a1^2, a2^2, c1, c2), arrays of w's shape, with 1/D(k, w) = c1 / (k^2 - a1^2) +
        c2 / (k^2 - a2^2) for w != 0 [rad/s] (real or complex): the squared free wavenumbers
        [rad^2/m^2] and the residues [1/N]. Euler-Bernoulli: a^2 = +-lambda^2,
        lambda^4 = m w^2 / EI, c = +-1/(2 EI lambda^2). Timoshenko: the roots of the quadratic
        in k^2, kappa G A EI k^4 - (kappa G A rho I + m EI) w^2 k^2 - m w^2 (kappa G A -
        rho I w^2) (for real w one positive, one negative), c_r = B(a_r^2) / (kappa G A EI
        (a_r^2 - a_s^2)), B = EI k^2 + kappa G A - rho I w^2."""
        w2 = np.asarray(w) ** 2 + 0j
        EI, m = self.bending_stiffness, self.mass_per_length
        if not self.timoshenko:
            lam2 = np.sqrt(m * w2 / EI)
            c = 1.0 / (2 * EI * lam2)
            return lam2, -lam2, c, -c
        G, J = self.shear_stiffness, self.rotary_inertia
        alpha = G * EI
        beta = (G * J + m * EI) * w2
        gamma = m * w2 * (G - J * w2)
        # alpha x^2 - beta x - gamma = 0; the root of larger modulus without cancellation, the
        # other from the product of the roots (-gamma / alpha)
        root = np.sqrt(beta * beta + 4 * alpha * gamma)
        root = np.where(np.abs(beta + root) >= np.abs(beta - root), root, -root)
        r1 = (beta + root) / (2 * alpha)
        r2 = -gamma / (alpha * r1)
        rest = G - J * w2
        return r1, r2, (EI * r1 + rest) / (alpha * (r1 - r2)), (EI * r2 + rest) / (alpha * (r2 - r1))

    # the supports -------------------------------------------------------------------------
    def support_stiffness(self, w) -> np.ndarray:
        """s(w) [N/m] of one support at frequency w [rad/s] (real or complex; module
        docstring); complex."""
        w = np.asarray(w)
        sp = self.pad_stiffness + 1j * w * self.pad_damping
        if not self.layered:
            return sp + 0j
        sb = self.ballast_stiffness + 1j * w * self.ballast_damping - self.sleeper_mass * w * w
        return sp * sb / (sp + sb)

    @property
    def damped(self) -> bool:
        """Whether the supports dissipate (the periodic level needs it)."""
        return self.pad_damping > 0.0 or (self.layered and self.ballast_damping > 0.0)

    # lattice sums -------------------------------------------------------------------------
    def lattice_sum(self, k, w) -> np.ndarray:
        """S(k, w) = (1/d) sum_q 1/D(k_q, w) [m/N] (module docstring) in closed form; k
        [rad/m] and w [rad/s] broadcast, real or complex, w != 0."""
        x = 0.5 * self.bay * np.asarray(k)
        out = 0.0
        for a2, c in self._fractions(w):
            a = np.sqrt(a2)  # either root: the sum is even in a
            y = 0.5 * self.bay * a
            out = out + c / (4.0 * a) * (_cot(x - y) - _cot(x + y))
        return out

    def lattice_sum_excluding(self, k, w, shift) -> np.ndarray:
        """S(k, w) without its term q = ``shift`` [m/N], from g(z) = cot z - 1/z, which stays
        accurate at that term's pole (where S - h_q would cancel)."""
        x = 0.5 * self.bay * (np.asarray(k) + 2.0 * math.pi * np.asarray(shift) / self.bay)
        out = 0.0
        for a2, c in self._fractions(w):
            a = np.sqrt(a2)
            y = 0.5 * self.bay * a
            out = out + c / (4.0 * a) * (_cot_minus_inverse(x - y) - _cot_minus_inverse(x + y))
        return out

    def _fractions(self, w):
        a1, a2, c1, c2 = self.partial_fractions(w)
        return ((a1, c1), (a2, c2))


def _cot(z) -> np.ndarray:
    """cot z for complex z without overflow: i (1 + e) / (e - 1), e = exp(2 i z) (|e| <= 1), or
    the mirrored form for Im z < 0."""
    z = np.asarray(z, dtype=complex)
    up = z.imag >= 0.0
    e = np.exp(2j * np.where(up, z, -z))  # |e| <= 1
    val = 1j * (1.0 + e) / (e - 1.0)
    return np.where(up, val, -val)


def _cot_minus_inverse(z) -> np.ndarray:
    """g(z) = cot z - 1/z, smooth at z = 0: its Taylor series (``_COT_SERIES``, relative
    truncation error below 1e-16 for |z| < _SERIES_LIMIT) near 0, else directly (losing at most
    about 1.5 digits to the cancellation just above the limit)."""
    z = np.asarray(z, dtype=complex)
    small = np.abs(z) < _SERIES_LIMIT
    zs = np.where(small, z, 0.0)
    z2 = zs * zs
    acc = np.zeros_like(zs)
    for b in reversed(_COT_SERIES):
        acc = acc * z2 + b
    series = -zs * acc
    zd = np.where(small, 1.0, z)
    return np.where(small, series, _cot(zd) - 1.0 / zd)
