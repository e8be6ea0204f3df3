"""The harmonic balance of the wheel on the periodic track: the scene's track, its own-weight
sag and one balance over the side bands (docs: Model § The periodic level).

``periodic_track`` is the scene's track as the periodic level sees it, ``own_weight_sag`` the
rail's sag between the sleepers that the wheel rolls over, ``balance`` one balance of the
contact over the side bands Omega + p w_s."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...scene import Scene
from ._moving import receptance_matrix
from ._track import PeriodicTrack
from .wheel import wheel_contact_receptance, wheel_receptance

__all__ = ["DEFAULT_RTOL", "Balance", "balance", "own_weight_sag", "periodic_track"]

#: Default relative tolerance of the k quadrature of the receptance matrix [-]
DEFAULT_RTOL = 1e-7


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
    sup.one_value("the periodic level needs supports that repeat every bay")
    if sup.unilateral:
        raise ValueError("the periodic level is linear: Supports.void and "
                         "Supports.ballast_tensionless make the ballast push only; give void = 0 "
                         "and ballast_tensionless = False, or run a time-domain level")
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
