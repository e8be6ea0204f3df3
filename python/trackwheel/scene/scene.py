"""Scene description: frozen dataclasses in SI units (docs: Model § Scene).

Every field carries its unit; every value is validated on construction, so a scene that
exists is a scene the kernel can run. Variations are made with :func:`dataclasses.replace`::

    scene = Scene.kato2005()
    soft = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports, stiffness=40e6))
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace

import numpy as np

from ..base import validate as v
from ..base.limits import MAX_ELEMENTS, MAX_STATIC_SAG, ranges_doc
from ..excitation.irregularity import Irregularity
from .contact import Contact
from .rail import AbsorbingEnds, Rail
from .supports import PER_SUPPORT, Supports
from .vehicle import Vehicle
from .wheel import Wheel
from .window import Window

#: Standard gravity used by the paper's scene [m/s^2]: F = 47040 N is 4800 kg x 9.8 m/s^2.
GRAVITY = 9.8


@dataclass(frozen=True)
class Scene:
    """A wheel (or a vehicle) on a rail on supports: everything the kernel needs, in SI units.

    ``vehicle=None`` (the default) is the single wheel ``Scene.wheel`` under its constant load,
    the paper's model. With a :class:`~trackwheel.Vehicle` the wheels, their places and their
    loads come from the vehicle, and ``Scene.wheel`` is derived from it, whatever was given:
    the vehicle's first wheel carrying the mean static wheel load (it sets the contact
    stiffness and the default mesh and step). Give the wheels in the Vehicle; so
    ``dataclasses.replace(scene, vehicle=other)`` works, and ``vehicle=None`` turns the scene
    back into the single (derived) wheel. All wheels of a vehicle share one contact law, so they
    need the same radius and elastic constants.

    Every parameter of every part is checked against its plausible range when the part is
    built (:data:`trackwheel.base.limits.RANGES`, listed with each part), and the scene checks
    that the track can carry its weight and the wheel load: :attr:`static_sag` at most
    ``MAX_STATIC_SAG`` (1 m), so that a soft support, a weak rail or a huge load is a
    ValueError naming them here rather than a failed static solve in the kernel.
    """

    rail: Rail = field(default_factory=Rail)
    supports: Supports = field(default_factory=Supports)
    wheel: Wheel = field(default_factory=Wheel)
    contact: Contact = field(default_factory=Contact)
    gravity: float = GRAVITY  #: g on rail and wheel [m/s^2]; the rail's weight pre-loads supports
    rail_gravity: bool = True  #: apply the rail's own weight
    #: rail profile r(X) [m] (positive = bump, docs: Model § Irregularities), or None for a smooth rail
    irregularity: Irregularity | None = None
    #: the vehicle (trackwheel.Vehicle), or None: the single wheel ``wheel``
    #: (docs: Model § The vehicle)
    vehicle: Vehicle | None = None
    #: the travelling window (:class:`Window`), or None: the rail is the whole track
    window: Window | None = None

    def __post_init__(self):
        for f in fields(self)[:4]:
            value = getattr(self, f.name)
            if not isinstance(value, f.default_factory):
                raise TypeError(f"Scene.{f.name} must be a {f.default_factory.__name__}, "
                                f"got {type(value).__name__}")
        v.field("Scene.gravity", self.gravity)
        v.boolean("Scene.rail_gravity", self.rail_gravity)
        if self.irregularity is not None and not isinstance(self.irregularity, Irregularity):
            raise TypeError(f"Scene.irregularity must be a trackwheel.Irregularity or None, "
                            f"got {type(self.irregularity).__name__}")
        if self.vehicle is not None:
            self._derive_wheel()
        if self.wheel.load == 0.0 and self.gravity == 0.0:  # P = F + M g = 0
            raise ValueError("Wheel.load = 0 N with Scene.gravity = 0 m/s^2 leaves the wheel "
                             "unloaded (F + M g = 0 N); allowed: Wheel.load > 0 or "
                             "Scene.gravity > 0")
        # supports must lie on the rail, with valid properties at each
        self.supports.check_at(self.supports.resolve(self.rail.length),
                               along_track=self.window is not None)
        if self.window is not None:
            self._check_window()
        self._check_sag()

    def _check_sag(self):
        sag = self.static_sag
        if sag > MAX_STATIC_SAG:
            s, sv = self.supports, self.support_values
            where = "" if s.uniform else " at support {j} (X = {x:g} m)"
            if s.layered and sv.position.size and np.max(
                    sleeper := sv.sleeper_mass * self.gravity / sv.ballast_stiffness
                    ) > MAX_STATIC_SAG:
                j = int(np.argmax(sleeper))
                what = (f"Supports.sleeper_mass = {sv.sleeper_mass[j]:g} kg on "
                        f"Supports.ballast_stiffness = {sv.ballast_stiffness[j]:g} N/m"
                        + where.format(j=j, x=sv.position[j]))
            elif s.positions is None or s.positions:
                j = int(np.argmin(sv.static_stiffness))
                what = (f"Supports.stiffness = {sv.stiffness[j]:g} N/m"
                        + (f" on Supports.ballast_stiffness = {sv.ballast_stiffness[j]:g} N/m"
                           if s.layered else "")
                        + f" every {s.spacing:g} m" + where.format(j=j, x=sv.position[j]))
            else:
                what = "no supports"
            raise ValueError(
                f"the track sags about {sag:.3g} m under its own weight and the wheel load "
                f"({what}, Rail.length = {self.rail.length:g} m, EI = "
                f"{self.rail.bending_stiffness:.3g} N m^2, static wheel load "
                f"{max(self.active_vehicle.static_loads(self.gravity)):.4g} N); allowed at "
                f"most {MAX_STATIC_SAG:g} m (a real track sags a few mm): stiffer supports, a "
                f"shorter rail or a lighter load")

    def _check_window(self):
        w = self.window
        if not isinstance(w, Window):
            raise TypeError(f"Scene.window must be a trackwheel.Window or None, "
                            f"got {type(w).__name__}")
        if self.supports.positions is not None:
            raise ValueError("Scene.window needs equal supports every Supports.spacing: leave "
                             "Supports.positions None")
        _window_supports(self.supports)
        d = self.supports.spacing
        rear, front = self.active_vehicle.span
        L = w.length(front - rear, d)
        n_bays = round(self.rail.length / d)
        if abs(n_bays * d - self.rail.length) > 1e-9 * L or self.rail.length < L * (1 - 1e-9):
            raise ValueError(f"Rail.length = {self.rail.length} m must be a whole number of "
                             f"{d} m bays, at least the window's length {L:.6g} m "
                             f"({w.n_bays(front - rear, d)} bays: Window.length(span, "
                             "spacing)); Scene.windowed(window) sets it")
        if self.rail.n_elements % n_bays:
            raise ValueError(f"Rail.n_elements = {self.rail.n_elements} must be a whole number "
                             f"of elements per bay: a multiple of the window's {n_bays} bays")

    def _derive_wheel(self):
        veh = self.vehicle
        if not isinstance(veh, Vehicle):
            raise TypeError(f"Scene.vehicle must be a trackwheel.Vehicle or None, "
                            f"got {type(veh).__name__}")
        w0 = veh.wheels[0]
        for i, w in enumerate(veh.wheels):
            if (w.radius, w.youngs_modulus, w.poisson_ratio) != (
                    w0.radius, w0.youngs_modulus, w0.poisson_ratio):
                raise ValueError(f"Vehicle.wheels[{i}] differs from wheel 0 in radius or elastic "
                                 "constants; the wheels share one contact law")
        loads = veh.static_loads(self.gravity)
        derived = replace(w0, load=max(sum(loads) / len(loads) - w0.mass * self.gravity, 0.0))
        object.__setattr__(self, "wheel", derived)

    def windowed(self, window: Window | None) -> "Scene":
        """This scene on the travelling ``window`` (None: the scene without one, its rail as
        given): the rail's length becomes ``window.length`` for the vehicle's span, with as many
        elements per bay as the scene's mesh has (at least one), and absorbing end zones of
        :meth:`Window.zone_bays` bays unless the rail has its own."""
        if window is None:
            return replace(self, window=None)
        if not isinstance(window, Window):
            raise TypeError(f"window must be a trackwheel.Window or None, "
                            f"got {type(window).__name__}")
        d = self.supports.spacing
        rear, front = self.active_vehicle.span
        epb = max(1, round(self.rail.n_elements / max(1, round(self.rail.length / d))))
        n_el = window.n_bays(front - rear, d) * epb
        if n_el > MAX_ELEMENTS:
            raise ValueError(f"the window's {window.n_bays(front - rear, d)} bays with {epb} "
                             f"elements each need {n_el} elements; allowed at most "
                             f"{MAX_ELEMENTS}: fewer Window.bays_behind/bays_ahead")
        rail = replace(self.rail, length=window.length(front - rear, d), n_elements=n_el)
        if window.zone_bays(d) > 0 and rail.absorbing_ends is None:
            rail = replace(rail, absorbing_ends=AbsorbingEnds(window.zone_bays(d) * d))
        return replace(self, rail=rail, window=window)

    @property
    def active_vehicle(self):
        """The vehicle that runs: ``vehicle``, or ``Vehicle.single_wheel(wheel)`` if None."""
        return Vehicle.single_wheel(self.wheel) if self.vehicle is None else self.vehicle

    @classmethod
    def kato2005(cls) -> "Scene":
        """The paper's scene exactly as docs: Model § Scene fixes it (L = 5 m, nine supports of
        140 MN/m every 0.5 m, 10 kg wheel of radius 0.1 m under 47040 N, 20 elements)."""
        return cls()

    @classmethod
    def ballasted_track(cls, length: float = 30.0, *, elements_per_bay: int = 4,
                        window: Window | None = None) -> "Scene":
        """A high-speed wheel on UIC60 rail on ballasted track with concrete monobloc sleepers
        (docs: Model § Layered supports).

        Track (the parameter set of docs: Model § Layered supports): UIC60 rail,
        E = 210 GPa, nu = 0.3, rho = 7850 kg/m^3, A = 7.69e-3 m^2, I = 3.055e-5 m^4 (the
        section values of EN 13674-1); sleepers every 0.6 m, rail pad k_p = 180 MN/m and
        c_p = 18 kN s/m, half a monobloc sleeper m_s = 150 kg, ballast k_b = 105 MN/m and
        c_b = 48 kN s/m per half sleeper. Sets of this size for such a track are tabulated in
        Thompson, *Railway Noise and Vibration* (2009), ch. 3, and in Zhai, Wang & Cai,
        "Fundamentals of vehicle-track coupled dynamics", Vehicle System Dynamics 47 (2009);
        the numbers here are the specification's, not copied from either table.

        Wheel: a high-speed wheel of 0.92 m nominal diameter (rho0 = 0.46 m), half of an
        unsprung wheelset of about 1800 kg (M = 900 kg), static wheel load P = F + M g = 70 kN
        (a 14 t axle), contact stiffness the linearised Hertz of docs: Model § Contact.
        g = 9.81 m/s^2.

        length [m]: the rail between its rigid end supports (default 30 m: room for a passage
        of several metres away from the ends); supports every 0.6 m between them. Elements:
        ``elements_per_bay`` per 0.6 m bay (default 4: 0.15 m elements, sleepers on nodes).
        The rail's ends rest on rigid supports, so the track stiffens within a few metres of
        them: run passages well inside, e.g. ``simulate(scene, v, x_start=10.0, x_end=20.0)``.

        window: a :class:`Window` makes the rail a travelling window of that many bays (the
        length is then the window's, ``length`` is ignored) for runs of any length, e.g.
        ``simulate(scene, v, distance=1000.0, fidelity="linear/hertz")``.
        """
        spacing = 0.6
        if window is not None:
            return cls.ballasted_track(elements_per_bay=elements_per_bay).windowed(window)
        length = v.number("length", length, low=3 * spacing, unit="m")
        epb = v.integer("elements_per_bay", elements_per_bay, low=1, high=64)
        n_bays = round(length / spacing)
        if abs(n_bays * spacing - length) > 1e-9 * length:
            raise ValueError(f"length = {length} m must be a whole number of 0.6 m sleeper bays; "
                             f"allowed: k x 0.6 m with k >= 3 (e.g. {n_bays * spacing:.4g} m)")
        n_el = n_bays * epb
        if n_el > MAX_ELEMENTS:
            raise ValueError(f"length = {length} m with elements_per_bay = {epb} needs {n_el} "
                             f"elements; allowed at most {MAX_ELEMENTS}")
        g = 9.81
        mass, load = 900.0, 70e3
        return cls(
            rail=Rail(length=length, youngs_modulus=210e9, poisson_ratio=0.3, density=7850.0,
                      area=7.69e-3, second_moment=3.055e-5, n_elements=n_el),
            supports=Supports(stiffness=180e6, damping=18e3, spacing=spacing, sleeper_mass=150.0,
                              ballast_stiffness=105e6, ballast_damping=48e3),
            wheel=Wheel(mass=mass, radius=0.46, load=load - mass * g, youngs_modulus=210e9,
                        poisson_ratio=0.3),
            gravity=g)

    # derived quantities -------------------------------------------------------------------
    @property
    def support_positions(self) -> tuple[float, ...]:
        """X_j [m]."""
        return self.supports.resolve(self.rail.length)

    @property
    def static_load(self) -> float:
        """P = F + M g on the contact [N]."""
        return self.wheel.load + self.wheel.mass * self.gravity

    @property
    def effective_modulus(self) -> float:
        """E* with 1/E* = (1 - nu_w^2)/E_w + (1 - nu_r^2)/E_r [Pa]."""
        w, r = self.wheel, self.rail
        return 1.0 / ((1 - w.poisson_ratio**2) / w.youngs_modulus
                      + (1 - r.poisson_ratio**2) / r.youngs_modulus)

    @property
    def hertz_constant(self) -> float:
        """C_H = 4/3 E* sqrt(rho0) [N/m^1.5] (docs: Model § Contact)."""
        return 4.0 / 3.0 * self.effective_modulus * math.sqrt(self.wheel.radius)

    @property
    def contact_stiffness(self) -> float:
        """Linear contact rigidity k [N/m]: the given one, or Hertz linearised at P
        (k = 1.5 C_H^(2/3) P^(1/3)). For ``law="hertz"`` this is always the linearisation."""
        c = self.contact
        if c.law == "linear" and c.stiffness is not None:
            return c.stiffness
        ch = c.stiffness if (c.law == "hertz" and c.stiffness is not None) else self.hertz_constant
        return 1.5 * ch ** (2.0 / 3.0) * max(self.static_load, 1e-300) ** (1.0 / 3.0)

    @property
    def static_sag(self) -> float:
        """Estimate of the track's static sag [m] under the rail's weight q = rho A g and the
        heaviest static wheel load P (docs: Model § Validation): the smaller of the beam on a
        Winkler foundation of the supports, q / k_f + P beta / (2 k_f) with
        beta = (k_f / (4 EI))^(1/4) (plus a sleeper's sag under its own weight,
        m_s g / k_b), and the rail bridging its rigid ends, 5 q L^4 / (384 EI) +
        P L^3 / (48 EI) (q with the sleepers' weight, which then hangs from the pads).
        Checked at construction against MAX_STATIC_SAG."""
        r, s, g = self.rail, self.supports, self.gravity
        q = r.mass_per_length * g if self.rail_gravity else 0.0
        P = max(self.active_vehicle.static_loads(g))
        EI, L = r.bending_stiffness, r.length
        sv = self.support_values
        n = sv.position.size
        # bridging, the rail carries the sleepers too (they hang from the pads)
        q_s = float(np.sum(sv.sleeper_mass)) * g / L if s.layered else 0.0
        bridge = 5.0 * (q + q_s) * L**4 / (384.0 * EI) + P * L**3 / (48.0 * EI)
        if n == 0:
            return bridge
        kf = float(np.min(sv.static_stiffness)) * n / L
        beta = (kf / (4.0 * EI)) ** 0.25
        winkler = q / kf + P * beta / (2.0 * kf)
        if s.layered:
            winkler += float(np.max(sv.sleeper_mass * g / sv.ballast_stiffness))
        return min(winkler, bridge)

    @property
    def winkler_modulus(self) -> float:
        """Equivalent foundation modulus k_f = k_s / d_s [N/m^2] (docs: Model § Validation);
        layered supports: their static series stiffness per spacing. Supports the same
        everywhere only (ValueError otherwise)."""
        return self.supports.static_stiffness / self.supports.spacing

    @property
    def support_values(self):
        """The supports' properties at their positions X_j (:meth:`Supports.values`)."""
        return self.supports.values(self.support_positions)


def _window_supports(supports: Supports) -> None:
    """The travelling window streams the track's sleepers in as it moves, so a property that
    varies along X must be a function of X (a recipe such as Supports.transition's or
    Supports.scattered's): ValueError for a per-support sequence, which numbers the rail's
    supports, not the track's sleepers."""
    seq = [n for n in PER_SUPPORT if isinstance(getattr(supports, n), tuple)]
    if seq:
        raise ValueError(f"Scene.window takes each support property as one value or a function "
                         f"of X (the window streams the track's sleepers in as it moves); "
                         f"Supports.{', Supports.'.join(seq)} {'is a' if len(seq) == 1 else 'are'}"
                         f" per-support sequence{'' if len(seq) == 1 else 's'}: give a function "
                         f"of X (e.g. Supports.transition, Supports.scattered)")


Scene.__doc__ += ranges_doc("Scene")
