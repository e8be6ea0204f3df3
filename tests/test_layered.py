"""Layered supports: rail pad (k_p, c_p), sleeper m_s, ballast (k_b, c_b), and the ballasted
preset (docs: Model § Layered supports).

Checks: the single-spring limit (k_b -> inf, m_s -> 0), the series stiffness and the sleeper's
bounce frequency against closed forms, the static balance of the ballast forces, the energy
balance with sleepers, and the preset's two track resonances against the two-layer closed form
of a continuously supported track.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel
from trackwheel.eigen import rail_frequencies

KATO = tw.Scene.kato2005()
#: k_b / k_p of the single-spring limit: the series stiffness k_p k_b/(k_p + k_b) is k_p (1 -
#: 1e-4), and a sleeper of 1 g adds 0.01 N of weight (2e-7 of P) and a mode at 6 MHz
STIFF = 1e4


def limit_scene(scene=KATO):
    s = scene.supports
    return dc.replace(scene, supports=dc.replace(s, sleeper_mass=1e-3,
                                                 ballast_stiffness=STIFF * s.stiffness))


def layered_kato(**changes):
    return dc.replace(KATO, supports=dc.replace(KATO.supports, sleeper_mass=150.0,
                                                ballast_stiffness=105e6, **changes))


# ------------------------------------------------------------------ validation

@pytest.mark.parametrize("changes, match", [
    ({"sleeper_mass": 150.0}, "together"),
    ({"ballast_stiffness": 1e8}, "together"),
    ({"sleeper_mass": -1.0, "ballast_stiffness": 1e8}, "Supports.sleeper_mass"),
    ({"sleeper_mass": 150.0, "ballast_stiffness": 0.0}, "Supports.ballast_stiffness"),
    ({"sleeper_mass": 150.0, "ballast_stiffness": 1e8, "ballast_damping": -1.0},
     "Supports.ballast_damping"),
    ({"ballast_damping": 1e4}, "needs a sleeper layer"),
])
def test_bad_layers_are_named(changes, match):
    with pytest.raises(ValueError, match=match):
        tw.Supports(**changes)


def test_single_springs_stay_the_default():
    assert not KATO.supports.layered
    assert KATO.supports.static_stiffness == KATO.supports.stiffness
    assert tw.Scene.ballasted_track().supports.layered


# ------------------------------------------------------------------ the single-spring limit

def test_stiff_ballast_and_light_sleeper_reproduce_single_springs_statically():
    """Deflection under the wheel: the supports' flexibility changes by k_p/k_b = 1e-4, so the
    deflection by at most that (measured 7.6e-5); tolerance 2e-4 relative."""
    a, b = tw.static(KATO, 2.5), tw.static(limit_scene(), 2.5)
    assert abs(b.y_contact / a.y_contact - 1.0) < 2.0 * (1.0 / STIFF)
    assert b.y_contact < a.y_contact  # softer in series, never stiffer


def test_stiff_ballast_and_light_sleeper_reproduce_single_spring_frequencies():
    """The lowest six coupled modes move by at most (1/2) k_p/k_b = 5e-5 relative (a frequency
    goes as the square root of a stiffness; measured 4.8e-5); tolerance 1e-4. The sleepers' own modes lie near
    sqrt(k_b/m_s)/2pi = 6 MHz, far above."""
    fa = tw.eigen(KATO, [2.5], 6).frequencies
    fb = tw.eigen(limit_scene(), [2.5], 6).frequencies
    np.testing.assert_allclose(fb, fa, rtol=1.0 / STIFF)


@pytest.mark.parametrize("fidelity", ["full", "linear/sprung"])
def test_stiff_ballast_and_light_sleeper_reproduce_a_single_spring_passage(fidelity):
    """A 0.5 m passage at 300 km/h: the contact force and the rail displacement agree within
    1e-3 of their range and value (the track's stiffness differs by 1e-4; generalized-alpha
    damps the 6 MHz sleeper modes at once, rho_inf = 0.8; measured 1.2e-4 of the force range,
    8e-5 of the displacement on both paths)."""
    kw = {"x_start": 2.0, "x_end": 2.5, "dt": 1e-5, "fidelity": fidelity}
    a = tw.simulate(KATO, tw.kmh(300), **kw)
    b = tw.simulate(limit_scene(), tw.kmh(300), **kw)
    scale = np.ptp(a.normal_force)
    assert scale > 100.0  # the force varies: the comparison is not vacuous
    assert np.max(np.abs(b.normal_force - a.normal_force)) < 1e-3 * scale
    assert np.max(np.abs(b.y_contact - a.y_contact)) < 1e-3 * np.max(np.abs(a.y_contact))


# ------------------------------------------------------------------ closed forms

def one_support_scene(second_moment, youngs_modulus=2.058e11, rail_gravity=False):
    """A 1 m rail pinned at its ends on one layered support at mid-span (2 elements)."""
    return tw.Scene(rail=tw.Rail(length=1.0, n_elements=2, second_moment=second_moment,
                                 youngs_modulus=youngs_modulus),
                    supports=tw.Supports(stiffness=140e6, positions=(0.5,), sleeper_mass=150.0,
                                         ballast_stiffness=105e6),
                    rail_gravity=rail_gravity)


def test_static_deflection_is_that_of_pad_and_ballast_in_series(validation):
    """A point load P at mid-span of a pinned span L on a spring k deflects it by
    P / (k + 48 EI/L^3) (exact for the cubic Hermite beam with the load on a node); with a pad
    and a ballast in series k = k_p k_b/(k_p + k_b). A flexible rail (I = 3e-9 m^4, 48 EI/L^3 =
    3e4 N/m) makes the support carry nearly all of P. The ANCF rail's geometric nonlinearity is
    (y/L)^2 ~ 1e-6 (measured 9e-7); tolerance 1e-5 relative. The sleeper's deflection is the ballast's share,
    P/k_b (ballast force = P)."""
    scene = one_support_scene(3e-9)
    r = tw.static(scene, 0.5)
    kp, kb = 140e6, 105e6
    EI = scene.rail.bending_stiffness
    P = scene.static_load
    expected = -P / (kp * kb / (kp + kb) + 48.0 * EI)
    assert abs(r.y_contact / expected - 1.0) < 1e-5
    validation.record(
        "statics.pad_and_ballast_in_series", level="statics", kind="closed form",
        quantity="one pad-sleeper-ballast support under a flexible pinned span: deflection",
        reference="P/(k_p k_b/(k_p + k_b) + 48 EI/L³)",
        measured=abs(r.y_contact / expected - 1.0), tolerance=1e-5)
    support_load = P * (1.0 - 48.0 * EI / (kp * kb / (kp + kb) + 48.0 * EI))
    assert abs(r.ballast_force[0] / support_load - 1.0) < 1e-5
    assert abs(r.sleeper_z[0] / (-support_load / kb) - 1.0) < 1e-5


def test_sleeper_bounce_under_a_stiff_rail_is_the_two_spring_frequency(validation):
    """Under a nearly rigid rail (E x 1e4: mid-span stiffness k_r = 48 EI/L^3 = 3e12 N/m, the
    rail's own modes above 50 kHz) the sleeper bounces between the pad, in series with the
    rail, and the ballast: omega^2 = (k_p k_r/(k_p + k_r) + k_b)/m_s. The rail's mass shifts it
    by ~(omega/omega_rail)^2 ~ 1e-5 (measured 2e-10); tolerance 1e-4."""
    scene = one_support_scene(3.08961e-5, youngs_modulus=2.058e15)
    kp, kb, ms = 140e6, 105e6, 150.0
    kr = 48.0 * scene.rail.bending_stiffness
    f = math.sqrt((kp * kr / (kp + kr) + kb) / ms) / (2.0 * math.pi)
    f0 = rail_frequencies(scene, 1)[0]
    assert abs(f0 / f - 1.0) < 1e-4
    validation.record(
        "eigen.sleeper_bounce", level="eigen analysis", kind="closed form",
        quantity="one sleeper under a nearly rigid rail: its bounce frequency",
        reference="ω² = (k_p k_r/(k_p + k_r) + k_b)/m_s",
        measured=abs(f0 / f - 1.0), tolerance=1e-4)


def test_ballast_carries_the_wheel_load_and_each_sleeper_its_bay():
    """Vertical equilibrium: the ballast carries the wheel load, the rail's weight and the
    sleepers' weight, less what the rail's rigid ends take. 30 m of ballasted track, wheel at
    mid-length: the wheel's deflection decays as exp(-beta x), beta = (k/(4 EI))^(1/4) =
    1.4 1/m, so at the ends (15 m) its share is e^-21; the ballast forces with the wheel less
    those without must sum to P (measured 7e-10; tolerance 1e-8 of P). Far from the ends
    the track is periodic, so the middle sleeper without the wheel carries one bay of rail,
    d rho A g, plus its own weight m_s g (measured 5e-10; tolerance 1e-6)."""
    scene = tw.Scene.ballasted_track()
    loaded = tw.static(scene, 15.0)
    bare = _core.testing.track_static(_kernel.rail_model(scene))
    F0 = np.asarray(bare["ballast_force"])
    n = len(scene.support_positions)
    assert loaded.ballast_force.shape == (n,) and F0.shape == (n,)
    P = scene.static_load
    assert abs((loaded.ballast_force - F0).sum() / P - 1.0) < 1e-8
    g = scene.gravity
    bay = 0.6 * scene.rail.mass_per_length * g + 150.0 * g
    assert abs(F0[n // 2] / bay - 1.0) < 1e-6
    # every ballast spring is compressed, and most under the wheel
    assert np.all(loaded.ballast_force > 0.0)
    assert int(np.argmax(loaded.ballast_force)) == n // 2


def test_energy_balance_with_sleepers():
    """Undamped layered supports: the total energy (now with the sleepers' kinetic energy, the
    pad's (1/2) k_p (y - z)^2, the ballast's (1/2) k_b z^2 and the sleepers' weight m_s g z)
    changes only by the driving reaction's work, as in test_invariants.py (rho_inf = 1, the
    trapezoidal rule). Measured 2.6e-9 of max |W| = 5.4 J; tolerance 1e-6 of max |W| as there
    (the sleepers' energies are quadratic, so the trapezoidal rule keeps them exactly)."""
    scene = layered_kato()
    v = tw.kmh(100)
    r = tw.simulate(scene, v, x_end=1.0, dt=2.5e-6, n_elements=20, rho_inf=1.0, energy=True)
    work = np.concatenate([[0.0], np.cumsum(0.5 * (r.reaction[1:] + r.reaction[:-1]) * v
                                            * np.diff(r.t))])
    assert np.max(np.abs(work)) > 1.0
    np.testing.assert_allclose(r.energy - r.energy[0], work, rtol=0,
                               atol=1e-6 * np.max(np.abs(work)))


# ------------------------------------------------------------------ the ballasted preset

def two_layer_cut_on(scene):
    """The two cut-on frequencies [Hz] of a rail on a continuous pad-sleeper-ballast
    foundation (per metre: m, k_p/d, m_s/d, k_b/d): at wavenumber 0 the rail and sleeper
    layers move uniformly, det([k_p' - m w^2, -k_p'], [-k_p', k_p' + k_b' - m_s' w^2]) = 0."""
    s, d = scene.supports, scene.supports.spacing
    m, ms = scene.rail.mass_per_length * d, s.sleeper_mass
    kp, kb = s.stiffness, s.ballast_stiffness
    # m ms w^4 - (kp ms + (kp + kb) m) w^2 + kp kb = 0
    a, b, c = m * ms, -(kp * ms + (kp + kb) * m), kp * kb
    root = math.sqrt(b * b - 4 * a * c)
    w2 = sorted(((-b - root) / (2 * a), (-b + root) / (2 * a)))
    return [math.sqrt(x) / (2.0 * math.pi) for x in w2]


def test_ballasted_preset_track_resonances():
    """Two resonances of a ballasted track (Thompson, Railway Noise and Vibration (2009), ch. 3;
    Knothe & Grassie, Vehicle System Dynamics 22 (1993)): the whole track, rail and sleepers,
    bouncing on the ballast (typically 50-150 Hz) and the rail bouncing on its pads against the
    sleepers (typically 400-600 Hz for 'medium' pads). At wavenumber 0 a discrete support acts
    as its continuous smear (the rail moves uniformly), so the two-layer closed form holds at
    the cut-on; the finite 30 m rail's lowest mode has a 30 m half wave, whose bending adds
    EI (pi/L)^4 ~ 1e-5 of the foundation stiffness. Tolerances: the lowest mode within 0.2 % of
    f1 (measured -1.1e-4: f1 = 118.1 Hz); between the sleeper's own frequency
    sqrt((k_p + k_b)/m_s)/2pi = 219 Hz, the top of the lower branch, and f2 = 400 Hz no mode
    (the stop band); the first mode above it within 1 % of f2 (measured -0.4 %: the discrete
    supports and the rigid rail ends shift the upper branch's lowest finite-rail mode)."""
    scene = tw.Scene.ballasted_track()
    f1, f2 = two_layer_cut_on(scene)
    assert 50.0 < f1 < 150.0 and 400.0 < f2 < 600.0
    s = scene.supports
    fs = math.sqrt((s.stiffness + s.ballast_stiffness) / s.sleeper_mass) / (2.0 * math.pi)
    f = rail_frequencies(scene, 200)
    assert abs(f[0] / f1 - 1.0) < 2e-3
    above = f[f > fs]
    assert above.size > 0 and np.all(above > 0.99 * f2)
    assert abs(above[0] / f2 - 1.0) < 1e-2
    # the lower branch fills the band up to the sleeper frequency
    assert np.count_nonzero((f > f1) & (f < fs)) > 20


def test_cli_runs_the_ballasted_track(capsys):
    """``trackwheel run --track ballasted`` simulates Scene.ballasted_track() (pad stiffness
    180 MN/m, static wheel load 70 kN) and reports it by name."""
    from trackwheel import cli

    code = cli.main(["run", "--track", "ballasted", "--speed-kmh", "300", "--x-start", "14.1",
                     "--x-end", "15.3", "--fidelity", "linear/sprung"])
    out = capsys.readouterr().out
    assert code == 0
    assert "Scene.ballasted_track(), k_p = 180 MN/m" in out
    assert "static load 70000.0 N" in out


def test_cli_eigen_of_the_ballasted_track(capsys):
    """``trackwheel eigen --track ballasted`` prints the preset's modes: the first two as
    ``trackwheel.eigen`` gives them (to the printed 0.01 Hz)."""
    from trackwheel import cli

    assert cli.main(["eigen", "--track", "ballasted", "--position", "15", "--n-modes", "2"]) == 0
    out = capsys.readouterr().out
    f = tw.eigen(tw.Scene.ballasted_track(), [15.0], 2).frequencies[0]
    assert "Scene.ballasted_track(), wheel at X = 15 m" in out
    for k, fk in enumerate(f, start=1):
        assert f"  {k:>3}  {fk:10.2f} Hz\n" in out


def test_kernel_names_bad_layer_vectors():
    """The kernel checks what Python did not: one entry per support in each layer vector."""
    scene = layered_kato()
    r = scene.rail
    p = _core.RailParams()
    p.length, p.EA, p.EI = r.length, r.axial_stiffness, r.bending_stiffness
    p.rhoA = r.mass_per_length
    p.n_elements, p.n_gauss = 20, 5
    s = _core.SupportParams()
    s.position = list(scene.support_positions)
    s.stiffness = [140e6] * 9
    s.damping = [0.0] * 9
    s.sleeper_mass = [150.0] * 8
    s.ballast_stiffness = [105e6] * 9
    s.ballast_damping = [0.0] * 9
    with pytest.raises(ValueError, match="one entry per support"):
        _core.RailModel(p, s)
    s.sleeper_mass = [150.0] * 8 + [0.0]
    with pytest.raises(ValueError, match="sleeper_mass must be > 0 kg"):
        _core.RailModel(p, s)


@pytest.mark.parametrize("fidelity", ["full", "linear/hertz"])
def test_layered_runs_are_bit_identical(fidelity):
    """Same inputs, same outputs, to the bit, with sleepers too."""
    scene = layered_kato(damping=2e4, ballast_damping=5e4)
    kw = {"x_start": 2.0, "x_end": 2.3, "dt": 1e-5, "fidelity": fidelity}
    a, b = tw.simulate(scene, tw.kmh(300), **kw), tw.simulate(scene, tw.kmh(300), **kw)
    assert np.array_equal(a.normal_force, b.normal_force)
    assert np.array_equal(a.y_contact, b.y_contact)
