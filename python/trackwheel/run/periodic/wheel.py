"""The wheel as the periodic level sees it: its load, mass and contact law, and its receptance
with the vehicle's linear suspensions (docs: Model § The periodic level, § The vehicle)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...base import validate as v
from ...scene import Scene
from .. import kernel

#: The time-domain levels the periodic level reproduces (the linear track with the wheel's
#: contact law linear or linearised): "linear/sprung" (linear spring k), "linear/hertz"
#: (Hertz linearised at the static wheel load), "linear/moving_mass" (rigid contact),
#: "linear/moving_force" (a constant force P, no wheel dynamics)
PERIODIC_FIDELITIES = ("linear/sprung", "linear/hertz", "linear/moving_mass",
                       "linear/moving_force")
#: The nonlinear levels, which the periodic level refuses
FULL_FIDELITIES = ("full", "ancf/sprung", "ancf/hertz")


@dataclass(frozen=True)
class PeriodicWheel:
    """What the harmonic balance needs of the wheel and its contact."""

    load: float  #: P, the static wheel load [N]
    mass: float  #: M [kg]
    contact_stiffness: float  #: k [N/m]; inf: rigid (moving mass)
    contact_damping: float  #: [N s/m]
    static_compression: float  #: delta at the static load [m]
    radius: float  #: rho0 [m]
    #: (M_v, K_v, C_v) of the vehicle over u = [Y, (z, phi) per body] (the kernel's,
    #: ``kernel.vehicle_matrices``), or None for a wheel without bodies above it
    vehicle: tuple | None
    gravity: float


def wheel_of(scene: Scene, fidelity: str) -> PeriodicWheel:
    veh = scene.active_vehicle
    if veh.n_wheels != 1:
        raise ValueError(
            f"the periodic level takes one wheel (with its vehicle's bodies and suspensions); "
            f"the scene's vehicle has {veh.n_wheels}: its wheels would interact through the "
            "rail, which the periodic level does not model; use simulate, or one wheel of the "
            "vehicle")
    w = veh.wheels[0]
    if w.brake_torque > 0.0:
        raise ValueError("Wheel.brake_torque > 0 needs the wheel's rotation, which the periodic "
                         "level (the linear levels' vertical model) does not have")
    P = float(veh.static_loads(scene.gravity)[0])
    c = scene.contact
    if fidelity == "linear/sprung":
        # the linear/sprung level's spring: the given k, or Hertz linearised at the static load
        k = scene.contact_stiffness
        comp = P / k
    elif fidelity == "linear/hertz":
        ch = c.stiffness if (c.law == "hertz" and c.stiffness is not None) else scene.hertz_constant
        if c.law == "linear" and c.stiffness is not None:
            # a given linear k becomes the Hertz constant with that stiffness at the static load
            # (as simulate's linear/hertz level does)
            ch = (c.stiffness / (1.5 * scene.static_load ** (1.0 / 3.0))) ** 1.5
        k = 1.5 * ch ** (2.0 / 3.0) * P ** (1.0 / 3.0)  # dN/d delta at N = P
        comp = (P / ch) ** (2.0 / 3.0)
    else:
        k, comp = math.inf, 0.0
    bodies = None
    if scene.vehicle is not None and scene.vehicle.n_bodies:
        vm = kernel.vehicle_matrices(scene)
        bodies = (np.diag(vm.mass), vm.K, vm.C)
    return PeriodicWheel(load=P, mass=w.mass, contact_stiffness=k, contact_damping=c.damping,
                  static_compression=comp, radius=w.radius, vehicle=bodies,
                  gravity=scene.gravity)


def wheel_receptance(wheel: PeriodicWheel, w: np.ndarray) -> np.ndarray:
    """alpha_W(w) [m/N]: the wheel centre's displacement per upward force on it at w [rad/s]
    (w != 0): -1/(M w^2) for a free wheel, else the wheel's entry of the inverse of the
    vehicle's dynamic stiffness K_v + i w C_v - w^2 M_v over u = [Y_wheel, (z, phi) per body],
    the kernel's matrices (docs: Model § The vehicle)."""
    w = np.asarray(w, dtype=float)
    if wheel.vehicle is None:
        return -1.0 / (wheel.mass * w * w) + 0j
    M, K, C = wheel.vehicle
    Z = K[None] + 1j * w[:, None, None] * C[None] - (w * w)[:, None, None] * M[None]
    rhs = np.zeros((w.size, M.shape[0], 1), complex)
    rhs[:, 0, 0] = 1.0
    return np.linalg.solve(Z, rhs)[:, 0, 0]


def fidelity_of(scene, fidelity) -> str:
    if fidelity is None:
        return "linear/hertz" if getattr(scene.contact, "law", "") == "hertz" else "linear/sprung"
    if fidelity in FULL_FIDELITIES:
        raise ValueError(
            f"fidelity = {fidelity!r}: the periodic level is the linear track in the frequency "
            "domain; the full ANCF model (large-rotation rail, contact-point search with "
            "obliquity, rolling constraint with slip) is nonlinear, so its steady state is not a "
            "superposition of harmonics; use simulate(scene, speed, fidelity="
            f"{fidelity!r}); allowed here: {', '.join(PERIODIC_FIDELITIES)}")
    v.choice("fidelity", fidelity, set(PERIODIC_FIDELITIES))
    return fidelity


def wheel_contact_receptance(wheel: PeriodicWheel, w) -> np.ndarray:
    """alpha_C + alpha_W at w [rad/s] (w != 0) [m/N]."""
    k = wheel.contact_stiffness
    contact = 0.0 if math.isinf(k) else 1.0 / (k + 1j * np.asarray(w) * wheel.contact_damping)
    return contact + wheel_receptance(wheel, w)
