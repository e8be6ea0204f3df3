"""Every input limit of trackwheel, defined once.

The first group mirrors the C++ kernel's ``cpp/limits.hpp`` (the source: the kernel checks
them too and exports them as ``_core.MAX_ELEMENTS`` ...); this plain-Python copy lets the scene
layer validate without importing the compiled module, and ``tests/test_limits.py`` checks that
the two agree. The second group are limits of the Python side only; the third, the plausible
range of every physical parameter (``RANGES``), with the thresholds of the warnings about
likely unit slips.
"""

from __future__ import annotations

from typing import NamedTuple

# --- mirrored from cpp/limits.hpp (tests/test_limits.py checks them against _core) ----------
#: Most rail elements a scene or a call may use [-]: 20000 allows 1.5 km at 8 elements per
#: 0.6 m bay; everything per element is banded, O(n) (the dense eigen paths are bounded by
#: MAX_DENSE_EIGEN_DOF instead).
MAX_ELEMENTS: int = 20000
#: Most coordinates of a dense generalised eigenproblem [-] (the dense eigen analysis and the
#: linear path's modal reduction); larger ones take the partial sparse solver.
MAX_DENSE_EIGEN_DOF: int = 4000
#: Gauss points per element for the elastic forces, (lowest, highest) [-]: one point
#: under-integrates the bending stiffness (singular, zero-frequency modes); ten integrate the
#: exact-curvature forces to round-off.
GAUSS_RANGE: tuple[int, int] = (2, 10)
#: Highest forward speed of a run [m/s] (1080 km/h): far above any railway speed; the contact
#: search and the derived time steps are not meant for faster runs.
MAX_SPEED: float = 300.0
#: Most supports a rail may carry [-] (a guard against a tiny ``Supports.spacing`` exhausting
#: memory; 5 m at 0.5 m spacing has nine).
MAX_SUPPORTS: int = 100_000

# --- the Python side's own limits ------------------------------------------------------------
#: Most time steps one run may take [-] (10^12: far beyond any practical run; keeps the step and
#: decimation counts inside the kernel's integer types).
MAX_STEPS: int = 10**12
#: Output arrays of a run larger than this raise before it starts [bytes].
MAX_OUTPUT_BYTES: int = 2 * 1024**3
#: Largest seed of a random irregularity or a sweep's realisation [-] (numpy's 63-bit range).
MAX_SEED: int = 2**63 - 1
#: Most whole sleeper bays on either side of the vehicle in a travelling window [-].
MAX_WINDOW_BAYS: int = 1000

# --- plausible ranges of the physical parameters ---------------------------------------------
#: Highest frequency of the frequency-domain track (``receptance``, ``decay_rate``) [Hz]: the
#: beam models of the rail hold to a few kHz (above about 5 kHz the rail's cross-section
#: deforms); 100 kHz is twenty times that, and the complex band solve stays well conditioned.
MAX_FREQUENCY: float = 1e5
#: Steepest rail profile, max |dr/dX| of a sine (2 pi a / lambda) or a dipped joint
#: (pi d / l) [-]: a 1:10 ramp, ten times the steepest worn running surface (a 3 mm dip over
#: 0.3 m is 0.03); beyond it a rail profile is a step, not a running surface.
MAX_PROFILE_SLOPE: float = 0.1
#: Fastest railway run on record [m/s] (574.8 km/h, TGV V150, 2007): a faster ``speed`` is
#: allowed (up to MAX_SPEED) but warned about as a likely km/h for m/s slip.
RECORD_SPEED: float = 574.8 / 3.6
#: Softest support, pad or ballast stiffness [N/m] taken without a warning: a thousand times
#: softer than the softest rail pads and ballast (about 1e7 N/m); a softer value is allowed
#: but warned about as a likely MN/m (or kN/m) for N/m slip. (Not higher: a beam on closely
#: spaced supports, a Winkler foundation of 1e6-1e7 N/m^2 every 5 cm, has 1e5 N/m supports.)
SOFTEST_SUPPORT: float = 1e4


#: Largest static sag of the track a scene may have [m]: the sag under the rail's weight and
#: the heaviest wheel's load (estimated at construction: ``Scene.static_sag``). A real track
#: sags 1-3 mm; beyond 1 m the scene is a slip of units (a support of 140 N/m on a long rail)
#: or no track at all, and the kernel's static solve may not converge.
MAX_STATIC_SAG: float = 1.0


class Range(NamedTuple):
    """The plausible range of one physical parameter: ``low`` .. ``high`` in ``unit``, each
    end included unless ``low_open`` / ``high_open``; ``why`` says where the ends come from."""

    low: float
    high: float
    unit: str
    why: str = ""
    low_open: bool = False
    high_open: bool = False

    def text(self) -> str:
        """The range as an interval, e.g. "(0, 1e+14] N/m"."""
        lo = "(" if self.low_open else "["
        hi = ")" if self.high_open else "]"
        unit = f" {self.unit}" if self.unit not in ("", "-") else ""
        return f"{lo}{self.low:g}, {self.high:g}{hi}{unit}"


def _positive(high: float, unit: str, why: str = "") -> Range:
    return Range(0.0, high, unit, why, low_open=True)


#: The plausible range of every physical parameter of a scene, its excitation and its vehicle,
#: by the name the error messages use (``Class.field``), in SI units. Each is checked when the
#: scene (or profile, defect, vehicle) is built, with a ValueError naming the parameter and its
#: range. The ends lie orders of magnitude beyond any real track (so that rigid and massless
#: limits, 1e12-1e13 N/m supports or a 1e15 Pa rail, still fit) and inside the range where the
#: kernel's double-precision solves stay conditioned (support stiffnesses run to 1e16 N/m and
#: dampings to 1e15 N s/m before they fail).
RANGES: dict[str, Range] = {
    "Rail.length": _positive(1e4, "m", "10 km; a longer track runs on a travelling window"),
    "Rail.youngs_modulus": Range(1e8, 1e16, "Pa", "stiff polymers to 5e4 x steel (a rigid "
                                 "rail)"),
    "Rail.poisson_ratio": Range(0.0, 0.5, "-", "isotropic solids", high_open=True),
    "Rail.density": Range(1.0, 1e5, "kg/m^3", "four times the densest metal"),
    "Rail.area": Range(1e-6, 100.0, "m^2", "UIC60: 7.7e-3; a bridge girder ~1"),
    "Rail.second_moment": Range(1e-12, 100.0, "m^4", "UIC60: 3.1e-5; a bridge girder ~3"),
    "Rail.shear_coefficient": _positive(1.0, "-", "about 0.4 for a rail's vertical bending"),
    "Rail.shear_modulus": Range(1e7, 1e16, "Pa", "steel ~8e10; E / (2 (1 + nu)) if not given"),
    "AbsorbingEnds.length": _positive(1e3, "m", "and at most half the rail"),
    "AbsorbingEnds.damping": Range(0.0, 1e12, "N s/m^2", "the default design is ~1e6"),
    "AbsorbingEnds.axial_damping": Range(0.0, 1e12, "N s/m^2", "the default design is ~1e6"),
    "Supports.stiffness": _positive(1e14, "N/m", "pads and ballast 1e7-1e9; rigid limits "
                                    "1e12-1e13"),
    "Supports.damping": Range(0.0, 1e10, "N s/m", "pads 1e4-1e5"),
    "Supports.stiffness.layered": _positive(1e10, "N/m", "a rail pad on a sleeper: pads "
                                            "5e7-1e9; a stiffer pad over soft ballast leaves "
                                            "the static solve ill-conditioned: use single "
                                            "springs for a rigid pad"),
    "Supports.sleeper_mass": _positive(1e5, "kg", "half a sleeper 100-200 kg; a slab a few t"),
    "Supports.ballast_stiffness": _positive(1e14, "N/m", "ballast 3e7-3e8 per half sleeper"),
    "Supports.ballast_damping": Range(0.0, 1e10, "N s/m", "ballast 3e4-1e5"),
    "Supports.void": Range(0.0, 0.1, "m", "a hanging sleeper's gap: 0.5-5 mm; gaps are in m, "
                           "1 mm is 1e-3"),
    "Wheel.mass": _positive(1e5, "kg", "half a wheelset ~900 kg"),
    "Wheel.radius": Range(1e-3, 10.0, "m", "scale models to 20 m wheels (rail: 0.3-0.6 m)"),
    "Wheel.load": Range(0.0, 1e8, "N", "a 30 t axle: 150 kN per wheel"),
    "Wheel.inertia": _positive(1e6, "kg m^2", "half a wheelset ~100 kg m^2"),
    "Wheel.youngs_modulus": Range(1e8, 1e16, "Pa", "as the rail's"),
    "Wheel.poisson_ratio": Range(0.0, 0.5, "-", "isotropic solids", high_open=True),
    "Wheel.torque": Range(-1e6, 1e6, "N m", "traction ~1e4 N m per wheel"),
    "Wheel.brake_torque": Range(0.0, 1e6, "N m", "brakes ~1e4 N m per wheel"),
    "Contact.stiffness": _positive(1e14, "N/m", "linear law; its Hertz linearisation is ~1e9 "
                                   "N/m"),
    "Contact.stiffness.hertz": _positive(1e17, "N/m^1.5", "Hertz law, C_H = 4/3 E* sqrt(rho0): "
                                         "~1e11 for steel wheels; 1e17 holds every E and "
                                         "radius of the ranges"),
    "Contact.damping": Range(0.0, 1e10, "N s/m", "as the supports'"),
    "Contact.friction": Range(0.0, 10.0, "-", "dry steel on steel ~0.3-0.6"),
    "Scene.gravity": Range(0.0, 100.0, "m/s^2", "ten g"),
    "Window.absorbing_length": Range(0.0, 1e3, "m", "the default is 4.8 m"),
    "Vehicle.positions": Range(-1e3, 1e3, "m", "a train is at most ~400 m"),
    "Bogie.centre": Range(-1e3, 1e3, "m", "as the wheels' positions"),
    "Bogie.mass": _positive(1e5, "kg", "half a frame ~1750 kg"),
    "Bogie.pitch_inertia": _positive(1e7, "kg m^2", "half a frame ~900 kg m^2"),
    "Bogie.primary_stiffness": _positive(1e12, "N/m", "primary springs ~1e6"),
    "Bogie.primary_damping": Range(0.0, 1e10, "N s/m", "~2e4"),
    "Bogie.load": Range(0.0, 1e8, "N", "a quarter of a car body ~8e4"),
    "CarBody.centre": Range(-1e3, 1e3, "m", "as the wheels' positions"),
    "CarBody.mass": _positive(1e6, "kg", "half a car ~2e4 kg"),
    "CarBody.pitch_inertia": _positive(1e9, "kg m^2", "half a car ~8e5 kg m^2"),
    "CarBody.secondary_stiffness": _positive(1e12, "N/m", "secondary springs ~6e5"),
    "CarBody.secondary_damping": Range(0.0, 1e10, "N s/m", "~1e4"),
    "Irregularity.sine.wavelength": Range(1e-4, 1e4, "m", "corrugation 25 mm to long waves of "
                                          "~100 m; 0.1 mm, a hundredth of a contact patch, for "
                                          "harmonic limits; and 2 pi a / lambda <= "
                                          "MAX_PROFILE_SLOPE"),
    "Irregularity.sine.amplitude": Range(0.0, 0.1, "m", "corrugation ~1e-5, long waves ~1e-2"),
    "Irregularity.dipped_joint.depth": _positive(0.1, "m", "joints and welds 1-3 mm"),
    "Irregularity.dipped_joint.length": Range(1e-3, 1e3, "m", "0.2-1 m; and pi d / l <= "
                                              "MAX_PROFILE_SLOPE"),
    "Irregularity.samples.x": Range(-1e7, 1e7, "m", "10 000 km of track either way"),
    "Irregularity.samples.r": Range(-0.1, 0.1, "m", "as a sine's amplitude"),
    "WheelFlat.length": Range(1e-4, 10.0, "m", "flats 10-100 mm; and shorter than the wheel's "
                              "diameter"),
    "WheelFlat.depth": _positive(0.1, "m", "a rounded flat's ~0.1-2 mm"),
    "Polygon.amplitude": Range(0.0, 0.1, "m", "polygons ~1e-5-1e-4; and below the radius"),
}
#: Finest spacing of measured profile samples, ``Irregularity.samples`` [m]: 1 um, a hundred
#: times finer than a rail-roughness trolley's 0.1-1 mm.
MIN_SAMPLE_SPACING: float = 1e-6


def ranges_doc(prefix: str, indent: str = "    ") -> str:
    """The ranges of ``RANGES`` whose names start with ``prefix`` as reST bullet lines, for the
    docstring of the class or function they belong to (``indent``: the docstring's own)."""
    lines = ["", "Plausible ranges, checked when it is built "
             "(:data:`trackwheel.base.limits.RANGES`):", ""]
    for name, r in RANGES.items():
        if name.startswith(prefix + "."):
            why = f" ({r.why})" if r.why else ""
            lines.append(f"- ``{name[len(prefix) + 1:]}``: {r.text()}{why}")
    return "\n".join(indent + line if line else "" for line in lines) + "\n"
