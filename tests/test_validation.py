"""Input validation at the Python boundary (issue 8): every public function rejects bad
arguments with ``ValueError``/``TypeError`` whose message names the parameter, the offending
value and the allowed range (or choices). (Split from test_robustness.py by room.)
"""

from __future__ import annotations

import dataclasses as dc
import math
import re
import sys

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import cli, plots

EIGEN = sys.modules["trackwheel.eigen"]
KATO = tw.Scene.kato2005()
BALLASTED = tw.Scene.ballasted_track(12.0)
NAN, INF = float("nan"), float("inf")


def _eigen_result():
    return tw.eigen(KATO, [1.0, 2.5], n_modes=4)


# --------------------------------------------------------------------------------------------
# 1. input validation at the Python boundary
# --------------------------------------------------------------------------------------------
# (call, exception, fragments the message must contain: the parameter, the value and the range)
BAD_CALLS = [
    # scene dataclasses
    (lambda: tw.Rail(length=0.0), ValueError, ["Rail.length", "0.0", "(0, 10000] m"]),
    (lambda: tw.Rail(length=-5.0), ValueError, ["Rail.length", "-5.0", "allowed range"]),
    (lambda: tw.Rail(length=NAN), ValueError, ["Rail.length", "nan", "not finite"]),
    (lambda: tw.Rail(length="5"), TypeError, ["Rail.length", "real number", "str"]),
    (lambda: tw.Rail(youngs_modulus=INF), ValueError, ["Rail.youngs_modulus", "inf"]),
    (lambda: tw.Rail(poisson_ratio=0.5), ValueError, ["Rail.poisson_ratio", "0.5", "0.5)"]),
    (lambda: tw.Rail(density=-1.0), ValueError, ["Rail.density", "-1.0", "allowed range"]),
    (lambda: tw.Rail(area=0.0), ValueError, ["Rail.area", "0.0", "allowed range"]),
    (lambda: tw.Rail(second_moment=None), TypeError, ["Rail.second_moment", "NoneType"]),
    (lambda: tw.Rail(n_elements=0), ValueError, ["Rail.n_elements", "0", "[1, 20000]"]),
    (lambda: tw.Rail(n_elements=20.0), TypeError, ["Rail.n_elements", "integer", "float"]),
    (lambda: tw.Rail(n_elements=True), TypeError, ["Rail.n_elements", "integer", "bool"]),
    (lambda: tw.Rail(curvature="linear"), ValueError, ["Rail.curvature", "'linear'", "exact"]),
    (lambda: tw.Rail(curvature=["exact"]), ValueError, ["Rail.curvature", "['exact']", "exact"]),
    (lambda: tw.Rail(far_end=None), ValueError, ["Rail.far_end", "None", "roller"]),
    (lambda: tw.Rail(n_gauss=11), ValueError, ["Rail.n_gauss", "11", "[2, 10]"]),
    # one Gauss point under-integrates bending: singular stiffness, silent 0 Hz modes
    (lambda: tw.Rail(n_gauss=1), ValueError, ["Rail.n_gauss", "1", "[2, 10]"]),
    (lambda: tw.Supports(stiffness=0.0), ValueError, ["Supports.stiffness", "0.0", "(0, 1e+14] N/m"]),
    (lambda: tw.Supports(spacing=-0.5), ValueError, ["Supports.spacing", "-0.5"]),
    (lambda: tw.Supports(damping=-1.0), ValueError, ["Supports.damping", "-1.0", "[0, 1e+10] N s/m"]),
    (lambda: tw.Supports(positions=(1.0, NAN)), ValueError, ["Supports.positions", "NaN"]),
    (lambda: tw.Supports(positions=("a",)), TypeError, ["Supports.positions", "real numbers"]),
    (lambda: tw.Supports(positions=[[1.0, 2.0]]), ValueError, ["Supports.positions", "1-d"]),
    (lambda: tw.Scene(supports=tw.Supports(positions=(1.0, 5.0))), ValueError,
     ["Supports.positions", "5.0", "(0, 5.0)"]),
    (lambda: tw.Scene(supports=tw.Supports(spacing=4.0)), ValueError,
     ["Supports.spacing", "4.0", "allowed range"]),
    # a tiny spacing used to try to build 5e9 supports and exhaust memory
    (lambda: tw.Scene(supports=tw.Supports(spacing=1e-9)), ValueError,
     ["Supports.spacing", "1e-09", "allowed range"]),
    (lambda: tw.Wheel(mass=0.0), ValueError, ["Wheel.mass", "0.0", "(0, 100000] kg"]),
    (lambda: tw.Wheel(radius=-0.1), ValueError, ["Wheel.radius", "-0.1"]),
    (lambda: tw.Wheel(load=-1.0), ValueError, ["Wheel.load", "-1.0", "[0, 1e+08] N"]),
    (lambda: tw.Wheel(inertia=0.0), ValueError, ["Wheel.inertia", "0.0"]),
    (lambda: tw.Wheel(torque=NAN), ValueError, ["Wheel.torque", "nan"]),
    (lambda: tw.Contact(law="quadratic"), ValueError, ["Contact.law", "'quadratic'", "hertz"]),
    (lambda: tw.Contact(stiffness=-1.0), ValueError, ["Contact.stiffness", "-1.0"]),
    (lambda: tw.Contact(friction=INF), ValueError, ["Contact.friction", "inf"]),
    (lambda: tw.Contact(damping=-2.0), ValueError, ["Contact.damping", "-2.0"]),
    (lambda: tw.Scene(gravity=-9.8), ValueError, ["Scene.gravity", "-9.8", "[0, 100] m/s^2"]),
    (lambda: tw.Scene(rail_gravity="yes"), TypeError, ["Scene.rail_gravity", "str"]),
    # huge values: a ValueError naming the field, not the kernel's RuntimeError (singular
    # stiffness, lost contact) or a DivergenceError blaming the time step
    (lambda: tw.Supports(stiffness=1e300), ValueError, ["Supports.stiffness", "(0, 1e+14] N/m"]),
    (lambda: tw.Supports(stiffness=1e20), ValueError, ["Supports.stiffness", "1e+20"]),
    (lambda: tw.Supports(damping=1e300), ValueError, ["Supports.damping", "[0, 1e+10]"]),
    (lambda: tw.Supports(sleeper_mass=1e15, ballast_stiffness=1e8), ValueError,
     ["Supports.sleeper_mass", "1e+15", "(0, 100000] kg"]),
    (lambda: tw.Supports(sleeper_mass=150.0, ballast_stiffness=1e300), ValueError,
     ["Supports.ballast_stiffness", "(0, 1e+14] N/m"]),
    (lambda: tw.Rail(youngs_modulus=1e300), ValueError, ["Rail.youngs_modulus", "1e+16"]),
    (lambda: tw.Wheel(mass=1e300), ValueError, ["Wheel.mass", "(0, 100000] kg"]),
    (lambda: tw.Contact(stiffness=1e300), ValueError, ["Contact.stiffness", "1e+14] N/m"]),
    (lambda: tw.Contact(law="hertz", stiffness=1e300), ValueError, ["Contact.stiffness",
                                                                   "N/m^1.5"]),
    (lambda: tw.Bogie(wheels=(0, 1), centre=1.0, primary_stiffness=1e300), ValueError,
     ["Bogie.primary_stiffness", "(0, 1e+12] N/m"]),
    (lambda: tw.Window(absorbing_length=1e300), ValueError, ["Window.absorbing_length"]),
    # a sleeper sinking metres into soft ballast under its own weight: a conditioning check
    # that names both fields (the kernel's contact search failed on it)
    (lambda: dc.replace(BALLASTED, supports=dc.replace(BALLASTED.supports, sleeper_mass=1e5,
                                                       ballast_stiffness=1e4)), ValueError,
     ["sags", "Supports.sleeper_mass = 100000 kg", "Supports.ballast_stiffness = 10000 N/m"]),
    # a rail of E = 1e8 Pa on supports of 1e4 N/m under 47 kN: 1.5 m of sag
    (lambda: dc.replace(KATO, supports=dc.replace(KATO.supports, stiffness=1e4),
                        rail=dc.replace(KATO.rail, youngs_modulus=1e8)), ValueError,
     ["sags about 1.47 m", "Supports.stiffness = 10000 N/m", "allowed at most 1 m"]),
    (lambda: tw.Scene(wheel=tw.Rail()), TypeError, ["Scene.wheel", "Wheel", "Rail"]),
    (lambda: tw.kmh(-300), ValueError, ["speed_kmh", "-300", "[0.0, inf]"]),
    (lambda: tw.kmh("300"), TypeError, ["speed_kmh", "str"]),
    # statics
    (lambda: tw.static(KATO, 5.5), ValueError, ["x_wheel", "5.5", "[0.0, 5.0]"]),
    (lambda: tw.static(KATO, -0.1), ValueError, ["x_wheel", "-0.1", "[0.0, 5.0]"]),
    (lambda: tw.static(KATO, NAN), ValueError, ["x_wheel", "nan"]),
    (lambda: tw.static(KATO, None), TypeError, ["x_wheel", "NoneType"]),
    (lambda: tw.static("kato", 1.0), TypeError, ["scene", "str"]),
    (lambda: tw.static(KATO, 1.0, n_elements=0), ValueError, ["n_elements", "0", "[1, 20000]"]),
    (lambda: tw.static(KATO, 2.5).rail_shape(1), ValueError, ["n_points", "1"]),
    (lambda: tw.quasi_static(KATO, []), ValueError, ["positions", "non-empty"]),
    (lambda: tw.quasi_static(KATO, [1.0, 6.0]), ValueError, ["positions", "6.0", "[0.0, 5.0]"]),
    (lambda: tw.quasi_static(KATO, [1.0, INF]), ValueError, ["positions", "inf"]),
    (lambda: tw.quasi_static(KATO, None), TypeError, ["positions", "NoneType"]),
    (lambda: tw.quasi_static(KATO, [True, False]), TypeError, ["positions", "bool"]),
    # eigen
    (lambda: tw.eigen(KATO, [7.0]), ValueError, ["positions", "7.0", "[0.0, 5.0]"]),
    (lambda: tw.eigen(KATO, "2.5"), TypeError, ["positions", "str"]),
    (lambda: tw.eigen(KATO, [2.5], n_modes=0), ValueError, ["n_modes", "0", "[1, 161]"]),
    (lambda: tw.eigen(KATO, [2.5], n_modes=162), ValueError, ["n_modes", "162", "[1, 161]"]),
    (lambda: tw.eigen(KATO, [2.5], n_axial=-1), ValueError, ["n_axial", "-1"]),
    (lambda: tw.eigen(KATO, [2.5], n_elements=2.5), TypeError, ["n_elements", "float"]),
    (lambda: tw.eigen(None, [2.5]), TypeError, ["scene", "NoneType"]),
    (lambda: _eigen_result().rail_mode_shape(2, 0), ValueError, ["i_pos", "2", "[-2, 1]"]),
    (lambda: _eigen_result().rail_mode_shape(0, 4), ValueError, ["mode", "4", "[0, 3]"]),
    (lambda: _eigen_result().rail_mode_shape(0.0, 0), TypeError, ["i_pos", "float"]),
    (lambda: EIGEN.rail_frequencies(None), TypeError, ["scene", "NoneType"]),
    # simulate
    (lambda: tw.simulate(KATO, -1.0), ValueError, ["speed", "-1.0", "[0.0, 300.0]"]),
    (lambda: tw.simulate(KATO, NAN), ValueError, ["speed", "nan"]),
    (lambda: tw.simulate(KATO, "fast"), TypeError, ["speed", "str"]),
    (lambda: tw.simulate(KATO, 0.0), ValueError, ["speed = 0", "duration"]),
    (lambda: tw.simulate(KATO, 10.0, dt=0.0), ValueError, ["dt", "0.0", "(0.0, 1.0]"]),
    (lambda: tw.simulate(KATO, 10.0, dt=-1e-5), ValueError, ["dt", "-1e-05", "(0.0, 1.0]"]),
    (lambda: tw.simulate(KATO, 10.0, dt=INF), ValueError, ["dt", "inf"]),
    # a step longer than the run, and a step so short the run could never finish
    (lambda: tw.simulate(KATO, 10.0, duration=1e-6, dt=1e-5), ValueError,
     ["dt", "1e-05", "allowed range"]),
    (lambda: tw.simulate(KATO, 10.0, dt=1e-20), ValueError, ["dt", "1e-20", "allowed range"]),
    (lambda: tw.simulate(KATO, 10.0, x_start=1.0, x_end=0.5), ValueError,
     ["x_end", "0.5", "x_start", "1.0"]),
    (lambda: tw.simulate(KATO, 10.0, x_start=1.0, x_end=1.0), ValueError, ["x_end", "1.0"]),
    (lambda: tw.simulate(KATO, 10.0, x_start=-0.1), ValueError, ["x_start", "-0.1", "[0.0, 5.0]"]),
    (lambda: tw.simulate(KATO, 10.0, x_end=5.1), ValueError, ["x_end", "5.1", "[0.0, 5.0]"]),
    (lambda: tw.simulate(KATO, 10.0, duration=1.0), ValueError, ["duration", "1.0", "beyond"]),
    (lambda: tw.simulate(KATO, 10.0, duration=0.0), ValueError, ["duration", "0.0"]),
    (lambda: tw.simulate(KATO, 10.0, integrator="rk4"), ValueError,
     ["integrator", "'rk4'", "generalized_alpha"]),
    (lambda: tw.simulate(KATO, 10.0, integrator=["explicit"]), ValueError, ["integrator"]),
    (lambda: tw.simulate(KATO, 10.0, start="moving"), ValueError, ["start", "'moving'", "static"]),
    (lambda: tw.simulate(KATO, 10.0, n_elements=0), ValueError, ["n_elements", "0"]),
    (lambda: tw.simulate(KATO, 10.0, output_every=0), ValueError, ["output_every", "0"]),
    (lambda: tw.simulate(KATO, 10.0, output_every=2**31), ValueError, ["output_every"]),
    (lambda: tw.simulate(KATO, 10.0, output_every=2.0), TypeError, ["output_every", "float"]),
    (lambda: tw.simulate(KATO, 10.0, rho_inf=1.5), ValueError, ["rho_inf", "1.5", "[0.0, 1.0]"]),
    (lambda: tw.simulate(KATO, 10.0, baumgarte=-1.0), ValueError, ["baumgarte", "-1.0"]),
    (lambda: tw.simulate(KATO, 10.0, drop_height=0.2), ValueError,
     ["drop_height", "0.2", "[0.0, 0.1]"]),
    (lambda: tw.simulate(KATO, 10.0, max_newton=0), ValueError, ["max_newton", "0"]),
    (lambda: tw.simulate(KATO, 10.0, newton_tol=0.0), ValueError, ["newton_tol", "0.0"]),
    (lambda: tw.simulate(KATO, 10.0, rolling=1), TypeError, ["rolling", "True or False"]),
    (lambda: tw.simulate(KATO, 10.0, energy="yes"), TypeError, ["energy", "str"]),
    (lambda: tw.simulate(KATO, 10.0, progress="yes"), TypeError, ["progress", "str"]),
    (lambda: tw.simulate([], 10.0), TypeError, ["scene", "list"]),
    # plots
    (lambda: plots.eigen(KATO), TypeError, ["result", "EigenResult", "Scene"]),
    (lambda: plots.eigen(_eigen_result(), n_modes=5), ValueError, ["n_modes", "5", "[1, 4]"]),
    (lambda: plots.eigen(_eigen_result(), ax="axes"), TypeError, ["ax", "str"]),
    (lambda: plots.mode_shapes(_eigen_result(), 3), ValueError, ["i_pos", "3", "[-2, 1]"]),
    (lambda: plots.mode_shapes(_eigen_result(), 0, modes=None), TypeError, ["modes", "NoneType"]),
    (lambda: plots.mode_shapes(_eigen_result(), 0, modes=[4]), ValueError,
     ["modes", "4", "[0, 3]"]),
    (lambda: plots.mode_shapes(_eigen_result(), 0, modes=[]), ValueError, ["modes"]),
]


@pytest.mark.parametrize("call,exc,fragments", BAD_CALLS,
                         ids=[f"bad{i:03d}" for i in range(len(BAD_CALLS))])
def test_bad_argument_names_parameter_value_and_range(call, exc, fragments):
    with pytest.raises(exc) as info:
        call()
    assert type(info.value) is exc  # not a subclass such as DivergenceError
    msg = str(info.value)
    for frag in fragments:
        assert frag in msg, f"{frag!r} missing from the message {msg!r}"


@pytest.mark.parametrize("argv,fragment", [
    (["eigen", "--position", "nan"], "--position"),
    (["eigen", "--position", "7"], "allowed range [0, 5] m"),
    (["eigen", "--n-modes", "0"], "--n-modes"),
    (["eigen", "--n-modes", "500"], "--n-modes = 500 is outside the allowed range [1, 161]"),
    (["reproduce"], "--out"),
    (["reproduce", "--out", "/proc/no/such/folder"], "cannot create the folder"),
    (["no-such-command"], "invalid choice"),
])
def test_cli_bad_arguments_exit_2_with_a_message(argv, fragment, capsys):
    assert cli.main(argv) == 2
    assert fragment in capsys.readouterr().err


def test_eigen_default_axial_modes_on_a_one_element_rail():
    """The default n_axial = 3 is capped at the axial modes a coarse mesh has (it raised)."""
    one = dc.replace(KATO, rail=dc.replace(KATO.rail, n_elements=1, far_end="pinned"),
                     supports=tw.Supports(positions=()))
    r = tw.eigen(one, [2.5], n_modes=1)
    # pinned at both ends, the only free axial coordinates are the two end slopes x_s
    assert r.axial_frequencies.shape == (2,)
    # the lower is the bar's fixed-fixed fundamental c/(2L), c = sqrt(EA/(rho A)); one cubic
    # element carries the half sine with a 0.7 % (Rayleigh-Ritz, from above) error
    c = math.sqrt(KATO.rail.axial_stiffness / KATO.rail.mass_per_length)
    assert c / (2 * 5.0) < r.axial_frequencies[0] < 1.02 * c / (2 * 5.0)


def test_supports_explicit_positions_accept_a_scalar_and_the_empty_tuple():
    assert tw.Supports(positions=2.5).positions == (2.5,)
    assert tw.Supports(positions=[]).positions == ()
    assert tw.Scene(supports=tw.Supports(positions=())).support_positions == ()


# --------------------------------------------------------------------------------------------
# likely slips of units: warned about (PlausibilityWarning, a UserWarning) or refused
def test_a_speed_above_the_record_is_a_likely_km_h_slip():
    """simulate(scene, 300): 300 m/s is 1080 km/h, inside the allowed range (MAX_SPEED) but
    faster than any train has run (574.8 km/h): the warning names the likely slip. At the
    record itself and below, no warning."""
    with pytest.warns(tw.PlausibilityWarning, match=r"speed = 300 m/s is 1080 km/h.*did you "
                      r"mean tw\.kmh\(300\) = 83\.33 m/s\?"):
        tw.simulate(KATO, 300.0, x_end=0.3, n_elements=20, dt=1e-5, progress=False)
    assert issubclass(tw.PlausibilityWarning, UserWarning)
    tw.simulate(KATO, tw.kmh(574.8), x_end=0.3, n_elements=20, dt=1e-5, progress=False)


@pytest.mark.parametrize("value, slip", [(140.0, "(140 MN/m is 1.4e+08 N/m: did you mean that?)"),
                                         (1e-3, "stiffnesses are in N/m")])
def test_a_support_softer_than_any_track_is_a_likely_mn_m_slip(value, slip):
    """Below 1e4 N/m, a thousand times softer than any pad or ballast: a warning, with the
    reading in MN/m (or kN/m) where that one is a track's."""
    with pytest.warns(tw.PlausibilityWarning, match=rf"Supports\.stiffness = {value:g} N/m .*"
                      + re.escape(slip)):
        tw.Supports(stiffness=value)
    with pytest.warns(tw.PlausibilityWarning, match="Supports.ballast_stiffness = 140 N/m"):
        tw.Supports(sleeper_mass=150.0, ballast_stiffness=140.0)


def test_a_rail_profile_in_millimetres_is_refused():
    """Irregularity.sine(wavelength=0.5, amplitude=1): a 1 m corrugation, refused with the
    metre named; 1 mm on 0.5 m is taken."""
    with pytest.raises(ValueError, match=r"Irregularity\.sine\.amplitude = 1\.0 .*\[0, 0\.1\] m "
                       r"\(rail profiles are in m: 1 mm is 1e-3\)"):
        tw.Irregularity.sine(wavelength=0.5, amplitude=1)
    assert tw.Irregularity.sine(wavelength=0.5, amplitude=1e-3)(0.125) == pytest.approx(1e-3)


def test_cli_support_stiffness_in_n_m_is_a_one_line_warning(capsys):
    """--support-stiffness 140 (N/m, meant MN/m): the run goes ahead (the value is allowed)
    with one warning line naming the option and the slip."""
    assert cli.main(["run", "--speed-kmh", "100", "--support-stiffness", "140", "--x-end", "0.5",
                     "--n-elements", "20", "--dt", "1e-5"]) == 0
    err = [line for line in capsys.readouterr().err.splitlines() if "warning" in line]
    assert len(err) == 1 and "--support-stiffness = 140 N/m" in err[0] and "140 MN/m" in err[0]


def test_a_fidelity_levels_contact_law_names_itself_when_its_rewrite_is_out_of_range():
    """ancf/hertz on a stiff linear contact under a 1 N load: the same stiffness at the static
    load is a Hertz constant of 5.5e14 N/m^1.5; within the Hertz range (1e17) it runs, and
    beyond it the message says which rewrite (the fidelity level's law) and what to do, not a
    bare Contact.stiffness the user never gave."""
    light = dc.replace(KATO, wheel=dc.replace(KATO.wheel, load=1.0, mass=1e-3),
                       contact=tw.Contact(stiffness=1e10))
    r = tw.simulate(light, 10.0, fidelity="ancf/hertz", x_end=0.3, n_elements=20, dt=1e-5,
                    progress=False)
    assert np.all(np.isfinite(r.normal_force))
    stiff = dc.replace(light, contact=tw.Contact(stiffness=1e14))
    with pytest.raises(ValueError, match=r"the fidelity level's hertz contact law from Contact\("
                       r"law='linear', stiffness=1e\+14\) at the static load .*Contact\.stiffness"
                       r" = .* \(0, 1e\+17\] N/m\^1\.5"):
        tw.simulate(stiff, 10.0, fidelity="ancf/hertz", x_end=0.3, n_elements=20, dt=1e-5,
                    progress=False)
