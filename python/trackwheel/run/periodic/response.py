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
from dataclasses import dataclass, field
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
from .balance import DEFAULT_RTOL, balance, own_weight_sag, periodic_track
from . import outputs as _outputs
from .outputs import extremes
from .wheel import PERIODIC_FIDELITIES, fidelity_of, wheel_of

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
    #: the balances solved, the sleeper passing first, then one per sine: (omega [rad/s],
    #: N_p [N], y_p [m]) over all kept p (the sleeper passing's y_p: the rail under the wheel,
    #: own-weight sag included), for the outputs of ``.outputs``
    balances: tuple = field(default=(), repr=False, compare=False)

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

    @cached_property
    def amplitude(self) -> float:
        """max |d| [m] over the steady state, d = y_B - y_qs(X_A) the dynamic part of the rail
        under the wheel (as ``Analysis.amplitude``; y_qs the quasi-static line of the infinite
        track, ``quasi_static_line``)."""
        return _outputs.amplitude(self)

    @cached_property
    def main_frequency(self) -> float:
        """The frequency of the largest line of d [Hz] (as ``Analysis.main_frequency``, exact:
        no record, no resolution); NaN if d has none."""
        return _outputs.main_frequency(self)

    @cached_property
    def force_rms(self) -> float:
        """RMS of N - P over a long run [N]."""
        return _outputs.force_rms(self)

    def quasi_static_line(self, x) -> np.ndarray:
        """y_qs [m] at wheel positions ``x`` [m] (from a support): the rail under the wheel
        resting there, the static load on the infinite track with its own weight (as
        ``Analysis.y_qs``)."""
        c = _outputs.quasi_static_harmonics(self.scene, (len(self.balances[0][2]) - 1) // 2)
        n = (c.size - 1) // 2
        phase = 2j * math.pi * np.multiply.outer(np.asarray(x, dtype=float), np.arange(-n, n + 1))
        return (np.exp(phase / self.scene.supports.spacing) @ c).real

    def outputs(self) -> dict:
        """The scalar outputs of the steady state by quantity name, as ``Analysis.outputs``
        gives them by column (a sweep's row; NaN where the periodic level has none: the
        frequency resolution, P1/P2)."""
        return _outputs.outputs(self)

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
    balances = [(0.0, sp.N, sp.y)]
    for s in sines:
        rhs = np.zeros(2 * n + 1, complex)
        rhs[i0] = s.amplitude
        b = balance(track, wheel, fidelity, speed, s.omega, n, rhs, rtol=rtol)
        envelopes.append(b.N)
        balances.append((s.omega, b.N, b.y))
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
        contact_stiffness=wheel.contact_stiffness, rows=tuple(rows), balances=tuple(balances))


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
