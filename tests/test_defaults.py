"""The defaults a user gets without choosing (docs: Model § Default time step and mesh,
§ Outputs): each default rule against a refined computation, the stretch of a run that
``analyse`` measures, a vehicle wheel's own quasi-static line, the steady state's robustness to
a ripple that is not bay-periodic, receptances at many points, and the rail's shear modulus.

The project's rule: a user who changes nothing gets the converged answer for the scene.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import cli
from trackwheel.run import defaults as D
from trackwheel.run import stretch as S
from trackwheel.run import frequency as fr
from trackwheel.study.steady import steady_state


def _beam(scene: tw.Scene, beam: str) -> tw.Scene:
    return dc.replace(scene, rail=dc.replace(scene.rail, beam=beam))


# --------------------------------------------------------------------------------------------
# the rules
def test_the_paper_scene_keeps_its_defaults():
    """The rules reduce to the paper's former defaults for Scene.kato2005(): 8 elements per bay
    (the pinned-pinned wavelength needs only 5 with the Euler-Bernoulli rail) and 150 steps per
    period of the 10 kg wheel on its contact spring (20 per period of the 2147 Hz
    pinned-pinned frequency would allow 2.3e-5 s); the run and its measurement cover the whole
    5 m rail (its ends are 3.9 m clearances apart: no stretch clear of both)."""
    s = tw.Scene.kato2005()
    d = tw.default_settings(s)
    assert d["n_elements"] == 80
    assert d["dt"] == 1.0 / (150 * D.wheel_frequency(s))
    assert S.default_start(s) == 0.25 and S.default_end(s, 0.25) == 4.75
    assert S.clear_stretch(s) is None
    assert S.measured_stretch(s, tw.kmh(300), 0.25, 4.75) is None


def test_frequencies_and_wavelengths_of_the_rules():
    """The pinned-pinned frequency has the bending wavelength 2 d_s in either beam theory
    (bending_wavelength inverts the frequency equation the pinned-pinned closed form solves,
    to 1e-9); the contact resonance balances the real parts of the wheel's, the contact's and
    the free rail's receptances (checked by substitution), above sqrt(k/M) for the paper's
    light wheel and near the rail's local mass on k for the ballasted preset's heavy one."""
    for scene in (tw.Scene.kato2005(), tw.Scene.ballasted_track()):
        for beam in ("euler", "timoshenko"):
            sb = _beam(scene, beam)
            lam = D.bending_wavelength(sb, D.pinned_pinned_frequency(sb))
            assert lam == pytest.approx(2.0 * sb.supports.spacing, rel=1e-9)
        r = scene.rail
        w = 2.0 * math.pi * D.contact_resonance(scene)
        kb = (r.mass_per_length * w * w / r.bending_stiffness) ** 0.25
        balance = 1.0 / (scene.wheel.mass * w * w) + 1.0 / (4.0 * r.bending_stiffness * kb**3)
        assert balance * scene.contact_stiffness == pytest.approx(1.0, rel=1e-9)
    assert D.contact_resonance(tw.Scene.kato2005()) > D.wheel_frequency(tw.Scene.kato2005())
    heavy = tw.Scene.ballasted_track()
    assert 700.0 < D.contact_resonance(heavy) < 800.0 < D.pinned_pinned_frequency(heavy)


@pytest.mark.parametrize("beam, per_bay", [("euler", 8), ("timoshenko", 12)])
def test_derived_mesh_and_step_of_the_ballasted_track(beam, per_bay):
    """8 elements per bay for the Euler-Bernoulli rail (the moving contact's minimum), 12 for
    the Timoshenko one (24 per pinned-pinned wavelength 1.2 m); the step 150 per period of
    the 196 Hz wheel on its spring, which also gives >= 20 per period of the highest frequency
    of interest (the pinned-pinned 1422 / 1068 Hz)."""
    s = _beam(tw.Scene.ballasted_track(), beam)
    d = tw.default_settings(s)
    assert d["n_elements"] == 50 * per_bay
    assert d["dt"] == pytest.approx(1.0 / (150 * D.wheel_frequency(s)), rel=1e-12)
    assert d["dt"] <= 1.0 / (20 * D.highest_frequency(s))
    assert tw.eigen(s, [15.3], n_modes=1).n_elements == d["n_elements"]


def _run_force(scene, speed, n_elements, dt, x0=5.1, x1=12.9, xm=8.1):
    """(max N / P, bay-averaged profile max / P, min / P) over X >= xm of a run x0 -> x1."""
    r = tw.simulate(scene, speed, n_elements=n_elements, dt=dt, x_start=x0, x_end=x1,
                    progress=False)
    x, N, P, d = r.x_wheel, r.normal_force, scene.static_load, scene.supports.spacing
    start = math.ceil(xm / d) * d
    n = int((x[-1] - start) // d)
    prof = np.interp(start + d * np.arange(n * 128) / 128, x, N).reshape(n, 128).mean(axis=0)
    return np.array([N[x >= xm].max(), prof.max(), prof.min()]) / P


@pytest.mark.slow
def test_default_run_against_a_refined_run_on_the_ballasted_track():
    """The derived mesh and step against twice the elements and half the step, on the
    ballasted track (Euler-Bernoulli rail) at 300 km/h: the dynamic factor and the bay-averaged
    contact-force profile's extremes agree within 1e-3 of the static load (the issue's target
    for the profile is 0.5 %; measured 3e-4). Measured once more finely (32 elements per bay,
    a quarter step): the 8-per-bay, derived-step values are within 2.5e-4 at 100-400 km/h,
    even at 400 km/h where v / l_e meets the pinned-pinned frequency."""
    s = tw.Scene.ballasted_track(18.0)
    d = tw.default_settings(s)
    base = _run_force(s, tw.kmh(300), d["n_elements"], d["dt"])
    fine = _run_force(s, tw.kmh(300), 2 * d["n_elements"], 0.5 * d["dt"])
    err = float(np.max(np.abs(base - fine)))
    assert err < 1e-3


@pytest.mark.slow
@pytest.mark.skipif(not hasattr(tw.Contact(), "element_compliance"),
                    reason="needs the consistent moving contact on the shear rail: without it "
                           "the node-crossing kicks leave 12 per bay 1.5-2.6 % high")
def test_default_run_on_the_timoshenko_rail_against_a_refined_run():
    """The derived mesh of the Timoshenko rail (12 per bay: 24 per pinned-pinned wavelength)
    against 32 per bay, ballasted track at 200 km/h, where v / l_e = 1.1 kHz meets the
    pinned-pinned frequency: the dynamic factor and the bay profile's extremes within 2e-3 of
    the static load (measured 1.1e-3 with the element compliance of the contact; 2.6e-2
    without it, which is why this waits for it)."""
    s = _beam(tw.Scene.ballasted_track(18.0), "timoshenko")
    d = tw.default_settings(s)
    assert d["n_elements"] == 30 * 12
    base = _run_force(s, tw.kmh(200), d["n_elements"], d["dt"])
    fine = _run_force(s, tw.kmh(200), 30 * 32, d["dt"])
    assert np.max(np.abs(base - fine)) < 2e-3


@pytest.mark.parametrize("beam", ["euler", "timoshenko"])
def test_default_receptance_against_a_refined_mesh(beam):
    """receptance's default mesh (frequency_mesh at the highest frequency asked) puts the
    mid-span pinned-pinned peak of the ballasted track within 0.1 % of 64 elements per bay
    (the scene's own 4 per bay put it 1 % high with the Timoshenko rail); 0.05 Hz steps."""
    s = _beam(tw.Scene.ballasted_track(), beam)
    f_pp = D.pinned_pinned_frequency(s)
    f = np.arange(0.97 * f_pp, 1.03 * f_pp, 0.05)
    x = fr.receptance_points(s)["mid-span"]

    def peaks(**kw):
        m = np.abs(tw.receptance(s, x, f, **kw))
        i = np.flatnonzero((m[1:-1] > m[:-2]) & (m[1:-1] >= m[2:])) + 1
        return f[i[np.argmin(np.abs(f[i] - f_pp))]]

    default, fine = peaks(), peaks(n_elements=50 * 64)
    coarse = peaks(n_elements=s.rail.n_elements)
    err = abs(default / fine - 1.0)
    assert err < 1e-3
    if beam == "timoshenko":
        assert abs(coarse / fine - 1.0) > 5e-3  # what the scene's own mesh gave


def test_default_decay_rates_against_a_refined_mesh():
    """band_decay_rates' default mesh (frequency_mesh at 5.6 kHz, whole quarter bays; 8
    frequencies per band) on the 60 m ballasted track: every band within 1 % of twice the
    elements with the Euler-Bernoulli rail (measured 4e-4); with the Timoshenko rail within
    1 % except the 1 kHz band, whose
    0.26 dB/m (below the standard's 0.22 dB/m resolution of a 66-bay line, an upper bound
    only) converges as the pinned-pinned stop band does: 3 % there."""
    for beam, skip in (("euler", ()), ("timoshenko", (6,))):
        s = _beam(tw.Scene.ballasted_track(60.0), beam)
        n = D.frequency_mesh(s, float(fr.iso3095_band_edges()[-1]))
        a = fr.band_decay_rates(s)
        b = fr.band_decay_rates(s, n_elements=2 * n)
        keep = np.setdiff1d(np.arange(a.size), skip)
        assert np.max(np.abs(a[keep] / b[keep] - 1.0)) < 0.01, beam
        assert np.all(np.abs(a / b - 1.0) < 0.05)


@pytest.mark.parametrize("beam", ["euler", "timoshenko"])
def test_default_eigen_against_a_refined_mesh(beam):
    """eigen's default mesh (the run's) on a 6 m ballasted track, wheel at 3.3 m: the
    frequencies up to 1.05 x the pinned-pinned one (19 modes) within 0.1 % of four times the
    elements (measured 1e-5 and 8e-4); the Timoshenko rail on 8 per bay would miss by 0.2 %."""
    s = _beam(tw.Scene.ballasted_track(6.0), beam)
    e = tw.eigen(s, [3.3], n_modes=30)
    ref = tw.eigen(s, [3.3], n_modes=30, n_elements=4 * e.n_elements).frequencies[0]
    keep = ref <= 1.05 * D.pinned_pinned_frequency(s)
    assert keep.sum() >= 15
    assert np.max(np.abs(e.frequencies[0][keep] / ref[keep] - 1.0)) < 1e-3


def test_frequency_mesh_resolves_the_beams_own_wavelength():
    """The Timoshenko wavelength is shorter than the Euler-Bernoulli one at the same frequency
    and the Timoshenko element needs more per wavelength: at 5 kHz on the ballasted track
    (EB 0.64 m) the frequency mesh takes 4 x 3 per bay (0.05 m elements) and 4 x 10 with
    shear; quarter bays whole, at least the scene's own mesh."""
    s = tw.Scene.ballasted_track()
    for beam in ("euler", "timoshenko"):
        sb = _beam(s, beam)
        n = D.frequency_mesh(sb, 5000.0)
        per_bay = n // 50
        assert n % 50 == 0 and per_bay % 4 == 0 and n >= sb.rail.n_elements
        lam = D.bending_wavelength(sb, 5000.0)
        need = D.ELEMENTS_PER_WAVELENGTH[beam]
        assert sb.supports.spacing / per_bay <= lam / need
        assert sb.supports.spacing / (per_bay - 4) > lam / need
    assert D.bending_wavelength(_beam(s, "timoshenko"), 5000.0) < D.bending_wavelength(s, 5000.0)


# --------------------------------------------------------------------------------------------
# the stretch measured
def test_end_clearance_and_startup_length_of_the_ballasted_track():
    """end_clearance = ln(1000) / beta with beta from the supports' static stiffness per
    length (the pad and ballast in series); the default run starts in the middle of the first
    bay beyond it and ends in the last; the start-up length is one decay length v / (zeta w)
    of the wheel's bounce on the track, whose half-power band (57 Hz, zeta ~ 5 %) is read
    off the receptance: between 3 and 6 m at 300 km/h, proportional to the speed."""
    s = tw.Scene.ballasted_track()
    k_f = s.supports.static_stiffness * len(s.support_positions) / s.rail.length
    beta = (k_f / (4.0 * s.rail.bending_stiffness)) ** 0.25
    assert S.end_clearance(s) == pytest.approx(math.log(1e3) / beta, rel=1e-12)
    assert S.default_start(s) == pytest.approx(5.1) and S.default_end(s, 5.1) == pytest.approx(24.9)
    a, b = S.startup_length(s, tw.kmh(300)), S.startup_length(s, tw.kmh(150))
    assert 3.0 < a < 6.0 and a == pytest.approx(2.0 * b, rel=1e-12)
    short = tw.Scene.ballasted_track(2.4)  # a bare 30 m rail would sag metres: refused
    bare = dc.replace(short, supports=dc.replace(short.supports, positions=()))
    assert S.end_clearance(bare) == math.inf and S.clear_stretch(bare) is None


@pytest.mark.slow
def test_default_run_of_the_ballasted_track_measures_the_steady_dynamic_factor():
    """tw.analyse(tw.simulate(Scene.ballasted_track(), 300 km/h)) with every default: run from
    5.1 m, measured clear of the ends and the start-up transient; its dynamic factor within
    0.5 % of the steady one (the issue asks 2 %), the steady one from a 60 m rail measured over
    steady_state's steady part (1.0059); the whole run from the rail's first bay, as before,
    reported 1.32. analyse says what it measured (x_range)."""
    s = tw.Scene.ballasted_track()
    a = tw.analyse(tw.simulate(s, tw.kmh(300), progress=False))
    assert a.x_range[0] > 5.1 + 3.0 and a.x_range[1] == pytest.approx(24.9, abs=2e-3)
    long = tw.Scene.ballasted_track(60.0)
    r = tw.simulate(long, tw.kmh(300), x_start=5.1, x_end=54.9, progress=False)
    steady = tw.analyse(r, steady=True).dynamic_factor
    err = abs(a.dynamic_factor / steady - 1.0)
    assert err < 5e-3


def test_a_vehicle_wheel_is_measured_from_its_own_quasi_static_line():
    """Bogie on the ballasted track (full model and linear/hertz): each wheel's d starts at 0
    (the run starts from the vehicle's static state, which is the line's value there: 1e-12 m
    against a 14.8 um offset when the neighbour's deflection was counted as dynamic), and the
    line interpolated between the nodes any wheel crosses matches direct vehicle statics."""
    s = dc.replace(tw.Scene.ballasted_track(15.0), vehicle=tw.Vehicle.bogie())
    for fidelity in ("full", "linear/hertz"):
        r = tw.simulate(s, tw.kmh(200), x_start=5.1, duration=2e-3, fidelity=fidelity,
                        progress=False)
        for i in range(2):
            a = tw.analyse(r, wheel=i, measure="run")
            assert abs(a.dynamic[0]) < 1e-12
    a = tw.analyse(r, wheel=1, measure="run")
    from trackwheel.statics import vehicle_static

    x = float(r.x_wheel[-1, 0])
    from trackwheel.statics import linear_vehicle_line

    direct = linear_vehicle_line(s, [x], n_elements=r.settings.n_elements)[0, 1]
    assert a.y_qs[-1] == pytest.approx(direct, abs=1e-12)
    r = tw.simulate(s, tw.kmh(200), x_start=5.1, duration=2e-3, progress=False)
    a = tw.analyse(r, wheel=1, measure="run")
    st = vehicle_static(s, float(r.x_wheel[-1, 0]), n_elements=r.settings.n_elements)
    assert a.y_qs[-1] == pytest.approx(st.y_contact[1], abs=1e-12)


def test_analyse_measure_options():
    """measure='run' takes every sample, (x_from, x_to) those in the range; the paper's scene
    is measured whole by default; bad values are named."""
    r = tw.simulate(tw.Scene.kato2005(), tw.kmh(200), dt=1e-5, progress=False)
    whole = tw.analyse(r)
    assert whole.x_range == (r.x_wheel[0], r.x_wheel[-1])
    assert tw.analyse(r, measure="run").amplitude == whole.amplitude
    part = tw.analyse(r, measure=(1.0, 2.0))
    x = r.x_wheel
    inside = x[(x >= 1.0) & (x <= 2.0)]  # the samples the range selects, and only those
    assert part.x_range == (inside[0], inside[-1])
    assert part.x_range[0] - 1.0 < x[1] - x[0] and 2.0 - part.x_range[1] < x[1] - x[0]
    with pytest.raises(ValueError, match="measure"):
        tw.analyse(r, measure="all")
    with pytest.raises(ValueError, match="measure"):
        tw.analyse(r, measure=(2.0, 1.0))
    with pytest.raises(ValueError, match="measure"):
        tw.analyse(r, measure=(1.0, 2.0), t_from=0.01)


def test_cli_prints_the_range_run_and_measured(capsys):
    """trackwheel run prints the X range run and measured, for one wheel and per wheel of a
    vehicle (a short ballasted rail keeps it cheap: 12 m, stretch clear of the ends)."""
    args = ["run", "--track", "ballasted", "--length", "12", "--speed-kmh", "100",
            "--fidelity", "linear/hertz"]
    assert cli.main(args) == 0
    out = capsys.readouterr().out
    assert "run            : X = 5.1 -> 6.9 m" in out and "measured       : X = " in out
    assert cli.main([*args, "--vehicle", "quarter-car"]) == 0
    out = capsys.readouterr().out
    assert "run      : X = 5.1 -> 6.9 m" in out and "measured X = " in out


# --------------------------------------------------------------------------------------------
# steady state
def _fake_run(force, x, t, scene, speed):
    """A Result carrying the given contact force [N] at wheel positions x [m] and times t [s]
    (the other arrays from a short real run, resampled)."""
    base = tw.simulate(scene, speed, duration=1e-3, dt=1e-4, progress=False)
    arrays = {name: np.interp(t, base.t, getattr(base, name), period=base.t[-1] + 1e-4)
              for name in ("y_contact", "acc_contact")}
    return dc.replace(base, t=t, x_wheel=x, normal_force=force, **arrays,
                      settings=dc.replace(base.settings, speed=speed))


def test_steady_state_with_a_ripple_that_is_not_bay_periodic():
    """A synthetic contact force on the ballasted track at 200 km/h: a bay-periodic profile
    (harmonics 1-3 of f_s, 2 kN), a start-up transient at 57 Hz decaying at 19 1/s from 3 kN,
    and a ripple of 350 N near the pinned-pinned frequency whose phase jumps at every bay (as
    the shear rail's node-crossing ripple, 5e-3 of the load) plus sampling noise of 300 N above
    the highest frequency of interest. The steady state is found (the former criterion, every
    bay within 1e-3 of the last, could not be met with this ripple), its scatter is the
    ripple's, it starts where the transient has fallen below twice the scatter (within a
    bay), and its mean bay is the periodic profile within the ripple's average over the steady
    bays (< 3 scatter / sqrt(n_bays) of the load)."""
    s = tw.Scene.ballasted_track()
    v, d, P = tw.kmh(200), s.supports.spacing, s.static_load
    dt = 2e-5
    t = np.arange(0.0, 0.5, dt)
    x = 0.3 + v * t
    fs = v / d
    rng = np.random.default_rng(1)
    periodic = sum(a * np.cos(2 * np.pi * k * (x - 0.3) / d + p)
                   for k, a, p in ((1, 2000.0, 0.3), (2, 700.0, 1.0), (3, 200.0, 2.0)))
    transient = 3000.0 * np.exp(-19.0 * t) * np.sin(2 * np.pi * 57.0 * t)
    bay = np.floor((x - 0.3) / d).astype(int)
    phase = rng.uniform(0, 2 * np.pi, bay.max() + 1)[bay]
    ripple = 350.0 * np.sin(2 * np.pi * 9.3 * fs * t + phase)
    noise = 300.0 * np.sin(2 * np.pi * 2100.0 * t + rng.uniform(0, 2 * np.pi, t.size))
    force = P + periodic + transient + ripple + noise
    r = _fake_run(force, x, t, s, v)
    st = steady_state(r)
    assert 2e-3 < st.scatter < 2e-2 and st.f_cut == D.highest_frequency(s)
    # where the transient's envelope falls below twice the scatter
    t_expect = math.log(3000.0 / (2.0 * st.scatter * P)) / 19.0
    assert abs(st.t_from - t_expect) < 2.0 * d / v
    truth = P + np.interp(np.mod(np.arange(128) / 128 * d + st.x_from - 0.3, d),
                          np.mod(x[:2000] - 0.3, d)[np.argsort(np.mod(x[:2000] - 0.3, d))],
                          (periodic[:2000])[np.argsort(np.mod(x[:2000] - 0.3, d))])
    assert np.max(np.abs(st.bay_profile - truth)) < 3.0 * st.scatter * P / math.sqrt(st.n_bays)
    # the same without the ripple: the tolerance 1e-3 of the load decides, as before
    clean = steady_state(_fake_run(P + periodic + transient, x, t, s, v))
    assert clean.scatter < 1e-4
    t_clean = math.log(3000.0 / (1e-3 * P)) / 19.0
    assert abs(clean.t_from - t_clean) < 2.0 * d / v


@pytest.mark.slow
def test_steady_state_of_a_real_run_on_the_shear_rail():
    """Timoshenko rail on the ballasted track, 8 elements per bay, 200 km/h, 30 m: the steady
    state is found and the mean contact force over it is the static load (the wheel's mean
    acceleration is zero) within the run's scatter."""
    s = _beam(tw.Scene.ballasted_track(), "timoshenko")
    r = tw.simulate(s, tw.kmh(200), n_elements=400, progress=False)
    st = steady_state(r)
    assert st.n_bays >= 3
    assert abs(st.mean / s.static_load - 1.0) < max(1e-3, st.scatter)


# --------------------------------------------------------------------------------------------
# receptance at many points, the shear modulus
def test_receptance_at_many_points_in_one_call():
    """Shapes by the table of the docstring; every entry equals the one-point call; the matrix
    between points is symmetric (reciprocity: Z is symmetric); the one-point call keeps its
    shape."""
    s = tw.Scene.kato2005()
    f = [0.0, 300.0, 1200.0]
    xe, xr = [1.1, 2.25, 3.0], [0.7, 2.25]
    kw = dict(n_elements=80)
    full = tw.receptance(s, xe, f, xr, **kw)
    assert full.shape == (3, 2, 3)
    assert tw.receptance(s, 2.25, f, **kw).shape == (3,)
    assert tw.receptance(s, 2.25, f, xr, **kw).shape == (3, 2)
    assert tw.receptance(s, xe, f, 0.7, **kw).shape == (3, 3)
    point = tw.receptance(s, xe, f, **kw)
    assert point.shape == (3, 3)
    for j, x in enumerate(xe):
        np.testing.assert_array_equal(point[:, j], tw.receptance(s, x, f, **kw))
        np.testing.assert_array_equal(full[:, :, j], tw.receptance(s, x, f, xr, **kw))
    sq = tw.receptance(s, xe, f, xe, **kw)
    np.testing.assert_allclose(sq, np.transpose(sq, (0, 2, 1)), rtol=1e-9, atol=0)


def test_shear_modulus_given_is_independent_of_nu():
    """Rail(shear_modulus=G): the Timoshenko rail takes G whatever nu (nu then enters only the
    Hertz constant); given as the isotropic E / (2 (1 + nu)) it is the default rail exactly,
    and a softer G lowers the pinned-pinned peak of the receptance to the closed form's."""
    r = tw.Rail(beam="timoshenko")
    assert r.shear_modulus is None
    same = dc.replace(r, shear_modulus=r.youngs_modulus / 2.6)
    assert same.shear_stiffness == r.shear_stiffness
    other_nu = dc.replace(same, poisson_ratio=0.25)
    assert other_nu.shear_stiffness == r.shear_stiffness
    assert dc.replace(r, poisson_ratio=0.25).shear_stiffness != r.shear_stiffness
    with pytest.raises(ValueError, match="Rail.shear_modulus"):
        tw.Rail(shear_modulus=-1.0)
    s = tw.Scene.kato2005()
    s = dc.replace(s, rail=dc.replace(s.rail, length=30.0, n_elements=600, beam="timoshenko",
                                      shear_modulus=s.rail.youngs_modulus / 4.0),
                   supports=dc.replace(s.supports, damping=2e3), rail_gravity=False)
    f_t = D.pinned_pinned_frequencies(s)[1]
    soft = D.pinned_pinned_frequencies(dc.replace(s, rail=dc.replace(s.rail, shear_modulus=None)))[1]
    assert f_t < soft
    f = np.arange(0.95 * f_t, 1.05 * f_t, 0.5)
    peak = f[np.argmax(np.abs(tw.receptance(s, 15.25, f)))]
    assert peak == pytest.approx(f_t, rel=0.01)
