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


@pytest.mark.parametrize("wavelength", [0.01, 0.02, 0.04])  # f = 200, 100, 50 Hz
def test_steady_force_under_sine_profile_matches_receptance_formula(wavelength):
    scene = winkler_scene(wavelength)
    f = SPEED / wavelength
    run = tw.simulate(scene, SPEED, x_start=2.6, x_end=2.6 + 0.25 * SPEED, dt=2e-5,
                      progress=False)
    expected = receptance_amplitude(scene, f)
    got = steady_amplitude(run, f, n_periods=10)
    # steady: the start-up transient has decayed (the last 5 periods give the same amplitude)
    assert steady_amplitude(run, f, n_periods=5) == pytest.approx(got, rel=1e-3)
    # 1 % (the issue allows 2 %): the discrete supports (spacing 1/7 of the decay length) and
    # v > 0 each shift the amplitude by well under 1 %, most at the shortest wavelength
    assert got == pytest.approx(expected, rel=0.01)


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
