"""The periodic level as a fidelity level: "periodic/linear" in FIDELITY_LEVELS, refused by
simulate, run by adequacy, sweep and the ``trackwheel periodic`` command.

Docs: Model § The periodic level.

The physics checks: the outputs a sweep tabulates (max |d|, the main frequency, the force's
extremes and RMS) against the time domain's steady part on a long rail, and against the steady
signal itself sampled over many bays; the quasi-static line against the linear track's statics.
The rest checks the plumbing: a sweep's row is the periodic response's outputs, NaN where the
level has no counterpart, refused cases are error rows, the command's output and errors.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel.cli.main import main
from trackwheel.study.columns import OUTPUTS, PERIODIC_OUTPUTS

V = 300 / 3.6  # [m/s]


def ballasted(**kw) -> tw.Scene:
    return dc.replace(tw.Scene.ballasted_track(), **kw)


def long_rail(scene: tw.Scene, length: float = 60.0, per_bay: int = 8) -> tw.Scene:
    n_el = round(length / scene.supports.spacing) * per_bay
    return dc.replace(scene, rail=dc.replace(scene.rail, length=length, n_elements=n_el,
                                             absorbing_ends=tw.AbsorbingEnds(6.0)))


# --------------------------------------------------------------------------------------------
# the outputs of the steady state
def test_steady_outputs_against_the_time_domain_steady_part(validation):
    """The ballasted preset at 300 km/h over a 0.37 m sine (10 um; incommensurate with the
    0.6 m bay) on a 60 m rail with absorbing ends (the linear/sprung level, 8 elements per bay,
    its default step): max |d|, the main frequency, the largest and least contact force and
    the RMS of N - P over the run's last 12 m (the start-up decayed: it moves max |d| by 1e-3
    from 33 m on) against the periodic level's steady outputs, within 1 % (the main frequency
    within the record's resolution 1/T)."""
    scene = ballasted(irregularity=tw.Irregularity.sine(0.37, 1e-5))
    r = tw.periodic_response(scene, V, fidelity="linear/sprung")
    run = tw.simulate(long_rail(scene), V, fidelity="linear/sprung", x_start=12.3, x_end=45.0,
                      progress=False)
    a = tw.analyse(run, t_from=(33.0 - 12.3) / V)
    pairs = {"amplitude": (a.amplitude, r.amplitude),
             "max force": (a.max_contact_force, r.max_force),
             "min force": (a.min_contact_force, r.min_force),
             "force rms": (a.force_rms, r.force_rms)}
    err = {k: abs(p / t - 1.0) for k, (t, p) in pairs.items()}
    assert max(err.values()) < 0.01, err
    assert abs(a.main_frequency - r.main_frequency) < a.frequency_resolution
    validation.record(
        "periodic.steady_outputs_vs_time_domain", level="periodic level", kind="path agreement",
        quantity="ballasted preset, 300 km/h, 0.37 m sine: max |d|, max and min N, RMS of N - P "
                 "of the steady state",
        reference="the time domain's linear/sprung level on a 60 m rail, its last 12 m",
        measured=max(err.values()), tolerance=0.01)


def test_outputs_are_those_of_the_sampled_steady_signal():
    """The outputs from the lines against the signals sampled over 3000 bays: for a sine
    incommensurate with the bay (0.37 m) the sampled max |d| and force extremes approach the
    envelope bounds from below (within 2e-3: the phases the samples visit), the RMS of N - P
    and the main frequency (the largest line of the sampled d's Fourier transform) agree; for
    a sine commensurate with it (0.3 m: lines at the sleeper-passing frequencies) the RMS of
    the merged lines is the sampled one and the extremes remain bounds."""
    for lam, exact in ((0.37, True), (0.3, False)):
        r = tw.periodic_response(ballasted(irregularity=tw.Irregularity.sine(lam, 1e-5)), V,
                                 fidelity="linear/sprung")
        t = np.arange(3_000 * 64) * (0.6 / V) / 64  # 64 samples per bay
        d = r.rail_displacement(t) - r.quasi_static_line(V * t)
        N = r.force(t)
        assert np.max(np.abs(d)) <= r.amplitude * (1 + 1e-12)
        assert r.min_force <= N.min() and N.max() <= r.max_force
        if exact:
            assert np.max(np.abs(d)) == pytest.approx(r.amplitude, rel=2e-3)
            assert N.max() == pytest.approx(r.max_force, rel=1e-4)
        assert np.std(N) == pytest.approx(r.force_rms, rel=1e-3)
        f = np.fft.rfftfreq(t.size, t[1])
        spec = np.abs(np.fft.rfft(d - d.mean()))
        assert f[np.argmax(spec)] == pytest.approx(r.main_frequency, abs=f[1])


def test_quasi_static_line_is_the_linear_statics(validation):
    """``PeriodicResponse.quasi_static_line`` (the moving force at 1 cm/s on the infinite track)
    against ``linear_quasi_static`` of a 30 m rail (800 elements) at its middle bay: within
    1e-5 of the deflection (measured 3e-6, at the support: the eight harmonics; 1e-6 between)."""
    s = ballasted()
    fe = dc.replace(s, rail=dc.replace(s.rail, n_elements=800))
    x = 15.0 + 0.6 * np.arange(16) / 16
    ref = tw.linear_quasi_static(fe, x)
    got = tw.periodic_response(s, V).quasi_static_line(x - 15.0)
    err = float(np.max(np.abs(got - ref)) / np.max(np.abs(ref)))
    assert err < 1e-5
    validation.record(
        "periodic.quasi_static_line", level="periodic level", kind="path agreement",
        quantity="ballasted preset: the quasi-static line y_qs over a bay (a moving force at "
                 "1 cm/s on the infinite track)",
        reference="the linear track's statics (linear_quasi_static) of a 30 m rail",
        measured=err, tolerance=1e-5, metric="of max |y_qs|")


# --------------------------------------------------------------------------------------------
# the fidelity level
def test_the_periodic_level_is_the_least_detailed_and_simulate_refuses_it():
    assert tw.FIDELITY_LEVELS[-1] == "periodic/linear"
    assert tw.FIDELITY_LEVELS[:-1] == tw.TIME_DOMAIN_LEVELS
    with pytest.raises(ValueError, match="periodic_response"):
        tw.simulate(tw.Scene.kato2005(), V, fidelity="periodic/linear")


def test_adequacy_runs_the_periodic_level():
    """On a 60 m rail the periodic row holds the steady state; measured like for like
    (``steady=True``) its peak force is within 1e-2 of the linear/sprung run's; on the paper's
    undamped track the row holds the reason it does not apply."""
    scene = long_rail(ballasted())
    df = tw.adequacy(scene, speeds=[V], levels=("linear/sprung", "periodic/linear"),
                     reference="linear/sprung", shear=False, steady=True, x_start=12.3,
                     x_end=45.0, progress=False)
    row = df[df.level == "periodic/linear"].iloc[0]
    assert row.error == ""
    assert row.d_peak_contact_force < 1e-2
    assert row.main_frequency_hz == pytest.approx(V / 0.6)
    paper = tw.adequacy(tw.Scene.kato2005(), speeds=[V], levels=("periodic/linear",),
                        reference="linear/sprung", shear=False, x_end=1.0, progress=False)
    row = paper[paper.level == "periodic/linear"].iloc[0]
    assert "damping" in row.error and not row.adequate
    with pytest.raises(ValueError, match="reference"):
        tw.adequacy(scene, speeds=[V], reference="periodic/linear")


# --------------------------------------------------------------------------------------------
# the sweep
def test_sweep_rows_are_the_periodic_outputs():
    s = ballasted()
    speeds, stiffs = [tw.kmh(100), tw.kmh(300)], [80e6, 180e6]
    df = tw.sweep(s, speeds, stiffs, fidelity="periodic/linear", progress=False)
    assert len(df) == 4 and (df.error == "").all() and (df.fidelity == "periodic/linear").all()
    for row in df.itertuples():
        sc = dc.replace(s, supports=dc.replace(s.supports, stiffness=row.support_stiffness_N_m))
        expect = tw.periodic_response(sc, row.speed_m_s).outputs()
        for q in OUTPUTS:
            got = getattr(row, q.label)
            if PERIODIC_OUTPUTS[q.name] is None:
                assert math.isnan(got), q.label
            else:
                assert got == expect[q.name], q.label
    for column in ("dt_s", "x_start_m", "t_end_s"):
        assert df[column].isna().all()


def test_sweep_records_refused_cases_and_refuses_time_domain_settings():
    # a dipped joint is no sum of sines: every case is an error row with the reason, and a
    # sweep whose every case failed raises with its table
    joint = ballasted(irregularity=tw.Irregularity.dipped_joint(1e-3, 0.5, 5.0))
    with pytest.raises(tw.SweepFailedError, match="sums of sines") as failed:
        tw.sweep(joint, [V], [80e6, 180e6], fidelity="periodic/linear", progress=False)
    df = failed.value.table
    assert len(df) == 2 and df.error.str.contains("sums of sines").all()
    assert df.amplitude_m.isna().all()
    with pytest.raises(ValueError, match="dt"):
        tw.sweep(ballasted(), [V], fidelity="periodic/linear", dt=1e-5, progress=False)


def test_sweep_store_resumes_periodic_cases(tmp_path):
    s = ballasted()
    a = tw.sweep(s, [V], [80e6, 180e6], fidelity="periodic/linear", store=tmp_path,
                 progress=False)
    b = tw.sweep(s, [V], [80e6, 180e6], fidelity="periodic/linear", store=tmp_path,
                 progress=False)
    assert b.attrs["from_store"] == 2 and b.attrs["computed"] == 0
    assert (a.amplitude_m.to_numpy() == b.amplitude_m.to_numpy()).all()


# --------------------------------------------------------------------------------------------
# the command
def test_cli_periodic_prints_the_harmonics_and_the_dynamic_factor(capsys, tmp_path):
    out_csv, png = tmp_path / "h.csv", tmp_path / "p.png"
    code = main(["periodic", "--speed-kmh", "100", "300", "--irregularity", "sine:0.5,1e-5",
                 "--harmonics", "3", "--out", str(out_csv), "--plot", str(png)])
    text = capsys.readouterr().out
    assert code == 0
    assert "sleeper_passing" in text and "rail sine 0.5 m" in text
    assert text.count("dynamic factor") == 2
    import pandas as pd

    table = pd.read_csv(out_csv)
    assert list(table.columns[:4]) == ["speed_kmh", "frequency_hz", "amplitude_n", "phase_rad"]
    r = tw.periodic_response(ballasted(irregularity=tw.Irregularity.sine(0.5, 1e-5)),
                             tw.kmh(300), n_harmonics=3)
    mine = table[np.isclose(table.speed_kmh, 300.0)].amplitude_n.to_numpy()
    np.testing.assert_allclose(mine, r.force_harmonics.amplitude_n, rtol=1e-12)
    assert png.stat().st_size > 0


def test_cli_periodic_random_profile(capsys):
    code = main(["periodic", "--speed-kmh", "100", "--irregularity", "iso3095",
                 "--wavelengths", "0.044", "0.44"])
    text = capsys.readouterr().out
    assert code == 0 and "percentiles" in text and "band [Hz]" in text


@pytest.mark.parametrize("argv, message", [
    (["--track", "kato2005"], "--support-damping"),
    (["--irregularity", "sine:0.2,5e-4"], "contact loss"),
    (["--speed-kmh", "2000"], "km/h"),
    (["--harmonics", "100"], "--harmonics"),
])
def test_cli_periodic_errors_are_one_line(capsys, argv, message):
    args = ["periodic"] + (argv if "--speed-kmh" in argv else ["--speed-kmh", "300"] + argv)
    assert main(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err


def test_cli_sweep_and_run_at_the_periodic_level(capsys, tmp_path):
    code = main(["sweep", "--speeds-kmh", "100", "300", "--track", "ballasted",
                 "--fidelity", "periodic/linear", "--store", str(tmp_path), "--no-progress"])
    out = capsys.readouterr().out
    assert code == 0 and "2 cases: 2 computed" in out
    # run simulates: its --fidelity offers the time-domain levels only
    assert main(["run", "--speed-kmh", "300", "--fidelity", "periodic/linear"]) == 2
    assert "invalid choice" in capsys.readouterr().err
