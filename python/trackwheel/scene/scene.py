"""Scene description: frozen dataclasses in SI units (docs: Model § Scene).

Every field carries its unit; every value is validated on construction, so a scene that
exists is a scene the kernel can run. Variations are made with :func:`dataclasses.replace`::

    scene = Scene.kato2005()
    soft = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports, stiffness=40e6))
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

from . import _validate as v
from .irregularity import WHEEL_DEFECTS, Irregularity

#: Most supports a scene may resolve to from ``Supports.spacing`` [-] (a guard against a tiny
#: spacing exhausting memory; 5 m at 0.5 m spacing has nine).
MAX_SUPPORTS = 100_000
#: Most rail elements a scene or a call may use [-] (defined in the kernel, cpp/limits.hpp).
MAX_ELEMENTS = v.MAX_ELEMENTS

#: Design of the default absorbing end zones (:attr:`Rail.absorbing_damping`): bending waves up
#: to ABSORBING_MAX_FREQUENCY [Hz] lose at least ABSORBING_ATTENUATION [dB] over the zone and
#: back (docs: Model § Long tracks and absorbing ends). 40 dB, not the 30 dB the zones must
#: reach: the zone's reflection at f_max equals the design (a 30 dB design measured -30.1 dB at
#: 3 kHz), so the design carries the margin.
ABSORBING_MAX_FREQUENCY = 3000.0
ABSORBING_ATTENUATION = 40.0
#: The axial zones' own design (:meth:`AbsorbingEnds.axial_c_max`): axial waves lose
#: ABSORBING_AXIAL_ATTENUATION [dB] from ABSORBING_AXIAL_MIN_FREQUENCY up (measured with 30 dB).
ABSORBING_AXIAL_ATTENUATION = 30.0
#: ... from this frequency [Hz] up: the sleeper-passing frequency v / d_s is 93-139 Hz at
#: 200-300 km/h on 0.6 m bays, where a travelling window's shifts knock its axial modes.
ABSORBING_AXIAL_MIN_FREQUENCY = 100.0

#: Standard gravity used by the paper's scene [m/s^2]: F = 47040 N is 4800 kg x 9.8 m/s^2.
GRAVITY = 9.8


def kmh(speed_kmh: float) -> float:
    """Convert a speed from km/h to m/s (``kmh(300)`` -> 83.33 m/s)."""
    return v.number("speed_kmh", speed_kmh, low=0.0, unit="km/h") / 3.6


@dataclass(frozen=True)
class AbsorbingEnds:
    """Absorbing end zones of a long rail (docs: Model § Long tracks and absorbing ends).

    Viscous dampers from the rail to the ground, per length, graded over the last ``length`` of
    each end: ``c(d) = c_max (1 - d / L_z)^2`` at distance d from the rail end (zero, with zero
    slope, where the zone meets the rail, so the zone's start does not reflect). ``damping=None``
    takes the c_max of :attr:`Rail.absorbing_damping`. The zone should be at least about two
    bending wavelengths long at the lowest frequency to absorb (10 m: from about 300 Hz for a
    UIC60-like rail). The statics are unaffected (dampers carry no static load).

    On periodic supports of spacing d the zones reflect near the stop band at the pinned-pinned
    frequency (where the bending wavenumber k nears pi / d) unless they are several beat lengths
    1 / |k - pi / d| long: on the paper's track 10 m zones reflect less than -30 dB except in
    1.95-2.39 kHz, 20 m zones except in 2.04-2.32 kHz (up to -5 dB at the stop band's edges,
    2.15 and 2.21 kHz). The dampers act on the rail, which moves at the pinned-pinned frequency
    where the supports do not (dampers at the supports would let those waves through).

    The zones damp the rail's axial motion x too, graded alike, ``c_x(d) = c_max,x (1 - d /
    L_z)^2`` (the full ANCF model; the linear levels have no axial motion):
    ``axial_damping=None`` takes c_max,x from the rail's axial stiffness and the zone length
    (:meth:`axial_c_max`), 0 switches it off.
    """

    length: float  #: L_z, zone length at each end [m]; several support bays
    damping: float | None = None  #: c_max, damping per length at the rail ends [N s/m^2]
    #: c_max,x, axial damping per length at the rail ends [N s/m^2]; None: :meth:`axial_c_max`
    axial_damping: float | None = None

    def __post_init__(self):
        v.positive("AbsorbingEnds.length", self.length, "m")
        if self.damping is not None:
            v.number("AbsorbingEnds.damping", self.damping, low=0.0, unit="N s/m^2")
        if self.axial_damping is not None:
            v.number("AbsorbingEnds.axial_damping", self.axial_damping, low=0.0,
                     unit="N s/m^2")

    def axial_c_max(self, axial_stiffness: float) -> float:
        """c_max,x [N s/m^2]: ``axial_damping``, or the damping that attenuates axial waves
        down to ``f_min`` = ABSORBING_AXIAL_MIN_FREQUENCY by ABSORBING_AXIAL_ATTENUATION = A dB on
        the way through the zone and back.

        A viscous foundation c_x per length turns the bar's dispersion into
        EA k^2 = m omega^2 - i omega c_x. Where c_x >> m omega (the zone at the low
        frequencies a travelling window's shifts excite: c_x / (m omega) is about 70 at 100 Hz
        for a 4.8 m zone on UIC60) the wave diffuses, Im k = sqrt(omega c_x / (2 EA)), weakest
        at the lowest frequency (above it, up to the light-damping limit c_x / (2 sqrt(EA m)),
        stronger). Through the graded zone and back, int sqrt(c_x) = sqrt(c_max,x) L_z / 2, so
        the amplitude falls by exp(-sqrt(omega c_max,x / (2 EA)) L_z); setting that to
        10^(-A/20) at f_min gives c_max,x = 2 EA ln(10^(A/20))^2 / (2 pi f_min L_z^2)
        (EA = ``axial_stiffness`` [N])."""
        if self.axial_damping is not None:
            return self.axial_damping
        loss = math.log(10.0 ** (ABSORBING_AXIAL_ATTENUATION / 20.0))
        omega = 2.0 * math.pi * ABSORBING_AXIAL_MIN_FREQUENCY
        return 2.0 * axial_stiffness * loss**2 / (omega * self.length**2)


@dataclass(frozen=True)
class Rail:
    """The rail: a planar ANCF beam simply supported at both ends (docs: Model § Rail).

    Defaults are the paper's rail (Kato et al. 2005, Table 1, made consistent in docs: Model § Scene).
    """

    length: float = 5.0  #: L, rail length between the end supports [m]
    youngs_modulus: float = 2.058e11  #: E [Pa]
    poisson_ratio: float = 0.30  #: nu [-] (used by the Hertz contact constant)
    density: float = 7850.0  #: rho [kg/m^3]
    area: float = 6.936e-3  #: A, section area [m^2]
    second_moment: float = 3.08961e-5  #: I, second moment of area [m^4]
    n_elements: int = 20  #: n_e, number of ANCF elements [-]
    curvature: str = "exact"  #: "exact" kappa = r_s x r_ss/|r_s|^3, or "simplified" r_s x r_ss
    far_end: str = "roller"  #: "roller" (x free at s = L) or "pinned"
    n_gauss: int = 5  #: Gauss points per element for the elastic forces [-], in
    #: ``_validate.GAUSS_RANGE`` = (2, 10) (one point under-integrates the bending stiffness:
    #: singular, zero-frequency modes)
    #: graded viscous end zones that absorb waves leaving the rail, or None (the paper's rail)
    absorbing_ends: AbsorbingEnds | None = None
    #: "euler" (Euler-Bernoulli) or "timoshenko" (shear deformation and rotary inertia: the
    #: shear-deformable ANCF rail of the full model, statics and eigen analysis, and the
    #: Timoshenko beam of the linear levels and receptance)
    beam: str = "euler"
    #: kappa, shear coefficient of the section [-], in (0, 1] (about 0.4 for a rail's vertical
    #: bending; used with beam="timoshenko")
    shear_coefficient: float = 0.4

    def __post_init__(self):
        v.positive("Rail.length", self.length, "m")
        v.positive("Rail.youngs_modulus", self.youngs_modulus, "Pa")
        v.number("Rail.poisson_ratio", self.poisson_ratio, low=0.0, high=0.5, high_open=True)
        v.positive("Rail.density", self.density, "kg/m^3")
        v.positive("Rail.area", self.area, "m^2")
        v.positive("Rail.second_moment", self.second_moment, "m^4")
        v.integer("Rail.n_elements", self.n_elements, low=1, high=MAX_ELEMENTS)
        v.choice("Rail.curvature", self.curvature, {"exact", "simplified"})
        v.choice("Rail.far_end", self.far_end, {"roller", "pinned"})
        v.integer("Rail.n_gauss", self.n_gauss, low=v.GAUSS_RANGE[0], high=v.GAUSS_RANGE[1])
        v.choice("Rail.beam", self.beam, {"euler", "timoshenko"})
        v.number("Rail.shear_coefficient", self.shear_coefficient, low=0.0, high=1.0,
                 low_open=True)
        z = self.absorbing_ends
        if z is not None:
            if not isinstance(z, AbsorbingEnds):
                raise TypeError(f"Rail.absorbing_ends must be a trackwheel.AbsorbingEnds or None, "
                                f"got {type(z).__name__}")
            v.number("Rail.absorbing_ends.length", z.length, low=0.0, low_open=True,
                     high=0.5 * self.length, unit="m")

    @property
    def absorbing_damping(self) -> float:
        """c_max of the end zones [N s/m^2] (0 without them): ``absorbing_ends.damping``, or
        the damping that attenuates bending waves up to ``f_max`` = ABSORBING_MAX_FREQUENCY by
        ABSORBING_ATTENUATION = A dB on the way through the zone and back.

        A viscous foundation c per length adds -i omega c to m omega^2 in the beam's dispersion
        EI k^4 = m omega^2 - i omega c, so for c << m omega a wave decays by
        Im k = k c / (4 m omega) per metre (on supports, the excess over the cut-on frequency
        makes it decay faster). Through the zone and back, int c = 2 c_max L_z / 3, so the
        amplitude falls by exp(-k c_max L_z / (6 m omega)), k = (m omega^2 / EI)^(1/4): weakest
        at the highest frequency. Setting that to 10^(-A/20) at f_max gives
        c_max = 6 ln(10^(A/20)) (m^3 EI)^(1/4) sqrt(2 pi f_max) / L_z."""
        z = self.absorbing_ends
        if z is None:
            return 0.0
        if z.damping is not None:
            return z.damping
        loss = math.log(10.0 ** (ABSORBING_ATTENUATION / 20.0))
        impedance = (self.mass_per_length**3 * self.bending_stiffness) ** 0.25
        return 6.0 * loss * impedance * math.sqrt(2.0 * math.pi * ABSORBING_MAX_FREQUENCY) / z.length

    @property
    def mass_per_length(self) -> float:
        """m = rho A [kg/m]."""
        return self.density * self.area

    @property
    def bending_stiffness(self) -> float:
        """EI [N m^2]."""
        return self.youngs_modulus * self.second_moment

    @property
    def axial_stiffness(self) -> float:
        """EA [N]."""
        return self.youngs_modulus * self.area

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) [Pa]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def shear_stiffness(self) -> float:
        """kappa G A [N] (Timoshenko beam)."""
        return self.shear_coefficient * self.shear_modulus * self.area

    @property
    def rotary_inertia(self) -> float:
        """rho I, mass moment of inertia per length [kg m] (Timoshenko beam)."""
        return self.density * self.second_moment


@dataclass(frozen=True)
class Supports:
    """Discrete elastic supports (rail pads/sleepers) under the rail (docs: Model § Scene, § Rail).

    By default ``n = round(L / spacing) - 1`` equal supports at ``spacing, 2 spacing, ...,
    L - spacing`` (nine for the paper's scene), between the two rigid end supports. Give
    ``positions`` to place them anywhere inside the rail, on or between nodes;
    ``positions=()`` leaves the rail simply supported at its ends only (a bare beam).

    Layered supports (docs: Model § Layered supports): give ``sleeper_mass`` and
    ``ballast_stiffness`` and each support becomes a rail pad (``stiffness``, ``damping``)
    between the rail and a sleeper of mass m_s, which rests on the ballast (k_b, c_b) on rigid
    ground; gravity pre-loads every layer. Without them (the default) each support is one
    spring and damper from the rail to the ground.
    """

    stiffness: float = 140e6  #: k_s, vertical stiffness of each support [N/m] (layered: pad k_p)
    spacing: float = 0.5  #: d_s, support interval [m]
    damping: float = 0.0  #: c_s, viscous damping of each support [N s/m] (layered: pad c_p)
    positions: tuple[float, ...] | None = None  #: explicit positions X_j [m], or None
    #: m_s, the sleeper's share of one rail (half a sleeper) [kg]; None: single springs
    sleeper_mass: float | None = None
    ballast_stiffness: float | None = None  #: k_b, ballast under each sleeper [N/m]
    ballast_damping: float = 0.0  #: c_b, ballast damping under each sleeper [N s/m]

    def __post_init__(self):
        v.positive("Supports.stiffness", self.stiffness, "N/m")
        v.positive("Supports.spacing", self.spacing, "m")
        v.number("Supports.damping", self.damping, low=0.0, unit="N s/m")
        self._check_layers()
        if self.positions is not None:
            empty = isinstance(self.positions, (tuple, list)) and len(self.positions) == 0
            pos = () if empty else tuple(
                float(x) for x in v.positions("Supports.positions", self.positions,
                                              -math.inf, math.inf))
            object.__setattr__(self, "positions", pos)

    def _check_layers(self):
        if self.sleeper_mass is None and self.ballast_stiffness is None:
            if self.ballast_damping != 0.0:
                raise ValueError(f"Supports.ballast_damping = {self.ballast_damping} N s/m needs "
                                 "a sleeper layer: give sleeper_mass and ballast_stiffness too")
            return
        if self.sleeper_mass is None or self.ballast_stiffness is None:
            raise ValueError("Supports.sleeper_mass and Supports.ballast_stiffness must be given "
                             "together (layered supports) or both be None (single springs); "
                             f"got sleeper_mass = {self.sleeper_mass}, ballast_stiffness = "
                             f"{self.ballast_stiffness}")
        v.positive("Supports.sleeper_mass", self.sleeper_mass, "kg")
        v.positive("Supports.ballast_stiffness", self.ballast_stiffness, "N/m")
        v.number("Supports.ballast_damping", self.ballast_damping, low=0.0, unit="N s/m")

    @property
    def layered(self) -> bool:
        """True for pad-sleeper-ballast supports (``sleeper_mass`` given)."""
        return self.sleeper_mass is not None

    @property
    def static_stiffness(self) -> float:
        """Static stiffness of one support [N/m]: k_s, or the pad and ballast in series,
        k_p k_b / (k_p + k_b)."""
        if not self.layered:
            return self.stiffness
        return self.stiffness * self.ballast_stiffness / (self.stiffness + self.ballast_stiffness)

    def resolve(self, length: float) -> tuple[float, ...]:
        """Support positions [m] on a rail of ``length`` [m]; checks they lie inside it."""
        if self.positions is not None:
            pos = self.positions
        else:
            if length / self.spacing > MAX_SUPPORTS + 1.5:
                raise ValueError(
                    f"Supports.spacing = {self.spacing} m puts more than {MAX_SUPPORTS} supports "
                    f"on a {length} m rail; allowed range [{length / (MAX_SUPPORTS + 1):.6g}, "
                    f"{length / 1.5:.6g}] m")
            n = int(round(length / self.spacing))
            if n < 2:
                raise ValueError(
                    f"Supports.spacing = {self.spacing} m leaves no support between the rail "
                    f"ends; allowed range (0, {length / 1.5:.6g}] m (or give positions=())")
            pos = tuple(self.spacing * j for j in range(1, n))
        for x in pos:
            if not 0.0 < x < length:
                raise ValueError(
                    f"Supports.positions: support at {x} m is outside the rail; "
                    f"allowed range (0, {length}) m")
        return pos


@dataclass(frozen=True)
class Wheel:
    """The wheel: a rigid disc loaded by the car body (docs: Model § Wheel)."""

    mass: float = 10.0  #: M [kg]
    radius: float = 0.1  #: rho0, undeformed radius [m]
    load: float = 47040.0  #: F, vertical load on the centre (car body weight) [N]; M g is added
    inertia: float | None = None  #: J, polar moment of inertia [kg m^2]; None: M rho0^2 / 2
    youngs_modulus: float = 2.058e11  #: E of the wheel [Pa] (Hertz constant)
    poisson_ratio: float = 0.30  #: nu of the wheel [-]
    torque: float = 0.0  #: external torque on the wheel, positive in the rolling direction [N m]
    #: T_b, a friction brake on the rotation [N m]: -T_b sign(theta') while the wheel turns; the
    #: wheel locks (theta' = 0) when its spin reaches zero and stays locked while the torque
    #: needed to hold it, abs(T - rho lambda), is <= T_b (beyond adhesion, T_b > mu P rho0, it
    #: locks and slides). Full and ancf/* levels only (docs: Model § Rolling and slip)
    brake_torque: float = 0.0
    #: out-of-roundness, a tuple of :class:`~trackwheel.irregularity.WheelFlat` /
    #: :class:`~trackwheel.irregularity.Polygon` (docs: Model § Irregularities); () is a round wheel
    defects: tuple = ()

    def __post_init__(self):
        v.positive("Wheel.mass", self.mass, "kg")
        v.positive("Wheel.radius", self.radius, "m")
        v.number("Wheel.load", self.load, low=0.0, unit="N")
        if self.inertia is not None:
            v.positive("Wheel.inertia", self.inertia, "kg m^2")
        v.positive("Wheel.youngs_modulus", self.youngs_modulus, "Pa")
        v.number("Wheel.poisson_ratio", self.poisson_ratio, low=0.0, high=0.5, high_open=True)
        v.number("Wheel.torque", self.torque, unit="N m")
        v.number("Wheel.brake_torque", self.brake_torque, low=0.0, unit="N m")
        if not isinstance(self.defects, (tuple, list)):
            raise TypeError(f"Wheel.defects must be a tuple of WheelFlat/Polygon, "
                            f"got {type(self.defects).__name__}")
        for d in self.defects:
            if not isinstance(d, WHEEL_DEFECTS):
                raise TypeError(f"Wheel.defects must hold WheelFlat or Polygon values, "
                                f"got {type(d).__name__}")
            d.check(self.radius)
        object.__setattr__(self, "defects", tuple(self.defects))

    @property
    def polar_inertia(self) -> float:
        """J [kg m^2]: the given value, or a uniform disc M rho0^2 / 2."""
        return self.inertia if self.inertia is not None else 0.5 * self.mass * self.radius**2


@dataclass(frozen=True)
class Contact:
    """Wheel/rail contact (docs: Model § Contact, § Rolling and slip).

    ``law="linear"``: N = k (rho0 - rho) (the paper's eq. 22); ``law="hertz"``:
    N = C_H (rho0 - rho)^1.5. ``stiffness=None`` takes the Hertz constant for the wheel on a flat
    rail, C_H = 4/3 E* sqrt(rho0) with 1/E* = (1 - nu_w^2)/E_w + (1 - nu_r^2)/E_r, and for the
    linear law its linearisation at the static load P = F + M g, k = 1.5 C_H^(2/3) P^(1/3)
    (about 7.1e8 N/m for the paper's scene).
    """

    law: str = "linear"  #: "linear" or "hertz"
    stiffness: float | None = None  #: k [N/m] (linear) or C_H [N/m^1.5] (hertz); None: Hertz
    damping: float = 0.0  #: contact damping [N s/m]
    friction: float = 0.3  #: mu, friction coefficient for the slip judgement [-]
    #: the wheel sees the rail profile averaged over its static Hertz patch, length 2a (the 1D
    #: contact filter; :func:`trackwheel.irregularity.contact_half_width` gives a)
    patch_filter: bool = False

    def __post_init__(self):
        v.choice("Contact.law", self.law, {"linear", "hertz"})
        v.boolean("Contact.patch_filter", self.patch_filter)
        if self.stiffness is not None:
            v.positive("Contact.stiffness", self.stiffness,
                       "N/m" if self.law == "linear" else "N/m^1.5")
        v.number("Contact.damping", self.damping, low=0.0, unit="N s/m")
        v.number("Contact.friction", self.friction, low=0.0, unit="-")


@dataclass(frozen=True)
class Window:
    """The travelling window (docs: Model § The travelling window): the rail is a fixed number of
    sleeper bays that travels with the wheels, so a run of any length costs the same per metre
    and the same memory.

    The window holds ``bays_behind`` whole bays behind the bay of the rearmost wheel, the bays
    the vehicle spans, and ``bays_ahead`` bays ahead of the leading wheel's bay; its rail length
    is :meth:`length` (a longer rail of whole bays adds bays ahead). When the rearmost wheel
    leaves its bay the state moves one bay back: the rear bay leaves, a fresh bay at rest under
    its own weight joins at the front. Needs a track periodic in its bay (equal supports every
    ``Supports.spacing``, ``Supports.positions`` not given) and, so that the rail's ends do not
    reflect, enough damping in the track (layered supports) or bays to let waves decay. Runs on
    every fidelity level, the full model with either integrator.

    The window's rail has absorbing end zones (:class:`AbsorbingEnds`) of about
    ``absorbing_length`` at each end (:meth:`zone_bays` whole bays) unless the scene's rail
    brings its own: they absorb the waves leaving the window and, on the full model, damp the
    rail's axial motion, which each shift knocks (without them the tangential force rings;
    docs: Model § The travelling window). ``absorbing_length=0`` leaves the rail's ends as they
    are.
    """

    bays_behind: int = 20  #: whole bays behind the rearmost wheel's bay [-], 1..1000
    bays_ahead: int = 20  #: whole bays ahead of the leading wheel's bay [-], 1..1000
    #: length of each absorbing end zone [m], >= 0 (8 bays of the ballasted preset)
    absorbing_length: float = 4.8

    def __post_init__(self):
        v.integer("Window.bays_behind", self.bays_behind, low=1, high=1000)
        v.integer("Window.bays_ahead", self.bays_ahead, low=1, high=1000)
        v.number("Window.absorbing_length", self.absorbing_length, low=0.0, unit="m")

    def zone_bays(self, spacing: float) -> int:
        """Whole bays of ``spacing`` [m] in each absorbing end zone: ``absorbing_length``
        rounded up, at most ``bays_behind`` and ``bays_ahead`` (the zones stay off the
        vehicle's bays) [-]."""
        return min(math.ceil(self.absorbing_length / spacing - 1e-9), self.bays_behind,
                   self.bays_ahead)

    def n_bays(self, span: float, spacing: float) -> int:
        """Bays of the window for wheels spanning ``span`` [m] on bays of ``spacing`` [m]."""
        return self.bays_behind + 1 + math.ceil(span / spacing - 1e-9) + self.bays_ahead

    def length(self, span: float, spacing: float) -> float:
        """The window's rail length [m]: :meth:`n_bays` x ``spacing``."""
        return self.n_bays(span, spacing) * spacing


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
    vehicle: object = None
    #: the travelling window (:class:`Window`), or None: the rail is the whole track
    window: Window | None = None

    def __post_init__(self):
        for f in fields(self)[:4]:
            value = getattr(self, f.name)
            if not isinstance(value, f.default_factory):
                raise TypeError(f"Scene.{f.name} must be a {f.default_factory.__name__}, "
                                f"got {type(value).__name__}")
        v.number("Scene.gravity", self.gravity, low=0.0, unit="m/s^2")
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
        self.supports.resolve(self.rail.length)  # supports must lie on the rail
        if self.window is not None:
            self._check_window()

    def _check_window(self):
        w = self.window
        if not isinstance(w, Window):
            raise TypeError(f"Scene.window must be a trackwheel.Window or None, "
                            f"got {type(w).__name__}")
        if self.supports.positions is not None:
            raise ValueError("Scene.window needs equal supports every Supports.spacing: leave "
                             "Supports.positions None")
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
        from dataclasses import replace

        from .vehicle import Vehicle

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
        from dataclasses import replace

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
        from .vehicle import Vehicle

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
    def winkler_modulus(self) -> float:
        """Equivalent foundation modulus k_f = k_s / d_s [N/m^2] (docs: Model § Validation);
        layered supports: their static series stiffness per spacing."""
        return self.supports.static_stiffness / self.supports.spacing
