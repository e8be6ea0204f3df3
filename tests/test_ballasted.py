"""The ballasted preset (Scene.ballasted_track) against the textbooks.

Docs: Model § Layered supports, § Receptance and decay rate; the closed forms of the pinned-pinned
frequency are in the section "Shear-deformable rail (Timoshenko)".

Textbook: D. Thompson, *Railway Noise and Vibration* (Elsevier 2009), ch. 3 (track dynamics:
receptance of rail on layered and discrete supports, the pinned-pinned resonance near 1 kHz for
0.6 m sleeper spacing, decay rate and its dependence on the pad). The full-track cut-on of the
preset (the track bouncing on the ballast near 118 Hz and the rail on its pads near 400 Hz, the
stop band between) is tested in tests/test_layered.py::test_ballasted_preset_track_resonances and
not repeated here.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel.frequency import band_decay_rates
from test_layered import two_layer_cut_on
from trackwheel.frequency import (ISO3095_BANDS, ISO3095_VERTICAL_LIMIT, decay_rate_positions,
                                  en15461_decay, iso3095_band_edges)

#: 60 m of the preset (the EN 15461 line, 39.6 m, with ten metres beyond each end) at 0.075 m
#: elements: ten per Euler-Bernoulli bending wavelength at 4.3 kHz, the top of the 5 kHz band
LONG = tw.Scene.ballasted_track(60.0, elements_per_bay=8)


def _beam(scene: tw.Scene, beam: str) -> tw.Scene:
    return dc.replace(scene, rail=dc.replace(scene.rail, beam=beam))


def timoshenko_pinned_pinned(rail: tw.Rail, d: float) -> float:
    """Lower root [Hz] of the Timoshenko frequency equation (docs: Model, section
    "Shear-deformable rail (Timoshenko)")
    (rho I rho / (kappa G)) w^4 - (rho A + rho I k^2 + E I k^2 rho / (kappa G)) w^2
    + E I k^4 = 0 with k = pi / d, from the section data alone."""
    rho, e_mod, area, inertia = rail.density, rail.youngs_modulus, rail.area, rail.second_moment
    kg = rail.shear_coefficient * e_mod / (2.0 * (1.0 + rail.poisson_ratio))
    k = math.pi / d
    a = rho * inertia * rho / kg
    b = rho * area + rho * inertia * k**2 + e_mod * inertia * k**2 * rho / kg
    c = e_mod * inertia * k**4
    w2 = (b - math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)
    return math.sqrt(w2) / (2.0 * math.pi)


def euler_pinned_pinned(rail: tw.Rail, d: float) -> float:
    """(pi / (2 d^2)) sqrt(EI / m) [Hz]."""
    return math.pi / (2.0 * d * d) * math.sqrt(rail.youngs_modulus * rail.second_moment
                                               / (rail.density * rail.area))


def layered_beta(scene: tw.Scene, f: np.ndarray) -> np.ndarray:
    """beta of the infinite Euler-Bernoulli beam on the continuous layered foundation,
    beta^4 = (k_eff(w) - m w^2) / (4 EI), k_eff = s_p (s_b - m_s w^2) / (s_p + s_b - m_s w^2)
    per spacing (s = k + i w c of pad and ballast); the principal root, Re beta >= |Im beta|,
    whose waves (1 -+ i) beta both decay away from the load."""
    w = 2.0 * np.pi * np.asarray(f, dtype=float)
    s, r = scene.supports, scene.rail
    sp = s.stiffness + 1j * w * s.damping
    sb = s.ballast_stiffness + 1j * w * s.ballast_damping - s.sleeper_mass * w**2
    k_eff = sp * sb / (sp + sb) / s.spacing
    return ((k_eff - r.mass_per_length * w**2 + 0j) / (4.0 * r.bending_stiffness)) ** 0.25


def layered_point_receptance(scene: tw.Scene, f: np.ndarray) -> np.ndarray:
    """alpha(0, 0) = 1 / (8 EI beta^3) [m/N] (docs: Model § Receptance and decay rate)."""
    return 1.0 / (8.0 * scene.rail.bending_stiffness * layered_beta(scene, f) ** 3)


def layered_band_decay_rates(scene: tw.Scene, per_band: int = 8) -> np.ndarray:
    """The EN 15461 band rates of the infinite beam on the continuous layered foundation:
    alpha(x)/alpha(0) = ((1 - i) exp(-k1 x) + (1 + i) exp(-k2 x)) / 2, k1,2 = (1 -+ i) beta, at
    the standard's positions, band-averaged as band_decay_rates does."""
    x = decay_rate_positions(scene)
    dx = x - x[0]
    edges = iso3095_band_edges()
    out = []
    for lo, hi in zip(edges[:-1], edges[1:]):
        beta = layered_beta(scene, np.geomspace(lo, hi, per_band + 2)[1:-1])
        k1, k2 = (1 - 1j) * beta, (1 + 1j) * beta
        a = 0.5 * ((1 - 1j) * np.exp(-np.outer(k1, dx)) + (1 + 1j) * np.exp(-np.outer(k2, dx)))
        out.append(en15461_decay(x, np.sqrt(np.mean(np.abs(a) ** 2, axis=0))[None, :])[0])
    return np.array(out)


# ------------------------------------------------------------------ pinned-pinned resonance

def test_pinned_pinned_frequency_of_uic60_on_0_6_m_sleepers_is_about_1_khz(validation):
    """Thompson (2009) ch. 3: for UIC60 on sleepers 0.6 m apart the pinned-pinned resonance is
    near 1 kHz; the Euler-Bernoulli formula overestimates it by a third. The Timoshenko root
    (1068 Hz) lies within 10 % of 1 kHz, and the Euler-Bernoulli one (1422 Hz) is 4/3 of it
    within 5 % (the book's "a third" is a one-figure statement).
    The library's pinned_pinned_frequencies agrees with the section-data derivation here to
    round-off."""
    rail, d = LONG.rail, LONG.supports.spacing
    f_e, f_t = tw.fidelity.pinned_pinned_frequencies(_beam(LONG, "timoshenko"))
    assert (f_e, f_t) == pytest.approx(
        (euler_pinned_pinned(rail, d), timoshenko_pinned_pinned(rail, d)), rel=1e-12)
    assert abs(f_t / 1000.0 - 1.0) < 0.10
    assert f_e / f_t == pytest.approx(4.0 / 3.0, rel=0.05)
    validation.record(
        "eigen.uic60_pinned_pinned_published", level="eigen analysis", kind="published",
        quantity="UIC60 on sleepers 0.6 m apart: pinned-pinned frequency with shear",
        reference="Thompson (2009), Railway Noise and Vibration, ch. 3: near 1 kHz",
        measured=abs(f_t / 1000.0 - 1.0), tolerance=0.10)
    validation.record(
        "eigen.uic60_shear_lowers_pinned_pinned", level="eigen analysis", kind="published",
        quantity="UIC60 on 0.6 m: Euler-Bernoulli over Timoshenko pinned-pinned frequency",
        reference="Thompson (2009), ch. 3: the Euler-Bernoulli beam overestimates it by a "
                  "third (4/3)",
        measured=abs(f_e / f_t / (4.0 / 3.0) - 1.0), tolerance=0.05)


@pytest.mark.parametrize("beam", ["euler", "timoshenko"])
def test_midspan_receptance_peaks_at_the_pinned_pinned_frequency(beam):
    """Above the track resonances the mid-span point receptance peaks where one bay bends between
    sleepers that hardly move: within 1 % of the closed form of the beam theory (measured
    +0.3 % Timoshenko, 0.0 % Euler-Bernoulli, in 1 Hz steps). The tolerance allows the pads'
    finite stiffness (a support of 180 MN/m is not a pin: it lifts the frequency slightly) and
    the 0.075 m elements (eight per bay)."""
    scene = _beam(tw.Scene.ballasted_track(30.0, elements_per_bay=8), beam)
    rail, d = scene.rail, scene.supports.spacing
    expected = (timoshenko_pinned_pinned if beam == "timoshenko" else euler_pinned_pinned)(
        rail, d)
    f = np.arange(700.0, 2000.0, 1.0)
    a = tw.receptance(scene, 15.3, f)  # the mid-span of the bay right of the middle sleeper
    assert f[np.argmax(np.abs(a))] == pytest.approx(expected, rel=0.01)


@pytest.mark.parametrize("beam", ["euler", "timoshenko"])
def test_decay_rate_dips_at_the_pinned_pinned_frequency(beam):
    """Thompson (2009) ch. 3: at the pinned-pinned frequency waves travel with the sleepers at
    their nodes, so the support damping hardly touches them and the decay rate has its minimum
    there. The lowest EN 15461 rate over 700-2500 Hz (2 Hz steps) lies within 1 % of the closed
    form (measured within 0.2 %)."""
    scene = _beam(LONG, beam)
    expected = (timoshenko_pinned_pinned if beam == "timoshenko" else euler_pinned_pinned)(
        scene.rail, scene.supports.spacing)
    f = np.arange(700.0, 2500.0, 2.0)
    assert f[np.argmin(tw.decay_rate(scene, f))] == pytest.approx(expected, rel=0.01)


# ------------------------------------------------------------------ low-frequency receptance

def test_low_frequency_receptance_is_the_beam_on_a_layered_foundation(validation):
    """Below the pad cut-on the discrete pad-sleeper-ballast supports act as their continuous
    smear k_eff(w) per spacing. Tolerances: below 150 Hz (the wave's length 2 pi / Re(beta) > 4 m,
    7 bays) within 0.15 dB and 0.01 rad at mid-span and above a sleeper, which bracket the
    continuous beam (mid-span softer, measured +0.08 dB / -0.05 dB: the rail's deflection
    ripples by about 1 % from bay to bay; the bracket holds while the rail deflects
    quasi-statically, below 3/4 of the track's resonance on the ballast, 118 Hz); 150-300 Hz
    within 0.6 dB and 0.1 rad (measured 0.44 dB near 260 Hz: between the sleeper frequency
    sqrt((k_p + k_b)/m_s)/2 pi = 219 Hz and the cut-on, k_eff changes fast with frequency and the
    rail bends over fewer bays)."""
    f = np.geomspace(20.0, 300.0, 40)
    a_inf = layered_point_receptance(LONG, f)
    low = f < 150.0
    mid = tw.receptance(LONG, 30.3, f)
    above = tw.receptance(LONG, 30.0, f)
    for a in (mid, above):
        db = 20.0 * np.log10(np.abs(a / a_inf))
        phase = np.angle(a / a_inf)
        assert np.max(np.abs(db[low])) < 0.15 and np.max(np.abs(phase[low])) < 0.01
        assert np.max(np.abs(db)) < 0.6 and np.max(np.abs(phase)) < 0.1
        if a is mid:
            validation.record(
                "frequency.layered_foundation_receptance", level="frequency domain",
                kind="closed form",
                quantity="ballasted preset, mid-span point receptance below 150 Hz",
                reference="infinite beam on the smeared pad-sleeper-ballast foundation",
                measured=np.max(np.abs(db[low])), tolerance=0.15, metric="dB")
    quasi_static = f < 0.75 * two_layer_cut_on(LONG)[0]  # well below the track resonance
    assert np.all(np.abs(mid[quasi_static]) > np.abs(a_inf[quasi_static]))
    assert np.all(np.abs(above[quasi_static]) < np.abs(a_inf[quasi_static]))


# ------------------------------------------------------------------ decay rate and ISO 3095

def test_stop_band_decay_rate_is_that_of_the_layered_foundation(validation):
    """In the 250-400 Hz bands (the stop band between the sleeper frequency, 219 Hz, and the pad
    cut-on, 400 Hz, tests/test_layered.py) no free wave propagates: the decay is reactive and
    large. The EN 15461 band rates of the discrete track equal those of the infinite beam on the
    continuous layered foundation within 5 % (measured 2.5 %: the bending wavelength is about
    four bays there, so the discrete supports differ from their smear by (d / lambda)^2 ~ 5 %),
    lie far above the ISO 3095 limit, and hardly depend on the support damping (doubling the
    pad damping moves the 250 and 315 Hz bands by less than 15 %, measured 11 %)."""
    bands = slice(0, 3)  # 250, 315, 400 Hz
    assert ISO3095_BANDS[bands] == (250.0, 315.0, 400.0)
    dr = band_decay_rates(LONG)
    np.testing.assert_allclose(dr[bands], layered_band_decay_rates(LONG)[bands], rtol=0.05)
    validation.record(
        "frequency.stop_band_decay_rate", level="frequency domain", kind="closed form",
        quantity="ballasted preset: EN 15461 decay rate in the 250-400 Hz bands",
        reference="infinite beam on the continuous layered foundation",
        measured=np.abs(dr[bands] / layered_band_decay_rates(LONG)[bands] - 1.0).max(),
        tolerance=0.05)
    assert np.all(dr[bands] >= np.asarray(ISO3095_VERTICAL_LIMIT)[bands])
    damped = dc.replace(LONG, supports=dc.replace(LONG.supports,
                                                  damping=2.0 * LONG.supports.damping))
    ratio = band_decay_rates(damped) / dr
    assert np.all(np.abs(ratio[:2] - 1.0) < 0.15)


def test_above_the_cut_on_the_decay_rate_comes_from_the_pads():
    """Above the cut-on the rail's bending wave propagates and loses energy only to the support
    damping and through the pads: doubling the pad damping raises the rate in every band from
    500 Hz up (by more than 10 %, measured 25-135 %), and so does a stiffer pad of the same loss
    factor (500 MN/m; Thompson (2009) ch. 3: stiffer pads couple the rail to the sleepers and
    give higher decay rates; measured 2.9-12x)."""
    s = _beam(LONG, "timoshenko")
    dr = band_decay_rates(s)
    above = np.asarray(ISO3095_BANDS) >= 500.0
    damped = dc.replace(s, supports=dc.replace(s.supports, damping=2.0 * s.supports.damping))
    assert np.all(band_decay_rates(damped)[above] > 1.1 * dr[above])
    stiff = dc.replace(s, supports=dc.replace(s.supports, stiffness=500e6,
                                              damping=s.supports.damping * 500e6 / 180e6))
    assert np.all(band_decay_rates(stiff)[above] > 1.1 * dr[above])


def test_iso3095_standing_of_the_preset():
    """Where the preset stands against the ISO 3095:2013 vertical limit (Timoshenko rail, the
    beam theory valid at these frequencies). Honestly: it meets the limit in the stop band
    (250-400 Hz, tested above against the closed form) and from the 1250 Hz band up (10 of 14
    bands), but not at 500-1000 Hz: its pad (180 MN/m, loss factor about 0.3 at 500 Hz) lets the
    rail decouple from the sleepers above the 400 Hz cut-on, and the pinned-pinned dip falls in
    the 1 kHz band. A track chosen for ISO 3095 pass-by tests has stiffer pads (the previous
    test: at 500 MN/m the rate rises in every band from 500 Hz). What is physically guaranteed
    is tested here: among the bands above the cut-on the lowest band rate is in the band that
    holds the pinned-pinned frequency (1068 Hz, the 1 kHz band), and above that band no rate
    falls to the EN 15461 grid's floor 2 x 4.343 / x_max (0.22 dB/m, EN 15461 clause 7: a rate
    below it is only an upper bound)."""
    s = _beam(LONG, "timoshenko")
    dr = band_decay_rates(s)
    edges = iso3095_band_edges()
    f_t = timoshenko_pinned_pinned(s.rail, s.supports.spacing)
    k_pp = int(np.searchsorted(edges, f_t)) - 1
    above_cut_on = np.asarray(ISO3095_BANDS) >= 500.0
    assert ISO3095_BANDS[k_pp] == 1000.0
    assert int(np.argmin(np.where(above_cut_on, dr, np.inf))) == k_pp
    x = decay_rate_positions(s)
    floor = 2.0 * 10.0 * math.log10(math.e) / (x[-1] - x[0])
    assert np.all(dr[k_pp + 1:] > floor)
