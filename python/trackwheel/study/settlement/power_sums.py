"""Partial sums of a power series, sum_{k=0}^{n-1} (a + k)^(-s), to round-off for any count
n, without summing n terms (docs: Model § Ballast settlement).

They are differences of the Hurwitz zeta function, ``zeta(s, a) - zeta(s, a + n)``; scipy's
``scipy.special.zeta(s, a)`` is defined for s > 1 only (NaN below), and the settlement law of
Varandas et al. needs s = beta = 0.82, so the sums are taken here directly: the first
``DIRECT_TERMS`` terms one by one, the rest by the Euler-Maclaurin formula

    sum_{k=0}^{m} f(x0 + k) = int_{x0}^{x1} f dx + (f(x0) + f(x1)) / 2
                              + sum_{j=1}^{6} B_2j / (2j)! (f^(2j-1)(x1) - f^(2j-1)(x0)) + R,

f(x) = x^-s, x1 = x0 + m, x0 = a + DIRECT_TERMS >= 17. The remainder R is bounded by the next
term, |B_14| / 14! (s)_13 x0^(-s-13) (rising factorial (s)_13): below 1e-15 of f(x0) for every
s in [0, 10] (the range the laws allow), so the sums are exact to round-off. Every operation is
element by element, so an element's value does not depend on the array it is part of.
"""

from __future__ import annotations

import math

import numpy as np

#: Terms summed one by one before the Euler-Maclaurin tail [-].
DIRECT_TERMS = 16
#: B_2j / (2j)! for j = 1..6 (Bernoulli numbers B_2 = 1/6, B_4 = -1/30, B_6 = 1/42,
#: B_8 = -1/30, B_10 = 5/66, B_12 = -691/2730).
_BERNOULLI = tuple(b / math.factorial(2 * j) for j, b in enumerate(
    (1 / 6, -1 / 30, 1 / 42, -1 / 30, 5 / 66, -691 / 2730), start=1))
#: Largest exponent s the sums are exact for (see the module docstring) [-].
MAX_EXPONENT = 10.0


def power_sum(s: float, a, n) -> np.ndarray:
    """sum_{k=0}^{n-1} (a + k)^(-s), element by element [-].

    ``s`` in [0, MAX_EXPONENT] (a float); ``a`` >= 1 and ``n`` >= 0 (whole numbers, as floats up
    to 2^53) broadcast together. n = 0 gives 0 exactly; s = 0 gives n; s = 1 the digamma
    difference psi(a + n) - psi(a).
    """
    s = float(s)
    a, n = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(n, dtype=float))
    out = np.zeros(a.shape)
    for k in range(DIRECT_TERMS):
        out = out + np.where(k < n, (a + k) ** -s, 0.0)
    tail = n > DIRECT_TERMS
    if np.any(tail):
        x0 = a + DIRECT_TERMS
        x1 = np.where(tail, a + n - 1.0, x0)
        out = out + np.where(tail, _euler_maclaurin(s, x0, x1), 0.0)
    return out


def _euler_maclaurin(s: float, x0: np.ndarray, x1: np.ndarray) -> np.ndarray:
    """sum_{k=0}^{x1-x0} (x0 + k)^(-s) for x0 >= 17: the integral, the end-point terms and six
    Bernoulli corrections."""
    t = 1.0 - s
    log_ratio = np.log1p((x1 - x0) / x0)  # ln(x1 / x0) without cancellation for x1 ~ x0
    # int_{x0}^{x1} x^-s dx = x0^(1-s) ((x1/x0)^(1-s) - 1) / (1-s); ln(x1/x0) at s = 1
    integral = log_ratio if t == 0.0 else x0 ** t * np.expm1(t * log_ratio) / t
    total = integral + 0.5 * (x0 ** -s + x1 ** -s)
    rising = s  # (s)_(2j-1): f^(2j-1)(x) = -(s)_(2j-1) x^(-s-2j+1)
    for j, coefficient in enumerate(_BERNOULLI, start=1):
        power = -s - 2 * j + 1
        total = total + coefficient * rising * (x0 ** power - x1 ** power)
        rising *= (s + 2 * j - 1) * (s + 2 * j)
    return total
