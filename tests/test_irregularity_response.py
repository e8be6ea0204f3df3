"""Wheel/rail force under a rail profile against the receptance formula (docs: Model §
Irregularities).

A wheel rolling slowly over a sine profile r = a sin(2 pi X / lambda) on a long rail on closely
spaced, damped supports reaches a steady state at f = v / lambda whose contact-force amplitude
is (the "moving irregularity" model, exact as v -> 0)
    |F| = a / |alpha_R(f) + alpha_C + alpha_W(f)|,
alpha_W = -1/(M omega^2) the wheel's receptance, alpha_C = 1/k the contact spring's, and
alpha_R the rail's point receptance, here the infinite Euler-Bernoulli beam on a continuous
viscoelastic (Winkler) foundation s = k_f + i omega c_f per metre:
    alpha_R = 1 / (8 EI beta^3),  beta^4 = (s - m omega^2) / (4 EI),
the root of the wave that decays away from the load (Re beta > 0).
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw

SPACING = 0.1  # support spacing [m]: 1/7 of the decay length 1/beta ~ 0.7 m
K_F, C_F = 140e6, 2e5  # foundation stiffness [N/m^2] and damping [N s/m^2] per metre
SPEED = 2.0  # [m/s]: 3e-3 of the bending phase speed at f, so v -> 0 holds to ~1e-3
AMPLITUDE = 5e-6  # [m]


def winkler_scene(wavelength):
    base = tw.Scene.kato2005()
    rail = dc.replace(base.rail, length=6.0, n_elements=120)  # two elements per bay
    supports = tw.Supports(stiffness=K_F * SPACING, damping=C_F * SPACING, spacing=SPACING)
    return dc.replace(base, rail=rail, supports=supports,
                      irregularity=tw.Irregularity.sine(wavelength, AMPLITUDE))


def receptance_amplitude(scene, f):
    """a / |alpha_R + alpha_C + alpha_W| at f [Hz] for the scene's rail, wheel and contact."""
    r = scene.rail
    EI, m = r.bending_stiffness, r.mass_per_length
    w = 2 * math.pi * f
    beta = ((K_F + 1j * w * C_F - m * w**2) / (4 * EI)) ** 0.25  # principal root: Re > 0
    alpha_r = 1 / (8 * EI * beta**3)
    alpha_c = 1 / scene.contact_stiffness
    alpha_w = -1 / (scene.wheel.mass * w**2)
    return AMPLITUDE / abs(alpha_r + alpha_c + alpha_w)


def steady_amplitude(run, f, n_periods):
    """Amplitude of the force's component at f [Hz] over its last n_periods (least squares on
    cos, sin and a constant: the static load)."""
    keep = run.t >= run.t[-1] - n_periods / f
    t, n = run.t[keep], run.normal_force[keep]
    basis = np.column_stack([np.cos(2 * math.pi * f * t), np.sin(2 * math.pi * f * t),
                             np.ones_like(t)])
    coef, *_ = np.linalg.lstsq(basis, n, rcond=None)
    return math.hypot(coef[0], coef[1])


@pytest.mark.parametrize("fidelity", ["full", "linear/sprung"])
@pytest.mark.parametrize("wavelength", [0.01, 0.02, 0.04])  # f = 200, 100, 50 Hz
def test_steady_force_under_sine_profile_matches_receptance_formula(wavelength, fidelity,
                                                                     validation):
    scene = winkler_scene(wavelength)
    f = SPEED / wavelength
    run = tw.simulate(scene, SPEED, x_start=2.6, x_end=2.6 + 0.25 * SPEED, dt=2e-5,
                      fidelity=fidelity, progress=False)
    expected = receptance_amplitude(scene, f)
    got = steady_amplitude(run, f, n_periods=10)
    # steady: the start-up transient has decayed (the last 5 periods give the same amplitude)
    assert steady_amplitude(run, f, n_periods=5) == pytest.approx(got, rel=1e-3)
    # 1 % (the issue allows 2 %): the discrete supports (spacing 1/7 of the decay length) and
    # v > 0 each shift the amplitude by well under 1 %, most at the shortest wavelength
    assert got == pytest.approx(expected, rel=0.01)
    if wavelength == 0.02:
        validation.record(
            f"excitation.sine_profile_force[{fidelity}]", level="excitation",
            kind="closed form",
            quantity=f"{fidelity} level, wheel rolling slowly over a 20 mm sine profile on a "
                     "closely supported damped rail: steady contact-force amplitude at 100 Hz",
            reference="moving-irregularity model a/|α_R + α_C + α_W| with the infinite "
                      "beam's receptance",
            measured=abs(got / expected - 1.0), tolerance=0.01)


def test_profile_sharper_than_the_wheel_is_refused_and_the_patch_filter_rounds_it():
    """A Kabo dipped joint has a cusp (r'' -> infinity): a wheel of radius rho0 bridges it on
    two points, so the model refuses it unless the contact patch averages it (the patch
    length 2a ~ 12 mm for the paper's wheel smooths the 9.4 mrad slope change to r'' ~ 1.3
    1/m < 1/rho0 = 10 1/m)."""
    base = tw.Scene.kato2005()
    joint = dc.replace(base, irregularity=tw.Irregularity.dipped_joint(1e-3, 0.4, 2.3))
    with pytest.raises(ValueError, match=r"Scene.irregularity curves upwards .* X = 2.5 m"):
        tw.static(joint, 1.0)
    filtered = dc.replace(joint, contact=dc.replace(joint.contact, patch_filter=True))
    rest = tw.static(filtered, 2.5)  # at the bottom of the dip
    # the static wheel sits in the dip: its centre is lower by the depth d than on the smooth
    # rail, less what the filter rounds off the cusp (~ slope change x a / 4 ~ 1.4e-5 m, 1.4 %
    # of d) and the wheel's bridging of the rounded bottom: within 5 % of d
    smooth = tw.static(base, 2.5)
    assert smooth.y_wheel - rest.y_wheel == pytest.approx(1e-3, rel=0.05)


def test_polygonal_wheel_equals_the_sine_profile_it_rolls_over(validation):
    """A wheel polygon a cos(m psi) rolling without slip (psi = theta = v t / rho0) excites the
    contact exactly as a rail profile a sin(2 pi X / lambda + phase) with lambda = 2 pi rho0 / m
    and the phase that lines them up. The linear path sees the same gap up to the two cubic
    splines' error, (2 pi dx / lambda)^4 / 384 ~ 1.7e-6 a, i.e. a force error up to
    k x 1.7e-6 a (measured 5.8e-3 N; bound 5e-6 k a). The full model agrees within its creep
    and the contact point's obliquity (the radius change acts along the wheel radius, the
    profile vertically; bound 2 % of the force swing)."""
    base = winkler_scene(0.04)
    rho0, m, a, x0 = base.wheel.radius, 16, 5e-6, 2.6
    lam = 2 * math.pi * rho0 / m
    poly = dc.replace(base, irregularity=None,
                      wheel=dc.replace(base.wheel, defects=(tw.Polygon(m, a),)))
    sine = dc.replace(base, irregularity=tw.Irregularity.sine(
        lam, a, phase=math.pi / 2 - 2 * math.pi * x0 / lam))
    kw = dict(x_start=x0, x_end=x0 + 0.1, dt=2e-5, progress=False)
    n_p = tw.simulate(poly, SPEED, fidelity="linear/sprung", **kw).normal_force
    n_s = tw.simulate(sine, SPEED, fidelity="linear/sprung", **kw).normal_force
    assert np.ptp(n_s[n_s.size // 2:]) > 5.0  # it is excited [N]
    assert np.max(np.abs(n_p - n_s)) < 5e-6 * base.contact_stiffness * a
    validation.record(
        "excitation.polygon_equals_sine_profile", level="excitation", kind="path agreement",
        quantity="linear/sprung, 16th-order wheel polygon: contact force",
        reference="the same wheel, round, over the rail profile the polygon rolls out",
        measured=np.max(np.abs(n_p - n_s)) / (base.contact_stiffness * a), tolerance=5e-6,
        metric="of k a")
    n_p = tw.simulate(poly, SPEED, **kw).normal_force
    n_s = tw.simulate(sine, SPEED, **kw).normal_force
    half = n_s.size // 2
    assert np.max(np.abs(n_p - n_s)[half:]) < 0.02 * np.ptp(n_s[half:])


def paper_damped():
    base = tw.Scene.kato2005()
    return dc.replace(base, supports=dc.replace(base.supports, damping=2e4))


def test_full_and_linear_paths_agree_under_a_small_profile_and_part_under_a_large_one():
    """The linear path is the full model linearised: under a 10 um random profile (FRA class 6,
    1.6-5 m) plus 20 um of 0.3 m corrugation they agree as on a smooth rail (0.5 % of the force
    swing). Under 0.15 mm of 30 mm corrugation at 300 km/h the wheel leaves the rail and the
    paths part: the unilateral Hertz contact and the wheel's geometric filtering of a
    wavelength comparable to its contact geometry are what the full model adds."""
    base = paper_damped()
    small = dc.replace(base, irregularity=(
        tw.Irregularity.random(tw.spectra.fra(6), seed=1, wavelengths=(1.6, 5.0))
        + tw.Irregularity.sine(0.3, 2e-5)))
    kw = dict(n_elements=40, dt=1e-5, progress=False)
    full = tw.simulate(small, tw.kmh(200), fidelity="ancf/hertz", **kw).normal_force
    lin = tw.simulate(small, tw.kmh(200), fidelity="linear/hertz", **kw).normal_force
    assert np.max(np.abs(full - lin)) < 5e-3 * np.ptp(full)
    large = dc.replace(base, irregularity=tw.Irregularity.sine(0.03, 1.5e-4))  # r'' = 6.6 1/m
    full = tw.simulate(large, tw.kmh(300), fidelity="ancf/hertz", **kw)
    lin = tw.simulate(large, tw.kmh(300), fidelity="linear/hertz", **kw)
    assert full.lost_contact and lin.lost_contact
    assert np.max(np.abs(full.normal_force - lin.normal_force)) > 0.05 * np.ptp(full.normal_force)


def impacts(run, n):
    """(psi - pi [rad], X [m]) of the largest force in each of the first n whole revolution
    windows theta in [2 pi k - pi/2, 2 pi k + 3 pi/2), centred on a flat at psi = pi."""
    th = run.theta
    out = []
    for k in range(n):
        sel = np.flatnonzero((th >= 2 * math.pi * k - math.pi / 2)
                             & (th < 2 * math.pi * k + 1.5 * math.pi))
        i = sel[np.argmax(run.normal_force[sel])]
        out.append((th[i] - 2 * math.pi * k - math.pi, run.x_wheel[i]))
    return np.array(out).T


def test_a_wheel_flat_returns_with_the_rolling_angle_not_the_distance():
    """A 20 mm flat (half-angle phi_f = 0.1 rad) centred at psi = pi: each revolution's impact
    comes as the flat passes the contact, theta - pi in (0, phi_f + 0.2) (mod 2 pi): rolling,
    every 2 pi rho0 of travel (1 %); driven beyond adhesion (T = 1.5 mu N rho0: the wheel
    slides and spins up) it comes round after less travel, still at the same rolling angle --
    slip shifts the defect along the track."""
    base = paper_damped()
    rho0, phi_f = base.wheel.radius, math.asin(0.01 / base.wheel.radius)
    flat = dc.replace(base, wheel=dc.replace(base.wheel,
                                             defects=(tw.WheelFlat(0.02, at_angle=math.pi),)))
    kw = dict(n_elements=40, dt=5e-6, progress=False)
    psi, x = impacts(tw.simulate(flat, tw.kmh(100), **kw), 6)
    assert np.all((psi > 0.0) & (psi < phi_f))
    np.testing.assert_allclose(np.diff(x), 2 * math.pi * rho0, rtol=0.01)
    torque = 1.5 * base.contact.friction * base.static_load * rho0
    slid = tw.simulate(dc.replace(flat, wheel=dc.replace(flat.wheel, torque=torque)),
                       tw.kmh(100), **kw)
    assert np.any(slid.slip_state == 2)
    psi, x = impacts(slid, 5)
    assert np.all((psi > 0.0) & (psi < phi_f + 0.2))
    assert np.all(np.diff(x) < 0.8 * 2 * math.pi * rho0)


@pytest.mark.parametrize("rounded", [False, True])
def test_a_wheel_flat_in_contact_at_the_start_is_in_static_equilibrium(rounded):
    """A flat at the wheel angle 0 (WheelFlat's default) stands on the rail at the start. The
    static start seeks the wheel centre from the radius at the contact, rho0 + Delta rho(0):
    the centre is lower by the flat's depth (10 mm on the paper's 0.1 m wheel: 0.125 mm deep,
    twice the static compression P / k, 67 um; from rho0 it started above the rail and the
    static solve refused with "the wheel lost contact"). In equilibrium N = P = F + M g to the
    static solve's tolerance; the wheel centre is the flat's depth below the round wheel's."""
    base = tw.Scene.kato2005()
    flat = tw.WheelFlat(0.01, rounded=rounded)
    scene = dc.replace(base, wheel=dc.replace(base.wheel, defects=(flat,)))
    r = tw.simulate(scene, 30.0, duration=2e-4, progress=False)
    assert r.normal_force[0] == pytest.approx(scene.static_load, rel=1e-6)
    round_start = tw.simulate(base, 30.0, duration=2e-4, progress=False)
    depth = -float(flat.delta_rho(0.0, base.wheel.radius))
    assert round_start.y_wheel[0] - r.y_wheel[0] == pytest.approx(depth, rel=1e-6)
