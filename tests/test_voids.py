"""Voids (hanging sleepers) and tensionless ballast: the unilateral ballast of the layered
supports (docs: Model § Voids and unilateral ballast).

Sleeper j's ballast pushes only: F_b = max(0, k_b d + c_b d'), d = -z_j - g_j when d > 0, else 0.
The kernel keeps a per-sleeper open/closed state with exact Jacobians (Sleepers in
cpp/sleepers.hpp); these tests reach it through the kernel's SupportParams (``void_gap``,
``tensionless``), edited on the way from a scene to the kernel (the ``supports`` fixture).

Checks: g = 0 is the intact track bit for bit; a void deeper than any motion is the sleeper
without ballast (k_b = c_b = 0 there) to round-off; the iteration matrix with open and closed
sleepers (damped) against central differences; statics against an independent active-set
finite-element model written here; the track's weight closing a void (closed form); the energy
balance of an undamped run over a void; the full and linear levels agreeing over a void as well
as on the intact track; events counted; eigen and receptance linearised with the open sleepers
off their ballast.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest
from test_system import central_difference_error

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel

BALLASTED = tw.Scene.ballasted_track()  # 30 m, 200 elements, 49 sleepers at 0.6 m
N_SUP = len(BALLASTED.support_positions)
MID = N_SUP // 2  # sleeper 24 at X = 14.7 m
X_MID = BALLASTED.support_positions[MID]
KATO = tw.Scene.kato2005()
LAYERED_KATO = dc.replace(KATO, supports=dc.replace(KATO.supports, sleeper_mass=150.0,
                                                    ballast_stiffness=105e6))


@pytest.fixture
def supports(monkeypatch):
    """edit(f): every kernel rail built from now on has its SupportParams passed through f
    (f(s) edits s in place); the rail cache is cleared before and after."""
    original = _kernel.support_params

    def edit(f):
        def support_params(scene, *args, **kwargs):
            s = original(scene, *args, **kwargs)
            f(s)
            return s
        monkeypatch.setattr(_kernel, "support_params", support_params)
        _kernel.rail_model.cache_clear()

    yield edit
    _kernel.rail_model.cache_clear()


def void_at(gaps: dict, tensionless=False):
    """A SupportParams edit: void_gap g_j at the sleepers of ``gaps`` {j: g [m]}, 0 elsewhere."""
    def f(s):
        g = [0.0] * len(s.position)
        for j, v in gaps.items():
            g[j] = v
        s.void_gap = g
        s.tensionless = tensionless
    return f


def no_ballast_at(j):
    """A SupportParams edit: sleeper j without ballast (k_b = c_b = 0), the rest as given."""
    def f(s):
        kb, cb = list(s.ballast_stiffness), list(s.ballast_damping)
        kb[j] = cb[j] = 0.0
        s.ballast_stiffness, s.ballast_damping = kb, cb
    return f


RUN = {"x_start": X_MID - 1.2, "x_end": X_MID + 1.2, "dt": 2e-5}
FIELDS = ("normal_force", "y_contact", "y_wheel")


# ------------------------------------------------------------------ validation

@pytest.mark.parametrize("edit, match", [
    (lambda s: setattr(s, "void_gap", [0.0] * 3), "one entry per support"),
    (lambda s: setattr(s, "void_gap", [-1e-3] + [0.0] * (len(s.position) - 1)), "void_gap"),
    (lambda s: setattr(s, "void_gap", [np.nan] * len(s.position)), "void_gap"),
])
def test_bad_voids_are_named(supports, edit, match):
    supports(edit)
    with pytest.raises(ValueError, match=match):
        _kernel.rail_model(BALLASTED)


def test_voids_need_sleepers_and_a_pad_to_hang_on(supports):
    supports(void_at({2: 1e-3}))
    with pytest.raises(ValueError, match="need layered supports"):
        _kernel.rail_model(KATO)

    def padless(s):
        void_at({2: 1e-3})(s)
        k = list(s.stiffness)
        k[2] = 0.0
        s.stiffness = k
    supports(padless)
    with pytest.raises(ValueError, match="support 2: a sleeper that can lose its ballast"):
        _kernel.rail_model(LAYERED_KATO)


# ------------------------------------------------------------------ the limits g = 0, g -> inf

def test_zero_void_is_the_intact_track_bit_for_bit(supports):
    """void_gap = 0 everywhere (not tensionless) keeps the linear ballast's code and arithmetic:
    statics and runs on the full path and a linear level are identical to the last bit."""
    ref_static = tw.static(BALLASTED, X_MID)
    ref = {f: tw.simulate(BALLASTED, tw.kmh(200), fidelity=f, **RUN)
           for f in ("full", "linear/sprung")}
    supports(void_at({}))
    assert tw.static(BALLASTED, X_MID).y_contact == ref_static.y_contact
    for f, a in ref.items():
        b = tw.simulate(BALLASTED, tw.kmh(200), fidelity=f, **RUN)
        for name in FIELDS:
            np.testing.assert_array_equal(getattr(b, name), getattr(a, name))
        assert b.ballast_events == 0


def test_tensionless_ballast_that_stays_closed_is_the_intact_track(supports):
    """Tensionless ballast under gravity: every sleeper is pressed by the track's weight
    (1.8 kN each) beyond the uplift the wheel causes, so none opens (0 events) and the results
    are the intact track's up to the ballast force's other order of summation. Statically that
    is round-off: 1e-12 relative (measured ~1e-15). In a run, Newton stops each step within its
    tolerance (1e-11 m on the corrections, ~1e-2 N of contact force at ~1e9 N/m, 1.4e-7 of the
    load) from solutions whose residuals differ by round-off, so the runs agree to that bound:
    tolerance 1e-8 of the values (measured 1.1e-12)."""
    a_st = tw.static(BALLASTED, X_MID)
    a = tw.simulate(BALLASTED, tw.kmh(200), **RUN)
    supports(lambda s: setattr(s, "tensionless", True))
    b_st = tw.static(BALLASTED, X_MID)
    b = tw.simulate(BALLASTED, tw.kmh(200), **RUN)
    assert b.ballast_events == 0
    np.testing.assert_allclose(b_st.y_contact, a_st.y_contact, rtol=1e-12)
    np.testing.assert_allclose(b_st.ballast_force, a_st.ballast_force, rtol=1e-12)
    for name in FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        assert np.max(np.abs(y - x)) <= 1e-8 * np.max(np.abs(x)), name


@pytest.mark.parametrize("fidelity", ["full", "linear/hertz"])
def test_deep_void_is_the_sleeper_without_ballast(supports, fidelity):
    """A 10 cm void under sleeper 24 (deeper than any motion: the rail moves < 1 mm) keeps that
    sleeper open throughout, which is the same sleeper with k_b = c_b = 0 (the kernel takes a
    zero ballast per support). Both evaluate k_p (y - z) + c_p (y' - z') + 0 - m_s g and the
    same D_j, so the results agree to round-off: tolerance 1e-12 of the values (measured:
    identical)."""
    supports(no_ballast_at(MID))
    a_st = tw.static(BALLASTED, X_MID)
    a = tw.simulate(BALLASTED, tw.kmh(200), fidelity=fidelity, **RUN)
    supports(void_at({MID: 0.1}))
    b_st = tw.static(BALLASTED, X_MID)
    b = tw.simulate(BALLASTED, tw.kmh(200), fidelity=fidelity, **RUN)
    assert b.ballast_events == 0 and b.ballast_contact_time[MID] == 0.0
    assert b_st.ballast_force[MID] == 0.0
    np.testing.assert_allclose(b_st.y_contact, a_st.y_contact, rtol=1e-12)
    np.testing.assert_allclose(b_st.ballast_force, a_st.ballast_force, rtol=1e-12, atol=1e-9)
    for name in FIELDS:
        x, y = getattr(a, name), getattr(b, name)
        assert np.max(np.abs(y - x)) <= 1e-12 * np.max(np.abs(x)), name


# ------------------------------------------------------------------ the iteration matrix

def test_iteration_matrix_with_open_and_closed_sleepers_matches_central_differences(supports):
    """The generalized-alpha iteration matrix of a damped layered track (pad 2e4, ballast 5e4
    N s/m) with tensionless ballast and a 1 mm void under sleeper 3 (X = 2 m): the open sleeper
    has no k_b, c_b in its row, the closed ones have both (the force's damping term included).
    Column i of J against -(R(x + h e_i) - R(x - h e_i)) / 2h, as in test_system.py (h = 1e3
    m/s^2 moves a sleeper by ~3e-8 m, far from every threshold: the open sleeper hangs 0.9 mm
    above its bed, the closed ones are pressed ~1e-5 m into theirs, so no state flips between
    the probes). Tolerance 1e-6 of each column's largest entry, as there (measured 9.3e-9)."""
    supports(void_at({3: 1e-3}, tensionless=True))
    scene = dc.replace(LAYERED_KATO, supports=dc.replace(
        LAYERED_KATO.supports, damping=2e4, ballast_damping=5e4))
    model = _kernel.rail_model(scene, 20)
    contact = _kernel.contact_params(scene)
    d = _core.static_solve(model, _kernel.wheel_params(scene), contact, 1.3)
    closed = np.asarray(d["sleeper_closed"])
    assert not closed[3] and closed.sum() == len(closed) - 1
    w = _core.WheelState()
    w.y, w.s, w.thetadot = d["y_wheel"], d["contact_s"], tw.kmh(300) / scene.wheel.radius
    w.state = _core.SlipState.stick
    st = _core.SimState()
    st.e, st.edot, st.wheels = np.asarray(d["e"]), np.zeros_like(d["e"]), [w]
    st.z, st.zdot = np.asarray(d["sleeper_z"]), 1e-4 * np.linspace(-1.0, 1.0, len(closed))
    s = _core.SimSettings()
    s.speed, s.x_start, s.dt, s.t_end = tw.kmh(300), 1.3, 1e-5, 1e-5

    def R(x=None):
        return _core.testing.ga_probe(model, [_kernel.wheel_params(scene)], contact, s, st,
                                      1e-5, x)

    p0 = R()
    x0, J = p0["start"], p0["matrix"]
    nf, ns = model.n_free, len(closed)
    h = np.full(len(x0), 1e3)
    h[nf + 2] = 1.0  # lambda [N]
    err = central_difference_error(R, x0, J, h)
    assert np.max(err) < 1e-6, (int(np.argmax(err)), float(np.max(err)))
    # the open sleeper's diagonal lacks the closed ones' beta' h^2 k_b + gamma' h c_b
    dz = np.diag(J)[-ns:]
    assert dz[3] < dz[2] and np.isclose(dz[2], dz[4], rtol=1e-12)


# ------------------------------------------------------------------ statics

def active_set_fe(scene, load_x, load, gaps):
    """An independent static model of the layered track without gravity: Euler-Bernoulli beam
    (cubic Hermite elements on the scene's mesh, deflection w and slope per node, w = 0 at both
    ends), pads k_p from the rail to sleeper z_j, ballast k_b from z_j to the ground, unilateral
    under a void g_j > 0 (the force k_b (-z_j - g_j) while -z_j - g_j > 0, else none), the load
    P downwards at a node. Active set: solve in the present states, reset each state by the
    sign of -z_j - g_j, until none changes. Returns (w at the load [m], ballast forces [N])."""
    r, s = scene.rail, scene.supports
    ne, L = r.n_elements, r.length
    le, EI = L / ne, r.bending_stiffness
    pos = np.asarray(scene.support_positions)
    nr, ns = 2 * (ne + 1), len(pos)
    n = nr + ns
    ke = EI / le**3 * np.array([[12, 6 * le, -12, 6 * le],
                                [6 * le, 4 * le**2, -6 * le, 2 * le**2],
                                [-12, -6 * le, 12, -6 * le],
                                [6 * le, 2 * le**2, -6 * le, 4 * le**2]])
    K0 = np.zeros((n, n))
    for e in range(ne):
        K0[2 * e:2 * e + 4, 2 * e:2 * e + 4] += ke
    node = np.rint(pos / le).astype(int)
    assert np.allclose(node * le, pos)  # the supports sit on nodes
    for j in range(ns):
        a, z = 2 * node[j], nr + j
        K0[a, a] += s.stiffness
        K0[z, z] += s.stiffness
        K0[a, z] -= s.stiffness
        K0[z, a] -= s.stiffness
    f0 = np.zeros(n)
    f0[2 * int(round(load_x / le))] = -load
    free = np.ones(n, bool)
    free[[0, 2 * ne]] = False
    gaps = np.asarray(gaps, float)
    closed = np.ones(ns, bool)
    for _ in range(50):
        K, f = K0.copy(), f0.copy()
        for j in np.nonzero(closed)[0]:
            K[nr + j, nr + j] += s.ballast_stiffness
            f[nr + j] -= s.ballast_stiffness * gaps[j]  # k_b (-z - g): -k_b g on the right
        u = np.zeros(n)
        u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
        z = u[nr:]
        new = (-z - gaps > 0.0) | (gaps == 0.0)
        if np.array_equal(new, closed):
            break
        closed = new
    else:
        raise AssertionError("the active set did not settle")
    fb = np.where(closed, s.ballast_stiffness * (-z - gaps), 0.0)
    return u[2 * int(round(load_x / le))], fb


@pytest.mark.parametrize("gap", [2e-4, 2e-3])
def test_statics_of_a_voided_sleeper_against_an_active_set_fe(supports, gap):
    """The wheel over sleeper 24 with a void under it, gravity off: a 0.2 mm void closes under
    the load (the rail there sinks 0.5 mm), a 2 mm one stays open; against active_set_fe (the
    same mesh, its own active-set loop). The kernel's rail is the nonlinear ANCF cable under a
    wheel on its contact spring: its geometric terms are (y/L_e)^2 ~ 1e-5 and its contact point
    sits on the rail's normal through the wheel centre: their effects go as the rail's slope
    squared, ~1e-6 here. Tolerance 1e-5 relative on the rail deflection under the load and 1e-5
    of the load on the ballast forces of the sleeper and its four neighbours (measured 9e-8 and
    1.1e-7). The kernel and the FE agree on which sleepers carry the ballast."""
    scene = dc.replace(BALLASTED, rail_gravity=False)
    supports(void_at({MID: gap}))
    r = tw.static(scene, X_MID)
    y_fe, fb_fe = active_set_fe(scene, X_MID, scene.static_load, [gap if j == MID else 0.0
                                                                 for j in range(N_SUP)])
    assert (r.ballast_force[MID] > 0.0) == (gap < 5e-4) == (fb_fe[MID] > 0.0)
    np.testing.assert_allclose(r.y_contact, y_fe, rtol=1e-5)
    near = [MID - 2, MID - 1, MID, MID + 1, MID + 2]
    np.testing.assert_allclose(r.ballast_force[near], fb_fe[near], rtol=0,
                               atol=1e-5 * scene.static_load)


def test_without_gravity_and_wheel_a_voided_sleeper_hangs_in_place(supports):
    """Gravity off, no wheel: nothing loads the track, so the voided sleeper stays at z = 0
    with no ballast force, exactly (and the rail with it)."""
    supports(void_at({MID: 1e-3}))
    d = _core.testing.track_static(_kernel.rail_model(dc.replace(BALLASTED, rail_gravity=False)))
    assert np.all(np.asarray(d["sleeper_z"]) == 0.0)
    assert np.all(np.asarray(d["ballast_force"]) == 0.0)
    assert not d["sleeper_closed"][MID]


def weight_per_sleeper(scene):
    """The rail's weight over one bay and the sleeper's own [N]."""
    g = scene.gravity
    return scene.rail.mass_per_length * g * scene.supports.spacing, scene.supports.sleeper_mass * g


def test_the_tracks_weight_closes_a_uniform_void(supports):
    """A void g = 5 um under every sleeper, gravity on: the track sinks by g onto its bed and
    then compresses it as the intact track, so away from the rail's pinned ends each sleeper
    sits at z = -g - (W_r + W_s)/k_b and the rail at z - W_r/k_p (W_r the rail's weight over a
    bay, W_s the sleeper's). The ends' influence decays as exp(-beta x), beta ~ 1.5/m: at the
    middle third (>= 10 m from an end) it is < 1e-6; the ANCF rail's nonlinearity at these
    slopes is far smaller. Tolerance 1e-6 relative (measured 1.3e-7)."""
    g = 5e-6
    supports(void_at(dict.fromkeys(range(N_SUP), g)))
    model = _kernel.rail_model(BALLASTED)
    d = _core.testing.track_static(model)
    Wr, Ws = weight_per_sleeper(BALLASTED)
    kb, kp = BALLASTED.supports.ballast_stiffness, BALLASTED.supports.stiffness
    mid = slice(N_SUP // 3, 2 * N_SUP // 3)
    z = np.asarray(d["sleeper_z"])[mid]
    y = model.positions(np.asarray(d["e"]), list(BALLASTED.support_positions[mid]))[:, 1]
    assert all(d["sleeper_closed"])
    np.testing.assert_allclose(z, -g - (Wr + Ws) / kb, rtol=1e-6)
    np.testing.assert_allclose(y, z - Wr / kp, rtol=1e-6)
    np.testing.assert_allclose(np.asarray(d["ballast_force"])[mid], Wr + Ws, rtol=1e-6)


def test_the_tracks_weight_closes_part_of_a_void_under_one_sleeper(supports):
    """One sleeper over a void, gravity on. A 1 mm void: the sleeper hangs on its pad, which
    carries exactly its weight (z_j = y_j - W_s/k_p to round-off), sinking with the rail by
    part of the void; its neighbours take its load (their ballast force above the intact
    track's). A 1 um void, below the 17 um the weight sinks an intact sleeper: the sleeper
    reaches its bed and carries part of its share (0 < F_b < the intact F_b)."""
    intact = _core.testing.track_static(_kernel.rail_model(BALLASTED))
    Wr, Ws = weight_per_sleeper(BALLASTED)
    kp = BALLASTED.supports.stiffness
    supports(void_at({MID: 1e-3}))
    model = _kernel.rail_model(BALLASTED)
    d = _core.testing.track_static(model)
    z = d["sleeper_z"][MID]
    y = model.positions(np.asarray(d["e"]), [X_MID])[0, 1]
    assert not d["sleeper_closed"][MID] and d["ballast_force"][MID] == 0.0
    assert -1e-3 < z < intact["sleeper_z"][MID] < 0.0  # sunk further, the void still open
    np.testing.assert_allclose(z, y - Ws / kp, rtol=1e-9)
    assert d["ballast_force"][MID + 1] > intact["ballast_force"][MID + 1]
    supports(void_at({MID: 1e-6}))
    d = _core.testing.track_static(_kernel.rail_model(BALLASTED))
    assert d["sleeper_closed"][MID]
    assert 0.0 < d["ballast_force"][MID] < intact["ballast_force"][MID]


# ------------------------------------------------------------------ time domain

def test_full_and_linear_levels_agree_over_a_void_as_on_the_intact_track(supports):
    """A 200 km/h passage over sleeper 24 with a 0.3 mm void (it closes under the wheel and
    opens behind it: 2 events), on the full path and the linear level with the same (linear)
    contact law. Intact, the levels differ by 4e-6 of the static load in the contact force and
    1.6e-6 of max |y| in the rail under the wheel (measured); over the void by 1.5e-5 and 2e-5
    (the rail sags into the void: its slope, on which the full model's contact geometry and the
    ANCF rail's nonlinearity act, is larger). Both cases are held to one tolerance, 1e-4 of
    the load and of max |y| (test_paths_agree.py holds the intact paths to 1e-3 of the load).
    The two levels see the same events and each sleeper on its ballast for the same time."""
    def compare():
        a = tw.simulate(BALLASTED, tw.kmh(200), fidelity="full", **RUN)
        b = tw.simulate(BALLASTED, tw.kmh(200), fidelity="linear/sprung", **RUN)
        assert np.max(np.abs(b.normal_force - a.normal_force)) < 1e-4 * BALLASTED.static_load
        assert np.max(np.abs(b.y_contact - a.y_contact)) < 1e-4 * np.max(np.abs(a.y_contact))
        assert a.ballast_events == b.ballast_events
        np.testing.assert_array_equal(a.ballast_contact_time, b.ballast_contact_time)
        return a

    intact = compare()
    assert intact.ballast_events == 0
    supports(void_at({MID: 3e-4}))
    voided = compare()
    assert voided.ballast_events == 2  # closed under the wheel, open again behind it
    assert 0.0 < voided.ballast_contact_time[MID] < voided.ballast_contact_time[MID + 1]
    # the void is felt: the wheel rides 0.13 mm lower over it
    assert voided.y_contact.min() < intact.y_contact.min() - 1e-4


@pytest.mark.parametrize("integrator", ["generalized_alpha", "explicit"])
def test_energy_balance_over_a_void(supports, integrator):
    """Undamped layered supports (test_layered.py's energy balance) with a 0.12 mm void under
    sleeper 2 (X = 1.5 m), which the passing wheel closes: the unilateral spring stores
    (1/2) k_b max(-z - g, 0)^2, a potential with a continuous slope, so it is conservative and
    the total energy changes only by the driving reaction's work. Generalized-alpha with
    rho_inf = 1 (the trapezoidal rule) steps over the kink in the force with an O(h^2) error
    (measured 1.3e-8, 3.4e-9, 6.9e-10 of max |W| at dt = 5, 2.5, 1.25 us, as intact: 2.6e-9 at
    2.5 us); RK4 at 0.5 us. Tolerance 1e-6 of max |W|, as there."""
    supports(void_at({2: 1.2e-4}))
    v = tw.kmh(100)
    dt = 2.5e-6 if integrator == "generalized_alpha" else 5e-7
    r = tw.simulate(LAYERED_KATO, v, x_end=1.0, dt=dt, n_elements=20, rho_inf=1.0, energy=True,
                    integrator=integrator)
    assert r.ballast_events >= 1
    work = np.concatenate([[0.0], np.cumsum(0.5 * (r.reaction[1:] + r.reaction[:-1]) * v
                                            * np.diff(r.t))])
    assert np.max(np.abs(work)) > 1.0
    np.testing.assert_allclose(r.energy - r.energy[0], work, rtol=0,
                               atol=1e-6 * np.max(np.abs(work)))


# ------------------------------------------------------------------ eigen and receptance

def test_modes_and_receptance_drop_the_ballast_of_an_open_sleeper(supports):
    """Linearised about the track's static state under its weight: sleeper 3 over a 1 mm void
    hangs (open), so the modes and the receptance are those of the track with k_b = c_b = 0
    there (the same matrices: equal to round-off, tolerance 1e-10 relative); a 1 um void, which
    the weight closes, keeps the ballast: the intact track's. And the hanging sleeper is felt:
    the receptance above it at 10 Hz (quasi-static) is larger than the intact track's."""
    scene = dc.replace(LAYERED_KATO, supports=dc.replace(LAYERED_KATO.supports,
                                                         ballast_damping=4e4))
    freqs = [10.0, 150.0, 600.0]
    X = scene.support_positions[3]

    def linearised():
        return (tw.eigen(scene, [1.3], 6).frequencies,
                tw.receptance(scene, X, freqs))

    f_int, a_int = linearised()
    supports(no_ballast_at(3))
    f_nb, a_nb = linearised()
    supports(void_at({3: 1e-3}))
    f_v, a_v = linearised()
    np.testing.assert_allclose(f_v, f_nb, rtol=1e-10)
    np.testing.assert_allclose(a_v, a_nb, rtol=1e-10)
    assert abs(a_v[0]) > 1.05 * abs(a_int[0])
    supports(void_at({3: 1e-6}))
    f_c, a_c = linearised()
    np.testing.assert_allclose(f_c, f_int, rtol=1e-10)
    np.testing.assert_allclose(a_c, a_int, rtol=1e-10)


def test_tensionless_ballast_on_the_travelling_window():
    """Tensionless ballast (the same law at every sleeper) travels with the window: the states
    move with their sleepers at each shift (Sleepers::shift). Over 10.1 .. 16 m at 300 km/h the
    window sees the same open/closed events as the fixed 30 m rail and differs from it by what
    the window differs by on the intact track (5.2 % of the force's range, the fixed rail's
    ends and the window's; measured equal to 1e-5 of that range): tolerance that difference
    + 1e-3 of the range."""
    tl = dc.replace(BALLASTED, supports=dc.replace(BALLASTED.supports, ballast_tensionless=True))
    kw = {"x_start": 10.1, "x_end": 16.0, "dt": 2e-5, "progress": False,
          "fidelity": "linear/sprung"}

    def window_vs_fixed(scene):
        a = tw.simulate(scene, tw.kmh(300), **kw)
        b = tw.simulate(dc.replace(scene, window=tw.Window(10, 10)), tw.kmh(300), **kw)
        return a, b, np.max(np.abs(a.normal_force - b.normal_force)) / np.ptp(a.normal_force)

    _, _, intact = window_vs_fixed(BALLASTED)
    a, b, err = window_vs_fixed(tl)
    assert a.ballast_events == b.ballast_events > 0
    assert err < intact + 1e-3
