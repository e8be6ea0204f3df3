"""The rail: a planar ANCF beam on its end supports, and its absorbing end zones.

Docs: Model § Rail, § Long tracks and absorbing ends.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..base import validate as v
from ..base.limits import GAUSS_RANGE, ranges_doc

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
        v.field("AbsorbingEnds.length", self.length)
        if self.damping is not None:
            v.field("AbsorbingEnds.damping", self.damping)
        if self.axial_damping is not None:
            v.field("AbsorbingEnds.axial_damping", self.axial_damping)

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
    #: ``trackwheel.base.limits.GAUSS_RANGE`` = (2, 10) (one point under-integrates the bending stiffness:
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
    #: G, shear modulus [Pa] (used with beam="timoshenko"), or None: the isotropic
    #: E / (2 (1 + nu)). Given, it is independent of ``poisson_ratio`` (which then enters only
    #: the Hertz contact constant); :attr:`modulus_of_rigidity` is the value used
    shear_modulus: float | None = None

    def __post_init__(self):
        for name in ("length", "youngs_modulus", "poisson_ratio", "density", "area",
                     "second_moment"):
            v.field(f"Rail.{name}", getattr(self, name))
        v.n_elements(self.n_elements, "Rail.n_elements")
        v.choice("Rail.curvature", self.curvature, {"exact", "simplified"})
        v.choice("Rail.far_end", self.far_end, {"roller", "pinned"})
        v.integer("Rail.n_gauss", self.n_gauss, low=GAUSS_RANGE[0], high=GAUSS_RANGE[1])
        v.choice("Rail.beam", self.beam, {"euler", "timoshenko"})
        v.field("Rail.shear_coefficient", self.shear_coefficient)
        if self.shear_modulus is not None:
            v.field("Rail.shear_modulus", self.shear_modulus)
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
    def modulus_of_rigidity(self) -> float:
        """G [Pa]: ``shear_modulus`` if given, else the isotropic E / (2 (1 + nu))."""
        if self.shear_modulus is not None:
            return self.shear_modulus
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def shear_stiffness(self) -> float:
        """kappa G A [N] (Timoshenko beam), G = :attr:`modulus_of_rigidity`."""
        return self.shear_coefficient * self.modulus_of_rigidity * self.area

    @property
    def rotary_inertia(self) -> float:
        """rho I, mass moment of inertia per length [kg m] (Timoshenko beam)."""
        return self.density * self.second_moment



Rail.__doc__ += ranges_doc("Rail")
AbsorbingEnds.__doc__ += ranges_doc("AbsorbingEnds")
