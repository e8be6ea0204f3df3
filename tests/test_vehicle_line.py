"""A vehicle's quasi-static line (docs: Model § Outputs) on long fixed rails and on the travelling
window over supports that vary along X.

Checks: the full level's line on a long fixed rail, each bay of the rear wheel solved on a piece
of the rail that holds the vehicle and ``piece_bays`` bays either side, equals the whole rail's
line (the route it replaces, O(L^2) per passage) within PIECE_DECAY's budget, 1e-8 of the static
deflection, for a half car and a bogie on a uniform track and over a stiffness transition with
scatter; on a window over a transition the line is the window's own statics where the run's
window stands and follows a long fixed rail's statics to the window's truncation, where the
periodic mapping it replaced is far off; on a periodic track it equals that mapping to round-off;
it is bit-identical whatever was cached; ``analyse`` of a half car's run reports the same
quantities with it as with the whole rail's line. The pieces (a vehicle's and a single
wheel's) are corrected for the axial stretch of the rail between the rail's held near end
and the piece's, without which they drift from the whole rail as they go further along it.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel, statics
from trackwheel.study import static_line

#: PIECE_DECAY's budget for the line against the deflection (docs: Model § Outputs): each of the
#: vehicle's wheels loads the piece, and each wheel's bowl reaches the piece's rigid ends
#: damped to about PIECE_DECAY (1e-9) of its deflection.
BUDGET = 1e-8

VEHICLES = {"half car": tw.Vehicle.half_car, "bogie": tw.Vehicle.bogie}


def _transition(scene: tw.Scene, at: float) -> tw.Scene:
    """The scene with a cosine ballast-stiffness transition 50 -> 200 MN/m over 3 m at X = at
    and a lognormal scatter (cv 0.3) per sleeper on it."""
    sup = scene.supports.transition(at, ramp=3.0, shape="cosine",
                                    ballast_stiffness=(50e6, 200e6)).scattered(0.3, seed=1)
    return dc.replace(scene, supports=sup)


def _lines(scene: tw.Scene, x: np.ndarray, linear: bool = False) -> np.ndarray:
    """Every wheel's line (n, n_wheels) [m] at the reference positions x [m]."""
    ne = scene.rail.n_elements
    return np.array([static_line.vehicle_quasi_static_line(scene, ne, x, w, linear)[0]
                     for w in range(scene.active_vehicle.n_wheels)]).T


def _direct(scene: tw.Scene, x: np.ndarray) -> np.ndarray:
    """Every wheel's y_B (n, n_wheels) [m] from the vehicle's static solve on the whole rail at
    each reference position."""
    return np.array([statics.vehicle_static(scene, xi).y_contact for xi in x])


# --------------------------------------------------------------------------------------------
# the full level on a long fixed rail: pieces
@pytest.mark.parametrize("track", ["uniform", "transition"])
@pytest.mark.parametrize("vehicle", list(VEHICLES))
def test_vehicle_pieces_match_the_whole_rail(vehicle, track, monkeypatch):
    """A 72 m ballasted rail (120 bays); with the transition (under the vehicle's middle at
    X = 36 m) the softest bed reaches further, B = 33 bays, and the half car's piece is
    33 + 1 + 34 + 33 = 101 bays. Positions in short clusters: near the rail's start (a piece
    from the rail's end), mid-rail, in the last group solved on a piece and in the first
    solved on the whole rail (where a piece would reach the far end). Against the whole rail's
    series (the route it replaces, ``vehicle_piece_bays`` forced to 0) and against direct
    static solves on the whole rail, each within PIECE_DECAY's budget, 1e-8 of the deflection
    (measured <= 1.7e-10; without the pieces' axial correction up to 1.06e-8, see
    :func:`test_the_axial_correction_of_a_piece`)."""
    veh = VEHICLES[vehicle]()
    scene = dc.replace(tw.Scene.ballasted_track(length=72.0), vehicle=veh)
    if track == "transition":
        scene = _transition(scene, 36.0)
    ne = scene.rail.n_elements
    bays = static_line.vehicle_piece_bays(scene, ne)
    assert bays == (25 if track == "uniform" else 33)
    ahead = static_line._ahead(scene)
    d, span = scene.supports.spacing, veh.span[1] - veh.span[0]
    last_piece = 120 - ahead - bays - 1  # the last rear-wheel bay solved on a piece
    starts = (1.3, 36.0 - 0.5 * span, last_piece * d + 0.2, (last_piece + 1) * d + 0.2)
    for x0 in starts:
        x = x0 + np.array([0.0, 0.031, 0.077, 0.12])
        y = _lines(scene, x)
        ref = _direct(scene, x)
        deflection = np.max(np.abs(ref))
        assert np.max(np.abs(y - ref)) < BUDGET * deflection
        with monkeypatch.context() as m:
            m.setattr(static_line, "vehicle_piece_bays", lambda scene, n_elements: 0)
            whole = _lines(scene, x)
        assert np.max(np.abs(y - whole)) < BUDGET * deflection


@pytest.mark.parametrize("profile", ["smooth", "FRA class 5"])
@pytest.mark.parametrize("vehicle", list(VEHICLES))
def test_the_axial_correction_of_a_piece(vehicle, profile, monkeypatch):
    """The whole rail is held axially only at X = 0, a piece at its own near end X_0: the
    rail between carries the wheels' horizontal load on the rail (its supports act
    vertically; a rail profile's slope tilts the contact force without loading the rail
    axially, as the contact reads the profile at the place) and stretches by H X_0 / EA,
    which moves the rail beyond against the wheels. On a 199.8 m rail with the transition at
    X = 150 m and the vehicle's middle on it, smooth or with an FRA class 5 profile, the
    pieces with the first-order correction y - y_s H X_0 / EA are within 1e-8 of the
    deflection of direct static solves on the whole rail (measured 5.8e-10 / 4.4e-10 smooth,
    6.4e-10 / 9.2e-10 with the profile, bogie / half car) and without it not (measured
    1.3e-7 to 1.4e-7): the error the correction removes grows with X_0, not with the piece's
    width."""
    veh = VEHICLES[vehicle]()
    irr = (None if profile == "smooth" else
           tw.Irregularity.random(tw.spectra.fra(5), seed=0, wavelengths=(1.524, 50.0)))
    scene = _transition(dc.replace(tw.Scene.ballasted_track(length=199.8), vehicle=veh,
                                   irregularity=irr), 150.0)
    x = 150.0 - 0.5 * veh.span[1] + np.linspace(-2.0, 2.0, 9)
    ref = _direct(scene, x)
    deflection = np.max(np.abs(ref))
    static_line.vehicle_group_series.cache_clear()
    assert np.max(np.abs(_lines(scene, x) - ref)) < BUDGET * deflection
    static_line.vehicle_group_series.cache_clear()
    with monkeypatch.context() as m:
        m.setattr(static_line, "_axial_correction", lambda y, du, b, y_lin: y)
        assert np.max(np.abs(_lines(scene, x) - ref)) > BUDGET * deflection
    static_line.vehicle_group_series.cache_clear()


def test_the_axial_correction_of_a_single_wheels_piece(monkeypatch):
    """The same correction on a single wheel's pieces (``piece_bay_series``): on a 150 m rail
    with the transition at X = 64.5 m, the line against direct static solves on the whole
    rail within 1e-8 of the deflection (measured 6.9e-10), 1.9e-7 without it."""
    scene = _transition(tw.Scene.ballasted_track(length=150.0), 64.5)
    ne = scene.rail.n_elements
    x = np.array([63.5, 65.3, 67.8, 105.0])
    ref = tw.quasi_static(scene, x, n_elements=ne).y_contact
    deflection = np.max(np.abs(ref))
    static_line.piece_bay_series.cache_clear()
    y, _ = static_line.quasi_static_line(scene, ne, x)
    assert np.max(np.abs(y - ref)) < BUDGET * deflection
    static_line.piece_bay_series.cache_clear()
    with monkeypatch.context() as m:
        m.setattr(static_line, "_axial_correction", lambda y, du, b, y_lin: y)
        y, _ = static_line.quasi_static_line(scene, ne, x)
        assert np.max(np.abs(y - ref)) > BUDGET * deflection
    static_line.piece_bay_series.cache_clear()


def test_vehicle_piece_rules():
    """Pieces only where ``piece_bays`` allows them and the vehicle's piece is shorter than
    the rail: the half car (20 m, 34 bays ahead of its rear wheel's) needs 85 bays on the
    ballasted preset, so a 50.4 m rail (84 bays) keeps the whole rail; a window never has
    pieces (its line is the window's own)."""
    half = tw.Vehicle.half_car()
    for length, bays in ((50.4, 0), (51.6, 25), (72.0, 25)):
        scene = dc.replace(tw.Scene.ballasted_track(length=length), vehicle=half)
        assert static_line.vehicle_piece_bays(scene, scene.rail.n_elements) == bays
    win = dc.replace(tw.Scene.ballasted_track(length=90.0), vehicle=half).windowed(tw.Window())
    assert static_line.vehicle_piece_bays(win, win.rail.n_elements) == 0


def test_vehicle_pieces_are_bit_identical_whatever_was_cached():
    scene = dc.replace(tw.Scene.ballasted_track(length=36.0), vehicle=tw.Vehicle.bogie())
    x = np.linspace(9.0, 9.9, 11)
    static_line.vehicle_group_series.cache_clear()
    a = _lines(scene, x)
    static_line.vehicle_group_series.cache_clear()
    _lines(scene, np.linspace(8.0, 11.0, 40))
    b = _lines(scene, x)
    assert np.array_equal(a, b)


# --------------------------------------------------------------------------------------------
# the travelling window over supports that vary along X
@pytest.fixture(scope="module")
def windowed():
    """The ballasted preset under each vehicle on its default window (20 + 1 + ahead + 20
    bays) over a transition at X = 30 m with scatter, and the same track on a fixed 90 m rail."""
    out = {}
    for name, make in VEHICLES.items():
        fixed = _transition(dc.replace(tw.Scene.ballasted_track(length=90.0), vehicle=make()),
                            30.0)
        out[name] = fixed.windowed(tw.Window()), fixed
    return out


def _window_direct(scene: tw.Scene, x: np.ndarray, linear: bool) -> np.ndarray:
    """Every wheel's static y_B (n, n_wheels) [m] solved directly on the window's rail as the
    run has it with its rear wheel at x + rear: origin X_w = (floor((x + rear) / d) -
    bays_behind) d (the kernel's window follower, trackwheel.run.passage.window_params),
    supports the track's at X_w + x_j, the wheels at X - X_w. The linear track's by the
    routes the line does not take: each wheel's own line from a band solve
    (``_core.linear_static_line``) and its neighbours' loads through the receptance at 0 Hz
    (``_core.receptance``); the ANCF model's by the vehicle's static solve."""
    veh = scene.active_vehicle
    ne = scene.rail.n_elements
    d, nb = scene.supports.spacing, scene.window.bays_behind
    loads = veh.static_loads(scene.gravity)
    out = []
    for xi in x:
        origin = (np.floor((xi + veh.span[0]) / d + 1e-9) - nb) * d
        X = (xi + np.asarray(veh.positions) - origin).tolist()
        model = kernel.rail_model(scene, ne, support_origin=origin)
        if linear:
            beam = kernel.beam_params(scene)
            alpha = np.asarray(_core.receptance(model, beam, X, X, [0.0])).real.reshape(
                len(X), len(X))
            y = [_core.linear_static_line(model, beam, loads[i], [X[i]], 0,
                                          kernel.element_compliance(scene))[0]
                 - sum(loads[j] * alpha[j, i] for j in range(len(X)) if j != i)
                 for i in range(len(X))]
        else:
            contacts = []
            for w in veh.wheels:
                c = kernel.contact_params(scene)
                c.radius = w.radius
                contacts.append(c)
            y = [r["y_contact"] for r in _core.static_solve_wheels(
                model, kernel.static_wheels_params(scene), contacts, X)]
        out.append(y)
    return np.asarray(out)


@pytest.mark.parametrize("linear", [True, False], ids=["linear", "ancf"])
@pytest.mark.parametrize("vehicle", list(VEHICLES))
def test_window_vehicle_line_over_a_transition_is_the_windows_own_statics(windowed, vehicle,
                                                                         linear):
    """Group by group on the window's rail where the run's window stands: equal to a direct
    static solve there at reference positions that take the vehicle across the transition,
    within the line's budget, 1e-8 of the deflection (the series' interpolation error;
    measured <= 1e-12 linear, where the line is the degree-6 polynomial, and ~1e-10 ANCF)."""
    scene, _ = windowed[vehicle]
    span = scene.active_vehicle.span[1]
    x = np.sort(np.random.default_rng(3).uniform(26.0, 33.0, 24 if linear else 6)) - 0.5 * span
    y = _lines(scene, x, linear)
    ref = _window_direct(scene, x, linear)
    deflection = np.max(np.abs(ref))
    assert np.max(np.abs(y - ref)) < BUDGET * deflection


@pytest.mark.parametrize("linear", [True, False], ids=["linear", "ancf"])
@pytest.mark.parametrize("vehicle", list(VEHICLES))
def test_window_vehicle_line_follows_the_fixed_rail_and_the_periodic_one_did_not(
        windowed, vehicle, linear):
    """Across the transition the window's line is a long fixed rail's statics to the window's
    truncation (its rigid ends 20 bays = 12 m from the outermost wheels: measured 1.5e-8 of the
    deflection linear, 2.1e-8 ANCF; bound 1e-7), while the periodic mapping it replaced (the
    vehicle read in the window's own bay at the start's supports) is off by the change of the
    track's stiffness: measured 27 % (half car) and 51 % (bogie) of the deflection, asserted
    > 2 %."""
    scene, fixed = windowed[vehicle]
    span = scene.active_vehicle.span[1]
    x = (np.linspace(25.0, 35.0, 41) if linear else np.linspace(27.0, 33.0, 5)) - 0.5 * span
    y = _lines(scene, x, linear)
    ref = statics.linear_vehicle_line(fixed, x) if linear else _direct(fixed, x)
    deflection = np.max(np.abs(ref))
    assert np.max(np.abs(y - ref)) < 1e-7 * deflection
    if linear:
        old = statics.linear_vehicle_line(scene, static_line.window_reference(scene, x))
        assert np.max(np.abs(old - ref)) > 0.02 * deflection


@pytest.mark.parametrize("linear", [True, False], ids=["linear", "ancf"])
@pytest.mark.parametrize("vehicle", list(VEHICLES))
def test_window_vehicle_line_on_a_periodic_track_is_the_periodic_mapping(vehicle, linear,
                                                                         monkeypatch):
    """On a track periodic in its bay every window's rail is the start window's, so the
    window's own statics (forced) equal the periodic mapping (``window_reference``) to
    round-off (measured <= 7e-16 of the deflection; bound 1e-13), at positions inside the
    rear wheel's bays (at a bay's end the line steps by the window's truncation, 6e-10 of the
    deflection here, on either route: the run's window moves there)."""
    veh = VEHICLES[vehicle]()
    scene = dc.replace(tw.Scene.ballasted_track(length=90.0), vehicle=veh).windowed(tw.Window())
    d = scene.supports.spacing
    x = (31.0 + np.arange(4)[:, None] * d + np.linspace(0.02, 0.58, 9 if linear else 3)).ravel()
    old = _lines(scene, x, linear)
    monkeypatch.setattr(static_line, "_streams", lambda scene: True)
    new = _lines(scene, x, linear)
    assert np.max(np.abs(new - old)) < 1e-13 * np.max(np.abs(old))


def test_window_vehicle_line_is_bit_identical_whatever_was_cached(windowed):
    scene, _ = windowed["bogie"]
    x = np.linspace(28.0, 31.0, 57)
    static_line.vehicle_group_series.cache_clear()
    a = _lines(scene, x, True)
    static_line.vehicle_group_series.cache_clear()
    _lines(scene, np.linspace(20.0, 40.0, 500), True)
    b = _lines(scene, x, True)
    assert np.array_equal(a, b)


def test_a_linear_vehicle_run_on_a_window_over_a_transition_starts_on_its_line(windowed,
                                                                               monkeypatch):
    """A linear half car's run on the window starts in static equilibrium on the window's rail
    where it stands: every wheel's d(0) is 0 to round-off of its own line (measured
    <= 2.4e-14), with the rear wheel before, on and after the transition, where the periodic
    mapping put some wheel 100 % (the softer bed ahead), 32 % and 54 % of its line off."""
    scene, _ = windowed["half car"]
    for x0 in (8.3, 18.95, 31.4):
        r = tw.simulate(scene, tw.kmh(100), x_start=x0, distance=0.3, fidelity="linear/hertz",
                        progress=False)
        for w in range(r.n_wheels):
            a = tw.analyse(r, wheel=w, measure="run")
            assert abs(a.dynamic[0]) < 1e-9 * abs(a.y_qs[0])
        with monkeypatch.context() as m:
            m.setattr(static_line, "_streams", lambda scene: False)
            off = max(abs(a.dynamic[0] / a.y_qs[0]) for a in (
                tw.analyse(r, wheel=w, measure="run") for w in range(r.n_wheels)))
        assert off > 0.02


# --------------------------------------------------------------------------------------------
# analyse with the line on pieces
def test_analyse_of_a_half_car_on_a_long_rail_is_the_same_with_pieces(monkeypatch):
    """A full-level half car's run of 0.5 m on a 72 m rail (its default mesh, 8 elements a
    bay), analysed for each wheel with its line on pieces and on the whole rail (the route
    replaced): the line, the dynamic displacement d = y_B - y_qs and its amplitude within 1e-8
    of the deflection (the line's budget; measured <= 1.8e-11, 7.5e-10 before the pieces'
    axial correction), the main frequency within 1e-6 of itself (measured 1e-10), the
    estimates of the line's error both below 1e-8 of the deflection, the contact force the
    same (the run is the same)."""
    scene = dc.replace(tw.Scene.ballasted_track(length=72.0), vehicle=tw.Vehicle.half_car())
    r = tw.simulate(scene, tw.kmh(100), x_start=20.0, distance=0.5, fidelity="full",
                    progress=False)
    assert static_line.vehicle_piece_bays(scene, r.settings.n_elements) == 25
    new = [tw.analyse(r, wheel=w, measure="run") for w in range(r.n_wheels)]
    monkeypatch.setattr(static_line, "vehicle_piece_bays", lambda scene, n_elements: 0)
    old = [tw.analyse(r, wheel=w, measure="run") for w in range(r.n_wheels)]
    for a, b in zip(new, old):
        deflection = np.max(np.abs(b.y_qs))
        assert np.max(np.abs(a.y_qs - b.y_qs)) < BUDGET * deflection
        assert np.max(np.abs(a.dynamic - b.dynamic)) < BUDGET * deflection
        assert abs(a.amplitude - b.amplitude) < BUDGET * deflection
        assert a.main_frequency == pytest.approx(b.main_frequency, rel=1e-6)
        assert max(a.y_qs_error, b.y_qs_error) < BUDGET * deflection
        assert np.array_equal(a.normal_force, b.normal_force)
