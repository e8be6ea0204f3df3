"""The travelling window (docs: Model § The travelling window).

The window's rail is a fixed number of sleeper bays that moves with the wheel; the state shifts
by one bay inside the kernel's time loop. Checks: it reproduces a long fixed track (same
irregularity, same supports), it gives the closed-form steady state of a constant force moving
along an infinite beam on an elastic foundation, its output size is that of the kept samples
whatever the distance, and it refuses tracks it cannot shift.
"""

from __future__ import annotations

import dataclasses as dc
import math
import re

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import spectra
from trackwheel.run import profile

V = tw.kmh(300)
#: the ballasted preset's static wheel load P = F + M g [N]
P_STATIC = 70e3


def _fra5():
    # wavelengths 3-50 m: the wheel keeps contact at 300 km/h, so the comparison tests the
    # shift, not the sensitivity of a wheel landing after a loss of contact
    return tw.Irregularity.random(spectra.fra(5), seed=3, wavelengths=(3.0, 50.0))


@pytest.mark.parametrize("absorbing", [0.0, 4.8])
def test_window_equals_long_fixed_track(absorbing, validation):
    """12 m of FRA class 5 at 300 km/h on a window of 20 + 1 + 20 bays (24.6 m, 20 shifts)
    against a 60 m fixed rail whose ends are 20 m behind the start and 28 m beyond the end:
    Hertzian contact force and wheel height agree within 1e-3 of the static load (and the
    corresponding 1e-3 P / k_H of the wheel) over the last 4 m. The first metres differ by up to
    8e-3 P: the start (static equilibrium at speed) and the irregularity send waves along the
    rail, which the window cuts 12 m from the wheel (its ends pin what reaches them, and each
    shift drops the rear bay's motion); they have died out by 8 m. With the window's default
    absorbing end zones of 8 bays (``Window.absorbing_length``: the damping band is the same
    after a shift) and without them (0) the same holds."""
    irr = _fra5()
    fixed = dc.replace(tw.Scene.ballasted_track(length=60.0), irregularity=irr)
    window = dc.replace(tw.Scene.ballasted_track(
        window=tw.Window(20, 20, absorbing_length=absorbing)), irregularity=irr)
    zone = window.rail.absorbing_ends
    assert (zone is None) if absorbing == 0 else zone.length == pytest.approx(8 * 0.6)
    kw = dict(x_start=20.1, x_end=32.1, fidelity="linear/hertz", progress=False)
    rf = tw.simulate(fixed, V, n_elements=fixed.rail.n_elements, **kw)
    rw = tw.simulate(window, V, n_elements=window.rail.n_elements, dt=rf.settings.dt, **kw)
    assert window.rail.length == pytest.approx(41 * 0.6) and rw.x_wheel[-1] > window.rail.length
    np.testing.assert_array_equal(rw.x_wheel, rf.x_wheel)  # outputs in the track's X
    stretch = rw.x_wheel >= 28.1
    assert np.ptp(rf.normal_force[stretch]) > 0.1 * P_STATIC  # the irregularity excites
    assert np.abs(rw.normal_force - rf.normal_force)[stretch].max() < 1e-3 * P_STATIC
    if absorbing > 0.0:
        validation.record(
            "long.window_equals_fixed_track", level="long tracks", kind="path agreement",
            quantity="linear/hertz on a travelling window of 41 bays, 12 m of FRA class 5 at "
                     "300 km/h: contact force over the last 4 m",
            reference="the same run on a 60 m fixed rail",
            measured=np.abs(rw.normal_force - rf.normal_force)[stretch].max() / P_STATIC,
            tolerance=1e-3, metric="of the static load")
    # the wheel's height to the same fraction: 1e-3 P over the Hertz stiffness at P
    k_h = 1.5 * window.hertz_constant ** (2 / 3) * P_STATIC ** (1 / 3)
    assert np.abs(rw.y_wheel - rf.y_wheel)[stretch].max() < 1e-3 * P_STATIC / k_h


def test_full_path_window_equals_long_fixed_track():
    """The full model (ANCF rail, rolling contact, generalized-alpha) on the same scene sizes
    as the linear test above: 12 m of FRA class 5 at 300 km/h on a window of 20 + 1 + 20 bays
    (20 shifts) against the 60 m fixed rail. Contact force and wheel height agree within 1e-3
    of the static load (and 1e-3 P / k_H) over the last 4 m, the contact point's X within
    0.1 mm (measured: 8e-4 P, as on the linear path the start's waves cut by the window's ends
    have died out there; up to 8e-3 P in the first metres). The window shifts the rail's
    departure from its nonlinear rest state under its own weight; shifting the state itself
    would carry the window ends' sag into the track."""
    irr = _fra5()
    fixed = dc.replace(tw.Scene.ballasted_track(length=60.0), irregularity=irr)
    window = dc.replace(tw.Scene.ballasted_track(window=tw.Window(20, 20)), irregularity=irr)
    kw = dict(x_start=20.1, x_end=32.1, progress=False)
    rf = tw.simulate(fixed, V, n_elements=fixed.rail.n_elements, **kw)
    rw = tw.simulate(window, V, n_elements=window.rail.n_elements, dt=rf.settings.dt, **kw)
    assert rw.settings.fidelity == "full" and rw.x_wheel[-1] > window.rail.length
    np.testing.assert_array_equal(rw.x_wheel, rf.x_wheel)
    stretch = rw.x_wheel >= 28.1
    assert np.ptp(rf.normal_force[stretch]) > 0.1 * P_STATIC
    assert np.abs(rw.normal_force - rf.normal_force)[stretch].max() < 1e-3 * P_STATIC
    k_h = 1.5 * window.hertz_constant ** (2 / 3) * P_STATIC ** (1 / 3)
    assert np.abs(rw.y_wheel - rf.y_wheel)[stretch].max() < 1e-3 * P_STATIC / k_h
    assert np.abs(rw.contact_s - rf.contact_s)[stretch].max() < 1e-4  # X of the contact


def test_full_path_window_axial_motion_equals_long_fixed_track():
    """The window's shifts drop the rear bay's axial motion and add a fresh bay at rest; the
    rail's axial waves (5 km/s, no axial support) carry that knock through the whole window.
    End zones that damp the axial motion too (``AbsorbingEnds``, c_max,x designed for 30 dB
    from 100 Hz) absorb it: 15 m of smooth ballasted track at 300 km/h on a window of
    20 + 1 + 20 bays with its default 8-bay zones (25 shifts) against a 60 m fixed rail with the same zones
    (its ends 20 m behind the start and 25 m beyond the end). The tangential force (the rolling
    constraint's multiplier) agrees within 1e-3 of the static load from 5 m on, the criterion
    the normal force meets above (measured 3.3e-4 P; without the axial damping the window's
    rings with a peak-to-peak growing to 2.4 kN, 2e-2 P), and the modified Newton needs no
    more iterations per step than on the fixed rail within 10 % (measured 0.3 %; without the
    axial damping 58 % more). Iterations are counts, the same on any machine."""
    window = tw.Scene.ballasted_track(window=tw.Window(20, 20))  # its default 8-bay zones
    zones = window.rail.absorbing_ends
    assert zones.length == pytest.approx(8 * 0.6)
    fixed = tw.Scene.ballasted_track(length=60.0)
    fixed = dc.replace(fixed, rail=dc.replace(fixed.rail, absorbing_ends=zones))
    kw = dict(x_start=20.1, x_end=35.1, progress=False)
    rf = tw.simulate(fixed, V, n_elements=fixed.rail.n_elements, **kw)
    rw = tw.simulate(window, V, n_elements=window.rail.n_elements, dt=rf.settings.dt, **kw)
    assert rw.settings.fidelity == "full" and rw.x_wheel[-1] - rw.x_wheel[0] > 24 * 0.6
    np.testing.assert_array_equal(rw.x_wheel, rf.x_wheel)
    stretch = rw.x_wheel >= 25.1
    assert np.abs(rw.tangential_force - rf.tangential_force)[stretch].max() < 1e-3 * P_STATIC
    assert np.abs(rw.normal_force - rf.normal_force)[stretch].max() < 1e-3 * P_STATIC
    per_step = [r.newton_iterations / r.steps for r in (rw, rf)]
    assert per_step[0] < 1.1 * per_step[1]


def _short_window():
    """4 m at 300 km/h on a window of 10 + 1 + 10 bays (6 shifts)."""
    scene = tw.Scene.ballasted_track(window=tw.Window(10, 10))
    return scene, dict(x_start=6.1, x_end=10.1, progress=False, n_elements=scene.rail.n_elements)


def test_integrators_agree_on_a_window():
    """Explicit RK4 against generalized-alpha on the same window, FRA class 5, same step (RK4's
    stability limit, 1.9 us): as tests/test_paths_agree.py asks of the integrators, the contact
    force within 1 % of its range and the heights within 1 % of the dynamic amplitude (measured
    0.19 % and 0.03 %; RK4 shifts its state only, generalized-alpha its history too)."""
    scene, kw = _short_window()
    scene = dc.replace(scene, irregularity=_fra5())
    ex = tw.simulate(scene, V, integrator="explicit", **kw)
    ga = tw.simulate(scene, V, dt=ex.settings.dt, **kw)
    assert ga.x_wheel[-1] - ga.x_wheel[0] > 6 * 0.6
    amp = tw.analyse(ga).amplitude
    assert np.abs(ex.normal_force - ga.normal_force).max() < 0.01 * np.ptp(ga.normal_force)
    assert np.abs(ex.y_wheel - ga.y_wheel).max() < 0.01 * amp
    assert np.abs(ex.y_contact - ga.y_contact).max() < 0.01 * amp


def test_linear_and_full_paths_agree_on_a_window():
    """The ANCF level and the linear level of the Hertz contact on the same window (smooth
    track, same step): tests/test_paths_agree.py's tolerances, forces within 1e-3 of the static
    load and heights within 1 % of the dynamic amplitude (measured 1e-5 and 1.2e-4: the ANCF
    rail's nonlinearity)."""
    scene, kw = _short_window()
    a = tw.simulate(scene, V, fidelity="ancf/hertz", **kw)
    b = tw.simulate(scene, V, fidelity="linear/hertz", dt=a.settings.dt, **kw)
    assert np.array_equal(a.t, b.t)
    amp = tw.analyse(a).amplitude
    assert np.abs(a.normal_force - b.normal_force).max() < 1e-3 * P_STATIC
    assert np.abs(a.y_contact - b.y_contact).max() < 0.01 * amp
    assert np.abs(a.y_wheel - b.y_wheel).max() < 0.01 * amp


def winkler_scene(zeta: float = 0.02) -> tuple[tw.Scene, float, float]:
    """A light beam on supports every 5 cm (lambda d = 0.1: the Winkler limit) on a window of
    401 bays (20 m, 40 / lambda), no gravity, the foundation damped at zeta of critical.
    Returns (scene, k [N/m^2], m [kg/m])."""
    EI, E, k, d = 37500.0, 210e9, 2.4e6, 0.05
    rail = tw.Rail(length=1.0, youngs_modulus=E, density=7850.0, area=7.69e-3,
                   second_moment=EI / E, n_elements=20)
    m = rail.mass_per_length
    c = 2.0 * zeta * math.sqrt(k * m)
    scene = tw.Scene(rail=rail, supports=tw.Supports(stiffness=k * d, damping=c * d, spacing=d),
                     wheel=tw.Wheel(load=1e4, mass=10.0), gravity=0.0, rail_gravity=False)
    return scene.windowed(tw.Window(bays_behind=200, bays_ahead=200)), k, m


@pytest.mark.parametrize("alpha", [0.0, 0.3, 0.5, 0.7])
def test_moving_load_on_winkler_beam(alpha, validation):
    """Steady deflection under a constant force P moving at v = alpha v_cr along an infinite
    Euler-Bernoulli beam on an elastic foundation (Winkler modulus k):
    w(0) = P lambda / (2 k) / sqrt(1 - alpha^2), lambda = (k / (4 EI))^(1/4),
    v_cr = (4 k EI / m^2)^(1/4) (docs: Model § Validation). It is the value at xi = 0 of the
    steady solution of EI w'''' + m v^2 w'' + k w = P delta(xi) in xi = x - v t,
    (P / pi) int_0^inf dkappa / (EI kappa^4 - m v^2 kappa^2 + k); the same closed form is
    Fryba, *Vibration of Solids and Structures under Moving Loads* (1999), ch. 4 (the infinite
    beam on an elastic foundation), undamped case.

    Tolerance 2e-3: the foundation damping zeta = 0.02 (there to let the start transient die)
    lowers w(0) by 8e-4 at alpha = 0.7 (the damped Fourier integral, evaluated separately:
    3e-5 at 0.3), 5 cm supports and elements differ from the continuous foundation by 1e-4,
    and the mean over the last 0.2 s averages the remaining transient (1 % peak to peak)."""
    scene, k, m = winkler_scene()
    EI = scene.rail.bending_stiffness
    lam = (k / (4.0 * EI)) ** 0.25
    v_cr = (4.0 * k * EI / m**2) ** 0.25
    speed = max(alpha * v_cr, 1.0)  # 1 m/s for the static limit: alpha = 0.01
    r = tw.simulate(scene, speed, fidelity="linear/moving_force", dt=2e-4, duration=1.2,
                    n_elements=scene.rail.n_elements, progress=False)
    a = speed / v_cr
    w0 = scene.static_load * lam / (2.0 * k) / math.sqrt(1.0 - a * a)
    assert r.x_wheel[-1] - r.x_wheel[0] > scene.rail.length or alpha < 0.3
    w = -r.y_contact[r.t > 1.0].mean()
    assert w == pytest.approx(w0, rel=2e-3)
    if alpha == 0.7:
        validation.record(
            "long.moving_load_on_a_winkler_beam", level="long tracks", kind="closed form",
            quantity="travelling window, constant force at 0.7 of the critical speed on a "
                     "beam on closely spaced supports: steady deflection under the load",
            reference="Frýba (1999) ch. 4: P λ/(2k)/√(1 - α²), λ = (k/4EI)^(1/4)",
            measured=abs(w / w0 - 1.0), tolerance=2e-3)


def test_output_size_independent_of_distance():
    """Memory: a run ten windows long keeps exactly its decimated samples (n_steps // every
    + 1 per field), and the kernel's state is the window's: the same rail size whatever the
    distance."""
    scene, _, _ = winkler_scene()
    kw = dict(fidelity="linear/moving_force", dt=2e-4, n_elements=scene.rail.n_elements,
              progress=False, output_every=50, x_start=0.3)
    short = tw.simulate(scene, 100.0, distance=20.0, **kw)
    long = tw.simulate(scene, 100.0, distance=200.0, **kw)
    assert long.x_wheel[-1] == pytest.approx(200.3)
    for r, dist in ((short, 20.0), (long, 200.0)):
        n_steps = round(dist / 100.0 / 2e-4)
        assert r.t.size == n_steps // 50 + 1
    assert long.settings.n_elements == short.settings.n_elements == scene.rail.n_elements


def test_profile_table_built_in_chunks_is_the_one_spline():
    """The rail profile over a long run is built chunk by chunk (trackwheel.run.profile.
    spline_table);
    the chunks (here 1000 intervals, 40 knots of overlap) join to the not-a-knot spline
    through all samples within round-off (the spline's dependence on a sample decays by
    2 - sqrt(3) per knot: 0.27^40 < 1e-22; measured bit-identical), at the samples of
    ``table``, with the same largest r'' and its place."""
    from scipy.interpolate import CubicSpline

    irr = _fra5()
    x0, h, r = irr.table(0.0, 10.0, 1e-3)
    x = x0 + h * np.arange(r.size)
    spline = CubicSpline(x, r)
    y0, k, c, worst, at = profile.spline_table(irr, 0.0, 10.0, 1e-3, chunk=1000)
    assert (y0, k) == (x0, h) and c.shape == spline.c.shape == (4, 10000)
    scale = np.abs(spline.c).max(axis=1, keepdims=True)
    assert np.all(np.abs(c - spline.c) <= 1e-13 * scale)
    curvature = spline(x, 2)
    assert worst == pytest.approx(curvature.max(), rel=1e-12)
    assert at == x[np.argmax(curvature)]


def test_profile_memory_in_python_is_independent_of_distance():
    """The kernel's rail profile is handed over chunk by chunk (65 536 intervals), so Python's
    peak while building it (numpy's allocations, traced) is the same for 200 m and 1 km of
    profile (2e5 and 1e6 samples at 1 mm; the 1 km table is 30.5 MiB, which the kernel streams
    and holds a few chunks of at a time: tests/test_profile_stream.py):
    within 1 MiB, against the 24.4 MiB the longer table adds (measured 0.01 MiB; the spline
    through all samples at once peaked at 4.75 tables). The work space is about two chunks'
    splines (12.5 MiB: the kernel's loop holds the previous chunk while the next is built).
    The table is the one spline's (see above), so the run is unchanged."""
    import tracemalloc

    scene = dc.replace(tw.Scene.ballasted_track(window=tw.Window(5, 5)),
                       irregularity=tw.Irregularity.sine(2.0, 1e-4))
    profile.rail_profile(scene, 10.0)  # imports and first-call allocations
    peaks = []
    for end in (200.0, 1000.0):
        tracemalloc.start()
        try:
            table = profile.rail_profile(scene, end)
            peaks.append(tracemalloc.get_traced_memory()[1])
        finally:
            tracemalloc.stop()
        assert table(end - 1.0)[0] == pytest.approx(1e-4 * math.sin(math.pi * (end - 1.0)),
                                                    abs=1e-9)
    assert peaks[1] < peaks[0] + 2**20


@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_window_runs_are_bit_identical(fidelity):
    scene = tw.Scene.ballasted_track(window=tw.Window(5, 5))
    kw = dict(fidelity=fidelity, distance=5.0, x_start=1.0, progress=False)
    a, b = tw.simulate(scene, V, **kw), tw.simulate(scene, V, **kw)
    np.testing.assert_array_equal(a.normal_force, b.normal_force)


def test_window_validation():
    with pytest.raises(ValueError, match="Window.bays_behind"):
        tw.Window(bays_behind=0)
    with pytest.raises(ValueError, match=r"Window.absorbing_length = -1.0 .*\[0, 1000\] m"):
        tw.Window(absorbing_length=-1.0)
    scene = tw.Scene.ballasted_track(window=tw.Window(5, 5))
    # the zones stay off the vehicle's bays: 5 bays each, not the 8 of 4.8 m
    assert scene.rail.absorbing_ends.length == pytest.approx(5 * 0.6)
    with pytest.raises(ValueError, match="n_modes"):
        tw.simulate(scene, V, distance=1.0, x_start=1.0, fidelity="linear/hertz", n_modes=10)
    with pytest.raises(ValueError, match="Rail.length"):
        dc.replace(scene, rail=dc.replace(scene.rail, length=6.0))
    with pytest.raises(ValueError, match="Supports.positions"):
        dc.replace(scene, supports=dc.replace(scene.supports, positions=(1.0, 2.0)))
    with pytest.raises(ValueError, match="multiple"):
        tw.simulate(scene, V, distance=1.0, x_start=1.0, fidelity="linear/hertz",
                    n_elements=scene.rail.n_elements + 1)
    with pytest.raises(ValueError, match="x_end or distance"):
        tw.simulate(scene, V, distance=1.0, x_end=3.0, fidelity="linear/hertz")


def test_cli_distance_runs_on_a_window(capsys):
    """``run --distance`` is the window run of the API (the same forces, bit for bit) and
    prints per-100-m statistics; --window without --distance is refused."""
    from trackwheel import cli

    args = ["run", "--track", "ballasted", "--speed-kmh", "300", "--distance", "3",
            "--window", "5,5", "--irregularity", "sine:3,1e-4"]
    assert cli.main(args) == 0
    out = capsys.readouterr().out
    assert "travelling window of 5 + 5 bays" in out and "per 100 m" in out
    scene = dc.replace(tw.Scene.ballasted_track(window=tw.Window(5, 5)),
                       irregularity=tw.Irregularity.sine(3.0, 1e-4))
    r = tw.simulate(scene, V, fidelity="linear/hertz", distance=3.0, x_start=0.3,
                    progress=False)
    assert f"{r.normal_force.max() / 1e3:.2f} kN" in out
    assert cli.main(["run", "--speed-kmh", "300", "--window", "5,5"]) == 2
    assert "--window needs --distance" in capsys.readouterr().err


@pytest.fixture(scope="module")
def smooth_run():
    """30 m of the smooth ballasted preset at 300 km/h on a window of 20 + 20 bays."""
    scene = tw.Scene.ballasted_track(window=tw.Window(20, 20))
    return tw.simulate(scene, V, fidelity="linear/hertz", distance=30.0, x_start=0.3,
                       progress=False)


def test_steady_state_mean_force_is_the_static_load(smooth_run):
    """Momentum balance: in a bay-periodic steady state the wheel's vertical velocity is
    periodic, so its mean acceleration over whole bays is zero and the mean contact force is
    the static load P = F + M g. Tolerance 1e-4 P: the resampling of the kept samples at 128
    per bay (linear interpolation, a 0.6 m bay in about 210 samples here) and what is left of
    the transient (bay-to-bay differences below tol = 1e-3 of the scale, alternating)."""
    s = tw.steady_state(smooth_run)
    assert s.mean == pytest.approx(P_STATIC, rel=1e-4)
    assert 0.0 < s.t_from < smooth_run.t[-1] and s.n_bays >= 10
    assert s.bay_difference < 1e-3
    assert s.sleeper_frequency == pytest.approx(V / 0.6)
    np.testing.assert_allclose(s.harmonics[0], V / 0.6 * np.arange(1, 5))
    # the sleeper-passing force: the first harmonic carries most of the bay's variation
    assert s.harmonics[1][0] > 0.5 * s.amplitude > 0.0
    a = tw.analyse(smooth_run, steady=True)
    assert a.t[0] >= s.t_from and a.t.size < smooth_run.t.size


def test_steady_state_recovers_known_harmonics(smooth_run):
    """A synthetic bay-periodic signal N = P + a1 cos(2 pi X/d) + a3 sin(6 pi X/d) under a
    transient 5 kN exp(-t/0.02 s): the harmonics come back to 1e-3 of a1 (the resampling
    error of 128 samples per bay on samples about 3 mm apart), the steady part starts where
    the transient is below tol x scale: 5 kN exp(-t/0.02) < 1e-3 x 70 kN at t > 0.085 s, so
    within one bay (7.2 ms) after that."""
    r = smooth_run
    x, t, d = r.x_wheel, r.t, 0.6
    a1, a3 = 500.0, 80.0
    N = (P_STATIC + a1 * np.cos(2 * np.pi * x / d) + a3 * np.sin(6 * np.pi * x / d)
         + 5e3 * np.exp(-t / 0.02))
    s = tw.steady_state(dc.replace(r, normal_force=N))
    amps = s.harmonics[1]
    np.testing.assert_allclose(amps, [a1, 0.0, a3, 0.0], atol=1e-3 * a1)
    t_settle = 0.02 * math.log(5e3 / (1e-3 * (P_STATIC + a1)))
    assert t_settle - 0.0075 <= s.t_from <= t_settle + 2 * d / V


def test_steady_state_refuses_an_unsettled_run(smooth_run):
    # a drift of 5 kN over the run's 50 bays: 100 N per bay, above tol x scale = 70 N, so no
    # three bays agree with the last one
    N = P_STATIC + 5e3 * smooth_run.x_wheel / 30.0
    with pytest.raises(ValueError, match="does not settle"):
        tw.steady_state(dc.replace(smooth_run, normal_force=N))


@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_bogie_on_a_window_equals_the_fixed_track(fidelity):
    """A bogie (two wheels 2.5 m apart, the window spans its wheelbase: 20 + 1 + 5 + 20 bays)
    over 10 m of the smooth preset at 300 km/h against a 60 m fixed rail, on the linear path
    and on the full model: each wheel's contact force agrees within 1e-3 of its static load
    from 4 m on (measured 1.2e-4 on the full model; the start transient's reflections from the
    window's ends, up to 1.3e-3 in the first metre, have died out)."""
    veh = tw.Vehicle.bogie()
    fixed = dc.replace(tw.Scene.ballasted_track(length=60.0), vehicle=veh)
    window = fixed.windowed(tw.Window(20, 20))
    assert window.rail.length == pytest.approx(46 * 0.6)
    kw = dict(x_start=20.1, x_end=30.1, fidelity=fidelity, progress=False)
    rf = tw.simulate(fixed, V, n_elements=fixed.rail.n_elements, **kw)
    rw = tw.simulate(window, V, n_elements=window.rail.n_elements, dt=rf.settings.dt, **kw)
    loads = np.asarray(veh.static_loads(fixed.gravity))
    stretch = rw.x_wheel[:, 0] >= 24.1
    err = np.abs(rw.normal_force - rf.normal_force)[stretch].max(axis=0)
    assert (err < 1e-3 * loads).all()


def _timoshenko_track_with_a_sprung_wheel(per_bay: int, **window) -> tw.Scene:
    """The ballasted preset's track with a UIC60 Timoshenko rail (kappa 0.4, G = E / 2.6) and a
    600 kg wheel under a 996 kg one-wheel bogie on a 1.2 MN/m primary spring, 80 kN static
    wheel load, linear contact 1.3374e9 N/m (a user's set-up); a 60 m fixed rail, or with
    ``window`` (Window's fields) the travelling window with its default end zones."""
    base = tw.Scene.ballasted_track(length=60.0, elements_per_bay=per_bay)
    g = base.gravity
    wheel = tw.Wheel(mass=600.0, radius=0.46, load=0.0, youngs_modulus=210e9,
                     poisson_ratio=0.3)
    bogie = tw.Bogie(wheels=(0,), centre=0.0, mass=996.0, pitch_inertia=100.0,
                     primary_stiffness=1.2e6, primary_damping=0.0,
                     load=80e3 - (600.0 + 996.0) * g)
    scene = dc.replace(base, rail=dc.replace(base.rail, beam="timoshenko", shear_coefficient=0.4),
                       vehicle=tw.Vehicle(wheels=(wheel,), positions=(0.0,), bogies=(bogie,)),
                       contact=dc.replace(base.contact, stiffness=1.3374e9))
    return scene.windowed(tw.Window(**window)) if window else scene


@pytest.mark.parametrize("per_bay", [8, 32, pytest.param(64, marks=pytest.mark.slow)])
def test_full_model_on_a_window_equals_a_fixed_rail_at_any_mesh(per_bay):
    """The full model with a shear-deformable rail on a window of 20 + 1 + 20 bays against a
    60 m fixed rail with the same end zones (the ends 20 m behind the start and 34 m beyond the
    end), 6 m of smooth track at 200 km/h, at 8, 32 and 64 elements per bay. From 2 m on
    (the start transient's reflections have died out, as above):

    - normal force within 1e-3 of the static load P (the criterion of the tests above;
      measured 1.8-3.3e-4 P);
    - tangential force within 2e-3 P: the rail has no axial support, so its axial response to
      the wheel's longitudinal force at the sleeper-passing frequency depends on the length of
      rail free to move; that harmonic of the tangential force is 68 N on this 24.6 m window,
      24 N on the 60 m rail and on a window of 40 + 40 bays, 10 N on a 90 m rail (measured at
      8 el/bay), and the window differs from the 60 m rail by 1.07e-3 P, alike at every
      mesh;
    - the wheel sticks throughout, and Newton needs as many iterations per step as on the fixed
      rail within 5 % (measured 0.0-0.1 %).

    Before the director's stretch had its stiffness (docs: Model, section "Shear-deformable
    rail (Timoshenko)") the window's shifts excited its near-free modes: here the tangential
    force reached 3.6 kN (4.4e-2 P off the fixed rail) at 32 el/bay, and at 64 el/bay the wheel
    slid (mu N = 24 kN) from 2.7 m on, with 18 % more Newton iterations per step than on the
    fixed rail."""
    fixed = _timoshenko_track_with_a_sprung_wheel(per_bay)
    window = _timoshenko_track_with_a_sprung_wheel(per_bay, bays_behind=20, bays_ahead=20)
    zones = window.rail.absorbing_ends
    fixed = dc.replace(fixed, rail=dc.replace(fixed.rail, absorbing_ends=zones))
    v = tw.kmh(200)
    rf = tw.simulate(fixed, v, x_start=20.1, x_end=26.1, n_elements=fixed.rail.n_elements,
                     progress=False)
    rw = tw.simulate(window, v, x_start=0.3, x_end=6.3, n_elements=window.rail.n_elements,
                     dt=rf.settings.dt, progress=False)
    assert rw.settings.fidelity == "full" and rw.x_wheel[-1] - 0.3 > 9 * 0.6  # 10 shifts
    np.testing.assert_allclose(rw.x_wheel - 0.3, rf.x_wheel - 20.1, atol=1e-9)
    P = 80e3
    stretch = rw.x_wheel >= 2.3
    assert np.abs(rw.normal_force - rf.normal_force)[stretch].max() < 1e-3 * P
    assert np.abs(rw.tangential_force - rf.tangential_force)[stretch].max() < 2e-3 * P
    assert np.all(rw.slip_state == 1) and np.all(rf.slip_state == 1)  # 1: sticking
    per_step = [r.newton_iterations / r.steps for r in (rw, rf)]
    assert per_step[0] < 1.05 * per_step[1]


@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_the_smallest_window_runs(fidelity):
    """Window(1, 1), inside the documented 1..1000 bays, runs on both paths (its hold, two bays,
    is exactly the rail length less one bay: the kernel once refused it by a rounding of
    3 x 0.6 m). Over the run the contact impulse balances the wheel's momentum,
    int (N - P) dt = M (Y'_end - Y'_start), to the trapezoid rule's error: each shift of the
    three-bay window loses no force. (So short a window knocks the wheel at every shift, on
    the full path off the rail for moments: it runs, it is not a good model.)"""
    s = tw.Scene.ballasted_track(window=tw.Window(1, 1))
    r = tw.simulate(s, 50.0, distance=3.0, fidelity=fidelity, output_every=1, progress=False)
    assert r.steps > 3.0 / s.supports.spacing  # several shifts of the window
    assert np.all(np.isfinite(r.normal_force)) and np.all(r.normal_force >= 0.0)
    impulse = np.trapezoid(r.normal_force - s.static_load, r.t)
    momentum = s.wheel.mass * (r.ydot_wheel[-1] - r.ydot_wheel[0])
    assert abs(impulse - momentum) < 1e-6 * s.static_load * r.t[-1]


def test_a_run_too_long_for_the_step_limit_names_its_distance():
    """distance = 1e15 m on a window: 5.9e17 steps of the derived dt, above MAX_STEPS. The
    message named dt (not given) and '2e+13 s'; it names the distance and the longest one
    allowed, MAX_STEPS dt v."""
    from trackwheel.base.limits import MAX_STEPS

    s = tw.Scene.ballasted_track(window=tw.Window())
    dt = tw.default_settings(s)["dt"]
    most = re.escape(f"{MAX_STEPS * dt * 50.0:.6g}")
    with pytest.raises(ValueError, match=rf"^distance = 1e\+15 m takes .* allowed: distance up "
                       rf"to {most} m$"):
        tw.simulate(s, 50.0, distance=1e15, fidelity="linear/hertz", progress=False)
