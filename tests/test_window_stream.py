"""The travelling window over a track whose supports differ from bay to bay (docs:
Model § The travelling window): the kernel streams each sleeper's properties into the window as it moves
(``WindowParams.supports``, one entry per sleeper the run meets).

Checks: the window over a stiffness transition and over a scattered bed reproduces a long fixed
rail with the same per-support properties (contact force and each sleeper's ballast-force
envelope), on the linear and the full path; a stream of equal values is the unstreamed window
bit for bit and refactorises nothing; the kernel refuses a stream that does not fit the window.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel
from trackwheel.run import simulate as sim
from trackwheel.run.start import initial_state

V = tw.kmh(300)
P_STATIC = 70e3  #: the ballasted preset's static wheel load [N]
D = 0.6  #: its sleeper bay [m]
#: the stretch where the start's waves have died out on both rails (tests/test_window.py)
STRETCH = 28.1


def _transition(x):
    """Soft to stiff: k_b x3 and k_p x1.5 over a linear ramp of 1.2 m at X = 29.5 m."""
    s = np.clip((x - 29.5) / 1.2 + 0.5, 0.0, 1.0)
    return {"ballast_stiffness": 1.0 + 2.0 * s, "stiffness": 1.0 + 0.5 * s}


def _scatter(x):
    """Lognormal scatter per sleeper (mean 1): cv 0.3 on k_b, 0.2 on k_p, 0.1 on m_s and c_b,
    drawn by the sleeper's index round(X / d), so both rails see the same bed."""
    k = np.rint(np.asarray(x) / D).astype(int)
    out = {}
    for i, (name, cv) in enumerate([("ballast_stiffness", 0.3), ("stiffness", 0.2),
                                     ("sleeper_mass", 0.1), ("ballast_damping", 0.1)]):
        sig = np.sqrt(np.log1p(cv * cv))
        xi = np.array([np.random.default_rng([11, i, int(j)]).standard_normal() for j in k])
        out[name] = np.exp(sig * xi - 0.5 * sig * sig)
    return out


def _supports(scene: tw.Scene, factors, x, position=None) -> _core.SupportParams:
    """The scene's supports at the track coordinates x [m], each property scaled by
    factors(x) (a dict of arrays), placed at ``position`` (default x)."""
    s = kernel._supports_at(scene, np.asarray(x, dtype=float), position)
    for name, f in factors(np.asarray(x, dtype=float)).items():
        setattr(s, name, list(np.asarray(getattr(s, name)) * f))
    return s


def _varied(plan, factors):
    """The plan with the supports scaled by factors(X): a fixed rail's own supports; on a
    window the start window's and the stream of every sleeper the run meets. The full path's
    start is solved again on the varied rail."""
    scene, w = plan.scene, plan.window
    x = np.asarray(scene.support_positions, dtype=float)
    origin = 0.0 if w is None else w.origin
    profile = plan.model.profile
    model = _core.RailModel(kernel.rail_params(scene, plan.settings.n_elements),
                            _supports(scene, factors, origin + x, x), profile)
    if w is not None:
        n = len(x) + int(np.ceil(plan.settings.speed * plan.settings.t_end / D)) + 2
        w.supports = _supports(scene, factors, origin + x[0] + D * np.arange(n))
    init = plan.init
    if init is not None:
        s0 = 0.0 if w is None else w.origin
        init = initial_state(scene, model, plan.settings.speed, plan.settings.x_start - s0,
                             "static", 0.0)
    return dc.replace(plan, model=model, init=init, window=w)


def _run(plan):
    return sim.execute(plan, False)


def _pair(factors, fidelity):
    """(window run, fixed-rail run, stretch mask) over 12 m at 300 km/h: the window of
    20 + 1 + 20 bays and the 60 m fixed rail of tests/test_window.py."""
    fixed = tw.Scene.ballasted_track(length=60.0)
    window = tw.Scene.ballasted_track(window=tw.Window(20, 20))
    kw = dict(x_start=20.1, x_end=32.1, fidelity=fidelity)
    pf = sim.plan_run(fixed, V, n_elements=fixed.rail.n_elements, **kw)
    pw = sim.plan_run(window, V, n_elements=window.rail.n_elements, dt=pf.settings.dt, **kw)
    rf, rw = _run(_varied(pf, factors)), _run(_varied(pw, factors))
    np.testing.assert_array_equal(rw.x_wheel, rf.x_wheel)
    return rw, rf, rw.x_wheel >= STRETCH


@pytest.mark.parametrize("factors", [_transition, _scatter], ids=["transition", "scatter"])
@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_window_streams_varying_supports_like_a_long_fixed_rail(factors, fidelity):
    """12 m at 300 km/h over a stiffness transition (k_b x3, k_p x1.5 over 1.2 m at X = 29.5
    m) and over a lognormally scattered bed (k_b, k_p, m_s, c_b per sleeper) on the window of
    20 + 1 + 20 bays against the 60 m fixed rail with the same properties per sleeper:
    tests/test_window.py's criterion, the contact force within 1e-3 of the static load over
    the last 4 m, and each sleeper's envelope (ballast and rail-seat force extremes within
    1e-3 P, its lowest displacement within 1e-3 P / k_b) for the sleepers the wheel passes
    there. Measured: contact force 1.6e-5 P (transition) and 2.3e-5 P (scatter) on both
    paths, envelopes 3.2e-6 P. The varying bed excites the wheel (its force ranges over 9 % and
    11 % of P), and a window that kept its start properties misses it: 6 % and 18 % of P off
    on the linear path."""
    rw, rf, stretch = _pair(factors, fidelity)
    assert np.ptp(rf.normal_force[stretch]) > 0.02 * P_STATIC
    assert np.abs(rw.normal_force - rf.normal_force)[stretch].max() < 1e-3 * P_STATIC
    ew, ef = rw.sleeper_envelope(), rf.sleeper_envelope()
    passed = (ef.x >= STRETCH + D) & (ef.x <= rw.x_wheel[-1] - D)
    ef = ef[passed].set_index("x")
    ew = ew.set_index(np.round(ew.x, 9)).loc[np.round(ef.index, 9)]
    assert len(ef) >= 4
    for name in ("ballast_force_max", "ballast_force_min", "rail_seat_force_max",
                 "rail_seat_force_min"):
        assert np.abs(ew[name].to_numpy() - ef[name].to_numpy()).max() < 1e-3 * P_STATIC, name
    kb = tw.Scene.ballasted_track().supports.ballast_stiffness
    assert np.abs(ew.sleeper_z_min.to_numpy() - ef.sleeper_z_min.to_numpy()).max() < \
        1e-3 * P_STATIC / kb
    # the envelope sees the transition: the stiff side's sleepers carry more of the load
    if factors is _transition:
        assert ef.ballast_force_max.iloc[-1] > 1.2 * ef.ballast_force_max.iloc[0]


def _short(fidelity):
    scene = tw.Scene.ballasted_track(window=tw.Window(10, 10))
    return sim.plan_run(scene, V, x_start=6.1, x_end=10.1, n_elements=scene.rail.n_elements,
                        fidelity=fidelity)


@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_uniform_stream_is_the_unstreamed_window_bit_for_bit(fidelity):
    """A stream whose every sleeper equals the rail's supports changes nothing: the kernel
    rebuilds and refactorises only where a property changes, so the run is the window's
    without a stream bit for bit (and takes the same Newton iterations)."""
    plan = _short(fidelity)
    a = _run(plan)
    b = _run(_varied(_short(fidelity), lambda x: {"stiffness": np.ones_like(x)}))
    assert len(b.scene.support_positions) > 0
    for name in ("normal_force", "y_wheel", "y_contact", "x_wheel", "tangential_force"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    for name, arr in a.support_envelope.items():
        np.testing.assert_array_equal(arr, b.support_envelope[name])
    assert a.newton_iterations == b.newton_iterations


def test_streamed_run_is_deterministic():
    runs = [_run(_varied(_short("linear/hertz"), _scatter)) for _ in range(2)]
    np.testing.assert_array_equal(runs[0].normal_force, runs[1].normal_force)
    for name, arr in runs[0].support_envelope.items():
        np.testing.assert_array_equal(arr, runs[1].support_envelope[name])


def test_envelope_counts_every_sleeper_passed_once():
    """On the window the envelope holds each physical sleeper once, in the order of X, spaced
    by the bay: those of the start window and one per shift."""
    plan = _short("linear/hertz")
    r = _run(plan)
    df = r.sleeper_envelope()
    n_start = len(plan.scene.support_positions)
    shifts = round((df.x.iloc[-1] - df.x.iloc[0]) / D) + 1 - n_start
    assert shifts >= 6
    np.testing.assert_allclose(np.diff(df.x), D, rtol=1e-9)
    assert df.x.iloc[0] == pytest.approx(plan.window.origin + plan.scene.support_positions[0])


@pytest.mark.parametrize("bad, match", [
    (lambda s: setattr(s, "position", list(np.asarray(s.position) + 0.1)), "stream entry 0"),
    (lambda s: setattr(s, "position", s.position[:5]), "fewer than the window"),
    (lambda s: setattr(s, "sleeper_mass", []), "each property"),
    (lambda s: setattr(s, "ballast_stiffness", [-1.0] * len(s.position)), "ballast_stiffness"),
])
def test_kernel_refuses_a_stream_that_does_not_fit(bad, match):
    plan = _varied(_short("linear/hertz"), _scatter)
    stream = plan.window.supports
    bad(stream)
    plan.window.supports = stream
    with pytest.raises(ValueError, match=match):
        _run(plan)


def test_public_path_streams_a_transition_with_scatter():
    """Through trackwheel.simulate: Supports.transition (k_b 105 -> 315 MN/m over a linear
    1.2 m ramp at X = 29.5 m) with Supports.scattered (cv 0.3, tied to each sleeper's absolute
    index, so both rails see the same bed) on the window of 20 + 1 + 20 bays against the 60 m
    fixed rail: the run streams the sleepers it meets (one per shift beyond the start window's)
    and agrees with the fixed rail as the kernel-level test above asks, contact force and
    ballast-force envelopes within 1e-3 P over the last 4 m."""
    sup = tw.Scene.ballasted_track().supports.transition(
        29.5, ramp=1.2, shape="linear", ballast_stiffness=(105e6, 315e6)).scattered(0.3, seed=4)
    fixed = dc.replace(tw.Scene.ballasted_track(length=60.0), supports=sup)
    window = dc.replace(tw.Scene.ballasted_track(window=tw.Window(20, 20)), supports=sup)
    kw = dict(x_start=20.1, x_end=32.1, fidelity="linear/hertz", progress=False)
    pw = sim.plan_run(window, V, n_elements=window.rail.n_elements, **kw)
    stream = pw.window.supports
    assert len(stream.position) >= len(window.support_positions) + 20
    np.testing.assert_allclose(stream.ballast_stiffness,
                               sup.values(stream.position).ballast_stiffness, rtol=0)
    rf = tw.simulate(fixed, V, n_elements=fixed.rail.n_elements, **kw)
    rw = tw.simulate(window, V, n_elements=window.rail.n_elements, dt=rf.settings.dt, **kw)
    stretch = rw.x_wheel >= STRETCH
    assert np.ptp(rf.normal_force[stretch]) > 0.02 * P_STATIC
    assert np.abs(rw.normal_force - rf.normal_force)[stretch].max() < 1e-3 * P_STATIC
    ef = rf.sleeper_envelope()
    ef = ef[(ef.x >= STRETCH + D) & (ef.x <= rw.x_wheel[-1] - D)].set_index("x")
    ew = rw.sleeper_envelope()
    ew = ew.set_index(np.round(ew.x, 9)).loc[np.round(ef.index, 9)]
    for name in ("ballast_force_max", "ballast_force_min"):
        assert np.abs(ew[name].to_numpy() - ef[name].to_numpy()).max() < 1e-3 * P_STATIC

