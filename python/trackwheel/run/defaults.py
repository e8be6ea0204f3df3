"""Defaults derived from a scene, defined once: mesh, time step and stability limit.

Every part of the package (``simulate``, ``receptance``, ``decay_rate``, ``eigen``, ``analyse``,
``converged``, ``adequacy``, the CLI) takes these values from here:

- :data:`MAX_SPEED`: the highest forward speed a run accepts [m/s];
- the frequencies that matter for a scene (docs: Model § Default time step and mesh):
  :func:`wheel_frequency` (the wheel on its contact spring), :func:`contact_resonance` (the
  wheel and the rail's local mass on the contact spring), :func:`pinned_pinned_frequency` (a
  support bay's span, of the scene's beam theory: what the mesh resolves) and the highest of
  them, :func:`highest_frequency` (what the time step resolves); :func:`bending_wavelength`
  of the scene's beam at a frequency;
- one mesh rule, :func:`elements_per_bay`: whole elements per support bay, at least
  ELEMENTS_PER_WAVELENGTH (of the beam theory's element) per bending wavelength at the highest
  frequency of the call -- :func:`derived_mesh` for a run and ``eigen`` (the pinned-pinned
  frequency, and at least ELEMENTS_PER_BAY per bay for the moving contact) and
  :func:`frequency_mesh` for ``receptance`` and ``decay_rate`` (the highest frequency asked);
- :func:`derived_dt` / :func:`default_settings`: the time step; :func:`mesh`: the mesh of a
  call (its ``n_elements``, checked, or the scene's);
- where a run starts and ends and which part of it ``analyse`` measures, away from the rail's
  rigid ends and the start-up transient, is :mod:`trackwheel.run.stretch`;
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
    "ELEMENTS_PER_WAVELENGTH",
    "MAX_SPEED",
    "STEPS_PER_HIGHEST_PERIOD",
    "STEPS_PER_PERIOD",
    "MeshWarning",
    "StabilityWarning",
    "bending_wavelength",
    "contact_resonance",
    "default_settings",
    "derived_dt",
    "derived_mesh",
    "elements_per_bay",
    "frequency_mesh",
    "highest_frequency",
    "mesh",
    "pinned_pinned_frequencies",
    "pinned_pinned_frequency",
    "stability_limit",
    "wheel_frequency",
]

#: Elements per support bay of a run's mesh at least (the moving contact; see
#: :func:`derived_mesh`).
ELEMENTS_PER_BAY = 8
#: Time steps per period of the wheel on its contact spring (see :func:`derived_dt`).
STEPS_PER_PERIOD = 150
#: Time steps per period of the highest frequency of interest at least (see :func:`derived_dt`).
STEPS_PER_HIGHEST_PERIOD = 20
#: Elements per bending wavelength that put the track's resonance frequencies within 0.1 % of
#: the converged ones, per beam theory (see :func:`elements_per_bay`): the Hermite cubic of the
#: Euler-Bernoulli rail converges as N^-4 (its pinned-pinned frequency is 0.03 % high with 8 per
#: wavelength), the interdependent interpolation element of the Timoshenko rail only as N^-2
#: (about 0.6 / N^2: 1 % high with 8, 0.09 % with 24; measured on the ballasted track against
#: 64 elements per bay, tests/test_defaults.py).
ELEMENTS_PER_WAVELENGTH = {"euler": 10, "timoshenko": 24}

class StabilityWarning(UserWarning):
    """The requested time step is above the predicted stability limit of the integrator."""


class MeshWarning(UserWarning):
    """The rail mesh is too coarse to resolve the support bays (fewer elements than bays)."""


def check_speed(speed, *, positive: bool = False) -> float:
    """``speed`` [m/s] as a float in [0, MAX_SPEED] ((0, MAX_SPEED] if ``positive``)."""
    return v.number("speed", speed, low=0.0, low_open=positive, high=MAX_SPEED, unit="m/s")


# --------------------------------------------------------------------------------------------
# the frequencies that matter for a scene
def support_bays(scene: Scene) -> int:
    """Number of support bays over the rail, L / d_s rounded, at least 1 [-]."""
    return max(1, round(scene.rail.length / scene.supports.spacing))


def wheel_frequency(scene: Scene) -> float:
    """sqrt(k/M) / 2 pi [Hz]: the wheel mass on the (linearised) contact spring over a rigid
    rail (about 1.34 kHz for the paper's 10 kg wheel, 196 Hz for the ballasted preset's 900 kg
    one)."""
    return math.sqrt(scene.contact_stiffness / scene.wheel.mass) / (2.0 * math.pi)


def contact_resonance(scene: Scene) -> float:
    """The contact resonance f_c [Hz]: the wheel and the rail under it vibrating against each
    other on the contact spring k, where the receptances of wheel, contact and rail add up to
    zero. Above the track's cut-on the rail's point receptance is that of a free infinite
    Euler-Bernoulli beam, -(1 + i) / (4 EI k_b^3) with k_b = (m w^2 / EI)^(1/4), and the
    wheel's -1 / (M w^2); the real parts balance 1 / k where

        1 / (M w^2) + 1 / (4 EI k_b^3) = 1 / k,

    a quartic in u = sqrt(w), M A u^4 - M k u - A k = 0 with A = 4 EI^(1/4) m^(3/4): one
    positive root. A light wheel is dominated by its own term (the paper's: 1.66 kHz, above
    sqrt(k/M) = 1.34 kHz), a heavy one by the rail's (the ballasted preset's: 770 Hz, the rail's
    local mass on k)."""
    r = scene.rail
    k, M = scene.contact_stiffness, scene.wheel.mass
    A = 4.0 * r.bending_stiffness ** 0.25 * r.mass_per_length ** 0.75
    roots = np.roots([M * A, 0.0, 0.0, -M * k, -A * k])
    u = max(float(z.real) for z in roots if abs(z.imag) < 1e-9 * abs(z) and z.real > 0.0)
    return u * u / (2.0 * math.pi)


def pinned_pinned_frequencies(scene: Scene) -> tuple[float, float]:
    """(Euler-Bernoulli, Timoshenko) pinned-pinned frequency [Hz] of one support span d_s:
    (pi/(2 d_s^2)) sqrt(EI/m), and the lower root of the Timoshenko frequency equation with
    k = pi/d_s (docs: Model, section "Shear-deformable rail (Timoshenko)"), the rail's
    shear coefficient and modulus whatever its beam theory."""
    r, d = scene.rail, scene.supports.spacing
    k = math.pi / d
    kg = r.shear_coefficient * r.modulus_of_rigidity
    a = r.rotary_inertia * r.density / kg
    b = r.mass_per_length + r.rotary_inertia * k**2 + r.bending_stiffness * k**2 * r.density / kg
    c = r.bending_stiffness * k**4
    f_t = math.sqrt((b - math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)) / (2.0 * math.pi)
    f_e = math.pi / (2.0 * d * d) * math.sqrt(r.bending_stiffness / r.mass_per_length)
    return f_e, f_t


def pinned_pinned_frequency(scene: Scene) -> float:
    """The pinned-pinned frequency [Hz] of one support span of the scene's beam theory
    (:func:`pinned_pinned_frequencies`): the track's resonance with the rail's bending
    wavelength 2 d_s, which the sleeper-passing harmonics excite."""
    f_e, f_t = pinned_pinned_frequencies(scene)
    return f_t if scene.rail.beam == "timoshenko" else f_e


def highest_frequency(scene: Scene) -> float:
    """The highest frequency of interest of a run [Hz], what its time step resolves
    (:func:`derived_dt`): the largest of the wheel on its contact spring
    (:func:`wheel_frequency`), the contact resonance (:func:`contact_resonance`) and the
    pinned-pinned frequency (:func:`pinned_pinned_frequency`). 2147 Hz for the paper's scene
    (pinned-pinned), 1422 Hz for the ballasted preset (1068 Hz with the Timoshenko rail)."""
    return max(wheel_frequency(scene), contact_resonance(scene), pinned_pinned_frequency(scene))


def bending_wavelength(scene: Scene, f: float) -> float:
    """The free rail's bending wavelength 2 pi / k [m] at ``f`` [Hz] (>= 1 Hz is used), of the
    scene's beam theory: Euler-Bernoulli, k^4 = m w^2 / EI; Timoshenko, the propagating root of
    EI k^4 - w^2 (rho I + EI rho / (kappa G)) k^2 + (rho I rho / (kappa G)) w^4 - m w^2 = 0
    (shorter: shear and rotary inertia soften the rail). The pinned-pinned frequency has the
    wavelength 2 d_s."""
    r = scene.rail
    w2 = (2.0 * math.pi * max(f, 1.0)) ** 2
    EI, m = r.bending_stiffness, r.mass_per_length
    if r.beam != "timoshenko":
        return 2.0 * math.pi * (EI / (m * w2)) ** 0.25
    kg = r.shear_coefficient * r.modulus_of_rigidity
    b = w2 * (r.rotary_inertia + EI * r.density / kg)
    c = r.rotary_inertia * r.density / kg * w2 * w2 - m * w2
    k2 = (b + math.sqrt(b * b - 4.0 * EI * c)) / (2.0 * EI)
    return 2.0 * math.pi / math.sqrt(k2)


# --------------------------------------------------------------------------------------------
# meshes and time step
def mesh(scene: Scene, n_elements: int | None = None) -> int:
    """The rail elements of a call [-]: ``n_elements`` checked against the element limit, or
    the scene's own ``rail.n_elements`` if None (the statics of the scene as described)."""
    return scene.rail.n_elements if n_elements is None else v.n_elements(n_elements)


def elements_per_bay(scene: Scene, f_max: float) -> int:
    """Elements per support bay that resolve the rail's bending up to ``f_max`` [Hz]:
    ELEMENTS_PER_WAVELENGTH[beam] per :func:`bending_wavelength` at ``f_max`` (the element's
    measured convergence: resonance frequencies within 0.1 %), in whole quarter bays: a
    multiple of 4 [-]. So the supports, the mid-spans and the quarter-bay points (EN 15461's
    positions) are nodes, where the Timoshenko element is exact: between nodes it misses the
    kink a point force puts into the sheared rail, an error of order l_e / (kappa G A) in the
    receptance there (on the ballasted track's decay rates, 43 elements per bay, whose
    mid-spans are not nodes, were further from the converged values than 20 per bay)."""
    per_wavelength = ELEMENTS_PER_WAVELENGTH[scene.rail.beam]
    quarters = per_wavelength * scene.supports.spacing / (4.0 * bending_wavelength(scene, f_max))
    return 4 * max(1, math.ceil(quarters - 1e-9))


def _capped(scene: Scene, per_bay: int, what: str) -> int:
    """``per_bay`` whole elements in each support bay, at least the scene's own mesh; where
    MAX_ELEMENTS caps it, the most whole elements per bay that fit, with a MeshWarning."""
    bays = support_bays(scene)
    n = max(bays * per_bay, scene.rail.n_elements)
    if n <= MAX_ELEMENTS:
        return n
    n = max(MAX_ELEMENTS // bays, 1) * bays
    warnings.warn(MeshWarning(
        f"{n} elements ({MAX_ELEMENTS} at most) give fewer than the {per_bay} per bay "
        f"{what}"), stacklevel=3)
    return n


def derived_mesh(scene: Scene) -> int:
    """Default number of rail elements of a run and of ``eigen``: whole elements per support
    bay, the more of ELEMENTS_PER_BAY (the moving contact: the paper's 2 per bay put the
    element-passing frequency v / l_e on the track's resonance and missed the amplitude by
    4-5 %, 8 per bay keep it within 0.5 %) and :func:`elements_per_bay` at the
    :func:`pinned_pinned_frequency` (its wavelength is 2 d_s: 5 per bay for the
    Euler-Bernoulli rail, 12 for the Timoshenko rail; the highest resonance at which the rail
    bends under a wheel: the rail's side of the contact resonance, its local mass on the
    contact spring, sits below it on real tracks, 500 Hz against 2147 Hz on the paper's and
    750 Hz against 1422 Hz on the ballasted preset), at least the scene's own
    ``rail.n_elements``: 80 for the paper's scene, 8 per bay on the ballasted preset, 12 with
    its Timoshenko rail; a rail without supports keeps its own. See
    :func:`default_settings`."""
    if not scene.support_positions:  # no bays to resolve: the scene's own mesh
        return scene.rail.n_elements
    per_bay = max(ELEMENTS_PER_BAY, elements_per_bay(scene, pinned_pinned_frequency(scene)))
    return int(_capped(scene, per_bay, "that resolve the rail's bending"))


def derived_dt(scene: Scene) -> float:
    """Default generalized-alpha time step [s]: STEPS_PER_PERIOD steps per period of the wheel
    on its contact spring, and at least STEPS_PER_HIGHEST_PERIOD per period of the
    :func:`highest_frequency` (4.96e-6 s for the paper's scene, from the first; 3.39e-5 s for
    the ballasted preset, which meets the second too). See :func:`default_settings`."""
    return min(1.0 / (STEPS_PER_PERIOD * wheel_frequency(scene)),
               1.0 / (STEPS_PER_HIGHEST_PERIOD * highest_frequency(scene)))


def default_settings(scene: Scene, speed: float | None = None,
                     integrator: str = "generalized_alpha") -> dict:
    """Time step [s] and mesh derived from the scene, as ``dict(dt=..., n_elements=...)``: what
    :func:`trackwheel.simulate` uses when neither is given, at every fidelity level (and
    ``eigen`` its mesh).

    Target: the headline outputs within 1 % of a refined run (the amplitude max |d| of the
    paper's scene, docs: Model § Outputs; the contact force's dynamic factor and bay profile
    within 0.1 % of the static load on the ballasted track). The scene's former defaults (20
    elements, dt = 1e-5 s) miss the paper's amplitude by up to 5.5 % (benchmarks/README.md,
    "Speed against accuracy").

    - ``n_elements`` (:func:`derived_mesh`): whole elements per support bay, at least
      ELEMENTS_PER_BAY = 8 and ELEMENTS_PER_WAVELENGTH per bending wavelength at the highest
      frequency of interest. Reasons: the cubic ANCF element interpolates the rail under a
      moving point contact with a contact-point stiffness that varies across each element, so
      the wheel is excited at the element-passing frequency v / l_e and its harmonics. With
      l_e = d_s / 2 (20 elements) or d_s / 4 (40) this spurious excitation meets the track's
      main resonance (about 340 Hz for the paper's scene) within 50-400 km/h -- at 300 km/h for
      20 elements, 150 km/h for 40 -- and moves the amplitude by 4-5 %; with d_s / 8 the effect
      stays below 0.5 % (160-element runs as reference), and on the ballasted track below
      3e-4 of the static load even where v / l_e meets the pinned-pinned frequency (400 km/h).
      So the rule needs no speed: what remains is resolving the track's highest resonance,
      the pinned-pinned one (its wavelength is 2 d_s), by the element's own convergence --
      which the Timoshenko element needs 24 per wavelength for, i.e. 12 per bay.
    - ``dt`` (:func:`derived_dt`): STEPS_PER_PERIOD = 150 steps per period of the wheel on its
      contact spring f_w = sqrt(k/M)/2 pi (1.34 kHz for the paper's scene, so
      dt = 4.96e-6 s). Phase errors of generalized-alpha grow with the passage time, so the
      slowest speed (50 km/h) sets the step: 1e-5 s gives -0.9 % there, 2.5e-6 s -0.2 %. A
      heavy wheel's f_w is low (196 Hz on the ballasted track, 3.39e-5 s), so the step also
      takes STEPS_PER_HIGHEST_PERIOD = 20 per period of the highest frequency of interest
      (period error (2 pi / 20)^2 / 12 = 0.8 % there, where the response is small: halving
      the ballasted track's step moves its dynamic factor by < 1e-4). The explicit scheme
      takes at most half its stability limit on the derived mesh.

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
    """Rail elements of the frequency-domain track up to ``f_max`` [Hz] (what ``receptance``,
    ``decay_rate`` and their commands use by default): :func:`elements_per_bay` at ``f_max``
    in every support bay (whole elements per bay), no fewer than the scene's. Where MAX_ELEMENTS
    caps the count, warns (:class:`MeshWarning`) and returns the most whole elements per bay
    that fit."""
    per_bay = elements_per_bay(scene, f_max)
    return _capped(scene, per_bay, f"that resolve the bending wavelength "
                   f"({bending_wavelength(scene, f_max):.3g} m) at {f_max:g} Hz")


def warn_unresolved_mesh(scene: Scene, n_elements: int, stacklevel: int = 3) -> bool:
    """Warn (:class:`MeshWarning`) and return True if ``n_elements`` is below the number of
    support bays: then some bay holds no node, and the rail's bending between two supports -- the
    wave the wheel excites -- cannot be represented (the derived mesh has ELEMENTS_PER_BAY)."""
    bays = support_bays(scene)
    if n_elements >= bays:
        return False
    warnings.warn(MeshWarning(
        f"n_elements = {n_elements} cannot resolve the {bays} support bays (fewer elements than "
        f"bays); the derived default is {derived_mesh(scene)} (at least {ELEMENTS_PER_BAY} per "
        f"bay, about 1 % on the amplitude)"), stacklevel=stacklevel)
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
    """Predicted largest stable time step [s] of ``integrator`` for ``scene`` on ``n_elements``
    (default: the derived mesh of a run, :func:`derived_mesh`).

    ``"explicit"`` (classical RK4, the paper's scheme): the stability interval of RK4 on the
    imaginary axis is |omega dt| <= 2 sqrt(2), so dt_max = 2 sqrt(2) / omega_max, with omega_max
    [rad/s] the highest eigenfrequency of the assembled system -- the ANCF rail on its supports
    with the wheel mass on its contact spring (docs: Model § Rail, § Wheel, § Contact), linearised at the static state
    with the wheel at ``x_start`` (default: the middle of the first support bay) -- found by power iteration in
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
    ne = derived_mesh(scene) if n_elements is None else mesh(scene, n_elements)
    half_bay = min(0.5 * scene.supports.spacing, 0.5 * scene.rail.length)
    x0 = half_bay if x_start is None else v.number("x_start", x_start, low=0.0,
                                                   high=scene.rail.length, unit="m")
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
