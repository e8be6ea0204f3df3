"""Paths that solve the same equations must agree (issue 17): the linear fast path against the
full ANCF path, and the explicit RK4 against generalized-alpha, with every parameter they share
set away from its default and non-zero (damping included), on the same mesh and time step.

Parameters of ``Scene`` and ``simulate`` and where each is exercised here:

- Rail: length, youngs_modulus, poisson_ratio (Hertz constant), density, area, second_moment,
  n_elements, curvature, far_end, n_gauss -- all changed in ``odd_scene``. ``curvature`` and
  ``far_end`` cannot matter to the linear path (straight-rail tangent; axial only), so there
  the full path must still agree.
- Supports: stiffness, damping, positions (uneven) -- ``odd_scene``; spacing -- the paper's
  scene with c_s = 2e5 N s/m.
- Wheel: mass, radius, load, youngs_modulus, poisson_ratio -- ``odd_scene``; inertia and torque
  act on the rolling constraint, which the linear (vertical) path does not model: they are
  compared between the integrators, and their physics is in test_slip_physics.py.
- Contact: law and stiffness (both levels, Hertz constant from the moduli); friction only
  matters to the rolling constraint (integrators); damping -- test_linear_path_models_contact_
  damping (both laws).
- Scene: gravity, rail_gravity -- on and off; irregularity and the wheel's defects --
  tests/test_irregularity_response.py (linear and full paths under the same profile).
- simulate: speed, dt, n_elements, x_start, x_end, rho_inf, output_every, start ("static",
  "sudden"), drop_height (contact lost and regained), n_modes (all modes = all coordinates),
  integrator and baumgarte (integrators), rolling (False: the frictionless full model, which
  the linear path must equal too).
  energy: not comparable between the paths (the full model's driving reaction also does work
  on the rail's axial motion and the wheel's rotation, which the linear path does not have:
  the energy changes differ by ~20 %); the full path's balance is in test_invariants.py.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw

V = tw.kmh(300)
#: the undamped paper's scene: the linear rail reproduces the ANCF rail's d(t) to 0.1 % of the
#: dynamic amplitude (the geometric nonlinearity, slope^2 ~ 1e-6, and the axial coupling the
#: linear rail leaves out). Damping is linear in both models and adds nothing to that
#: difference, so 0.5 % of the amplitude (5x the measured undamped difference) is the
#: tolerance; dropping the support damping from one path makes the amplitude 36 % off.
TOL_TRACE = 5e-3


def damped(scene, c_s=2e5):
    return dc.replace(scene, supports=dc.replace(scene.supports, damping=c_s))


@pytest.mark.parametrize("level", ["sprung", "hertz"])
def test_linear_matches_full_with_damped_supports(level, validation):
    """c_s = 2e5 N s/m at every support: max |d| and the trace d(t) of the linear level agree
    with the ANCF level of the same contact law (same mesh, same dt) within TOL_TRACE of the
    amplitude (measured: 0.06 % trace, 0.02 % amplitude)."""
    scene = damped(tw.Scene.kato2005())
    kw = {"n_elements": 20, "dt": 1e-5}
    full = tw.analyse(tw.simulate(scene, V, fidelity=f"ancf/{level}", **kw))
    lin = tw.analyse(tw.simulate(scene, V, fidelity=f"linear/{level}", **kw))
    assert abs(lin.amplitude / full.amplitude - 1.0) < TOL_TRACE
    assert np.max(np.abs(lin.dynamic - full.dynamic)) < TOL_TRACE * full.amplitude
    validation.record(
        f"paths.linear_equals_ancf[{level}]", level="paths agree", kind="path agreement",
        quantity=f"linear/{level} at 300 km/h over the paper's track with damped supports: "
                 "d(t)",
        reference=f"ancf/{level}, same mesh and step",
        measured=np.max(np.abs(lin.dynamic - full.dynamic)) / full.amplitude,
        tolerance=TOL_TRACE, metric="of the amplitude")
    # and damping matters here: the undamped amplitude differs by far more than the tolerance
    undamped = tw.analyse(tw.simulate(tw.Scene.kato2005(), V, fidelity=f"ancf/{level}", **kw))
    assert abs(undamped.amplitude / full.amplitude - 1.0) > 20 * TOL_TRACE


def odd_scene(**changes):
    """Every Rail, Supports, Wheel and Contact parameter away from the paper's value; supports
    damped and unevenly spaced."""
    scene = tw.Scene(
        rail=tw.Rail(length=4.0, youngs_modulus=2.1e11, poisson_ratio=0.28, density=7800.0,
                     area=7.7e-3, second_moment=3.05e-5, n_elements=16, curvature="simplified",
                     far_end="pinned", n_gauss=4),
        supports=tw.Supports(stiffness=100e6, damping=1e5,
                             positions=(0.55, 1.1, 1.6, 2.2, 2.7, 3.3)),
        wheel=tw.Wheel(mass=20.0, radius=0.12, load=60e3, youngs_modulus=2.1e11,
                       poisson_ratio=0.28),
        contact=tw.Contact(stiffness=None), gravity=9.81)
    return dc.replace(scene, **changes)


ODD_RUN = {"n_elements": 16, "dt": 1e-5, "x_start": 0.3, "x_end": 3.0, "rho_inf": 0.9,
           "output_every": 2}


@pytest.mark.parametrize("level,kw,changes", [
    ("sprung", {}, {}),
    ("hertz", {}, {}),
    ("sprung", {"start": "sudden"}, {}),
    ("hertz", {"start": "sudden"}, {}),
    ("hertz", {"drop_height": 2e-4}, {}),
    ("sprung", {}, {"gravity": 0.0, "rail_gravity": False}),
    ("hertz", {}, {"rail_gravity": False}),
    ("sprung", {"rolling": False}, {}),
])
def test_linear_matches_full_with_every_parameter(level, kw, changes, validation):
    """``odd_scene`` at 250 km/h: the rail under the wheel, the wheel height and the contact
    force of the linear level agree with the ANCF level within 1 % of the dynamic amplitude
    (forces: 1e-3 of the static load), with the static start, a sudden load, a dropped wheel
    that loses and regains contact, gravity off, and without friction (measured: <= 0.14 % and
    1e-4). The tolerance is 7x the measured difference, which is the ANCF rail's
    nonlinearity."""
    scene = odd_scene(**changes)
    run = {**ODD_RUN, **kw}
    a = tw.simulate(scene, tw.kmh(250), fidelity=f"ancf/{level}", **run)
    b = tw.simulate(scene, tw.kmh(250), fidelity=f"linear/{level}", **run)
    scale = tw.analyse(a).amplitude
    assert a.t.size == b.t.size and np.array_equal(a.t, b.t)
    assert np.max(np.abs(a.y_contact - b.y_contact)) < 0.01 * scale
    assert np.max(np.abs(a.y_wheel - b.y_wheel)) < 0.01 * scale
    assert np.max(np.abs(a.normal_force - b.normal_force)) < 1e-3 * scene.static_load
    assert a.lost_contact == b.lost_contact == ("drop_height" in kw)
    if "drop_height" in kw:
        validation.record(
            "paths.linear_equals_ancf_with_contact_loss", level="paths agree",
            kind="path agreement",
            quantity="linear/hertz, every parameter off its default, a dropped wheel losing "
                     "and regaining contact: rail under the wheel",
            reference="ancf/hertz, same mesh and step",
            measured=np.max(np.abs(a.y_contact - b.y_contact)) / scale, tolerance=0.01,
            metric="of the amplitude")


@pytest.mark.parametrize("level", ["sprung", "hertz"])
def test_linear_path_models_contact_damping(level):
    """Contact damping 1e4 N s/m: the linear level agrees with the ANCF level as closely as
    without it (TOL_TRACE); without the damper in the linear path it was 5 % of the amplitude
    off, the size of the damper's effect."""
    base = tw.Scene.kato2005()
    scene = dc.replace(base, contact=dc.replace(base.contact, damping=1e4))
    kw = {"n_elements": 20, "dt": 1e-5}
    full = tw.analyse(tw.simulate(scene, V, fidelity=f"ancf/{level}", **kw))
    lin = tw.analyse(tw.simulate(scene, V, fidelity=f"linear/{level}", **kw))
    assert np.max(np.abs(lin.dynamic - full.dynamic)) < TOL_TRACE * full.amplitude
    undamped = tw.analyse(tw.simulate(base, V, fidelity=f"linear/{level}", **kw))
    assert np.max(np.abs(undamped.dynamic - lin.dynamic)) > 10 * TOL_TRACE * full.amplitude


def test_modal_path_with_all_modes_equals_coordinates_with_damping(validation):
    """Modal superposition with all vertical modes is a change of coordinates: with damped
    supports (a full, non-diagonal modal damping matrix) it reproduces the band solution to
    round-off (1e-9 of the amplitude; the eigenvectors are accurate to ~1e-12)."""
    scene = damped(tw.Scene.kato2005())
    kw = {"n_elements": 10, "dt": 1e-5, "fidelity": "linear/sprung", "x_end": 2.0}
    band = tw.simulate(scene, V, **kw)
    modal = tw.simulate(scene, V, n_modes=2 * (10 + 1) - 2, **kw)
    scale = tw.analyse(band).amplitude
    np.testing.assert_allclose(modal.y_contact, band.y_contact, rtol=0, atol=1e-9 * scale)
    validation.record(
        "paths.modal_equals_band", level="paths agree", kind="path agreement",
        quantity="linear/sprung by modal superposition with every mode, damped supports: "
                 "rail under the wheel",
        reference="the band solve in the rail's coordinates",
        measured=np.max(np.abs(modal.y_contact - band.y_contact)) / scale, tolerance=1e-9,
        metric="of the amplitude")


@pytest.mark.parametrize("fidelity,integrator", [("full", "generalized_alpha"),
                                                  ("full", "explicit"),
                                                  ("linear/hertz", "generalized_alpha")])
def test_decimated_output_is_every_kth_sample(fidelity, integrator):
    """output_every = 3 keeps exactly the samples 0, 3, 6, ... of the undecimated run (the
    state does not depend on what is recorded). Generalized-alpha and the linear path: bit for
    bit. RK4 restarts a step from the evaluation made for the output when there is one, at the
    time (n-1) h instead of n h - h: a round-off difference, which the lightly damped axial
    ringing carries along (measured 1.3e-6 of the range in lambda, less elsewhere): 1e-5."""
    scene = damped(tw.Scene.kato2005())
    dt = 2e-6 if integrator == "explicit" else 1e-5
    kw = {"n_elements": 20, "dt": dt, "x_end": 0.6, "fidelity": fidelity,
          "integrator": integrator}
    every = tw.simulate(scene, V, output_every=1, **kw)
    third = tw.simulate(scene, V, output_every=3, **kw)
    n = third.t.size
    assert n == (every.t.size - 1) // 3 + 1
    for name in ("t", "y_contact", "y_wheel", "normal_force", "tangential_force"):
        a, b = getattr(third, name), getattr(every, name)[::3][:n]
        if integrator == "explicit":
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-5 * np.max(np.abs(b)))
        else:
            assert np.array_equal(a, b), name


def rolling_scene():
    """Everything the rolling model has, non-zero: damped supports, damped Hertz contact, a
    torque (0.3 of adhesion: sticks), a light wheel (J = 1e-3 kg m^2, so that lambda follows
    the torque: test_slip_physics.py), and gravity off (the wheel load alone)."""
    base = tw.Scene.kato2005()
    torque = 0.3 * 0.3 * base.wheel.load * base.wheel.radius
    return dc.replace(base, supports=dc.replace(base.supports, damping=2e5),
                      contact=tw.Contact(law="hertz", damping=1e4, friction=0.3),
                      wheel=dc.replace(base.wheel, torque=torque, inertia=1e-3),
                      gravity=0.0, rail_gravity=False)


@pytest.mark.parametrize("baumgarte", [0.0, 1e3])
def test_integrators_agree_with_every_rolling_parameter(baumgarte):
    """``rolling_scene`` at 300 km/h over 0.75 m, generalized-alpha at 2.5 us against RK4 at
    2 us (with and without Baumgarte stabilisation, which must not change the solution):
    y_B and Y_A agree within 1 % of the dynamic amplitude (measured 0.012 %), N within 1 % of
    its range (measured 0.1 %). The tangential force rings at the rail's axial frequencies,
    which the two schemes damp differently (rho_inf = 0.8 against none), so lambda is compared
    on average: both carry the torque, mean lambda = T / rho within 1 %, and the wheel turns
    through the same angle within 1e-6 of it."""
    scene = rolling_scene()
    kw = {"x_end": 1.0, "n_elements": 20}
    ga = tw.simulate(scene, V, dt=2.5e-6, **kw)
    ex = tw.simulate(scene, V, dt=2e-6, integrator="explicit", baumgarte=baumgarte, **kw)
    assert np.all(ga.slip_state == 1) and np.all(ex.slip_state == 1)
    amp = tw.analyse(ga).amplitude

    def at_ga(name):
        return np.interp(ga.t, ex.t, getattr(ex, name))

    assert np.max(np.abs(at_ga("y_contact") - ga.y_contact)) < 0.01 * amp
    assert np.max(np.abs(at_ga("y_wheel") - ga.y_wheel)) < 0.01 * amp
    assert np.max(np.abs(at_ga("normal_force") - ga.normal_force)) < 0.01 * np.ptp(
        ga.normal_force)
    T, rho0 = scene.wheel.torque, scene.wheel.radius
    for r in (ga, ex):
        assert abs(np.mean(r.tangential_force) / (T / rho0) - 1.0) < 0.01
    assert abs(ex.theta[-1] / ga.theta[-1] - 1.0) < 1e-6


def layered_scene():
    """The paper's scene on damped pad-sleeper-ballast supports (pad 140 MN/m and 2e4 N s/m,
    half sleeper 150 kg, ballast 105 MN/m and 5e4 N s/m)."""
    base = tw.Scene.kato2005()
    return dc.replace(base, supports=dc.replace(base.supports, damping=2e4, sleeper_mass=150.0,
                                                ballast_stiffness=105e6, ballast_damping=5e4))


@pytest.mark.parametrize("level", ["sprung", "hertz"])
def test_linear_matches_full_with_layered_supports(level):
    """Layered supports on both paths (the sleepers condensed into each path's band): as for
    single springs, the linear level's d(t) agrees with the ANCF level's within TOL_TRACE of
    the amplitude (measured 0.13 % of the trace, 0.08 % of the amplitude). The sleepers matter:
    the single-spring scene's amplitude differs from the layered one by 61 %."""
    scene = layered_scene()
    kw = {"n_elements": 20, "dt": 1e-5}
    full = tw.analyse(tw.simulate(scene, V, fidelity=f"ancf/{level}", **kw))
    lin = tw.analyse(tw.simulate(scene, V, fidelity=f"linear/{level}", **kw))
    assert abs(lin.amplitude / full.amplitude - 1.0) < TOL_TRACE
    assert np.max(np.abs(lin.dynamic - full.dynamic)) < TOL_TRACE * full.amplitude
    single = tw.analyse(tw.simulate(damped(tw.Scene.kato2005(), 2e4), V,
                                    fidelity=f"ancf/{level}", **kw))
    assert abs(single.amplitude / full.amplitude - 1.0) > 10 * TOL_TRACE


def test_integrators_agree_with_layered_supports():
    """Generalized-alpha (sleepers condensed in the Newton matrix) against RK4 (sleeper
    accelerations F_j/m_s explicitly) on the layered scene: y_B within 1 % of the dynamic
    amplitude (measured 0.02 %) and N within 1 % of its range (measured 0.1 %), as for single
    springs."""
    scene = layered_scene()
    kw = {"x_end": 1.0, "n_elements": 20}
    ga = tw.simulate(scene, V, dt=2.5e-6, **kw)
    ex = tw.simulate(scene, V, dt=2e-6, integrator="explicit", **kw)
    amp = tw.analyse(ga).amplitude
    assert np.max(np.abs(np.interp(ga.t, ex.t, ex.y_contact) - ga.y_contact)) < 0.01 * amp
    assert np.max(np.abs(np.interp(ga.t, ex.t, ex.normal_force) - ga.normal_force)) < 0.01 * (
        np.ptp(ga.normal_force))


def test_modal_path_refuses_layered_supports():
    with pytest.raises(ValueError, match="n_modes"):
        tw.simulate(layered_scene(), V, fidelity="linear/sprung", n_modes=10, x_end=1.0)
