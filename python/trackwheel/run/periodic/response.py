"""The periodic level: the steady response of a wheel at constant speed on the linear track
periodic in its sleeper bay, in the frequency domain (docs: Model § The periodic level).

:func:`periodic_response` solves, for the sleeper passing and for each harmonic of the running
surfaces, the harmonic balance of the moving contact over the side bands Omega + p w_s
(w_s = 2 pi v / d): with the moving-load receptance matrix A of the rail (``_moving``), the
wheel's receptance alpha_W and the contact's alpha_C,

    (diag(alpha_C(w_p) + alpha_W(w_p)) + A) N = r,

N_p the contact-force harmonics at w_p = Omega + p w_s [N] (upward on the wheel), r the
running-surface excitation [m]; for the sleeper passing N_0 = P is known and r is the rail's
own-weight sag between the sleepers (``own_weight_sag``), the rows p != 0 solved. No time
stepping, no mesh, no start-up transient.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from ...base import validate as v
from ...base.limits import MAX_SPEED
from ...excitation import (
    Irregularity,
    Polygon,
    SineProfile,
    contact_half_width,
    filter_attenuation,
)
from ...scene import Scene
from ._moving import receptance_matrix
from ._track import PeriodicTrack
from .wheel import (
    PERIODIC_FIDELITIES,
    fidelity_of,
    wheel_contact_receptance,
    wheel_of,
    wheel_receptance,
)

if TYPE_CHECKING:  # pandas is imported when a table is built: keeps `import trackwheel` light
    import pandas as pd

__all__ = ["DEFAULT_HARMONICS", "PERIODIC_FIDELITIES", "PeriodicResponse", "moving_receptance",
           "periodic_response", "periodic_track"]

#: Sleeper-passing harmonics and side bands on each side reported by default [-]: on 0.6 m bays
#: at 300 km/h up to 833 Hz; on an Euler-Bernoulli rail the sixth is 0.3 % of the first (the
#: Timoshenko rail's fall only like 1/k^2: ask for more there)
DEFAULT_HARMONICS = 6
#: Harmonics kept beyond the reported ones on each side of the balance [-]
HARMONIC_MARGIN = 2
#: Default relative tolerance of the k quadrature of the receptance matrix [-]
DEFAULT_RTOL = 1e-7
#: Bay phases sampled for the force's extremes [-]
PHASES = 512


def periodic_track(scene: Scene) -> PeriodicTrack:
    """The scene's linear track as the periodic level sees it: the infinite rail (the scene's
    beam theory) on its supports every ``Supports.spacing``, checked to be periodic and
    damped. The rail's length, its end supports and absorbing zones, a travelling window and
    the track's own weight do not enter (an infinite track; a static preload)."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    sup, rail = scene.supports, scene.rail
    if sup.positions is not None:
        raise ValueError("the periodic level needs a track periodic in its sleeper bay: equal "
                         "supports every Supports.spacing (Supports.positions must be None, got "
                         f"{len(sup.positions)} explicit positions)")
    track = PeriodicTrack(
        bay=sup.spacing, bending_stiffness=rail.bending_stiffness,
        mass_per_length=rail.mass_per_length,
        shear_stiffness=rail.shear_stiffness if rail.beam == "timoshenko" else math.inf,
        rotary_inertia=rail.rotary_inertia if rail.beam == "timoshenko" else 0.0,
        pad_stiffness=sup.stiffness, pad_damping=sup.damping,
        sleeper_mass=sup.sleeper_mass or 0.0, ballast_stiffness=sup.ballast_stiffness or 0.0,
        ballast_damping=sup.ballast_damping)
    if not track.damped:
        raise ValueError("the periodic level needs damping in the supports (Supports.damping > 0, "
                         "or Supports.ballast_damping > 0 with sleepers): on an undamped "
                         "periodic track the waves the moving wheel excites never decay, so "
                         "there is no steady state to compute (the time domain never settles "
                         "either)")
    return track



def own_weight_sag(scene: Scene, n: int) -> np.ndarray:
    """Fourier coefficients c_p, p = -n..n, of the track's rest state under its own weight
    (``Scene.rail_gravity``): the rail's height w_g(X) = sum_p c_p e^{i 2 pi p X / d} [m], X
    from a support. By symmetry each support carries the weight of one bay, q d (q = rho A g),
    and the rail has zero slope there, so each bay is a clamped-clamped beam under q:
    w_g = y_s - q x^2 (d - x)^2 / (24 EI) - q x (d - x) / (2 kappa G A) (the last term
    Timoshenko only), with the supports' own deflection y_s = -q d / k_s, or for pad-sleeper-
    ballast supports -q d / k_p - (q d + m_s g) / k_b. Its harmonics, c_p = q d^4 / (16 EI
    pi^4 p^4) + q d^2 / (4 kappa G A pi^2 p^2), are a bay-periodic profile the wheel rolls
    over: the rail sags between the sleepers under its own weight."""
    p = np.arange(-n, n + 1)
    out = np.zeros(p.size, complex)
    if not scene.rail_gravity:
        return out
    rail, sup = scene.rail, scene.supports
    d, q = sup.spacing, rail.mass_per_length * scene.gravity
    EI = rail.bending_stiffness
    shear = rail.beam == "timoshenko"
    GA = rail.shear_stiffness
    if sup.layered:
        y_s = -q * d / sup.stiffness - (q * d + sup.sleeper_mass * scene.gravity) / (
            sup.ballast_stiffness)
    else:
        y_s = -q * d / sup.stiffness
    out[n] = y_s - q * d**4 / (720.0 * EI) - (q * d * d / (12.0 * GA) if shear else 0.0)
    pp = p[p != 0].astype(float)
    out[p != 0] = q * d**4 / (16.0 * EI * math.pi**4 * pp**4) + (
        q * d * d / (4.0 * GA * math.pi**2 * pp**2) if shear else 0.0)
    return out


@dataclass(frozen=True)
class _Sine:
    """One harmonic of the running surfaces under the wheel: r(t) = Re(amplitude e^{i w t}),
    t = X_A / v."""

    omega: float  #: w = 2 pi v / lambda [rad/s]
    amplitude: complex  #: complex amplitude [m]
    label: str  #: e.g. "rail sine 0.05 m"
    wavelength: float  #: on the track [m]


def _sines(scene: Scene, irregularity, speed: float, radius: float) -> list[_Sine]:
    irr = scene.irregularity if irregularity is None else irregularity
    if irr is not None and not isinstance(irr, Irregularity):
        raise TypeError(f"irregularity must be a trackwheel.Irregularity or None, got "
                        f"{type(irr).__name__}")
    a_patch = contact_half_width(scene) if scene.contact.patch_filter else None
    out = []
    for i, p in enumerate(() if irr is None else irr.parts):
        if not isinstance(p, SineProfile):
            what = getattr(p, "kind", type(p).__name__)
            hint = (" (for a random profile give its spectrum to trackwheel.random_response)"
                    if what == "random" else "")
            raise ValueError(
                f"irregularity part {i} is a {what!r} profile: the periodic level takes rail "
                "profiles that are sums of sines (Irregularity.sine), whose response is a sum "
                f"of steady harmonics; a discrete or measured shape has none{hint}; use "
                "simulate")
        if p.amplitude == 0.0:
            continue
        gain = 1.0 if a_patch is None else float(filter_attenuation(p.wavelength, a_patch)[0])
        # a sin(2 pi X / lambda + phi) = Re(-i a e^{i phi} e^{i 2 pi X / lambda}), X = v t
        out.append(_Sine(2.0 * math.pi * speed / p.wavelength,
                         -1j * p.amplitude * gain * np.exp(1j * p.phase),
                         f"rail sine {p.wavelength:g} m", p.wavelength))
    for j, d in enumerate(scene.active_vehicle.wheels[0].defects):
        if not isinstance(d, Polygon):
            raise ValueError(
                f"Wheel.defects[{j}] is a {d.kind!r}: the periodic level takes out-of-round "
                "wheels that are sums of sines (Polygon); a flat's impacts need simulate")
        if d.amplitude == 0.0:
            continue
        # Delta rho = a cos(m psi + phi), psi = X_A / rho0 (the mark in contact at X = 0)
        out.append(_Sine(d.order * speed / radius, d.amplitude * np.exp(1j * d.phase) + 0j,
                         f"polygon order {d.order}", 2.0 * math.pi * radius / d.order))
    return out


def _table(rows, amplitude: str) -> pd.DataFrame:
    import pandas as pd

    return pd.DataFrame(rows, columns=["frequency_hz", amplitude, "phase_rad", "source", "order",
                                       "component"])


@dataclass(frozen=True)
class PeriodicResponse:
    """The steady response of :func:`periodic_response` (docs: Model § The periodic level).

    Signals are sums of cosines over the rows of their tables,
    ``value(t) = mean + sum amplitude cos(2 pi f t + phase)``, t [s] counted from the instant
    the wheel is over a support (X_A = 0; supports at X = j d), so that the force at the wheel
    position X is N(X / v). Rows with ``source`` "sleeper_passing" are the harmonics k v/d of
    the smooth track (``order`` k); rows "irregularity" the response to each harmonic of the
    running surfaces (``component`` names it) at its frequency (``order`` 0) and its
    parametric side bands f + k v/d (``order`` k). Displacements are upward positive: the
    rail's under the wheel from the undeformed straight rail (as ``Result.y_contact``: the
    track's own-weight sag included), the wheel centre's from where it would stand on the
    undeformed rail with an unloaded contact (``Result.y_wheel`` minus rho0).
    """

    scene: Scene
    speed: float  #: v [m/s]
    fidelity: str  #: the time-domain level it reproduces (``PERIODIC_FIDELITIES``)
    n_harmonics: int  #: n, harmonics and side bands reported on each side [-]
    sleeper_frequency: float  #: f_s = v / d [Hz]
    mean_force: float  #: P, the static wheel load (the steady mean) [N]
    mean_rail_displacement: float  #: mean of the rail under the wheel [m] (negative: down)
    mean_wheel_displacement: float  #: mean of the wheel centre [m]
    min_force: float  #: the least contact force over all phases of the steady state [N]
    max_force: float  #: the largest [N]
    contact_stiffness: float  #: k of the linear(ised) contact [N/m] (inf: rigid)
    #: the rows: (frequency [Hz], N, y, Y (complex amplitudes, [N], [m], [m]), the moving
    #: receptance [m/N], source, order, component); built into the tables on access
    rows: tuple = ()

    def _harmonics(self, column: int, amplitude: str) -> pd.DataFrame:
        return _table([(r[0], abs(r[column]), float(np.angle(r[column])), r[5], r[6], r[7])
                       for r in self.rows], amplitude)

    @cached_property
    def force_harmonics(self) -> pd.DataFrame:
        """Contact-force harmonics: frequency_hz, amplitude_n [N], phase_rad, source, order,
        component."""
        return self._harmonics(1, "amplitude_n")

    @cached_property
    def rail_harmonics(self) -> pd.DataFrame:
        """The rail's displacement under the wheel, rows as ``force_harmonics``, its amplitude
        in ``amplitude_m`` [m]."""
        return self._harmonics(2, "amplitude_m")

    @cached_property
    def wheel_harmonics(self) -> pd.DataFrame:
        """The wheel centre's displacement, rows as ``force_harmonics``, its amplitude in
        ``amplitude_m`` [m]."""
        return self._harmonics(3, "amplitude_m")

    @cached_property
    def moving_receptance(self) -> pd.DataFrame:
        """The moving (Doppler) receptance seen by the contact at each force harmonic's
        frequency: the rail's bay-averaged displacement at that frequency per unit force moving
        with the wheel, A_0(f) [m/N, complex] (frequency_hz, receptance, source, order,
        component)."""
        import pandas as pd

        return pd.DataFrame([(r[0], r[4], r[5], r[6], r[7]) for r in self.rows],
                            columns=["frequency_hz", "receptance", "source", "order",
                                     "component"])

    @property
    def dynamic_factor(self) -> float:
        """max N / P [-]."""
        return self.max_force / self.mean_force

    def force(self, t) -> np.ndarray:
        """N(t) [N] at times t [s] (t = 0: the wheel over a support), all rows summed with the
        running surfaces' phases as given."""
        return self._signal(self.mean_force, 1, t)

    def rail_displacement(self, t) -> np.ndarray:
        """The rail's displacement under the wheel at t [s] [m]."""
        return self._signal(self.mean_rail_displacement, 2, t)

    def wheel_displacement(self, t) -> np.ndarray:
        """The wheel centre's displacement at t [s] [m]."""
        return self._signal(self.mean_wheel_displacement, 3, t)

    def _signal(self, mean, column, t):
        t = np.asarray(t, dtype=float)
        if not self.rows:
            return np.full(t.shape, mean)
        f = np.array([r[0] for r in self.rows])
        a = np.array([r[column] for r in self.rows])
        return mean + (np.abs(a) * np.cos(2.0 * math.pi * np.multiply.outer(t, f)
                                          + np.angle(a))).sum(axis=-1)

    def __repr__(self) -> str:
        first = next((abs(r[1]) for r in self.rows if r[5] == "sleeper_passing"), 0.0)
        return (f"PeriodicResponse({self.fidelity} at {self.speed * 3.6:.4g} km/h: "
                f"P = {self.mean_force / 1e3:.4g} kN, sleeper passing {self.sleeper_frequency:.4g}"
                f" Hz with first harmonic {first:.4g} N, N in [{self.min_force / 1e3:.4g}, "
                f"{self.max_force / 1e3:.4g}] kN, {len(self.rows)} harmonics)")


@dataclass(frozen=True)
class Balance:
    """One harmonic balance: the harmonics p = -n..n at w_p = omega + p w_s."""

    w: np.ndarray  #: w_p [rad/s]
    A: np.ndarray  #: the rail's moving-load receptance matrix [m/N]
    N: np.ndarray  #: force harmonics [N]
    y: np.ndarray  #: the rail's displacement harmonics under the wheel [m]
    Y: np.ndarray  #: the wheel centre's [m]
    static: np.ndarray  #: harmonics at zero frequency (bool)


def balance(track, wheel, fidelity, speed, omega, n, rhs, *, mean=None, rtol=DEFAULT_RTOL):
    """Solve the harmonic balance at base frequency ``omega`` [rad/s] for the excitation
    ``rhs`` (the running surfaces' harmonics under the wheel, (2n+1,) [m]). ``mean`` = P
    [N]: the sleeper passing, whose harmonic p = 0 is the static load (known; its equation
    gives the mean displacements)."""
    p = np.arange(-n, n + 1)
    i0 = n
    ws = 2.0 * math.pi * speed / track.bay
    w = omega + p * ws
    A = receptance_matrix(track, speed, omega, n, rtol=rtol)[0]
    # a harmonic at zero frequency carries no force: the wheel's mean acceleration is zero
    static = np.abs(w) < 1e-9 * max(ws, abs(omega))
    if mean is not None:
        static = p == 0
    wsafe = np.where(static, 1.0, w)
    free = ~static
    N = np.zeros(p.size, complex)
    if mean is not None:
        N[i0] = mean
    if fidelity != "linear/moving_force":
        Z = A[np.ix_(free, free)] + np.diag(wheel_contact_receptance(wheel, wsafe[free]))
        N[free] = np.linalg.solve(Z, rhs[free] - A[np.ix_(free, static)] @ N[static])
    y = -A @ N
    if mean is not None:
        y = y + rhs  # the own-weight sag: part of the rail's height under the wheel
    Y = np.where(static, 0.0, wheel_receptance(wheel, wsafe)) * N
    if fidelity == "linear/moving_force":
        Y = y + (0.0 if mean is not None else rhs)
    return Balance(w, A, N, y, Y, static)


def periodic_response(scene: Scene, speed: float, *, irregularity: Irregularity | None = None,
                      n_harmonics: int = DEFAULT_HARMONICS, fidelity: str | None = None,
                      rtol: float = DEFAULT_RTOL, linearisation_tol: float = 0.02
                      ) -> PeriodicResponse:
    """The steady response of the scene's wheel at constant ``speed`` [m/s] on its linear
    track, periodic in the sleeper bay, in the frequency domain: the sleeper-passing harmonics
    k v/d and the response to each sine of the running surfaces with its side bands, without
    time stepping (docs: Model § The periodic level).

    Parameters
    ----------
    scene : the track (equal supports every ``Supports.spacing``, single or pad-sleeper-
        ballast, with damping; Euler-Bernoulli or Timoshenko rail; the rail's length, end
        zones and window do not enter: the track is infinite) and one wheel, free under its
        static load or on its vehicle's suspensions (one wheel: a ``Vehicle`` whose bogie and
        car body rest on it).
    speed : v in (0, ``MAX_SPEED``] [m/s].
    irregularity : the rail profile, a sum of ``Irregularity.sine``; None takes
        ``scene.irregularity`` (``Irregularity()`` for a smooth rail). Random, dipped-joint and
        sampled profiles are refused (a random profile's force spectrum comes from its
        spectrum: ``random_response``). Polygonal wheels (``Wheel.defects`` of ``Polygon``) are
        taken too, with the wheel angle psi = X_A / rho0.
    n_harmonics : n, sleeper-passing harmonics (1..n) and side bands (-n..n) reported [-],
        1..64; the balance keeps HARMONIC_MARGIN more on each side, so the reported ones do not
        feel the truncation.
    fidelity : the linear level reproduced (``PERIODIC_FIDELITIES``); None: "linear/hertz" for
        a Hertzian scene contact, else "linear/sprung". "full" and "ancf/..." are refused.
    rtol : relative tolerance of the wavenumber quadrature, of the receptance matrix's largest
        entry [-], in [1e-10, 1e-2].
    linearisation_tol : "linear/hertz" only: the largest estimated error of the linearised
        Hertz law, max |N - P| / (6 P) [-] (the second-order term of N = C_H delta^1.5 against
        the first); above it the response is refused.

    Raises ValueError (naming why) where the level does not apply: a non-periodic or undamped
    track, several wheels, a profile that is not a sum of sines, contact loss predicted by the
    linear result (min N <= 0), the Hertz law beyond its linearisation, the full ANCF model.
    """
    fidelity = fidelity_of(scene, fidelity)
    track = periodic_track(scene)
    speed = v.number("speed", speed, low=0.0, high=MAX_SPEED, low_open=True, unit="m/s")
    n_out = v.integer("n_harmonics", n_harmonics, low=1, high=64)
    rtol = v.number("rtol", rtol, low=1e-10, high=1e-2)
    linearisation_tol = v.number("linearisation_tol", linearisation_tol, low=0.0, low_open=True)
    wheel = wheel_of(scene, fidelity)
    sines = _sines(scene, irregularity, speed, wheel.radius)
    P = wheel.load
    n = n_out + HARMONIC_MARGIN
    i0 = n
    rows = []
    # the sleeper passing: N_0 = P known; the wheel rolls over the rail's own-weight sag
    # between the sleepers too (a bay-periodic profile)
    sag = own_weight_sag(scene, n)
    sp = balance(track, wheel, fidelity, speed, 0.0, n, sag, mean=P, rtol=rtol)
    mean_rail = float(sp.y[i0].real)
    mean_wheel = mean_rail - wheel.static_compression
    for q in range(1, n_out + 1):
        j = i0 + q
        rows.append((sp.w[j] / (2.0 * math.pi), 2.0 * sp.N[j], 2.0 * sp.y[j], 2.0 * sp.Y[j],
                     sp.A[j, j], "sleeper_passing", q, ""))
    envelopes = []  # per sine: the force harmonics, whose sum over p is its envelope
    for s in sines:
        rhs = np.zeros(2 * n + 1, complex)
        rhs[i0] = s.amplitude
        b = balance(track, wheel, fidelity, speed, s.omega, n, rhs, rtol=rtol)
        envelopes.append(b.N)
        for j in range(i0 - n_out, i0 + n_out + 1):
            if b.static[j]:
                continue
            f = b.w[j] / (2.0 * math.pi)
            # a component at negative frequency is the complex conjugate at |f|
            fix = (lambda z: z) if f > 0 else np.conj
            rows.append((abs(f), fix(b.N[j]), fix(b.y[j]), fix(b.Y[j]), fix(b.A[j, j]),
                         "irregularity", j - i0, s.label))
    lo, hi = extremes(sp.N, envelopes, n)
    if fidelity != "linear/moving_force":
        check_applies(fidelity, P, lo, hi, linearisation_tol)
    return PeriodicResponse(
        scene=scene, speed=speed, fidelity=fidelity, n_harmonics=n_out,
        sleeper_frequency=speed / track.bay, mean_force=P, mean_rail_displacement=mean_rail,
        mean_wheel_displacement=mean_wheel, min_force=lo, max_force=hi,
        contact_stiffness=wheel.contact_stiffness, rows=tuple(rows))


def extremes(Nsp, envelopes, n) -> tuple[float, float]:
    """(min N, max N) [N] over all phases: the sleeper passing at the bay phase theta plus,
    per sine, its envelope |G(theta)| at the least and the most favourable phase of the sine
    (exact for sines incommensurate with the bay, a bound otherwise)."""
    p = np.arange(-n, n + 1)

    def at_phases(N):  # sum_p N_p e^{i p theta_j}, theta_j = 2 pi j / PHASES
        spread = np.zeros(PHASES, complex)
        np.add.at(spread, p % PHASES, N)
        return np.fft.ifft(spread) * PHASES

    base = at_phases(Nsp).real
    spread = sum((np.abs(at_phases(N)) for N in envelopes), np.zeros(PHASES))
    return float((base - spread).min()), float((base + spread).max())


def check_applies(fidelity, P, lo, hi, tol, loss=True):
    if loss and lo <= 0.0:
        raise ValueError(
            f"the linear steady state predicts contact loss (least contact force {lo:.4g} N <= 0 "
            f"against the static load {P:.4g} N): the wheel would leave the rail, which the "
            "periodic level (a linear, bilateral contact) cannot follow; use simulate with "
            "fidelity 'linear/hertz' or 'full'")
    if fidelity == "linear/hertz":
        err = max(hi - P, P - lo) / (6.0 * P)
        if err > tol:
            raise ValueError(
                f"the Hertz contact is beyond its linearisation: the force swings by "
                f"{max(hi - P, P - lo):.4g} N about P = {P:.4g} N, an estimated error of "
                f"{err:.3g} > linearisation_tol = {tol:g} (the second-order term of "
                "N = C_H delta^1.5 against the first, |N - P| / (6 P)); use "
                "fidelity='linear/sprung' (a linear spring) or simulate with 'linear/hertz'")


def moving_receptance(scene: Scene, speed: float, freqs, *, n_harmonics: int = 4,
                      position: float | None = None, rtol: float = DEFAULT_RTOL) -> np.ndarray:
    """The moving (Doppler) receptance of the scene's periodic track [m/N]: a vertical force
    e^{i 2 pi f t} moving at ``speed`` v [m/s] (>= 0) displaces the rail under it by
    sum_n A_n(f) e^{i 2 pi (f + n v/d) t}; returns A_n at each of ``freqs`` f [Hz], shape
    (n_freq, 2 n + 1) for n = -n_harmonics..n_harmonics (column n_harmonics is A_0, the
    bay-averaged moving receptance). With ``position`` x [m] (in the bay, from a support) the
    receptance at the instant the force passes x, sum_n A_n e^{i 2 pi n x / d}, shape
    (n_freq,): at v = 0 the point receptance at x of the infinite track (``receptance`` of a
    long rail). f != 0 when v = 0."""
    track = periodic_track(scene)
    speed = v.number("speed", speed, low=0.0, high=MAX_SPEED, unit="m/s")
    f = np.atleast_1d(np.asarray(freqs, dtype=float))
    if f.ndim != 1 or f.size == 0 or not np.all(np.isfinite(f)):
        raise ValueError("freqs must be a non-empty 1-d sequence of finite frequencies [Hz]")
    if speed == 0.0 and np.any(f == 0.0):
        raise ValueError("freqs = 0 Hz with speed = 0 m/s is the static deflection of an "
                         "infinite free rail point: allowed f != 0 at v = 0")
    n = v.integer("n_harmonics", n_harmonics, low=0, high=64)
    rtol = v.number("rtol", rtol, low=1e-10, high=1e-2)
    out = np.empty((f.size, 2 * n + 1), complex)
    for i, fi in enumerate(f):
        out[i] = receptance_matrix(track, speed, 2.0 * math.pi * fi, n, rtol=rtol)[0][:, n]
    if position is None:
        return out
    x = v.number("position", position, unit="m")
    return out @ np.exp(2j * math.pi * np.arange(-n, n + 1) * x / track.bay)
