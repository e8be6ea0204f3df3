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

Quadrature over the whole real k axis: [-K, K] (K = 2 pi (n + 2) / d for harmonics |p| <= n)
in panels of half a Brillouin zone, the tails k = +-K / u over u in (0, 1] (the integrand falls
like 1/k^4, Timoshenko 1/k^2, so it stays bounded in u). The zeros k_c of 1 + s S near the
real axis are found first (Newton from the minima of |1 + s S| on a scan and from the free
rail's poles along the line) and their pole terms rho_c h(k_c) h(k_c)^T / (k - k_c),
rho_c = -d s / (1 + s S)'(k_c), are subtracted in the panels near them and added back
exactly (log((b - k_c) / (a - k_c))), so what the 15-point Gauss-Kronrod rule integrates is
smooth. Panels whose Kronrod and embedded 7-point Gauss results differ by more than the
tolerance are bisected (error proxies: the diagonal, the column m = 0 and the matrix times a
fixed vector).
"""

from __future__ import annotations

import math

import numpy as np

from ._track import PeriodicTrack

# 15-point Kronrod abscissae (positive half, descending) and weights, and the weights of the
# embedded 7-point Gauss rule on xgk[1::2] (QUADPACK's qk15; Piessens et al. 1983)
_XGK = np.array([0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                 0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                 0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                 0.207784955007898467600689403773245, 0.0])
_WGK = np.array([0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                 0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                 0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                 0.204432940075298892414161999234649, 0.209482141084727828012999174891714])
_WG = np.array([0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                0.381830050505118944950369775488975, 0.417959183673469387755102040816327])


def _rule():
    """(nodes on [-1, 1] (15,), Kronrod weights (15,), Kronrod minus Gauss weights (15,))."""
    x = np.concatenate((-_XGK[:-1], _XGK[::-1]))
    wk = np.concatenate((_WGK[:-1], _WGK[::-1]))
    wg_half = np.zeros(8)
    wg_half[1::2] = _WG
    wg = np.concatenate((wg_half[:-1], wg_half[::-1]))
    return x, wk, wk - wg


NODES, W_KRONROD, W_DIFF = _rule()
#: Zones beyond the highest harmonic in the central part of the k axis [-]
EXTRA_ZONES = 2
#: Most bisection rounds of the adaptive quadrature [-]
MAX_ROUNDS = 40
#: Most panels [-] (a guard: the subtracted integrand needs about a hundred)
MAX_PANELS = 20000
#: Scan points per half zone for the minima of |1 + s S| [-]
SCAN_PER_PANEL = 12
#: Zeros of 1 + s S with |Im k| above this many half zones (pi / d) are left to the quadrature
POLE_STRIP = 0.5
#: Most secant iterations for the zeros of 1 + s S [-]
NEWTON_STEPS = 30
#: |s h_m| above which the diagonal is formed without cancellation (``_Line.parts``) [-]
CANCELLATION = 1e3


class QuadratureError(RuntimeError):
    """The adaptive k quadrature did not reach its tolerance."""


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
    force; converged to ``rtol`` of its largest entry."""
    shifts = np.arange(-n, n + 1, dtype=float)
    offsets = np.atleast_1d(np.asarray(offsets, dtype=float))
    line = _Line(track, speed, omega, shifts)
    d = track.bay
    half = math.pi / d
    K = 2.0 * half * (n + EXTRA_ZONES)
    edges = half * np.arange(-2 * (n + EXTRA_ZONES), 2 * (n + EXTRA_ZONES) + 1)
    if speed > 0.0 and abs(omega / speed) < K:  # where w' = 0: S's static point
        edges = np.union1d(edges, [omega / speed])
    poles = _poles(line, edges)
    tails = np.array([0.0, 0.125, 0.25, 0.5, 1.0])
    a = np.concatenate((edges[:-1], tails[:-1], tails[:-1]))
    b = np.concatenate((edges[1:], tails[1:], tails[1:]))
    kind = np.concatenate((np.zeros(edges.size - 1, int), np.ones(4, int), np.full(4, 2)))
    return _integrate(line, poles, offsets, K, a, b, kind, rtol)


def _poles(line: _Line, edges: np.ndarray):
    """(k_c (n_c,) complex, rho_c (n_c,), h_c (n_c, M)): the zeros of 1 + s S within
    POLE_STRIP half zones of the real axis over the central panels, with the residue factors
    of the integrand's pole terms rho_c h_c h_c^T / (k - k_c)."""
    # a candidate may land on a pole of S or on the static point w' = 0 (an infinite or
    # undefined 1 + s S): it is dropped, not an error
    with np.errstate(all="ignore"):
        return _find_poles(line, edges)


def _find_poles(line: _Line, edges: np.ndarray):
    d = line.track.bay
    half = math.pi / d
    lo, hi = edges[0], edges[-1]
    # candidates: the local minima of |1 + s S| on a scan ...
    t = (np.arange(SCAN_PER_PANEL) + 0.5) / SCAN_PER_PANEL
    scan = (edges[:-1, None] + np.diff(edges)[:, None] * t).ravel()
    mag = np.abs(line.den(scan))
    inner = (mag[1:-1] < mag[:-2]) & (mag[1:-1] < mag[2:])
    starts = [scan[1:-1][inner]]
    # ... and next to the free rail's poles along the line, where the zeros hug them at high
    # frequency: from the pole k_p of h_q, 1 + s S = 0 at first order where
    # k - k_p = -s / (d D' (1 + s S_q')), D' = dD(k_q, Omega - k v)/dk along the line
    kp, q = _free_poles(line, lo, hi)
    if kp.size:
        w = line.omega - kp * line.speed
        sp = line.track.support_stiffness(w)
        excl = line.track.lattice_sum_excluding(kp, w, q)
        eps = 1e-6 * (1.0 + np.abs(kp))
        g = 2.0 * math.pi / d * q
        slope = (line.track.dynamic_stiffness(kp + eps + g, w - eps * line.speed)
                 - line.track.dynamic_stiffness(kp - eps + g, w + eps * line.speed)) / (2 * eps)
        starts.append(kp - sp / (d * slope * (1.0 + sp * excl)))
    k = np.concatenate(starts).astype(complex)
    k = k[np.isfinite(k)]
    if k.size == 0:
        return np.zeros(0, complex), np.zeros(0, complex), np.zeros((0, line.shifts.size), complex)
    # secant iterations (one evaluation each), the steps limited to a quarter half zone
    limit = 0.25 * half
    k_old = k + 1e-4 * half * (1 + 1j)
    f_old = line.den(k_old)
    f = line.den(k)
    for _ in range(NEWTON_STEPS):
        with np.errstate(all="ignore"):
            dk = f * (k - k_old) / (f - f_old)
        dk = np.where(np.isfinite(dk), dk, 0.0)
        big = np.abs(dk) > limit
        dk[big] *= limit / np.abs(dk[big])
        k_old, f_old = k, f
        k = k - dk
        f = line.den(k)
        if np.all((np.abs(dk) < 1e-12 * half) | ~np.isfinite(f)):
            break
    f = line.den(k)
    ok = (np.abs(f) < 1e-9) & (np.abs(k.imag) < POLE_STRIP * half) & (k.real > lo) & (
        k.real < hi) & np.isfinite(k)
    k = k[ok]
    if k.size == 0:
        return np.zeros(0, complex), np.zeros(0, complex), np.zeros((0, line.shifts.size), complex)
    k = np.sort_complex(k)
    keep = np.ones(k.size, bool)
    keep[1:] = np.abs(np.diff(k)) > 1e-8 * half
    k = k[keep]
    step = np.clip(1e-2 * np.abs(k.imag), 1e-9, 1e-4) * half
    slope = line.den_slope(k, step)
    h, _, _ = line.parts(k)
    w = line.omega - k * line.speed
    rho = -d * line.track.support_stiffness(w) / slope
    return k, rho, h


def _free_poles(line: _Line, lo: float, hi: float) -> np.ndarray:
    """(k (n,), q (n,)): the real k in (lo, hi) where the free rail wave of shift q meets the
    line, D(k + 2 pi q / d, Omega - k v) = 0 (a quartic in k per q)."""
    tr, v, om, d = line.track, line.speed, line.omega, line.track.bay
    g = 2.0 * math.pi / d
    q = np.arange(math.floor(-hi / g) - 3, math.ceil(-lo / g) + 4)
    # k_q = k + g q = x, w' = om - v (x - g q) = W - v x with W = om + v g q
    W = om + v * g * q
    EI, m = tr.bending_stiffness, tr.mass_per_length
    if not tr.timoshenko:
        # EI x^4 - m (W - v x)^2 = (sqrt(EI) x^2 - sqrt(m)(W - v x)) (sqrt(EI) x^2 + ...)
        a = math.sqrt(EI)
        c = math.sqrt(m)
        roots = []
        for sgn in (1.0, -1.0):
            # a x^2 + sgn c v x - sgn c W = 0
            disc = (c * v) ** 2 + 4 * a * sgn * c * W + 0j
            r = np.sqrt(disc)
            roots += [(-sgn * c * v + r) / (2 * a), (-sgn * c * v - r) / (2 * a)]
        x = np.stack(roots, axis=-1)  # (nq, 4)
    else:
        G, J = tr.shear_stiffness, tr.rotary_inertia
        # G EI x^4 - (G J + m EI) w^2 x^2 - m w^2 G + m J w^4 with w = W - v x: a quartic in x
        P = np.polynomial.polynomial
        coeffs = []
        for Wq in W:
            w = np.array([Wq, -v])  # W - v x
            w2 = P.polymul(w, w)
            poly = P.polyadd([0, 0, 0, 0, G * EI], -(G * J + m * EI) * P.polymul(w2, [0, 0, 1]))
            poly = P.polyadd(poly, -m * G * w2)
            poly = P.polyadd(poly, m * J * P.polymul(w2, w2))
            coeffs.append(np.pad(poly, (0, 5 - len(poly))))
        coeffs = np.array(coeffs)
        roots = [P.polyroots(c) if abs(c[-1]) > 0 else P.polyroots(c[:-1]) for c in coeffs]
        x = np.array([np.pad(r.astype(complex), (0, 4 - r.size), constant_values=np.nan)
                      for r in roots])
    k = x - g * q[:, None]
    qq = np.broadcast_to(q[:, None], k.shape)
    real = (np.abs(k.imag) < 1e-9 * (1.0 + np.abs(k.real))) & np.isfinite(k)
    k, qq = k.real[real], qq[real]
    inside = (k > lo) & (k < hi) & (np.abs(line.omega - k * line.speed) > 0.0)
    return k[inside], qq[inside]


def _integrate(line, poles, offsets, K, a, b, kind, rtol):
    """The adaptive Gauss-Kronrod quadrature of the module docstring over the panels
    [a, b] (kind 0: central, in k; 1 / 2: the right / left tail, in u)."""
    kc, rho, hc = poles
    M = line.shifts.size
    i0 = M // 2
    amp = rho[None, :] * np.exp(1j * kc[None, :] * offsets[:, None])  # (n_off, n_c)
    # the pole terms' error proxies: their diagonal and column m = 0, (2, n_c, M)
    pole_proxy = np.stack((hc * hc, hc * hc[:, i0:i0 + 1]))
    rank = np.zeros((offsets.size, M, M), complex)  # sum of w c h h^T over accepted panels
    diag = np.zeros((offsets.size, M), complex)  # sum of w d h
    fix = np.zeros(kc.size, complex)  # sum over accepted panels of (exact - Kronrod) 1/(k - k_c)
    scale = 0.0
    for _ in range(MAX_ROUNDS):
        P = a.size
        k, jac = _nodes(a, b, kind, K)
        h, c, dg_nodes = line.parts(k.ravel())
        h, c, dg_nodes = h.reshape(P, 15, M), c.reshape(P, 15), dg_nodes.reshape(P, 15, M)
        wk = jac * W_KRONROD / (2.0 * math.pi)
        wd = jac * W_DIFF / (2.0 * math.pi)
        near = _near(a, b, kind, kc)  # (P, n_c)
        inv = np.where(near[:, None, :], 1.0 / (k[:, :, None] - kc[None, None, :]), 0.0)
        lk = np.einsum("pk,pkc->pc", wk, inv)
        ld = np.einsum("pk,pkc->pc", wd, inv)
        with np.errstate(all="ignore"):
            exact = (np.log(b[:, None] - kc[None, :]) - np.log(a[:, None] - kc[None, :])) / (
                2.0 * math.pi)
        exact = np.where(near, exact, 0.0)
        column = c[..., None] * h * h[:, :, i0:i0 + 1]
        column[:, :, i0] = dg_nodes[:, :, i0]
        nodes_proxy = np.stack((dg_nodes, column))  # (2, P, 15, M)
        err = np.zeros(P)
        dg = np.zeros((offsets.size, P, M), complex)
        for j, off in enumerate(offsets):
            phase = np.exp(1j * k * off) if off != 0.0 else 1.0
            e = np.einsum("pk,xpkm->xpm", wd * phase, nodes_proxy) - np.einsum(
                "pc,xcm->xpm", ld * amp[j], pole_proxy)
            err = np.maximum(err, np.abs(e).max(axis=(0, 2)))
            dg[j] = np.einsum("pk,pkm->pm", wk * phase, dg_nodes)
        scale = max(scale, float(np.abs(diag + dg.sum(axis=1)).max()))
        tol = rtol * scale
        accept = np.ones(P, bool)
        if err.sum() > tol:
            order = np.argsort(err)[::-1]
            rest = err.sum() - np.cumsum(err[order])
            accept[order[:int(np.searchsorted(-rest, -0.5 * tol)) + 1]] = False
        hh = h[accept].reshape(-1, M)
        for j, off in enumerate(offsets):
            phase = np.exp(1j * k[accept] * off).ravel() if off != 0.0 else 1.0
            wa = (wk[accept] * c[accept]).ravel() * phase
            rank[j] += (hh * wa[:, None]).T @ hh
        diag += dg[:, accept].sum(axis=1)
        fix += (exact - lk)[accept].sum(axis=0)
        if accept.all():
            out = rank
            idx = np.arange(M)
            out[:, idx, idx] = diag  # the stable diagonal replaces the rank-one part's
            return out + np.einsum("jc,cp,cm->jpm", fix[None, :] * amp, hc, hc)
        s = ~accept
        mid = 0.5 * (a[s] + b[s])
        a, b = np.concatenate((a[s], mid)), np.concatenate((mid, b[s]))
        kind = np.concatenate((kind[s], kind[s]))
        if a.size > MAX_PANELS:
            break
    raise QuadratureError(
        f"the k quadrature of the moving-load receptance did not converge to rtol = {rtol:g} "
        f"(speed {line.speed:g} m/s, frequency {line.omega / (2 * math.pi):g} Hz): the track "
        "is nearly undamped at a wave the wheel excites; add support damping")


def _nodes(a, b, kind, K):
    """(k (P, 15), dk/dt (P, 15)) of the panels' Kronrod nodes: central panels in k, tails in
    u with k = +-K / u."""
    half = 0.5 * (b - a)
    t = 0.5 * (a + b)[:, None] + half[:, None] * NODES[None, :]
    jac = np.broadcast_to(half[:, None], t.shape).copy()
    k = t.copy()
    tail = kind > 0
    if tail.any():
        sign = np.where(kind[tail] == 2, -1.0, 1.0)[:, None]
        u = t[tail]
        k[tail] = sign * K / u
        jac[tail] = jac[tail] * K / u**2
    return k, jac


def _near(a, b, kind, kc):
    """(P, n_c): pole c is subtracted in central panel p when it lies within one panel width
    of the panel's interval."""
    if kc.size == 0:
        return np.zeros((a.size, 0), bool)
    width = (b - a)[:, None]
    dx = np.maximum(np.maximum(a[:, None] - kc.real[None, :], kc.real[None, :] - b[:, None]), 0.0)
    dist = np.hypot(dx, kc.imag[None, :])
    return (kind[:, None] == 0) & (dist < width)
