"""What a time-domain analysis measures, from a periodic response.

Docs: Model § The periodic level, § Outputs.

The quasi-static line, the dynamic part d = y_B - y_qs of the rail under the wheel, its
amplitude max |d| and main frequency, and the contact force's extremes and RMS.

The steady signals are sums of lines: the sleeper passing (the bay phase theta = w_s t) and,
per sine of the running surfaces, a carrier exp(i Omega t) times its own bay-periodic envelope
G(theta) = sum_p G_p exp(i p theta). For a sine incommensurate with the bay the carrier's
phase is independent of theta over a long run, so the extremes over all times are those over
theta of the sleeper passing plus or minus the sum of the envelopes' magnitudes (exact; for a
sine commensurate with the bay a bound, since the phases then keep a fixed relation).

The quasi-static line y_qs(X) (``Analysis.y_qs``: the rail under the wheel resting at X, same
load, own weight included) is the steady response of the moving force P at a vanishing speed:
its harmonics in the bay are those of the balance at ``QS_SPEED``, where the dynamic terms
(of order (v k / w_track) and v c / k_s) are below 1e-6 of the deflection.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from .balance import DEFAULT_RTOL, balance, own_weight_sag, periodic_track
from .wheel import wheel_of

__all__ = ["PHASES", "QS_SPEED", "amplitude", "extremes", "force_rms", "main_frequency",
           "outputs", "quasi_static_harmonics"]

#: Bay phases sampled for the extremes [-]
PHASES = 512
#: Speed of the moving force whose steady response is the quasi-static line [m/s]: on the
#: ballasted preset its harmonics change by < 1e-8 of the deflection from 1e-3 m/s, and it
#: follows ``linear_quasi_static`` within 1e-6 (Euler-Bernoulli, 8 harmonics)
QS_SPEED = 1e-2
#: Relative difference of two frequencies [-] below which their lines are one line
SAME_LINE = 1e-9


def at_phases(c: np.ndarray, n: int) -> np.ndarray:
    """sum_p c_p e^{i p theta_j} at theta_j = 2 pi j / PHASES, p = -n..n."""
    spread = np.zeros(PHASES, complex)
    np.add.at(spread, np.arange(-n, n + 1) % PHASES, c)
    return np.fft.ifft(spread) * PHASES


def extremes(base, envelopes, n) -> tuple[float, float]:
    """(min, max) over all phases of the sleeper-passing harmonics ``base`` (p = -n..n) plus,
    per sine, its envelope |G(theta)| at the least and the most favourable carrier phase
    (module docstring: exact for sines incommensurate with the bay, a bound otherwise)."""
    b = at_phases(base, n).real
    spread = sum((np.abs(at_phases(G, n)) for G in envelopes), np.zeros(PHASES))
    return float((b - spread).min()), float((b + spread).max())


@lru_cache(maxsize=256)
def quasi_static_harmonics(scene, n: int, rtol: float = DEFAULT_RTOL) -> np.ndarray:
    """c_p, p = -n..n [m]: the quasi-static line of the scene's wheel, y_qs(X) =
    sum_p c_p e^{i 2 pi p X / d} (X from a support), the static load P on the infinite periodic
    track with its own-weight sag (module docstring). Cached per scene."""
    wheel = wheel_of(scene, "linear/moving_force")
    b = balance(periodic_track(scene), wheel, "linear/moving_force", QS_SPEED, 0.0, n,
                own_weight_sag(scene, n), mean=wheel.load, rtol=rtol)
    out = b.y.copy()
    out.setflags(write=False)
    return out


def _dynamic(resp) -> tuple[np.ndarray, list[np.ndarray], int]:
    """(the sleeper passing's harmonics of d = y_B - y_qs, the sines' envelopes of y_B, n)."""
    (_, _, y_sp), *sines = resp.balances
    n = (y_sp.size - 1) // 2
    d = y_sp - quasi_static_harmonics(resp.scene, n)
    return d, [y for _, _, y in sines], n


def amplitude(resp) -> float:
    """max |d| [m] over the steady state, d = y_B - y_qs(X_A) (``Analysis.amplitude``)."""
    d, envs, n = _dynamic(resp)
    lo, hi = extremes(d, envs, n)
    return max(abs(lo), abs(hi))


def _lines(resp, column: int, base: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(frequencies [Hz] > 0, complex amplitudes) of a steady signal's lines, lines at the same
    frequency summed: ``base`` the sleeper passing's harmonics p = -n..n, and per sine its
    balance's ``column`` (1: N, 2: y)."""
    n = (base.size - 1) // 2
    ws = 2.0 * math.pi * resp.sleeper_frequency
    f = [p * ws for p in range(1, n + 1)]
    a = [2.0 * base[n + p] for p in range(1, n + 1)]
    for omega, *cols in resp.balances[1:]:
        w = omega + ws * np.arange(-n, n + 1)
        keep = np.abs(w) > 1e-9 * max(ws, omega)
        # a line at negative frequency is the complex conjugate at |w|
        f.extend(np.abs(w[keep]))
        a.extend(np.where(w[keep] > 0, cols[column - 1][keep], np.conj(cols[column - 1][keep])))
    f, a = np.asarray(f) / (2.0 * math.pi), np.asarray(a, complex)
    order = np.argsort(f, kind="stable")
    f, a = f[order], a[order]
    start = np.r_[True, np.diff(f) > SAME_LINE * f[1:]]
    group = np.cumsum(start) - 1
    return f[start], np.bincount(group, a.real) + 1j * np.bincount(group, a.imag)


def main_frequency(resp) -> float:
    """The frequency of d's largest line [Hz] (``Analysis.main_frequency``: the peak of its
    amplitude spectrum); NaN when d has no line (a smooth continuous foundation)."""
    d, _, _ = _dynamic(resp)
    f, a = _lines(resp, 2, d)
    if f.size == 0 or not np.any(np.abs(a) > 0.0):
        return math.nan
    return float(f[np.argmax(np.abs(a))])


def force_rms(resp) -> float:
    """RMS of N - P [N] over a long run: the root of half the sum of the squared line
    amplitudes (lines at the same frequency summed first)."""
    (_, N_sp, _), *_ = resp.balances
    _, a = _lines(resp, 1, N_sp)
    return math.sqrt(0.5 * float(np.sum(np.abs(a) ** 2)))


def outputs(resp) -> dict:
    """The scalar outputs a sweep tabulates per wheel, by quantity name
    (``trackwheel.study.columns.OUTPUTS``): those of the steady state, NaN where the periodic
    level has no counterpart (the frequency resolution of a record; P1/P2 after a joint)."""
    return {
        "amplitude": amplitude(resp), "main_frequency": main_frequency(resp),
        "frequency_resolution": math.nan, "min_contact_force": resp.min_force,
        "max_contact_force": resp.max_force, "lost_contact": False,
        "dynamic_factor": resp.max_force / resp.mean_force, "loss_duration": 0.0,
        "force_rms": force_rms(resp), "p1": math.nan, "p1_time": math.nan, "p2": math.nan,
        "p2_time": math.nan}
