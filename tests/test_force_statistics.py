"""Contact-force statistics on synthetic signals whose answers are known."""

import math

import numpy as np
import pytest

from trackwheel.force_statistics import (
    band_rms,
    contact_loss,
    force_spectrum,
    force_statistics,
    peak_forces,
    third_octave_bands,
)

P0 = 47138.0  # [N]


def test_band_centres_are_iec_base10():
    centres, edges = third_octave_bands(20.0, 20_000.0)
    # 1 kHz is a centre, neighbours 10^(1/10) apart, edges 10^(+-1/20) around
    assert np.any(np.isclose(centres, 1000.0, rtol=1e-14))
    assert np.allclose(centres[1:] / centres[:-1], 10**0.1, rtol=1e-13)
    assert np.allclose(edges[:, 1] / edges[:, 0], 10**0.1, rtol=1e-13)
    assert edges[0, 0] >= 20.0 and edges[-1, 1] <= 20_000.0
    # the 19.95 Hz band starts at 17.8 Hz, below 20: the first band wholly inside is 25.1 Hz
    assert centres[0] == pytest.approx(10**1.4, rel=1e-13)


@pytest.mark.parametrize("f0, amp", [(100.0, 500.0), (1000.0 * 10**0.3, 2000.0), (63.0, 10.0)])
def test_sine_lands_in_its_band_with_its_rms(f0, amp, validation):
    # a sine of amplitude A has RMS A / sqrt 2; with 0.37 s of record (not a whole number of
    # periods) the rectangular-window leakage outside a band of width 0.23 f0 >= 14 Hz
    # (>= 5 bins) is below a few percent of the power: within 0.5 dB
    dt = 1e-4
    t = np.arange(0.0, 0.37, dt)
    n = P0 + amp * np.sin(2 * math.pi * f0 * t + 0.3)
    centres, rms = band_rms(t, n)
    i = int(np.argmax(rms))
    lo, hi = centres[i] / 10**0.05, centres[i] * 10**0.05
    assert lo <= f0 < hi
    assert abs(20 * math.log10(rms[i] / (amp / math.sqrt(2)))) < 0.5
    if f0 == 100.0:
        validation.record(
            "excitation.band_rms_of_a_sine", level="excitation", kind="closed form",
            quantity="one-third-octave band RMS of a 100 Hz sine in the contact force",
            reference="A/√2 in the band holding 100 Hz (IEC 61260-1 base-10 bands)",
            measured=abs(20 * math.log10(rms[i] / (amp / math.sqrt(2)))), tolerance=0.5,
            metric="dB")


def test_amplitude_spectrum_of_an_on_bin_sine():
    dt, m = 1e-4, 4000
    t = dt * np.arange(m)
    f0 = 250.0  # 100 periods in the record: exactly on a bin
    f, a = force_spectrum(t, P0 + 300.0 * np.cos(2 * math.pi * f0 * t))
    k = int(np.argmax(a))
    assert f[k] == pytest.approx(f0, rel=1e-12)
    assert a[k] == pytest.approx(300.0, rel=1e-10)
    assert a[0] == 0.0  # the static load is not a vibration


def test_two_peak_signal_gives_p1_p2_exactly():
    dt = 1e-5
    t = np.arange(0.0, 0.05, dt)
    v = 50.0
    x = 1.0 + v * t
    x_d = 1.5  # reached at t_d = 10 ms
    td = (x_d - 1.0) / v
    n = np.full(t.size, P0)
    i1 = round((td + 0.3e-3) / dt)  # 0.3 ms after: inside the P1 window (0.5 ms)
    i2 = round((td + 6e-3) / dt)  # 6 ms after: inside the P2 window (0.5..10.5 ms)
    n[i1], n[i2] = 2.5 * P0, 1.8 * P0
    n[round((td + 15e-3) / dt)] = 3.0 * P0  # later than both windows: ignored
    got_td, p1, t1, p2, t2 = peak_forces(t, x, n, x_d)
    assert got_td == pytest.approx(td, abs=1e-12)
    assert (p1, t1, p2, t2) == (2.5 * P0, t[i1], 1.8 * P0, t[i2])
    st = force_statistics(t, x, n, P0, defect_at=x_d)
    assert st.p1 == 2.5 * P0 and st.p2 == 1.8 * P0
    assert st.max_force == 3.0 * P0 and st.dynamic_factor == pytest.approx(3.0, rel=1e-15)


def test_loss_duration_of_a_clipped_sine():
    # N = max(0, P0 + 2 P0 sin(w t)) is zero where sin < -1/2: per period a fraction 1/3
    # (7 pi/6 .. 11 pi/6); sampled loss is right to one step at each end
    dt = 1e-5
    f0 = 50.0
    t = np.arange(0.0, 0.1, dt)  # five periods
    n = np.maximum(0.0, P0 + 2 * P0 * np.sin(2 * math.pi * f0 * t))
    total, intervals = contact_loss(t, n)
    assert intervals.shape == (5, 2)
    assert total == pytest.approx(5 * (1 / 3) / f0, abs=5 * dt)
    first = (7 / 12) / f0, (11 / 12) / f0
    assert intervals[0] == pytest.approx(first, abs=dt)
    st = force_statistics(t, 1.0 + 10.0 * t, n, P0)
    assert st.loss_duration == total and st.min_force == 0.0


def test_no_loss_and_loss_at_the_record_end():
    t = np.linspace(0.0, 1.0, 11)
    assert contact_loss(t, np.full(11, P0)) == (0.0, pytest.approx(np.empty((0, 2))))
    n = np.full(11, P0)
    n[-3:] = 0.0  # lost from t = 0.8 to the end: counted from 0.75 to 1.0
    total, iv = contact_loss(t, n)
    assert total == pytest.approx(0.25, rel=1e-12) and iv[0, 1] == 1.0


@pytest.mark.parametrize("call, name", [
    (lambda t: force_statistics(t, t, np.ones(t.size), -1.0), "static_load"),
    (lambda t: peak_forces(t, t, np.ones(t.size), 5.0), "defect_at"),
    (lambda t: peak_forces(t, t, np.ones(t.size), 0.5, p1_period=0.0), "p1_period"),
    (lambda t: band_rms(t[::-1], np.ones(t.size)), "uniformly"),
    (lambda t: contact_loss(t, np.ones(t.size - 1)), "same length"),
])
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call(np.linspace(0.0, 1.0, 101))


def test_force_figures_carry_units_and_data():
    from matplotlib.figure import Figure

    from trackwheel import plots

    dt = 1e-4
    t = np.arange(0.0, 0.2, dt)
    x = 2.0 + 80.0 * t
    n = P0 + 5e3 * np.sin(2 * math.pi * 120.0 * t)
    fig = plots.contact_force(x, n, defect_at=5.0, static_load=P0)
    assert isinstance(fig, Figure)
    (ax,) = fig.axes
    assert "[m]" in ax.get_xlabel() and "[kN]" in ax.get_ylabel()
    gids = {ln.get_gid(): ln for ln in ax.get_lines()}
    assert np.array_equal(gids["force"].get_ydata(), n / 1e3)
    assert list(gids["defect"].get_xdata()) == [5.0, 5.0]
    st = force_statistics(t, x, n, P0)
    fig = plots.force_bands(st)
    (ax,) = fig.axes
    assert "[Hz]" in ax.get_xlabel() and "[N]" in ax.get_ylabel()
    (bands,) = ax.get_lines()
    # the 120 Hz sine is in the 125 Hz band (112-141 Hz): its marker is the highest
    assert bands.get_xdata()[np.argmax(bands.get_ydata())] == pytest.approx(10**2.1, rel=1e-12)


def test_statistics_of_a_simulated_run():
    # the paper's smooth track: the statistics read the run's own arrays, against its P0
    import trackwheel as tw
    from trackwheel.force_statistics import result_statistics

    scene = tw.Scene.kato2005()
    r = tw.simulate(scene, tw.kmh(200), x_start=1.5, x_end=2.6, progress=False)
    st = result_statistics(r, defect_at=2.0)
    assert st.max_force == r.normal_force.max() and st.min_force == r.normal_force.min()
    assert st.dynamic_factor == pytest.approx(r.normal_force.max() / (47040 + 10 * 9.8),
                                              rel=1e-15)
    td = float(np.interp(2.0, r.x_wheel, r.t))
    assert st.defect_time == pytest.approx(td, rel=1e-12)
    assert st.p1_time >= td and st.p2_time > st.p1_time
    # as many loss intervals as the Result's own contact-free intervals
    assert len(st.loss_intervals) == len(r.contact_free_intervals())
    with pytest.raises(TypeError, match="Result"):
        result_statistics(object())


def test_jenkins_p2_by_hand(validation):
    # illustrative values of the right order for a wheelset on ballasted track: P0 = 112.5 kN,
    # 2 alpha = 0.02 rad, v = 44.7 m/s, M_u = 1275 kg, M_t = 245 kg, K_t = 1.5e8 N/m,
    # C_t = 0.76e5 N s/m
    from trackwheel.force_statistics import jenkins_p2

    root = math.sqrt(1275 / 1520)
    damp = 1 - 0.76e5 * math.pi / (4 * math.sqrt(1.5e8 * 1520))
    expected = 112.5e3 + 0.02 * 44.7 * root * damp * math.sqrt(1.5e8 * 1275)
    got = jenkins_p2(112.5e3, 0.02, 44.7, 1275, 245, 1.5e8, 0.76e5)
    assert got == pytest.approx(expected, rel=1e-14)
    validation.record(
        "excitation.jenkins_p2", level="excitation", kind="published",
        quantity="P2 force of a dipped joint (trackwheel.force_statistics.jenkins_p2)",
        reference="Jenkins et al. (1974): P0 + 2α v √(M_u/(M_u + M_t)) (1 - C_t π/(4 √(K_t "
                  "(M_u + M_t)))) √(K_t M_u), evaluated by hand",
        measured=abs(got / expected - 1.0), tolerance=1e-14)
    assert jenkins_p2(1e5, 0.02, 0.0, 1275, 245, 1.5e8, 0.76e5) == 1e5  # at rest: P0
    with pytest.raises(ValueError, match="dip_angle"):
        jenkins_p2(1e5, -0.01, 10.0, 1275, 245, 1.5e8, 0.0)


def test_seed_percentiles():
    import pandas as pd

    from trackwheel.force_statistics import seed_percentiles

    # 101 seeds whose value is 0..100 at one speed, 100..200 at the other: the q-th
    # percentile of 0..100 is q exactly
    vals = np.arange(101.0)
    df = pd.DataFrame({"speed": np.repeat([50.0, 80.0], 101),
                       "max_force": np.concatenate((vals, vals + 100.0)),
                       "seed": np.tile(np.arange(101), 2)})
    df.loc[3, "max_force"] = np.nan  # a failed case is skipped, not propagated
    p = seed_percentiles(df, "max_force", q=(5, 50, 95))
    assert list(p.index) == [50.0, 80.0]
    assert p.loc[80.0, ("max_force", "p5")] == 105.0
    assert p.loc[80.0, ("max_force", "p95")] == 195.0
    assert p.loc[80.0, ("max_force", "p50")] == 150.0
    assert 50.0 < p.loc[50.0, ("max_force", "p50")] < 51.0  # one value (3) removed
    with pytest.raises(ValueError, match="dynamic_factor"):
        seed_percentiles(df, ["dynamic_factor"])


def test_repr_is_compact_and_carries_the_key_numbers():
    t = np.arange(0.0, 0.2, 1e-4)
    n = 50e3 + 5e3 * np.sin(2 * np.pi * 100.0 * t)
    st = force_statistics(t, 30.0 * t, n, 50e3)
    text = repr(st)
    assert len(text.splitlines()) <= 5 and len(text) < 400
    assert "dynamic factor 1.1" in text and "[45, 55] kN" in text
