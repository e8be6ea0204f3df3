"""Defaults derived from a scene, defined once: mesh, time step, stability limit, start and end.

Every part of the package (``simulate``, ``converged``, ``adequacy``, the CLI) takes these
values from here:

- :data:`MAX_SPEED`: the highest forward speed a run accepts [m/s];
- :func:`default_start` / :func:`default_end`: the wheel-centre start and end [m], the middles of
  the first and last support bays;
- :func:`mesh`: the mesh of a call (its ``n_elements``, checked, or the scene's);
- :func:`derived_mesh` / :func:`derived_dt` / :func:`default_settings`: the mesh and time step
  that keep the headline outputs within 1 % of a refined run;
- :func:`frequency_mesh`: the mesh of the frequency-domain track up to a highest frequency;
- :func:`stability_limit`: the predicted largest stable step of an integrator, and
  :func:`warn_above_stability_limit` / :func:`warn_unresolved_mesh`, the warnings issued before
  a run that will likely fail or cannot resolve the track.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .. import _core
from ..base import validate as v
from ..base.limits import MAX_ELEMENTS, MAX_SPEED
from ..scene import Scene
from . import kernel

__all__ = [
    "ELEMENTS_PER_BAY",
    "MAX_SPEED",
    "STEPS_PER_PERIOD",
    "MeshWarning",
    "StabilityWarning",
    "default_end",
    "default_settings",
    "default_start",
    "derived_dt",
    "derived_mesh",
    "frequency_mesh",
    "mesh",
    "stability_limit",
]

#: Elements per support bay of the derived default mesh (see :func:`default_settings`).
ELEMENTS_PER_BAY = 8
#: Time steps per period of the highest frequency of interest (see :func:`default_settings`).
STEPS_PER_PERIOD = 150
#: Elements per Euler-Bernoulli bending wavelength of the frequency-domain mesh at its highest
#: frequency (see :func:`frequency_mesh`).
ELEMENTS_PER_WAVELENGTH = 10


class StabilityWarning(UserWarning):
    """The requested time step is above the predicted stability limit of the integrator."""


class MeshWarning(UserWarning):
    """The rail mesh is too coarse to resolve the support bays (fewer elements than bays)."""


def check_speed(speed, *, positive: bool = False) -> float:
    """``speed`` [m/s] as a float in [0, MAX_SPEED] ((0, MAX_SPEED] if ``positive``)."""
    return v.number("speed", speed, low=0.0, low_open=positive, high=MAX_SPEED, unit="m/s")


# --------------------------------------------------------------------------------------------
# start and end of a passage
def default_start(scene: Scene) -> float:
    """Default wheel-centre start X_0 [m]: the middle of the first support bay, d_s / 2 (the
    middle of the rail if the rail is shorter than that). 0.25 m for the paper's scene."""
    half_bay = 0.5 * scene.supports.spacing
    return half_bay if half_bay < scene.rail.length else 0.5 * scene.rail.length


def default_end(scene: Scene, x_start: float) -> float:
    """Default wheel-centre end [m]: the middle of the last support bay, L - d_s / 2, but not
    before ``x_start`` [m]. 4.75 m for the paper's scene."""
    return max(scene.rail.length - 0.5 * scene.supports.spacing, x_start)


def start_position(scene: Scene, x_start) -> float:
    """``x_start`` [m] checked against the rail, or :func:`default_start` if None."""
    if x_start is None:
        return default_start(scene)
    return v.number("x_start", x_start, low=0.0, high=scene.rail.length, unit="m")


# --------------------------------------------------------------------------------------------
# meshes and time step
def mesh(scene: Scene, n_elements: int | None = None) -> int:
    """The rail elements of a call [-]: ``n_elements`` checked against the element limit, or
    the scene's own ``rail.n_elements`` if None."""
    return scene.rail.n_elements if n_elements is None else v.n_elements(n_elements)


def support_bays(scene: Scene) -> int:
    """Number of support bays over the rail, L / d_s rounded, at least 1 [-]."""
    return max(1, round(scene.rail.length / scene.supports.spacing))


def wheel_frequency(scene: Scene) -> float:
    """sqrt(k/M) / 2 pi [Hz]: the wheel mass on the (linearised) contact spring -- the highest
    physical frequency the paper's outputs resolve (about 1.34 kHz for its scene)."""
    return math.sqrt(scene.contact_stiffness / scene.wheel.mass) / (2.0 * math.pi)


def derived_mesh(scene: Scene) -> int:
    """Default number of rail elements: ELEMENTS_PER_BAY per support bay, at least the scene's
    own ``rail.n_elements`` (80 for the paper's scene). See :func:`default_settings`."""
    return int(max(scene.rail.n_elements, ELEMENTS_PER_BAY * support_bays(scene)))


def derived_dt(scene: Scene) -> float:
    """Default generalized-alpha time step [s]: STEPS_PER_PERIOD steps per period of the wheel
    on its contact spring (4.96e-6 s for the paper's scene). See :func:`default_settings`."""
    return 1.0 / (STEPS_PER_PERIOD * wheel_frequency(scene))


def default_settings(scene: Scene, speed: float | None = None,
                     integrator: str = "generalized_alpha") -> dict:
    """Time step [s] and mesh derived from the scene, as ``dict(dt=..., n_elements=...)``: what
    :func:`trackwheel.simulate` uses when neither is given, at every fidelity level.

    Target: at most 1 % error of the amplitude max |d| (docs: Model § Outputs) against a refined
    run. The scene's former defaults (20 elements, dt = 1e-5 s) miss it by up to 5.5 %
    (benchmarks/README.md, "Speed against accuracy").

    - ``n_elements``: ELEMENTS_PER_BAY = 8 elements per support bay (l_e = d_s / 8; at least
      the scene's own mesh). Reason: the cubic ANCF element interpolates the rail under a moving
      point contact with a contact-point stiffness that varies across each element, so the wheel
      is excited at the element-passing frequency v / l_e and its harmonics. With l_e = d_s / 2
      (20 elements) or d_s / 4 (40) this spurious excitation meets the track's main resonance
      (about 340 Hz for the paper's scene) within 50-400 km/h -- at 300 km/h for 20 elements,
      150 km/h for 40 -- and moves the amplitude by 4-5 %; with d_s / 8 the effect stays below
      0.5 % (160-element runs as reference).
    - ``dt``: STEPS_PER_PERIOD = 150 steps per period of the highest frequency of interest, the
      wheel on its contact spring f_w = sqrt(k/M)/2 pi (1.34 kHz for the paper's scene, so
      dt = 4.96e-6 s). Phase errors of generalized-alpha grow with the passage time, so the
      slowest speed (50 km/h) sets the step: 1e-5 s gives -0.9 % there, 2.5e-6 s -0.2 %.
      The explicit scheme takes at most half its stability limit on the derived mesh.

    ``speed`` [m/s] is checked and otherwise unused: the rule holds from 50 to 400 km/h.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    v.choice("integrator", integrator, {"explicit", "generalized_alpha"})
    if speed is not None:
        check_speed(speed)
    ne = derived_mesh(scene)
    dt = derived_dt(scene)
    if integrator == "explicit":
        dt = min(dt, 0.5 * stability_limit(scene, "explicit", n_elements=ne))
    return {"dt": float(dt), "n_elements": int(ne)}


def frequency_mesh(scene: Scene, f_max: float) -> int:
    """Rail elements of the frequency-domain track up to ``f_max`` [Hz] (what ``trackwheel
    receptance`` and ``decay-rate`` use): whole elements per support bay, at least
    ELEMENTS_PER_WAVELENGTH per Euler-Bernoulli bending wavelength 2 pi (EI / (m w^2))^(1/4)
    (shear shortens the wavelength a little; ten leave room), no fewer than the scene's. Where
    MAX_ELEMENTS caps the count, warns (:class:`MeshWarning`) and returns the most whole
    elements per bay that fit."""
    r, d = scene.rail, scene.supports.spacing
    w = 2.0 * math.pi * max(f_max, 1.0)
    wavelength = 2.0 * math.pi * (r.bending_stiffness / (r.mass_per_length * w * w)) ** 0.25
    n_bays = max(round(r.length / d), 1)
    n = max(n_bays * math.ceil(ELEMENTS_PER_WAVELENGTH * d / wavelength), r.n_elements)
    if n <= MAX_ELEMENTS:
        return n
    n = max(MAX_ELEMENTS // n_bays, 1) * n_bays
    warnings.warn(MeshWarning(
        f"{n} elements ({MAX_ELEMENTS} at most) give fewer than ten per bending wavelength "
        f"({wavelength:.3g} m) at {f_max:g} Hz"), stacklevel=2)
    return n


def warn_unresolved_mesh(scene: Scene, n_elements: int, stacklevel: int = 3) -> bool:
    """Warn (:class:`MeshWarning`) and return True if ``n_elements`` is below the number of
    support bays: then some bay holds no node, and the rail's bending between two supports -- the
    wave the wheel excites -- cannot be represented (the derived mesh has ELEMENTS_PER_BAY)."""
    bays = support_bays(scene)
    if n_elements >= bays:
        return False
    warnings.warn(MeshWarning(
        f"n_elements = {n_elements} cannot resolve the {bays} support bays (fewer elements than "
        f"bays); the derived default is {derived_mesh(scene)} ({ELEMENTS_PER_BAY} per bay, "
        f"about 1 % on the amplitude)"), stacklevel=stacklevel)
    return True


# --------------------------------------------------------------------------------------------
# stability limits
def _start_state(scene: Scene, ne: int, x0: float):
    model = kernel.rail_model(scene, ne)
    wheel = kernel.wheel_params(scene)
    contact = kernel.contact_params(scene)
    st = _core.static_solve(model, wheel, contact, x0)
    return model, wheel, contact, np.asarray(st["e"]), float(st["y_wheel"])


def explicit_limit(model, wheel, contact, e, x0: float, y: float) -> tuple[float, float]:
    """(dt_max [s], omega_max [rad/s]) of explicit RK4 at the given state."""
    omega = _core.highest_frequency(model, wheel, contact, e, x0, y)
    return _core.explicit_stability_limit(omega), omega


def stability_limit(scene: Scene, integrator: str = "explicit", *, n_elements: int | None = None,
                    speed: float = 0.0, rho_inf: float = 0.8,
                    x_start: float | None = None) -> float:
    """Predicted largest stable time step [s] of ``integrator`` for ``scene``.

    ``"explicit"`` (classical RK4, the paper's scheme): the stability interval of RK4 on the
    imaginary axis is |omega dt| <= 2 sqrt(2), so dt_max = 2 sqrt(2) / omega_max, with omega_max
    [rad/s] the highest eigenfrequency of the assembled system -- the ANCF rail on its supports
    with the wheel mass on its contact spring (docs: Model § Rail, § Wheel, § Contact), linearised at the static state
    with the wheel at ``x_start`` (default :func:`default_start`) -- found by power iteration in
    the kernel. omega_max grows as 1/l_e^2 (the shortest bending wave of an element), so dt_max
    falls by 4x per mesh doubling. The speed does not enter: the linearised system does not
    depend on it (the convective terms of the moving contact are small), which
    benchmarks/stability_map.py confirms from 50 to 400 km/h; ``speed`` [m/s] is accepted for
    symmetry with :func:`trackwheel.simulate` and checked only.

    ``"generalized_alpha"``: unconditionally stable for linear problems for every ``rho_inf`` in
    [0, 1] (Chung & Hulbert 1993), so the result is ``math.inf``. What fails first at large steps
    is Newton's iteration at contact loss/landing and stick/slip transitions, which no linear
    analysis predicts; benchmarks/stability_map.py measures where it stops converging.

    Raises ValueError / TypeError naming the parameter for bad arguments.
    """
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    v.choice("integrator", integrator, {"explicit", "generalized_alpha"})
    check_speed(speed)
    v.number("rho_inf", rho_inf, low=0.0, high=1.0)
    ne = mesh(scene, n_elements)
    x0 = start_position(scene, x_start)
    if integrator == "generalized_alpha":
        return math.inf
    dt_max, _ = explicit_limit(*_start_state(scene, ne, x0), x0)
    return dt_max


def warn_above_stability_limit(model, wheel, contact, e, x0: float, y: float, dt: float,
                               stacklevel: int = 3) -> float:
    """Warn (:class:`StabilityWarning`) if the explicit time step ``dt`` [s] is above the
    predicted RK4 limit at the given state; returns the limit [s]. Used by ``simulate``."""
    dt_max, omega = explicit_limit(model, wheel, contact, e, x0, y)
    if dt > dt_max:
        warnings.warn(StabilityWarning(
            f"dt = {dt:.3g} s is above the predicted stability limit of the explicit RK4 scheme, "
            f"{dt_max:.3g} s (2 sqrt(2)/omega_max, highest eigenfrequency "
            f"{omega / (2 * math.pi):.4g} Hz for this mesh): the run will almost certainly "
            f"diverge. Use dt <= {dt_max:.3g} s, fewer elements, or "
            f"integrator='generalized_alpha' (unconditionally stable)"), stacklevel=stacklevel)
    return dt_max
