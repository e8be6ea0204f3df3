"""The quasi-static line ``analyse`` measures from (docs: Model § Outputs), on long rails and on
the travelling window over supports that vary along X.

Checks: the linear track's line from the selected inverse of K (the entries of K^-1 within its
band, O(1) per position) equals a band solve per position (the independent route it replaced)
to round-off on every kind of track; the selected inverse equals the dense inverse within the
band; on a window over a stiffness transition and a scattered bed the line is the window's own
statics where the run's window stands (a run starts on it: d(0) = 0), it follows a long fixed
rail's statics within the window's truncation, and the periodic mapping it replaced is far off
there; the line is bit-identical whatever was cached before.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel
from trackwheel.run.statics import linear_line_of, static_rail
from trackwheel.study import static_line

#: Round-off bound of the line against the deflection: the static flexibility s^T K^-1 s comes
#: from the same band LU by two routes (a solve per position, the Takahashi recurrence), each
#: backward stable, so they differ by a small multiple of cond(K) eps in the flexibility, and
#: the flexibility's error is damped into y by the own-weight part; measured <= 8.3e-15 on the
#: tracks below. 1e-12 leaves a margin of 100 and is 1e-4 of the line's documented error
#: (1e-8 of the deflection).
ROUND_OFF = 1e-12


def _transition(scene: tw.Scene, at: float) -> tw.Scene:
    """The scene with a cosine ballast-stiffness transition 50 -> 200 MN/m over 3 m at X = at
    and a lognormal scatter (cv 0.3) per sleeper on it."""
    sup = scene.supports.transition(at, ramp=3.0, shape="cosine",
                                    ballast_stiffness=(50e6, 200e6)).scattered(0.3, seed=1)
    return dc.replace(scene, supports=sup)


def _points(scene: tw.Scene, lo: float, hi: float, n: int = 301) -> np.ndarray:
    return np.linspace(lo, hi, n)


TRACKS = {
    "paper (single springs)": lambda: tw.Scene.kato2005(),
    "ballasted 60 m (pads, sleepers, ballast)": lambda: tw.Scene.ballasted_track(length=60.0),
    "ballasted, Timoshenko rail": lambda: dc.replace(
        tw.Scene.ballasted_track(length=30.0),
        rail=dc.replace(tw.Scene.ballasted_track(length=30.0).rail, beam="timoshenko")),
    "ballasted, transition and scatter": lambda: _transition(
        tw.Scene.ballasted_track(length=60.0), 30.0),
}


@pytest.mark.parametrize("name", list(TRACKS))
def test_selected_inverse_line_equals_a_solve_per_position(name):
    """y(X) = s . q_g - P s^T K^-1 s from the band of K^-1 against K^-1 s solved at each X
    (``_core.linear_static_line``, the line as it was computed before): equal to round-off,
    element compliance included, over the whole rail (its rigid ends too)."""
    scene = TRACKS[name]()
    ne = scene.rail.n_elements
    x = _points(scene, 0.0, scene.rail.length, 997)
    for compliance in (False, True):
        ref = np.asarray(_core.linear_static_line(
            kernel.rail_model(scene, ne), kernel.beam_params(scene), scene.static_load,
            x.tolist(), 0, compliance))
        got = np.asarray(_core.linear_static_line_selected(
            static_rail(scene, ne), kernel.beam_params(scene), scene.static_load, x.tolist(),
            compliance))
        deflection = np.max(np.abs(ref))
        assert np.max(np.abs(got - ref)) < ROUND_OFF * deflection


def test_flexibility_from_the_selected_inverse_is_the_receptance_at_0_hz():
    """s^T K^-1 s from the band of K^-1 (the line's load-proportional part: y(0) - y(1 N))
    against the track's receptance at 0 Hz (``_core.receptance``, the frequency-domain solve),
    at nodes and inside elements of the paper's rail (well conditioned: to 1e-10)."""
    scene = dc.replace(tw.Scene.kato2005(), rail=dc.replace(tw.Scene.kato2005().rail,
                                                            n_elements=10))
    model = static_rail(scene)
    beam = kernel.beam_params(scene)
    x = np.linspace(0.0, scene.rail.length, 41)
    flex = (np.asarray(_core.linear_static_line_selected(model, beam, 0.0, x.tolist()))
            - np.asarray(_core.linear_static_line_selected(model, beam, 1.0, x.tolist())))
    alpha = np.array([np.asarray(_core.receptance(model, beam, [xi], [xi], [0.0])).real.ravel()[0]
                      for xi in x])
    assert np.max(alpha) > 1e-9
    assert np.allclose(flex, alpha, rtol=1e-10, atol=1e-12 * np.max(alpha))


def test_a_unilateral_ballast_falls_back_to_the_active_set():
    """A tensionless bed has no superposition: the selected-inverse binding solves the active
    set per position, as linear_static_line does (equal exactly: the same solves)."""
    scene = tw.Scene.ballasted_track(length=18.0)
    scene = dc.replace(scene, supports=dc.replace(scene.supports, ballast_tensionless=True))
    x = np.linspace(6.0, 12.0, 25).tolist()
    ne = scene.rail.n_elements
    a = np.asarray(_core.linear_static_line(kernel.rail_model(scene, ne),
                                            kernel.beam_params(scene), scene.static_load, x, 0,
                                            False))
    b = np.asarray(_core.linear_static_line_selected(static_rail(scene, ne),
                                                     kernel.beam_params(scene),
                                                     scene.static_load, x, False))
    assert np.array_equal(a, b)


def test_linear_quasi_static_series_matches_direct_solves_on_a_long_rail():
    """analyse's line (the Chebyshev series of 8 points per element) on a 120 m ballasted rail,
    against direct static solves at random positions: within the documented 1e-8 of the
    deflection (the series is exact to round-off for the degree-6 polynomial it represents)."""
    scene = tw.Scene.ballasted_track(length=120.0)
    ne = scene.rail.n_elements
    x = np.sort(np.random.default_rng(5).uniform(10.0, 110.0, 200))
    y, err = static_line.quasi_static_line(scene, ne, x, linear=True)
    ref = np.asarray(_core.linear_static_line(kernel.rail_model(scene, ne),
                                              kernel.beam_params(scene), scene.static_load,
                                              x.tolist(), 0, kernel.element_compliance(scene)))
    deflection = np.max(np.abs(ref))
    assert err < 1e-8 * deflection
    assert np.max(np.abs(y - ref)) < 1e-8 * deflection


# --------------------------------------------------------------------------------------------
# the travelling window over supports that vary along X
@pytest.fixture(scope="module")
def windowed():
    """The ballasted preset on its default window (20 + 1 + 20 bays) over a transition at
    X = 30 m with scatter, and the same track on a fixed 90 m rail."""
    base = tw.Scene.ballasted_track(window=tw.Window())
    fixed = tw.Scene.ballasted_track(length=90.0)
    return _transition(base, 30.0), _transition(fixed, 30.0)


def _window_direct(scene: tw.Scene, x: np.ndarray, linear: bool) -> np.ndarray:
    """The static line at each X solved directly on the window's rail as the run has it with
    its wheel at X: origin X_w = (floor(X / d) - bays_behind) d, supports the track's at
    X_w + x_j, the wheel at X - X_w."""
    d, nb = scene.supports.spacing, scene.window.bays_behind
    out = []
    for xi in x:
        origin = (np.floor(xi / d + 1e-9) - nb) * d
        model = kernel.rail_model(scene, scene.rail.n_elements, support_origin=origin)
        if linear:
            out.append(_core.linear_static_line(model, kernel.beam_params(scene),
                                                scene.static_load, [xi - origin], 0,
                                                kernel.element_compliance(scene))[0])
        else:
            out.append(_core.static_solve(model, kernel.wheel_params(scene),
                                          kernel.contact_params(scene), xi - origin)
                       ["y_contact"])
    return np.asarray(out)


@pytest.mark.parametrize("linear", [True, False], ids=["linear", "ancf"])
def test_window_line_over_a_transition_is_the_windows_own_statics(windowed, linear):
    """Bay by bay on the window's rail where the run's window stands: equal to a direct static
    solve there at positions across the transition, within the documented 1e-8 of the
    deflection (measured: 3.7e-15 linear, 2.5e-10 ANCF, whose series estimates its own error
    at 3.1e-9 here: the nonlinear line is not exactly the degree-6 polynomial)."""
    scene, _ = windowed
    x = np.sort(np.random.default_rng(2).uniform(27.0, 33.0, 40 if linear else 12))
    y, err = static_line.quasi_static_line(scene, scene.rail.n_elements, x, linear=linear)
    ref = _window_direct(scene, x, linear)
    deflection = np.max(np.abs(ref))
    assert err < 1e-8 * deflection
    assert np.max(np.abs(y - ref)) < 1e-8 * deflection + 1e-12


def test_window_line_follows_the_fixed_rail_and_the_periodic_one_did_not(windowed):
    """Across the transition the window's line is a long fixed rail's statics to the window's
    truncation (its rigid ends 20 bays = 12 m from the wheel: measured 1.1e-8 of the
    deflection, bound 1e-7), while the periodic mapping it replaced (every X read in the
    window's own bay at the start's supports) is off by the change of the track's stiffness:
    measured 54 % of the deflection on this 4x stiffening, asserted > 2 %."""
    scene, fixed = windowed
    x = np.linspace(25.0, 35.0, 101)
    y, _ = static_line.quasi_static_line(scene, scene.rail.n_elements, x, linear=True)
    ref = tw.linear_quasi_static(fixed, x)
    deflection = np.max(np.abs(ref))
    assert np.max(np.abs(y - ref)) < 1e-7 * deflection
    old = tw.linear_quasi_static(scene, static_line.in_window(scene, x))
    assert np.max(np.abs(old - ref)) > 0.02 * deflection


def test_a_linear_window_run_over_a_transition_starts_on_its_line(windowed):
    """A linear run on the window starts in static equilibrium on the window's rail where it
    stands: its d(0) is 0 to round-off (measured <= 2e-14 of y_qs), at starts on either side
    of the transition and on it."""
    scene, _ = windowed
    for x0 in (27.3, 29.95, 31.4):
        r = tw.simulate(scene, tw.kmh(100), x_start=x0, distance=0.3, fidelity="linear/hertz",
                        progress=False)
        a = tw.analyse(r, measure="run")
        assert abs(a.dynamic[0]) < 1e-9 * abs(a.y_qs[0])


def test_window_line_is_bit_identical_whatever_was_cached(windowed):
    """The same X give the same bits whether the bays were solved for them alone, for a
    longer passage before, or with the cache cleared."""
    scene, _ = windowed
    ne = scene.rail.n_elements
    x = np.linspace(28.0, 31.0, 57)
    static_line.window_bay_series.cache_clear()
    a, _ = static_line.quasi_static_line(scene, ne, x, linear=True)
    static_line.window_bay_series.cache_clear()
    static_line.quasi_static_line(scene, ne, np.linspace(20.0, 40.0, 500), linear=True)
    b, _ = static_line.quasi_static_line(scene, ne, x, linear=True)
    assert np.array_equal(a, b)


def test_linear_line_at_a_position_does_not_depend_on_the_others():
    """Each position's value comes from the same band of K^-1 whatever else is asked for, so
    a series solved for a short range or inside a long one holds the same bits."""
    scene = tw.Scene.ballasted_track(length=30.0)
    model = static_rail(scene)
    x = np.linspace(5.0, 25.0, 401)
    alone = linear_line_of(scene, model, scene.static_load, x[100:110])
    inside = linear_line_of(scene, static_rail(scene), scene.static_load, x)
    assert np.array_equal(alone, inside[100:110])


# --------------------------------------------------------------------------------------------
# the ANCF line of a long fixed rail, bay by bay on pieces of the rail
def _long(scene_len: float, **kw) -> tw.Scene:
    return dc.replace(tw.Scene.ballasted_track(length=scene_len), **kw)


def test_ancf_line_on_pieces_matches_the_whole_rail(monkeypatch):
    """The full level's line on a long ballasted rail, each bay solved on the piece of the rail
    B bays either side (PIECE_DECAY: beta x = 20.7 beyond the bay), the last B bays on the
    whole rail, at positions in the first bay, the middle and the last bay: over an FRA class 5
    profile (the piece reads its part of the rail's spline; 36 m) and over a transition with
    scatter (48 m: the softest bed reaches further, B = 33). Against the whole rail's series
    (the route it replaces) within 1e-8 of the deflection (measured <= 4.5e-9), and against
    direct static solves within the series' own error estimate (the degree-8 series of the
    nonlinear line is 4e-8 off in the first 0.1 m of the soft bed, on either route)."""
    irr = tw.Irregularity.random(tw.spectra.fra(5), seed=0, wavelengths=(1.524, 50.0))
    for scene, bays in ((_long(36.0, irregularity=irr), 25),
                        (_transition(tw.Scene.ballasted_track(48.0), 24.0), 33)):
        ne = scene.rail.n_elements
        L = scene.rail.length
        assert static_line.piece_bays(scene, ne) == bays
        x = np.array([0.05, 0.41, 0.5 * L - 3.07, 0.5 * L - 0.3, 0.5 * L + 0.35, 0.5 * L + 2.6,
                      L - 0.8, L - 0.07])
        y, err = static_line.quasi_static_line(scene, ne, x)
        ref = tw.quasi_static(scene, x, n_elements=ne).y_contact
        deflection = np.max(np.abs(ref))
        assert np.max(np.abs(y - ref)) <= 1.5 * err
        with monkeypatch.context() as m:
            m.setattr(static_line, "piece_bays", lambda scene, n_elements: 0)
            whole, _ = static_line.quasi_static_line(scene, ne, x)
        assert np.max(np.abs(y - whole)) < 1e-8 * deflection


def test_short_rails_windows_and_numbered_supports_keep_the_whole_rail():
    """The paper's 5 m rail (so its numbers do not move), a travelling window, supports at
    given positions, one value per support or a pinned far end: no pieces."""
    kato = tw.Scene.kato2005()
    assert static_line.piece_bays(kato, 80) == 0
    long = tw.Scene.ballasted_track(length=60.0)
    ne = long.rail.n_elements
    assert static_line.piece_bays(long, ne) == 25
    assert static_line.piece_bays(tw.Scene.ballasted_track(window=tw.Window()), 164) == 0
    n = len(long.support_positions)
    for sup in (dc.replace(long.supports, positions=long.support_positions),
                dc.replace(long.supports, ballast_stiffness=(105e6,) * n)):
        assert static_line.piece_bays(dc.replace(long, supports=sup), ne) == 0
    pinned = dc.replace(long, rail=dc.replace(long.rail, far_end="pinned"))
    assert static_line.piece_bays(pinned, ne) == 0
    assert static_line.piece_bays(long, ne + 1) == 0  # not whole elements per bay


def test_ancf_pieces_are_bit_identical_whatever_was_cached():
    scene = tw.Scene.ballasted_track(length=36.0)
    ne = scene.rail.n_elements
    x = np.linspace(9.0, 10.5, 11)
    static_line.piece_bay_series.cache_clear()
    a, _ = static_line.quasi_static_line(scene, ne, x)
    static_line.piece_bay_series.cache_clear()
    static_line.quasi_static_line(scene, ne, np.linspace(8.0, 12.0, 40))
    b, _ = static_line.quasi_static_line(scene, ne, x)
    assert np.array_equal(a, b)


# --------------------------------------------------------------------------------------------
# a vehicle's line: the static flexibility between its wheels
def _receptance_0(scene: tw.Scene, model, xa, xb) -> np.ndarray:
    beam = kernel.beam_params(scene)
    return np.array([np.asarray(_core.receptance(model, beam, [b], [a], [0.0])).real.ravel()[0]
                     for a, b in zip(xa, xb)])


@pytest.mark.parametrize("name", ["paper (single springs)",
                                  "ballasted 60 m (pads, sleepers, ballast)",
                                  "ballasted, transition and scatter"])
def test_static_flexibility_between_wheels_is_the_receptance_at_0_hz(name):
    """s(X_a)^T K^-1 s(X_b) from the entries of K^-1 within the pairs' span against the
    receptance at 0 Hz (a pivoted complex band solve per force): pairs 0 .. 2.6 m apart, at
    nodes and inside elements, to round-off (1e-10 of the point flexibility)."""
    scene = TRACKS[name]()
    L = scene.rail.length
    rng = np.random.default_rng(4)
    xa = rng.uniform(0.1 * L, 0.6 * L, 20)
    xb = np.minimum(xa + rng.uniform(0.0, min(2.6, 0.3 * L), 20), L)
    model = static_rail(scene)
    got = np.asarray(_core.linear_static_flexibility(model, kernel.beam_params(scene),
                                                     xa.tolist(), xb.tolist()))
    ref = _receptance_0(scene, model, xa, xb)
    scale = np.max(np.abs(_receptance_0(scene, model, xa, xa)))
    assert np.max(np.abs(got - ref)) < 1e-10 * scale


def test_static_flexibility_too_wide_to_hold_solves_per_pair():
    """Pairs 30 m apart on a 500 m rail of 10 000 elements would need 2.4e7 entries of K^-1
    (more than kMaxInverseEntries): a band solve per pair instead, the same numbers."""
    base = tw.Scene.kato2005()
    scene = dc.replace(base, rail=dc.replace(base.rail, length=500.0, n_elements=10000))
    model = static_rail(scene)
    xa, xb = [200.01, 240.3], [230.02, 210.1]
    got = np.asarray(_core.linear_static_flexibility(model, kernel.beam_params(scene), xa, xb))
    ref = _receptance_0(scene, model, xa, xb)
    assert np.max(np.abs(got - ref)) < 1e-10 * np.max(np.abs(ref)) + 1e-22


def test_vehicle_line_on_a_long_rail_is_the_superposition():
    """A bogie's wheels' line on the linear 60 m ballasted track: each wheel's own line minus
    its neighbour's load times the static flexibility, against the receptance route it
    replaced, to round-off of the deflection."""
    scene = dc.replace(tw.Scene.ballasted_track(length=60.0), vehicle=tw.Vehicle.bogie())
    x_ref = np.linspace(10.0, 40.0, 61)
    y = tw.run.statics.linear_vehicle_line(scene, x_ref)
    veh = scene.active_vehicle
    loads = veh.static_loads(scene.gravity)
    model = static_rail(scene)
    X = x_ref[:, None] + np.asarray(veh.positions)[None, :]
    ref = np.empty_like(X)
    for i in range(veh.n_wheels):
        ref[:, i] = linear_line_of(scene, model, loads[i], X[:, i])
        for j in range(veh.n_wheels):
            if j != i:
                ref[:, i] -= loads[j] * _receptance_0(scene, model, X[:, i], X[:, j])
    assert np.max(np.abs(y - ref)) < ROUND_OFF * np.max(np.abs(ref))


@pytest.mark.parametrize("vehicle", [None, "bogie"])
def test_an_asymmetric_window_measures_from_its_own_bay(vehicle):
    """The run holds its (rear) wheel in the window's bay ``bays_behind``, not in the middle
    bay: a window of 10 bays behind and 30 ahead starts on its line (d(0) = 0 to round-off),
    where the middle bay (20), 6 m further from the rear end than the run's, gave d(0) =
    2.5e-4 of y_qs (measured)."""
    scene = tw.Scene.ballasted_track()
    if vehicle:
        scene = dc.replace(scene, vehicle=tw.Vehicle.bogie())
    scene = scene.windowed(tw.Window(bays_behind=10, bays_ahead=30))
    r = tw.simulate(scene, tw.kmh(100), x_start=30.1, distance=0.3, fidelity="linear/hertz",
                    progress=False)
    a = tw.analyse(r, measure="run", wheel=0 if vehicle else None)
    assert abs(a.dynamic[0]) < 1e-9 * abs(a.y_qs[0])
