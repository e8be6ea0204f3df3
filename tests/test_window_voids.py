"""Voids (hanging sleepers) on the travelling window (docs: Model § The travelling window,
§ Voids and unilateral ballast): a void streams into the window like any support property and
stays with its physical sleeper as the window moves (the kernel shifts the sleepers' ballast
states with the state, streams the properties in, solves the rest again and lets the fresh
front sleeper join on or off its bed as it stands at that rest).

Checks, each against a long fixed rail with the same sleepers (the reference that needs no
window): a pair of hanging sleepers and a scattered bed with a transition and voids, on the
linear level and the full model (contact force, each sleeper's force envelope, the events and
each voided sleeper's gap closure and time on its bed); a sleeper that joins at the window's
front closed or open by its own gap at rest; a stream with a void field of zeros is the
unstreamed window bit for bit; the settlement loop with feedback on the window (a uniform
track settles uniformly; a transition settles as on the fixed rail).

The tolerances are those tests/test_window_stream.py holds the window to over varying
supports (contact force and envelope extremes within 1e-3 of the static load P over the
stretch the start's waves have left, displacements within 1e-3 P / k_b): a void changes what
the window carries, not how it travels.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw
from trackwheel.run import kernel
from trackwheel.run import simulate as sim

from test_window_stream import _short  # the short window run both files compare against

V = tw.kmh(300)
P = 70e3  #: the ballasted preset's static wheel load [N]
D = 0.6  #: its sleeper bay [m]
KB = tw.Scene.ballasted_track().supports.ballast_stiffness  #: [N/m]
#: where the start's waves have died out on both rails (tests/test_window.py)
STRETCH = 28.1
RUN = dict(x_start=20.1, x_end=32.1, progress=False)


def _pair(supports, fidelity):
    """(window run, fixed-rail run) over 12 m at 300 km/h with these supports: the window of
    20 + 1 + 20 bays and the 60 m fixed rail of tests/test_window.py, at one time step."""
    fixed = dc.replace(tw.Scene.ballasted_track(length=60.0), supports=supports)
    window = dc.replace(tw.Scene.ballasted_track(window=tw.Window(20, 20)), supports=supports)
    rf = tw.simulate(fixed, V, n_elements=fixed.rail.n_elements, fidelity=fidelity, **RUN)
    rw = tw.simulate(window, V, n_elements=window.rail.n_elements, fidelity=fidelity,
                     dt=rf.settings.dt, **RUN)
    np.testing.assert_array_equal(rw.x_wheel, rf.x_wheel)
    return rw, rf


def _envelopes(r):
    """The run's envelope with its kernel contact time per sleeper (``ct``), indexed by X."""
    df = r.sleeper_envelope()
    assert len(r.ballast_contact_time) == len(df)  # one per physical sleeper, in order of X
    df["ct"] = r.ballast_contact_time
    return df.set_index(np.round(df.x.to_numpy(), 9))


def _compare(rw, rf, voids):
    """The window against the fixed rail over the stretch: contact force, each sleeper's
    envelope the wheel passes there, and each voided sleeper's gap closure and time on its
    bed (the kernel's, counted per step: a state change one step apart moves it by dt)."""
    stretch = rw.x_wheel >= STRETCH
    assert np.abs(rw.normal_force - rf.normal_force)[stretch].max() < 1e-3 * P
    ef, ew = _envelopes(rf), _envelopes(rw)
    passed = ef.index[(ef.x >= STRETCH + D) & (ef.x <= rw.x_wheel[-1] - D)]
    assert len(passed) >= 4
    for name in ("ballast_force_max", "ballast_force_min", "rail_seat_force_max",
                 "rail_seat_force_min"):
        err = np.abs(ew.loc[passed, name] - ef.loc[passed, name]).max()
        assert err < 1e-3 * P, name
    assert np.abs(ew.loc[passed, "sleeper_z_min"] - ef.loc[passed, "sleeper_z_min"]).max() < \
        1e-3 * P / KB
    assert rw.ballast_events == rf.ballast_events
    dt = rf.settings.dt
    for x, gap in voids.items():
        x = round(x, 9)
        assert abs(ew.ct[x] - ef.ct[x]) <= dt, x
        closes = ef.sleeper_z_min[x] < -gap  # sank past its gap: the bed carried it
        assert (ef.ct[x] > 0.0) == closes and (ew.ct[x] > 0.0) == closes, x
        assert (ew.ballast_force_max[x] > 0.0) == closes, x
    return ew, ef


@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_window_over_hanging_sleepers_like_a_long_fixed_rail(fidelity):
    """Two neighbouring sleepers hang 0.3 mm above their bed (X = 30.0, 30.6 m): each closes
    under the wheel and opens behind it (4 events), carrying load for a fifth of the time the
    intact sleepers do; the wheel force dips and rises over them by 11 % of P. The window
    carries the voids with their sleepers as it moves and reproduces the fixed rail (measured:
    contact force 1.8e-5 P, envelopes 2.2e-6 P, each voided sleeper's time on its bed the same
    to the step)."""
    voids = {30.0: 3e-4, 30.6: 3e-4}
    sup = tw.Scene.ballasted_track().supports.hanging(list(voids), gap=list(voids.values()))
    rw, rf = _pair(sup, fidelity)
    assert rf.ballast_events == 4
    assert np.ptp(rf.normal_force[rw.x_wheel >= STRETCH]) > 0.05 * P
    ew, _ = _compare(rw, rf, voids)
    for x in voids:
        assert 0.0 < ew.ct[x] < 0.3 * ew.ct[round(x + 2 * D, 9)]


@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_window_over_a_scattered_bed_with_a_transition_and_voids(fidelity):
    """Supports.transition (k_b 105 -> 315 MN/m over 1.2 m at X = 29.5 m) with
    Supports.scattered (cv 0.3) and four voids: 0.5 mm at 14.4 m (in the start window, behind
    the wheel: it leaves the window untouched), 0.1 and 0.3 mm at 29.4 and 30.6 m (they close
    under the wheel) and 2 mm at 31.2 m (deeper than the rail sinks: it never closes, the
    wheel force drops by 75 % of P over it). The window against the fixed rail: measured
    contact force 2.0e-5 P (linear) and 3.3e-5 P (full), envelopes 4.2e-6 P, the closing
    sleepers' time on their bed the same to the step."""
    voids = {14.4: 5e-4, 29.4: 1e-4, 30.6: 3e-4, 31.2: 2e-3}
    sup = (tw.Scene.ballasted_track().supports
           .transition(29.5, ramp=1.2, shape="linear", ballast_stiffness=(105e6, 315e6))
           .scattered(0.3, seed=4).hanging(list(voids), gap=list(voids.values())))
    rw, rf = _pair(sup, fidelity)
    assert rf.ballast_events == 4
    ew, ef = _compare(rw, rf, {x: g for x, g in voids.items() if x > STRETCH})
    assert ew.ct[31.2] == 0.0 and ew.ct[29.4] > 0.0 and ew.ct[30.6] > 0.0
    # the sleeper that left behind the wheel hung all along: no load on either rail
    assert ew.ct[14.4] == ef.ct[14.4] == 0.0
    assert ew.ballast_force_max[14.4] == ef.ballast_force_max[14.4] == 0.0


def test_fresh_sleepers_join_on_or_off_their_bed_as_at_rest():
    """Sleepers that join the window at its front, far ahead of the wheel, take their state at
    the window's rest. At rest the track's and the sleeper's weight sink a sleeper on its bed
    by about 18 um (the fixed rail's: measured 19 um), so it closes a 2 um void (its bed
    carries it from the moment it joins) but not a 0.2 mm one (it hangs, no load), on the
    window as on the fixed rail, with no event from either. (Near its ends the window's rest is
    not the track's: the rail is held at its end, the front sleepers carry up to 20 % less
    than on the fixed rail; a void within a few um of closing may flip there, so the voids
    here keep a margin.)"""
    voids = {40.2: 2e-6, 40.8: 2e-4}
    sup = tw.Scene.ballasted_track().supports.hanging(list(voids), gap=list(voids.values()))
    rw, rf = _pair(sup, "linear/hertz")
    assert rw.ballast_events == rf.ballast_events == 0
    ef, ew = _envelopes(rf), _envelopes(rw)
    start_front = rw.x_wheel[0] + 20 * D + D  # beyond the start window: they joined later
    assert min(voids) > start_front
    dt = rf.settings.dt
    closed, hanging = 40.2, 40.8
    assert ef.sleeper_z_min[closed] < -voids[closed]
    assert abs(ef.ct[closed] - rf.t[-1]) <= dt
    assert 0.0 < ew.observed_time[closed] < ef.observed_time[closed]
    assert abs(ew.ct[closed] - ew.observed_time[closed]) <= dt
    assert ew.ballast_force_min[closed] > 0.0
    assert ew.ct[hanging] == ef.ct[hanging] == 0.0
    assert ew.ballast_force_max[hanging] == ef.ballast_force_max[hanging] == 0.0


@pytest.mark.parametrize("fidelity", ["linear/hertz", "full"])
def test_zero_voids_on_the_window_are_the_window_bit_for_bit(fidelity):
    """A stream whose every sleeper is the rail's with a void field of zeros: the window's
    supports take the field, its sleepers are set up unilateral (the steppers' unilateral
    code paths) but every ballast stays linear, so the run is the unstreamed window's bit for
    bit, Newton iterations included. Through the public path, a void of 0 m is no void."""
    a = sim.execute(_short(fidelity), False)
    plan = _short(fidelity)
    x = plan.window.origin + plan.scene.support_positions[0] + D * np.arange(
        len(plan.scene.support_positions) + 12)
    stream = kernel._supports_at(plan.scene, x)
    stream.void_gap = [0.0] * len(x)
    plan.window.supports = stream
    b = sim.execute(plan, False)
    for name in ("normal_force", "y_wheel", "y_contact", "x_wheel", "tangential_force"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    for name, arr in a.support_envelope.items():
        np.testing.assert_array_equal(arr, b.support_envelope[name])
    np.testing.assert_array_equal(a.ballast_contact_time, b.ballast_contact_time)
    assert a.newton_iterations == b.newton_iterations and b.ballast_events == 0
    scene = tw.Scene.ballasted_track(window=tw.Window(10, 10))
    kw = dict(x_start=6.1, x_end=10.1, fidelity=fidelity, progress=False)
    c = tw.simulate(scene, V, **kw)
    d = tw.simulate(dc.replace(scene, supports=scene.supports.hanging(9.0, gap=0.0)), V, **kw)
    np.testing.assert_array_equal(c.normal_force, d.normal_force)


@pytest.mark.parametrize("bad, match", [
    (lambda s: setattr(s, "void_gap", [-1e-3] * len(s.position)), "void_gap"),
    (lambda s: setattr(s, "void_gap", [0.0] * 3), "each property"),
    (lambda s: setattr(s, "tensionless", True), "tensionless"),
    (lambda s: (setattr(s, "void_gap", [1e-3] * len(s.position)),
                setattr(s, "stiffness", [0.0] * len(s.position))), "pad stiffness"),
])
def test_kernel_refuses_a_void_stream_that_does_not_fit(bad, match):
    plan = _short("linear/hertz")
    x = plan.window.origin + plan.scene.support_positions[0] + D * np.arange(
        len(plan.scene.support_positions) + 12)
    stream = kernel._supports_at(plan.scene, x)
    stream.void_gap = [0.0] * len(x)
    bad(stream)
    plan.window.supports = stream
    with pytest.raises(ValueError, match=match):
        sim.execute(plan, False)


def test_scene_places_a_window_void_at_any_sleeper_of_the_track():
    """On a window the rail is not the track: a void may stand at any of the track's sleepers
    (X = k d), not only at the window's own; off the grid it is refused."""
    scene = tw.Scene.ballasted_track(window=tw.Window(10, 10))
    far = dc.replace(scene, supports=scene.supports.hanging(300.0, gap=1e-3))
    assert far.supports.void(np.array([300.0]))[0] == 1e-3
    with pytest.raises(ValueError, match="no sleeper at X"):
        dc.replace(scene, supports=dc.replace(
            scene.supports, void=type(far.supports.void)((300.1,), (1e-3,))))


# ------------------------------------------------------------------ settlement on the window

def _settle(window: bool, transition: bool, stages: int):
    """The settlement of 10^3 passes of one wheel at 200 km/h with feedback over X = 5.1 ..
    31.1 m: on the 36 m fixed rail or the window of 20 + 1 + 20 bays; a uniform bed or a step
    of the ballast stiffness 50 -> 200 MN/m at X = 18 m."""
    base = tw.Scene.ballasted_track(36.0)
    sup = (base.supports.transition(18.0, ballast_stiffness=(50e6, 200e6)) if transition
           else base.supports)
    scene = (dc.replace(tw.Scene.ballasted_track(window=tw.Window(20, 20)), supports=sup)
             if window else dc.replace(base, supports=sup))
    return tw.settle(scene, tw.kmh(200), 10**3, stages=stages, feedback=True, x_start=5.1,
                     x_end=31.1, progress=False)


def test_settle_on_the_window_settles_a_uniform_track_uniformly():
    """A uniform track under one wheel settles uniformly on the window with the settled bed
    fed back: clear of the start's transient (12 m past the first settling sleeper, as the
    fixed rail's test in tests/test_settle_loop.py) the settlement's spread is below 1e-3 of
    its mean (measured 2.2e-4, as on the fixed rail)."""
    h = _settle(True, False, 3)
    s, x = h.settlement[-1], h.sleepers
    np.testing.assert_allclose(np.diff(x), D, rtol=1e-9)
    clear = x >= x[0] + 12.0
    assert clear.sum() >= 15
    assert np.ptp(s[clear]) < 1e-3 * s[clear].mean()


def test_settle_on_the_window_with_feedback_is_the_fixed_rails():
    """A stiffness step settled with feedback in 4 stages: the later stages run over the voids
    the settlement opened (up to 0.4 mm), which the window carries with their sleepers. Its
    peaks are the fixed rail's within 1e-3 P (the window's force tolerance) and so its
    settlement within 5e-3 (Varandas' settlement goes as F^1.6 and the peaks are about P/2:
    1.6 x 2e-3 = 3.2e-3, and the stages compound little); measured 6.6e-4 and 4.3e-4."""
    hf, hw = _settle(False, True, 4), _settle(True, True, 4)
    np.testing.assert_allclose(hw.sleepers, hf.sleepers, rtol=0, atol=1e-9)
    assert hw.voids[-1].max() > 1e-4
    assert np.abs(hw.peak_force - hf.peak_force).max() < 1e-3 * P
    np.testing.assert_allclose(hw.settlement[-1], hf.settlement[-1], rtol=5e-3)
