"""Analysis of a run: spectra, main frequency, the quasi-static line and the dynamic part
(issue 5 part 1, docs: Model § Outputs). Each test asserts a fact with a justified tolerance."""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest
import trackwheel as tw


def tone(n, dt, freq, amp=1.0, phase=0.0):
    t = np.arange(n) * dt
    return amp * np.sin(2.0 * math.pi * freq * t + phase)


# --------------------------------------------------------------------------------------------
# spectra of synthetic signals
def test_main_frequency_of_pure_tones_within_a_thousandth_of_a_bin():
    """Pure tones at random frequencies (5 bins above 0 Hz to 5 bins below Nyquist), phases and
    record lengths: the parabolic-on-log-magnitude estimate with Hann window and 8x zero padding
    is within 2e-3 of the resolution 1/(N dt). Without interpolation the padded grid alone
    would allow 1/16 bin; the measured worst case over 6000 tones is 7.7e-4 bins (the leakage of
    the negative-frequency image through the Hann side lobes), so 2e-3 leaves a margin of 2.6."""
    rng = np.random.default_rng(1)
    worst = 0.0
    for _ in range(200):
        n = int(rng.integers(300, 4000))
        dt = float(rng.uniform(1e-6, 1e-3))
        res = 1.0 / (n * dt)
        f0 = float(rng.uniform(5 * res, 0.5 / dt - 5 * res))
        x = tone(n, dt, f0, amp=float(rng.uniform(1e-9, 1.0)), phase=float(rng.uniform(0, 7)))
        worst = max(worst, abs(tw.main_frequency(x, dt) - f0) / res)
    assert worst < 2e-3


def test_main_frequency_picks_the_stronger_of_two_tones():
    """Two tones 6 bins apart, amplitude ratio 2, either order: the stronger one is found and
    the weaker one's leakage (Hann side lobes fall as k^-3) shifts it by < 5e-3 bins
    (measured worst 1.9e-3 over a grid of frequencies and phases)."""
    n, dt = 1000, 1e-4
    res = 1.0 / (n * dt)
    for f_strong, f_weak in [(1234.5, 1234.5 + 6 * res), (2345.6, 2345.6 - 6 * res)]:
        for phase in (0.0, 0.7, 2.1):
            x = tone(n, dt, f_strong, 1.0, phase) + tone(n, dt, f_weak, 0.5, 2 * phase + 0.3)
            assert abs(tw.main_frequency(x, dt) - f_strong) < 5e-3 * res


def test_main_frequency_offset_and_search_band():
    """A constant offset 1e6 times the tone is removed with the mean (it would otherwise leak
    through the window's 0 Hz lobe, but f_min = 1/(N dt) skips that lobe anyway); f_min/f_max
    restrict the search: below a strong 2 kHz tone, the weaker 700 Hz one is found. Same
    2e-3-bin tolerance as a pure tone (the 2 kHz tone is 260 bins away: leakage < 1e-7)."""
    n, dt = 2000, 1e-4
    res = 1.0 / (n * dt)
    x = 3.0 + tone(n, dt, 700.0, 3e-6, 0.2)
    assert abs(tw.main_frequency(x, dt) - 700.0) < 2e-3 * res
    y = tone(n, dt, 700.0, 0.1, 0.2) + tone(n, dt, 2000.0, 1.0)
    assert abs(tw.main_frequency(y, dt) - 2000.0) < 2e-3 * res
    assert abs(tw.main_frequency(y, dt, f_max=1500.0) - 700.0) < 2e-3 * res
    assert abs(tw.main_frequency(y, dt, f_min=500.0, f_max=1000.0) - 700.0) < 2e-3 * res


def test_spectrum_amplitude_of_a_tone():
    """The amplitude spectrum is scaled by the window's coherent gain: a tone of amplitude A
    peaks at A within the Hann scalloping loss for the worst offset from the padded grid
    (1/16 bin with 8x padding: 1 - sinc(1/16)/(1 - 1/16^2) = 0.25 %), plus image leakage
    (< 1e-4 at 50 bins). Frequencies are rfft bins of n_fft = 2^k >= 8 N."""
    n, dt, amp = 1500, 2e-5, 3e-6
    for f0 in (1000.0, 1001.3, 1003.7):
        freqs, spec = tw.amplitude_spectrum(tone(n, dt, f0, amp, 0.4), dt)
        assert freqs.size == 16384 // 2 + 1 and freqs[1] == pytest.approx(1 / (16384 * dt))
        assert amp * (1 - 0.0026) < spec.max() < amp * (1 + 1e-4)


@pytest.mark.parametrize("call,match", [
    (lambda: tw.main_frequency([1.0, 2.0, 3.0], 1e-3), "at least 4"),
    (lambda: tw.main_frequency([1.0, 2.0, np.nan, 4.0, 5.0], 1e-3), "NaN"),
    (lambda: tw.main_frequency(np.ones((4, 4)), 1e-3), "1-d"),
    (lambda: tw.main_frequency(np.ones(10), 0.0), "dt"),
    (lambda: tw.main_frequency(np.ones(10), -1e-3), "dt"),
    (lambda: tw.amplitude_spectrum(np.ones(10), 1e-3, n_fft=8), "n_fft"),
    (lambda: tw.main_frequency(np.ones(10), 1e-3, f_min=-1.0), "f_min"),
])
def test_spectrum_arguments_rejected(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_analyse_needs_a_result():
    with pytest.raises(TypeError, match="result"):
        tw.analyse(np.zeros(10))


# --------------------------------------------------------------------------------------------
# analyse on real runs
@pytest.fixture(scope="module")
def run300():
    """The paper's scene at 300 km/h over the first support (0.25 -> 0.75 m), dt 1e-5 s,
    20 elements (the numbers quoted below are for this mesh)."""
    return tw.simulate(tw.Scene.kato2005(), tw.kmh(300), x_start=0.25, x_end=0.75, dt=1e-5,
                       n_elements=20)


def test_quasi_static_line_matches_direct_static_solves(run300):
    """d(t) = y_B - y_qs(X_A): y_qs from each element's degree-8 Chebyshev series (8 static
    solves per element, cached) equals direct static solves at 12 sample positions within the
    interpolation error. Within an element y_qs is a degree-6 polynomial up to the geometric
    nonlinearity, so the series is nearly exact: measured 1.7e-13 m here, estimated by the
    analysis (y_qs_error = |c_7| + |c_8|) at 5e-13 m; the static solver's own tolerance is
    ~1e-13 m. Both are < 1e-7 of the dynamic amplitude (~5e-6 m)."""
    a = tw.analyse(run300)
    assert a.y_qs_error < 1e-11
    idx = np.random.default_rng(3).choice(run300.t.size, 12, replace=False)
    ref = tw.quasi_static(run300.scene, run300.x_wheel[idx],
                          n_elements=run300.settings["n_elements"]).y_contact
    d_ref = run300.y_contact[idx] - ref
    assert np.max(np.abs(a.dynamic[idx] - d_ref)) <= 1.5 * a.y_qs_error + 1e-13
    assert np.max(np.abs(a.y_qs[idx] - ref)) <= 1.5 * a.y_qs_error + 1e-13
    # the run starts from static equilibrium at X_0 = 0.25 m, an element end where the series
    # interpolates a static solve: d(0) = 0 to the static solver's tolerance
    assert abs(a.dynamic[0]) < 1e-12
    assert a.amplitude > 1e6 * a.y_qs_error


def test_analysis_outputs_are_consistent(run300):
    """Amplitude = max |d| at its time; frequency resolution = 1/(N dt); contact force extremes
    and the acceleration terms are the run's own (docs: Model § Outputs)."""
    a = tw.analyse(run300)
    n = run300.t.size
    assert a.amplitude == np.max(np.abs(a.dynamic))
    assert a.dynamic[np.searchsorted(a.t, a.amplitude_time)] in (a.amplitude, -a.amplitude)
    assert a.frequency_resolution == pytest.approx(1.0 / (n * 1e-5), rel=1e-12)
    assert a.sample_spacing == pytest.approx(1e-5, rel=1e-9)
    assert a.min_contact_force == run300.normal_force.min()
    assert a.max_contact_force == run300.normal_force.max()
    assert a.lost_contact is run300.lost_contact
    for term in "ABCDE":
        assert getattr(a, f"acc_{term}") is getattr(run300, f"acc_{term}")
    assert a.main_frequency == tw.main_frequency(a.dynamic, 1e-5)
    assert a.n_fft >= 8 * n and a.n_fft & (a.n_fft - 1) == 0


def test_amplitude_and_frequency_of_a_known_dynamic_part(run300):
    """Replace the run's contact displacement by y_qs + d_known with d_known a 400 Hz tone of
    2e-6 m plus a 900 Hz tone of 5e-7 m: analyse returns max |d_known| to rounding (a few ulps
    of y_qs ~ 1e-4 m, i.e. 1e-19 m) and the 400 Hz tone within 0.03 of the resolution. The
    record is short (6 ms, resolution 166 Hz): 400 Hz is only 2.4 bins above 0 Hz, where the
    negative-frequency image biases the estimate by up to 0.013 bins (pure tones 2-5 bins up,
    measured), and the 900 Hz tone 3 bins away adds its own leakage (measured total 0.012)."""
    a = tw.analyse(run300)
    t = run300.t
    d_known = 2e-6 * np.sin(2 * math.pi * 400.0 * t + 0.3) + 5e-7 * np.sin(2 * math.pi * 900 * t)
    fake = dc.replace(run300, y_contact=a.y_qs + d_known)
    b = tw.analyse(fake)
    assert abs(b.amplitude - np.max(np.abs(d_known))) < 1e-18
    assert np.max(np.abs(b.dynamic - d_known)) < 1e-18
    assert abs(b.main_frequency - 400.0) < 0.03 * b.frequency_resolution


def test_slow_passage_dynamic_part_is_small_and_linear_in_speed():
    """Quasi-static passage. Starting from static equilibrium with the rail at rest, the wheel
    at speed v meets a rail whose quasi-static state moves at v dy_qs/dX: the mismatch excites
    free vibration of amplitude ~ v |dy_qs/dX| / omega, linear in v; inertia corrections are
    O(v dy''/(omega dy')) ~ 4e-4 relative at 2 km/h. So over the same 0.1 s
    at 1 and 2 km/h the amplitude doubles to 2e-3 (measured 2.0002), and at 1 km/h it is below
    1e-3 of the static deflection (measured 2e-4: 1.75e-8 m vs 8.6e-5 m). dt = 1e-4 s: the
    response is in the lowest coupled modes (~400 Hz, 25 steps per period)."""
    scene = tw.Scene.kato2005()
    amps = []
    for kmh in (1.0, 2.0):
        r = tw.simulate(scene, tw.kmh(kmh), x_start=0.25, duration=0.1, dt=1e-4)
        a = tw.analyse(r)
        amps.append(a.amplitude)
    assert amps[0] < 1e-3 * np.max(np.abs(a.y_qs))
    assert amps[1] / amps[0] == pytest.approx(2.0, abs=2e-3)


def test_decimated_output_uses_the_sample_spacing():
    """With output_every = 4 the record's spacing is 4 dt: the resolution is 1/(N 4 dt), the
    quasi-static line is evaluated at the kept positions, and the amplitude (a max over a subset
    of samples) is at most the full record's."""
    scene = tw.Scene.kato2005()
    kw = {"x_start": 0.25, "x_end": 0.75, "dt": 1e-5, "n_elements": 20}
    full = tw.analyse(tw.simulate(scene, tw.kmh(300), **kw))
    dec = tw.analyse(tw.simulate(scene, tw.kmh(300), output_every=4, **kw))
    assert dec.sample_spacing == pytest.approx(4e-5, rel=1e-9)
    assert dec.frequency_resolution == pytest.approx(1.0 / (dec.t.size * 4e-5), rel=1e-12)
    np.testing.assert_array_equal(dec.dynamic, full.dynamic[::4])
    assert dec.amplitude <= full.amplitude


# --------------------------------------------------------------------------------------------
# contact-force statistics in analyse (issue 13)
def test_force_statistics_of_a_known_force(run300):
    """analyse(run) on a run whose contact force is replaced by a known one: P0 = F + M g =
    47138 N plus a 0.3 P0 sine on a bin of the record (f = 20 / duration, a whole number of
    periods, so Parseval puts exactly its mean square A^2/2 in its one-third-octave band:
    RMS A/sqrt(2) to rounding, < 1e-9 relative), and N = 0 on 25 samples (a contact loss of
    25 dt, exact with the midpoint rule). The dynamic factor is max N / P0 exactly, and the
    vibration outputs of analyse do not depend on N (bit-identical to the plain analysis)."""
    t = run300.t
    dt = 1e-5
    p0 = run300.scene.static_load
    assert p0 == pytest.approx(47040.0 + 98.0, rel=1e-15)
    f0 = 20.0 / (t.size * dt)
    amp = 0.3 * p0
    n = p0 + amp * np.sin(2.0 * math.pi * f0 * t)
    a = tw.analyse(dc.replace(run300, normal_force=n))
    k = int(np.argmin(np.abs(a.forces.band_centres - f0)))
    assert a.forces.band_rms[k] == pytest.approx(amp / math.sqrt(2.0), rel=1e-9)
    assert a.dynamic_factor == n.max() / p0 and a.loss_duration == 0.0
    assert a.forces.max_force == n.max() and a.forces.min_force == n.min()
    plain = tw.analyse(run300)
    for name in ("amplitude", "amplitude_time", "main_frequency", "frequency_resolution",
                 "y_qs_error"):
        assert getattr(a, name) == getattr(plain, name), name
    n_loss = n.copy()
    n_loss[300:325] = 0.0
    b = tw.analyse(dc.replace(run300, normal_force=n_loss))
    assert b.loss_duration == pytest.approx(25 * dt, rel=1e-9)
    np.testing.assert_allclose(b.forces.loss_intervals, [[t[300] - dt / 2, t[324] + dt / 2]],
                               rtol=0, atol=1e-15)


def test_p1_p2_after_a_defect(run300):
    """With defect_at X_d the P1/P2 peaks are the maxima of N in the windows after t_d (the time
    X_A(t) reaches X_d): two spikes placed 0.3 ms (P1 window, T_1/2 = 0.5 ms) and 4 ms (P2
    window, up to (T_1 + T_2)/2 = 10.5 ms) after t_d are found with their values and times.
    Without defect_at there are no peaks (NaN) and the repr says nothing of them."""
    t, x = run300.t, run300.x_wheel
    p0 = run300.scene.static_load
    x_d = 0.3
    t_d = float(np.interp(x_d, x, t))
    n = np.full(t.size, p0)
    i1 = int(np.searchsorted(t, t_d + 3e-4))
    i2 = int(np.searchsorted(t, t_d + 4e-3))
    n[i1], n[i2] = 1.8 * p0, 1.3 * p0
    fake = dc.replace(run300, normal_force=n)
    a = tw.analyse(fake, defect_at=x_d)
    f = a.forces
    assert f.defect_time == pytest.approx(t_d, rel=1e-12)
    assert (f.p1, f.p1_time, f.p2, f.p2_time) == (1.8 * p0, t[i1], 1.3 * p0, t[i2])
    assert "P1" in repr(a) and f"{f.p1:.5g}" in repr(a)
    plain = tw.analyse(fake)
    assert math.isnan(plain.forces.p1) and "P1" not in repr(plain)
    with pytest.raises(ValueError, match="defect_at"):
        tw.analyse(fake, defect_at=2.0)  # the run ends at X = 0.75 m


def test_defect_position_is_the_joint_middle():
    """The P1/P2 reference of a scene is the cusp of its first dipped joint, X_j + l/2 (where
    the slope of the Kabo dip jumps); no joint, no position."""
    from trackwheel.force_statistics import defect_position

    irr = tw.Irregularity.sine(0.5, 1e-5) + tw.Irregularity.dipped_joint(2e-3, 0.6, at=2.0)
    scene = dc.replace(tw.Scene.kato2005(), irregularity=irr)
    assert defect_position(scene) == pytest.approx(2.3, rel=1e-15)
    assert defect_position(tw.Scene.kato2005()) is None
    joint = irr.parts[1]
    x = np.array([2.3 - 1e-7, 2.3 + 1e-7])
    assert np.all(np.abs(joint.slope(x)) == pytest.approx(math.pi * 2e-3 / 0.6, rel=1e-6))
