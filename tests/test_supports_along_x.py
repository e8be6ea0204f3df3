"""Supports that vary along X (docs: Model § Supports varying along the track): one value per
support or a function of X for every support property, resolved and checked per support; a
uniform sequence is the scalar scene bit for bit; the places that need one value refuse a
varying track by name."""

from __future__ import annotations

import dataclasses as dc
import re

import numpy as np
import pytest

import trackwheel as tw

# a short ballasted track: 15 bays of 0.6 m, 2 elements per bay (fast statics and runs)
BALLASTED = tw.Scene.ballasted_track(9.0, elements_per_bay=2)
N_SLEEPERS = len(BALLASTED.support_positions)  # 14
KATO = tw.Scene.kato2005()


def with_supports(scene: tw.Scene, **changes) -> tw.Scene:
    return dc.replace(scene, supports=dc.replace(scene.supports, **changes))


def _arrays(r) -> dict:
    """Every array a result holds, by name."""
    names = [f.name for f in dc.fields(r)]
    return {n: getattr(r, n) for n in names if isinstance(getattr(r, n), np.ndarray)}


def assert_bit_identical(a, b):
    xa, xb = _arrays(a), _arrays(b)
    assert xa.keys() == xb.keys() and xa
    for name in xa:
        assert xa[name].dtype == xb[name].dtype and xa[name].shape == xb[name].shape, name
        assert xa[name].tobytes() == xb[name].tobytes(), f"{name} differs"


# ---------------------------------------------------------------------------------------------
# one value per support, bit for bit
def uniform_sequences(scene: tw.Scene) -> tw.Scene:
    """The scene with every support property given as a sequence of its one value."""
    s, n = scene.supports, len(scene.support_positions)
    names = ("stiffness", "damping") + (
        ("sleeper_mass", "ballast_stiffness", "ballast_damping", "void") if s.layered else ())
    seq = {name: [getattr(s, name)] * n for name in names}
    return with_supports(scene, **seq)


@pytest.mark.parametrize("scene", [KATO, BALLASTED], ids=["single", "layered"])
def test_a_uniform_sequence_is_the_scalar_scene_bit_for_bit_in_statics(scene):
    seq = uniform_sequences(scene)
    assert not seq.supports.uniform and scene.supports.uniform
    x = 0.5 * scene.rail.length + 0.1
    a, b = tw.static(scene, x), tw.static(seq, x)
    assert a.rail_coordinates.tobytes() == b.rail_coordinates.tobytes()
    assert (a.y_contact, a.normal_force) == (b.y_contact, b.normal_force)
    if scene.supports.layered:
        assert a.sleeper_z.tobytes() == b.sleeper_z.tobytes()
        assert a.ballast_force.tobytes() == b.ballast_force.tobytes()
    xs = np.linspace(x - 0.3, x + 0.3, 5)
    assert tw.linear_quasi_static(scene, xs).tobytes() == tw.linear_quasi_static(seq, xs).tobytes()


@pytest.mark.parametrize("fidelity", ["full", "linear/hertz"])
def test_a_uniform_sequence_is_the_scalar_scene_bit_for_bit_in_a_run(fidelity):
    seq = uniform_sequences(BALLASTED)
    kw = dict(x_start=4.2, x_end=4.5, dt=5e-5, fidelity=fidelity, progress=False)
    a, b = tw.simulate(BALLASTED, tw.kmh(200), **kw), tw.simulate(seq, tw.kmh(200), **kw)
    assert a.steps > 50
    assert_bit_identical(a, b)


def test_a_function_of_x_equals_its_values_per_support():
    """k_b(X) as a function and as the sequence of its values at the X_j: the same kernel input,
    the same statics bit for bit (the function is evaluated once, at the supports)."""
    def k_b(x):
        return 105e6 * (1.0 + 0.5 * np.sin(x))

    pos = np.asarray(BALLASTED.support_positions)
    fn = with_supports(BALLASTED, ballast_stiffness=k_b)
    seq = with_supports(BALLASTED, ballast_stiffness=list(k_b(pos)))
    assert np.array_equal(fn.support_values.ballast_stiffness, seq.support_values.ballast_stiffness)
    a, b = tw.static(fn, 4.5), tw.static(seq, 4.5)
    assert a.rail_coordinates.tobytes() == b.rail_coordinates.tobytes()
    assert fn.supports.value_at("ballast_stiffness", pos[3]) == k_b(pos[3])
    # a sequence is read back at its supports, and only there
    assert seq.supports.value_at("ballast_stiffness", pos[[2, 5]]).tolist() == k_b(pos[[2, 5]]
                                                                                   ).tolist()
    with pytest.raises(ValueError, match=r"given per support \(14 values\): X = 0.9 m is not"):
        seq.supports.value_at("ballast_stiffness", 0.9)


def test_a_stiffer_stretch_carries_more_and_sags_less():
    """Statics see each support's own values: with the ballast under one half of the track
    twice as stiff, the rail under the wheel sags less, the stiff half's ballast carries more of
    the load, and the sleeper next to the wheel on the stiff side more than its mirror image on
    the soft side (the wheel at the middle of the rail, between two sleepers; the ballast force
    positive in compression)."""
    pos = np.asarray(BALLASTED.support_positions)
    mid = 0.5 * BALLASTED.rail.length
    stiff_right = with_supports(BALLASTED, ballast_stiffness=list(np.where(pos > mid, 210e6,
                                                                           105e6)))
    a, b = tw.static(BALLASTED, mid), tw.static(stiff_right, mid)
    assert b.y_contact > a.y_contact  # less sag (y up)
    left, right = b.ballast_force[pos < mid][::-1], b.ballast_force[pos > mid]
    assert right[0] > left[0] and right.sum() > left.sum()


# ---------------------------------------------------------------------------------------------
# validation
@pytest.mark.parametrize("make, exc, words", [
    (lambda: tw.Supports(stiffness=[140e6, 140e6, -1.0]), ValueError,
     ["Supports.stiffness at support 2 (X = 1.5 m) = -1.0", "(0, 1e+14] N/m"]),
    (lambda: tw.Supports(spacing=0.6, sleeper_mass=150.0, ballast_stiffness=[1e8] * 12 + [-1.0]),
     ValueError, ["Supports.ballast_stiffness at support 12 (X = 7.8 m) = -1.0",
                  "(0, 1e+14] N/m"]),
    (lambda: tw.Supports(damping=[0.0, float("nan")]), ValueError,
     ["Supports.damping at support 1 (X = 1 m)", "not finite"]),
    (lambda: tw.Supports(stiffness=[1e8, 1e8], positions=(1.0, 2.0, 3.0)), ValueError,
     ["Supports.stiffness has 2 values for 3 supports"]),
    (lambda: tw.Scene(supports=tw.Supports(stiffness=[1e8] * 5)), ValueError,
     ["Supports.stiffness has 5 values for 9 supports"]),
    (lambda: tw.Scene(supports=tw.Supports(stiffness=lambda x: 140e6 - 40e6 * x)), ValueError,
     ["Supports.stiffness at support 6 (X = 3.5 m) = 0.0", "(0, 1e+14] N/m"]),
    (lambda: tw.Scene(supports=tw.Supports(stiffness=lambda x: np.ones(2))), ValueError,
     ["Supports.stiffness: the function of X returned shape (2,) for 9 positions"]),
    (lambda: tw.Supports(stiffness="soft"), TypeError, ["Supports.stiffness must be"]),
    (lambda: tw.Supports(stiffness=[[1e8, 1e8]]), ValueError, ["1-d sequence"]),
    (lambda: tw.Supports(void=1e-3), ValueError, ["Supports.void = 0.001 m needs a sleeper"]),
    (lambda: tw.Supports(ballast_tensionless=True), ValueError,
     ["ballast_tensionless = True needs a sleeper layer"]),
    (lambda: tw.Supports(ballast_damping=[0.0, 1.0]), ValueError,
     ["Supports.ballast_damping = (0.0, 1.0) N s/m needs a sleeper"]),
    (lambda: tw.Supports(spacing=0.6, sleeper_mass=150.0, ballast_stiffness=1e8, void=-1e-3),
     ValueError, ["Supports.void = -0.001 is outside the allowed range [0, 0.1] m"]),
    (lambda: tw.Supports(spacing=0.6, sleeper_mass=150.0, ballast_stiffness=1e8,
                         void=[0.0, 2e-3, 5.0]),
     ValueError, ["Supports.void at support 2 (X = 1.8 m) = 5.0", "[0, 0.1] m"]),
])
def test_bad_values_name_the_support_and_its_position(make, exc, words):
    with pytest.raises(exc) as info:
        make()
    for w in words:
        assert w in str(info.value), (w, str(info.value))


def test_a_function_is_checked_wherever_it_is_read():
    sup = tw.Supports(stiffness=lambda x: np.where(x > 100.0, -1.0, 140e6))
    tw.Scene(supports=sup)  # fine on the 5 m rail
    with pytest.raises(ValueError, match=re.escape("Supports.stiffness at X = 150 m = -1.0")):
        sup.value_at("stiffness", [50.0, 150.0])


def test_a_soft_function_warns_of_units_like_a_soft_value():
    with pytest.warns(tw.PlausibilityWarning, match="Supports.stiffness = 140 N/m"):
        tw.Scene(supports=tw.Supports(stiffness=lambda x: np.full_like(x, 140.0)))
    with pytest.warns(tw.PlausibilityWarning, match="Supports.ballast_stiffness = 140 N/m"):
        tw.Supports(spacing=0.6, sleeper_mass=150.0, ballast_stiffness=[1e8, 140.0])


# ---------------------------------------------------------------------------------------------
# equality, hashing, repr
def test_sequences_are_stored_as_tuples_and_compare_by_value():
    a = tw.Supports(stiffness=np.array([1e8, 2e8]), positions=(1.0, 2.0))
    b = tw.Supports(stiffness=[1e8, 2e8], positions=(1.0, 2.0))
    assert a.stiffness == (1e8, 2e8) and a == b and hash(a) == hash(b)
    assert tw.Supports(stiffness=np.float64(1e8)) == tw.Supports(stiffness=1e8)


def test_a_function_is_equal_to_itself_only_and_prints_by_name():
    def k(x):
        return np.full_like(x, 1e8)

    a, b = tw.Supports(stiffness=k), tw.Supports(stiffness=k)
    assert a == b and hash(a) == hash(b)
    assert a != tw.Supports(stiffness=lambda x: k(x))
    text = repr(a)
    assert "stiffness=<function test_supports_along_x." in text and "k>" in text
    assert " at 0x" not in text  # no memory address: the text is stable


def test_recipes_compare_and_print_by_value():
    s = BALLASTED.supports
    a = s.transition(4.5, ramp=1.2, shape="cosine", ballast_stiffness=(50e6, 200e6))
    b = s.transition(4.5, ramp=1.2, shape="cosine", ballast_stiffness=(50e6, 200e6))
    assert a == b and hash(a) == hash(b)
    assert ("ballast_stiffness=Transition(before=50000000.0, after=200000000.0, at=4.5, "
            "ramp=1.2, shape='cosine')") in repr(a)
    assert eval(repr(a.ballast_stiffness), vars(tw)) == a.ballast_stiffness
    d = dc.asdict(a)["ballast_stiffness"]
    assert d == {"before": 50e6, "after": 200e6, "at": 4.5, "ramp": 1.2, "shape": "cosine",
                 "kind": "transition"}


# ---------------------------------------------------------------------------------------------
# where one value is needed
def test_uniform_and_static_stiffness():
    assert KATO.supports.uniform and KATO.supports.static_stiffness == 140e6
    varying = tw.Supports(stiffness=[1e8, 2e8], positions=(1.0, 2.0))
    assert not varying.uniform
    with pytest.raises(ValueError, match=r"Supports.static_stiffness is one value only .*"
                                         r"Supports.stiffness varies along X"):
        varying.static_stiffness
    # a damping that varies leaves the static stiffness one value
    assert tw.Supports(damping=[0.0, 1e3], positions=(1.0, 2.0)).static_stiffness == 140e6
    vals = varying.values((1.0, 2.0))
    assert vals.static_stiffness.tolist() == [1e8, 2e8] and not vals.layered


def test_the_periodic_level_refuses_supports_that_vary():
    scene = with_supports(BALLASTED, ballast_stiffness=[105e6] * N_SLEEPERS)
    with pytest.raises(ValueError, match="the periodic level needs supports that repeat every "
                                         "bay; Supports.ballast_stiffness varies along X"):
        tw.periodic_response(scene, tw.kmh(200))


def test_the_window_refuses_per_support_sequences():
    """The window streams the track's sleepers in (tests/test_window_stream.py): a function of
    X is taken, a sequence over the rail's supports is refused."""
    scene = tw.Scene.ballasted_track(window=tw.Window(bays_behind=4, bays_ahead=4))
    with_supports(scene, ballast_stiffness=lambda x: np.full_like(x, 105e6))
    n = len(scene.support_positions)
    with pytest.raises(ValueError, match="Scene.window takes each support property as one "
                                         "value or a function of X.*ballast_stiffness is a "
                                         "per-support sequence"):
        with_supports(scene, ballast_stiffness=[105e6] * n)


def test_voids_reach_the_kernels_unilateral_ballast():
    """Each form of a void, and tensionless ballast, reaches the kernel (its physics:
    tests/test_voids.py): a ballast that pushes only never pulls, the hanging sleeper carries
    no ballast force, and void = 0 is the intact track bit for bit."""
    for sup in (dc.replace(BALLASTED.supports, void=1e-3),
                dc.replace(BALLASTED.supports, ballast_tensionless=True)):
        st = tw.static(dc.replace(BALLASTED, supports=sup), 4.5)
        assert np.all(st.ballast_force >= 0.0)
    hanging = BALLASTED.supports.hanging(4.5, gap=1e-3)
    hung = tw.static(dc.replace(BALLASTED, supports=hanging), 4.5)
    j = int(np.argmax(hanging.values(np.asarray(BALLASTED.support_positions)).void))
    assert hung.ballast_force[j] == 0.0
    zero = with_supports(BALLASTED, void=[0.0] * N_SLEEPERS)
    assert tw.static(zero, 4.5).y_contact == tw.static(BALLASTED, 4.5).y_contact


def test_the_sag_check_takes_the_softest_support():
    """The construction-time sag check estimates a track made of the softest support, and names
    it (a 30 m rail, which cannot bridge its length, with one sleeper on 2 kN/m of ballast: a
    slip of units, which warns too)."""
    long = tw.Scene.ballasted_track()
    k_b = [105e6] * 49
    k_b[20] = 2e3
    with pytest.raises(ValueError, match=r"Supports.stiffness = 1.8e\+08 N/m on Supports."
                                         r"ballast_stiffness = 2000 N/m every 0.6 m at support "
                                         r"20 \(X = 12.6 m\)"), pytest.warns(
            tw.PlausibilityWarning, match="Supports.ballast_stiffness = 2000 N/m"):
        with_supports(long, ballast_stiffness=k_b)


def test_a_sweep_keeps_a_stiffness_that_varies_and_tabulates_functions(tmp_path):
    """The sweep's stiffness axis defaults to the scene's own supports (column NaN); a function
    of X enters the case as its values at the supports (stored by value, picklable)."""
    scene = with_supports(KATO, damping=2e4, stiffness=lambda x: 140e6 + 1e6 * x)
    kw = dict(x_start=0.25, x_end=0.5, dt=2e-5, max_workers=1, progress=False)
    df = tw.sweep(scene, [tw.kmh(100)], store=tmp_path, **kw)
    assert np.isnan(df["support_stiffness_N_m"].iloc[0]) and df["error"].iloc[0] == ""
    direct = tw.simulate(scene, tw.kmh(100), x_start=0.25, x_end=0.5, dt=2e-5, progress=False)
    assert df["amplitude_m"].iloc[0] == tw.analyse(direct).amplitude
    [record] = list(tmp_path.glob("case-*.json"))
    assert '"stiffness": [' in record.read_text()


def test_the_command_line_table_says_along_x_for_a_stiffness_that_varies(tmp_path, capsys):
    """The CLI's sweep table prints "along X", not the column's NaN, for the scene's own
    supports, and the largest ballast force (kN) and its X when the sweep measured one."""
    from trackwheel.cli.commands.sweep import _print_sweep

    base = tw.Scene.ballasted_track(12.0)
    scene = dc.replace(base, supports=base.supports.transition(
        6.0, stiffness=(120e6, 180e6), ballast_stiffness=(50e6, 200e6)))
    df = tw.sweep(scene, [tw.kmh(100)], store=tmp_path, max_workers=1, progress=False,
                  fidelity="linear/hertz")
    _print_sweep(df, tmp_path, "smooth")
    out = capsys.readouterr().out
    header, row = out.splitlines()[1:3]
    assert "along X" in row and "nan" not in row
    assert "max F_b [kN]" in header
    assert f"{df['max_ballast_force_N'].iloc[0] / 1e3:.2f}" in row


# ---------------------------------------------------------------------------------------------
# statics of a stiffness step against an independent linear finite-element track
def fe_track(scene: tw.Scene, x_load: float, load: float, *, max_element: float = 0.075):
    """The scene's track as a linear Euler-Bernoulli finite-element model written here: Hermite
    beam elements (nodes at the rail's ends, every support and the load, and no element longer
    than ``max_element``), the rail pinned at both ends, a pad spring from the rail to each
    sleeper's own DOF z_j, the sleeper on its ballast to the ground; the rail's weight as
    consistent nodal loads and the sleepers' weights (``Scene.rail_gravity``), ``load`` [N]
    down at ``x_load`` [m]. Point forces at nodes make the exact solution cubic between nodes,
    so these elements are exact. A sleeper with a void g_j (or every sleeper with tensionless
    ballast) rests on its ballast only while it is pressed into it, delta_j = -z_j - g_j > 0
    (the others keep the linear ballast): an active-set iteration (the ballast force k_b delta_j on the closed sleepers) until the
    set repeats. Returns (nodes [m], rail deflection w at the nodes [m], ballast forces [N],
    positive in compression)."""
    rail, sv = scene.rail, scene.support_values
    L, EI = rail.length, rail.bending_stiffness
    g = scene.gravity if scene.rail_gravity else 0.0
    q = rail.mass_per_length * g
    # a load within a micrometre of a support goes onto the support's node (an element that
    # short would ruin the conditioning; the deflection moves by the slope times 1e-6 m, ~1e-10)
    near = np.abs(sv.position - x_load) < 1e-6
    x_load = float(sv.position[near][0]) if near.any() else x_load
    keys = np.concatenate([[0.0, L], sv.position, [x_load]])
    grid = np.linspace(0.0, L, int(np.ceil(L / max_element)) + 1)
    # no grid node within 1 mm of a key node (a tiny element ruins the conditioning)
    grid = grid[np.min(np.abs(grid[:, None] - keys[None, :]), axis=1) > 1e-3]
    nodes = np.unique(np.concatenate([grid, keys]))
    n, ns = nodes.size, sv.position.size
    K, f = np.zeros((2 * n + ns, 2 * n + ns)), np.zeros(2 * n + ns)
    for e, le in enumerate(np.diff(nodes)):
        a, b, c = 6 * le, 4 * le**2, 2 * le**2
        k = EI / le**3 * np.array([[12, a, -12, a], [a, b, -a, c], [-12, -a, 12, -a],
                                   [a, c, -a, b]])
        dofs = np.arange(2 * e, 2 * e + 4)
        K[np.ix_(dofs, dofs)] += k
        f[dofs] -= q * np.array([le / 2, le**2 / 12, le / 2, -le**2 / 12])
    rail_dof = 2 * np.searchsorted(nodes, sv.position)
    z = 2 * n + np.arange(ns)
    kp = sv.stiffness
    K[rail_dof, rail_dof] += kp
    K[z, z] += kp
    K[rail_dof, z] -= kp
    K[z, rail_dof] -= kp
    f[z] -= sv.sleeper_mass * g
    f[2 * np.searchsorted(nodes, x_load)] -= load
    free = np.setdiff1d(np.arange(2 * n + ns), [0, 2 * (n - 1)])
    gap = sv.void
    # the unilateral sleepers: every one with tensionless ballast, else those over a void (a
    # sleeper with g_j = 0 keeps the linear ballast, which also pulls)
    unilateral = np.full(ns, True) if sv.ballast_tensionless else gap > 0.0
    closed = np.ones(ns, bool)
    for _ in range(ns + 2):
        Kc, fc = K.copy(), f.copy()
        Kc[z[closed], z[closed]] += sv.ballast_stiffness[closed]
        fc[z[closed]] -= sv.ballast_stiffness[closed] * gap[closed]
        u = np.zeros(2 * n + ns)
        u[free] = np.linalg.solve(Kc[np.ix_(free, free)], fc[free])
        delta = -u[z] - gap
        new = (delta > 0.0) | ~unilateral
        if np.array_equal(new, closed):
            break
        closed = new
    else:
        raise AssertionError("the active set did not settle")
    force = np.where(closed, sv.ballast_stiffness * delta, 0.0)
    return nodes, u[:2 * n:2], force


LONG = tw.Scene.ballasted_track(30.0, elements_per_bay=4)


@pytest.mark.parametrize("gravity", [True, False], ids=["gravity", "no_gravity"])
@pytest.mark.parametrize("k_b", [(60e6, 200e6), (200e6, 60e6)], ids=["soft_to_stiff",
                                                                      "stiff_to_soft"])
def test_statics_of_a_stiffness_step_match_an_independent_finite_element_track(
        k_b, gravity, validation):
    """A ballast stiffness step at the middle of a bay (X0 = 15.3 m, sleepers at 15.0 and
    15.6 m) of the ballasted track, the wheel resting on it, against :func:`fe_track` loaded by
    the kernel's contact force at the kernel's contact point (which sits rho0 theta off the
    wheel centre on the sloping rail): the deflection under the load and every sleeper's ballast
    force. The two differ by the ANCF rail's geometric nonlinearity only, of order theta^2 with
    slopes theta ~ 3e-4, ~1e-7 (measured 7e-8 and 6e-8): tolerance 1e-6 of the deflection
    under the load and of the largest ballast force. Gravity off: the wheel load P = F alone."""
    scene = dc.replace(LONG, supports=LONG.supports.transition(15.3, ballast_stiffness=k_b))
    if not gravity:
        scene = dc.replace(scene, gravity=0.0, rail_gravity=False,
                           wheel=dc.replace(scene.wheel, load=70e3))
    st = tw.static(scene, 15.3)
    nodes, w, fb = fe_track(scene, st.contact_s, st.normal_force)
    w_load = w[np.searchsorted(nodes, st.contact_s)]
    err_w = abs(st.y_contact / w_load - 1.0)
    err_f = np.max(np.abs(st.ballast_force - fb)) / np.max(np.abs(fb))
    assert err_w < 1e-6 and err_f < 1e-6
    # the step is there: the stiff side's sleeper next to the load carries more
    pos = np.asarray(scene.support_positions)
    before, after = fb[np.isclose(pos, 15.0)][0], fb[np.isclose(pos, 15.6)][0]
    assert (after > before) == (k_b[1] > k_b[0])
    if gravity and k_b[0] < k_b[1]:
        validation.record(
            "statics.stiffness_step_fe", level="statics", kind="path agreement",
            quantity="ballasted track, ballast stiffness step 60 -> 200 MN/m mid-bay, wheel on "
                     "it (gravity on): deflection under the wheel and every ballast force",
            reference="linear Euler-Bernoulli FE track (pads, sleepers, ballast) written in the "
                      "test, dense solve",
            measured=max(err_w, err_f), tolerance=1e-6)


def test_statics_of_a_voided_sleeper_match_an_independent_finite_element_track():
    """A sleeper hanging 0.5 mm over its ballast next to the wheel, against :func:`fe_track`'s
    active set (docs: Model § Supports varying along the track): tolerance as for the
    stiffness step."""
    scene = dc.replace(LONG, supports=LONG.supports.hanging(15.6, gap=5e-4))
    st = tw.static(scene, 15.3)
    nodes, w, fb = fe_track(scene, st.contact_s, st.normal_force)
    assert abs(st.y_contact / w[np.searchsorted(nodes, st.contact_s)] - 1.0) < 1e-6
    assert np.max(np.abs(st.ballast_force - fb)) < 1e-6 * np.max(np.abs(fb))


@pytest.mark.parametrize("x_wheel", [13.8, 14.4, 15.0])
def test_statics_of_a_settled_bed_with_many_hanging_neighbours_match_the_finite_elements(x_wheel):
    """A settled transition (60 -> 200 MN/m at 10.5 m): 0.04-0.17 mm voids under every sleeper
    around the wheel (110 kN), deeper than the unloaded track's sag, so that from rest every
    sleeper under the wheel hangs; the solver must find the ones the load closes (from rest,
    the first correction carried the rail on no ballast there and lost the wheel: the closed
    start, statics.cpp). Against :func:`fe_track`'s active set, tolerance as for one voided
    sleeper."""
    base = tw.Scene.ballasted_track(21.0)
    voids = np.r_[np.full(15, 0.045), 0.039, 0.0, 0.17, 0.117, np.full(15, 0.115)] * 1e-3
    scene = dc.replace(base, wheel=dc.replace(base.wheel, load=110e3), supports=dc.replace(
        base.supports.transition(10.5, ballast_stiffness=(60e6, 200e6)), void=tuple(voids)))
    st = tw.static(scene, x_wheel)
    nodes, w, fb = fe_track(scene, st.contact_s, st.normal_force)
    at = np.argmin(np.abs(nodes - st.contact_s))
    assert abs(st.y_contact / w[at] - 1.0) < 1e-6
    assert np.max(np.abs(st.ballast_force - fb)) < 1e-6 * np.max(np.abs(fb))
    assert 0 < np.sum(st.ballast_force == 0.0) < len(voids)  # some hang, some carry


def test_the_finite_element_track_of_these_tests_is_the_linear_level_of_the_kernel():
    """:func:`fe_track` itself against the kernel's linear track (``linear_quasi_static``,
    Euler-Bernoulli Hermite elements assembled in C++): both linear and exact at nodes, they
    agree to round-off (measured 3e-12); a check of the reference, not of the code."""
    scene = dc.replace(LONG, supports=LONG.supports.transition(15.3,
                                                              ballast_stiffness=(60e6, 200e6)))
    nodes, w, _ = fe_track(scene, 15.3, scene.static_load)
    lin = tw.linear_quasi_static(scene, [15.3], n_elements=400)[0]
    assert lin == pytest.approx(w[np.searchsorted(nodes, 15.3)], rel=1e-9)


# ---------------------------------------------------------------------------------------------
# the continuous-foundation limit: an infinite beam on two Winkler foundations
def _waves(beta: float, sign: int):
    """x -> (4, 2): w, w', w'', w''' of e^{sign beta x} cos(beta x) and e^{sign beta x}
    sin(beta x), the real and imaginary parts of e^{(sign + i) beta x}."""
    lam = beta * (sign + 1j)

    def at(x):
        e = np.exp(lam * x) * lam ** np.arange(4)
        return np.stack([e.real, e.imag], axis=1)
    return at


def two_winkler(EI: float, k1: float, k2: float, P: float, a: float, x) -> np.ndarray:
    """w(x) [m] of an infinite Euler-Bernoulli beam on the foundation k1 [N/m^2] for x < 0 and
    k2 for x > 0 under the point load P [N] down at x = a
    (docs: Model § Supports varying along the track, its known answers): on each side
    EI w'''' + k w = -P delta(x - a); the waves e^{-beta_i |x|}(A cos beta_i x + B sin beta_i x),
    beta_i = (k_i / (4 EI))^(1/4), decaying away from the load; between the step and the load
    all four. w, w', w'', w''' continuous at 0; w, w', w'' continuous and EI w''' jumping by
    -P at a: an 8 x 8 system. A load on the left is the mirror image."""
    x = np.asarray(x, dtype=float)
    if a < 0.0:
        return two_winkler(EI, k2, k1, P, -a, -x)
    b1, b2 = (k1 / (4.0 * EI)) ** 0.25, (k2 / (4.0 * EI)) ** 0.25
    left, grow, decay = _waves(b1, +1), _waves(b2, +1), _waves(b2, -1)
    A, rhs = np.zeros((8, 8)), np.zeros(8)
    A[:4, 0:2], A[:4, 2:4], A[:4, 4:6] = left(0.0), -grow(0.0), -decay(0.0)
    A[4:, 2:4], A[4:, 4:6], A[4:, 6:8] = grow(a), decay(a), -decay(a)
    rhs[7] = P / EI  # w'''(a-) - w'''(a+) = P / EI
    c = np.linalg.solve(A, rhs)
    out = np.empty(x.size)
    for i, xi in enumerate(x.ravel()):
        if xi < 0.0:
            out[i] = left(xi)[0] @ c[0:2]
        elif xi < a:
            out[i] = grow(xi)[0] @ c[2:4] + decay(xi)[0] @ c[4:6]
        else:
            out[i] = decay(xi)[0] @ c[6:8]
    return out.reshape(x.shape)


def test_the_two_foundation_closed_form_has_its_limits():
    """The closed form itself: one foundation gives the Winkler deflection P beta / (2 k) under
    the load; far from the step the deflection under the load tends to P beta_i / (2 k_i)."""
    EI, P = KATO.rail.bending_stiffness, 50e3

    def winkler(k):
        return -P * (k / (4.0 * EI)) ** 0.25 / (2.0 * k)

    assert two_winkler(EI, 1e8, 1e8, P, 0.3, 0.3) == pytest.approx(winkler(1e8), rel=1e-12)
    assert two_winkler(EI, 1e8, 4e8, P, 6.0, 6.0) == pytest.approx(winkler(4e8), rel=1e-6)
    assert two_winkler(EI, 1e8, 4e8, P, -6.0, -6.0) == pytest.approx(winkler(1e8), rel=1e-6)


def step_scene(spacing: float, k1: float, k2: float, x0: float, load: float) -> tw.Scene:
    """The paper's rail, 30 m long, on single springs every ``spacing`` with the foundation
    modulus k1 [N/m^2] before ``x0`` and k2 after (k_s = k d), no gravity, the wheel load
    ``load``: a node on every support."""
    return dc.replace(
        KATO, rail=dc.replace(KATO.rail, length=30.0, n_elements=round(30.0 / spacing)),
        supports=tw.Supports(spacing=spacing,
                             stiffness=tw.Transition(k1 * spacing, k2 * spacing, at=x0)),
        gravity=0.0, rail_gravity=False, wheel=dc.replace(KATO.wheel, load=load))


def test_a_stiffness_step_on_dense_supports_is_the_beam_on_two_winkler_foundations(validation):
    """Springs every d with k_s = k_f d, the step at a bay's middle (each spring stands for the
    foundation of its bay), k_f 100 -> 400 MN/m^2 (beta 1.4 -> 2.0 /m; the rail's ends 15 m
    away, exp(-21)): the deflection under the wheel, resting 1 m before the step, at it, 0.5 m
    and 1 m after, against :func:`two_winkler`, and the rail over +-4 m around the step. What
    separates them is the discreteness of the supports: second order in d (measured: the error
    under the wheel falls 3.6-6.4 times as d halves from 0.1 to 0.05 m, to at most 1.8e-4;
    along the rail 3e-4 of the deflection under the wheel). Tolerances: 5e-4 under the wheel,
    1e-3 along the rail, and a fall of at least 3 times from d = 0.1 m."""
    EI, P, k1, k2 = KATO.rail.bending_stiffness, 50e3, 100e6, 400e6
    errors = {}
    for d in (0.1, 0.05):
        x0 = 15.0 + d / 2
        scene = step_scene(d, k1, k2, x0, P)
        for a in (-1.0, 0.0, 0.5, 1.0):
            st = tw.static(scene, round((x0 + a - d / 2) / d) * d)  # on a support
            ref = two_winkler(EI, k1, k2, P, st.contact_s - x0, st.contact_s - x0)
            errors[d, a] = abs(st.y_contact / ref - 1.0)
            if d == 0.05:
                x, y = st.rail_shape(3001)
                near = np.abs(x - x0) < 4.0
                along = np.max(np.abs(y[near] - two_winkler(EI, k1, k2, P, st.contact_s - x0,
                                                             x[near] - x0))) / abs(ref)
                assert along < 1e-3, (a, along)
    for a in (-1.0, 0.0, 0.5, 1.0):
        assert errors[0.05, a] < 5e-4 and errors[0.05, a] < errors[0.1, a] / 3.0, a
    validation.record(
        "statics.two_winkler_step", level="statics", kind="closed form",
        quantity="deflection under the wheel near a support stiffness step 100 -> 400 MN/m^2, "
                 "30 m rail on springs every 0.05 m (wheel 1 m before, at, 0.5 and 1 m after)",
        reference="infinite Euler-Bernoulli beam on two Winkler foundations (8 x 8 system of "
                  "the decaying waves)",
        measured=max(errors[0.05, a] for a in (-1.0, 0.0, 0.5, 1.0)), tolerance=5e-4)


# ---------------------------------------------------------------------------------------------
# presets: transitions, hanging sleepers, scatter
def test_transition_shapes_follow_their_formulas():
    """The transition shapes (docs: Model § Supports varying along the track):
    p = p1 + (p2 - p1) s((X - X0) / L_r): step H (1/2 at X0), linear clip(xi + 1/2, 0, 1),
    cosine (1 - cos(pi clip(xi + 1/2, 0, 1))) / 2; exactly p1 and p2 off
    the ramp (bit for bit), the mean at X0, monotone, the cosine's slope zero at both ends
    of the ramp (central differences over 1e-6 m: below 1e-6 of the linear ramp's slope)."""
    p1, p2, x0, lr = 50e6, 200e6, 10.0, 4.0
    x = np.linspace(5.0, 15.0, 1001)
    step = tw.Transition(p1, p2, at=x0)
    assert step(np.array([x0 - 1e-9, x0, x0 + 1e-9])).tolist() == [p1, 0.5 * (p1 + p2), p2]
    for shape in ("linear", "cosine"):
        t = tw.Transition(p1, p2, at=x0, ramp=lr, shape=shape)
        y = t(x)
        off = (x <= x0 - lr / 2) | (x >= x0 + lr / 2)
        assert np.all(y[off] == np.where(x[off] < x0, p1, p2))  # exactly, not nearly
        assert t(x0) == pytest.approx(0.5 * (p1 + p2), rel=1e-15)
        assert np.all(np.diff(y) >= 0.0)
        xi = (x - x0) / lr
        s = np.clip(xi + 0.5, 0.0, 1.0)
        expected = s if shape == "linear" else 0.5 * (1.0 - np.cos(np.pi * s))
        assert np.allclose(y, p1 + (p2 - p1) * expected, rtol=1e-14, atol=0.0)
    cos = tw.Transition(p1, p2, at=x0, ramp=lr, shape="cosine")
    h = 1e-6
    for end in (x0 - lr / 2, x0 + lr / 2):
        slope = (cos(end + h) - cos(end - h)) / (2 * h)
        assert abs(slope) < 1e-6 * (p2 - p1) / lr
    # a falling transition, and ramp 0 is a step whatever the shape
    fall = tw.Transition(p2, p1, at=x0, ramp=lr, shape="linear")
    assert fall(x0 - lr / 4) == pytest.approx(p2 - 0.25 * (p2 - p1), rel=1e-14)
    assert tw.Transition(p1, p2, at=x0, shape="cosine")(x).tolist() == step(x).tolist()


def test_a_transition_changes_several_properties_at_one_place():
    s = BALLASTED.supports.transition(4.5, ramp=1.2, shape="linear",
                                      ballast_stiffness=(50e6, 200e6), damping=(18e3, 30e3))
    scene = dc.replace(BALLASTED, supports=s)
    v = scene.support_values
    pos = v.position
    assert np.all(v.ballast_stiffness[pos < 3.9] == 50e6)
    assert np.all(v.ballast_stiffness[pos > 5.1] == 200e6)
    assert np.all(v.damping[pos > 5.1] == 30e3) and np.all(v.sleeper_mass == 150.0)
    inside = (pos > 3.9) & (pos < 5.1)  # 4.2 and 4.8 m: s = 1/4 and 3/4
    assert v.ballast_stiffness[inside].tolist() == pytest.approx([87.5e6, 162.5e6], rel=1e-14)


@pytest.mark.parametrize("make, exc, words", [
    (lambda: tw.Transition(1.0, 2.0, at=3.0, ramp=1.0), ValueError, ["a step has no ramp"]),
    (lambda: tw.Transition(1.0, 2.0, at=3.0, ramp=-1.0, shape="linear"), ValueError,
     ["Transition.ramp"]),
    (lambda: tw.Transition(1.0, 2.0, at=3.0, shape="smooth"), ValueError,
     ["Transition.shape", "'smooth'"]),
    (lambda: KATO.supports.transition(2.5), ValueError, ["at least one property=(before, after)"]),
    (lambda: KATO.supports.transition(2.5, pad=(1.0, 2.0)), TypeError,
     ["Supports.transition got pad=...", "ballast_stiffness"]),
    (lambda: KATO.supports.transition(2.5, stiffness=1e8), ValueError, ["must be a pair"]),
    (lambda: tw.Scene(supports=KATO.supports.transition(2.5, stiffness=(1e8, -1e8))),
     ValueError, ["Supports.stiffness at support 4 (X = 2.5 m) = 0.0"]),
    (lambda: tw.Scatter(1e8, cv=-0.1, seed=0, spacing=0.6), ValueError, ["Scatter.cv"]),
    (lambda: KATO.supports.scattered(0.2, seed=0, property="ballast_stiffness"), ValueError,
     ["the mean of ballast_stiffness must be one value or a Transition; got None"]),
    (lambda: KATO.supports.hanging(2.5, gap=1e-3), ValueError,
     ["Supports.void = Voids(positions=(2.5,), gaps=(0.001,)) m needs a sleeper layer"]),
    (lambda: BALLASTED.supports.hanging(4.2, gap=-1e-3), ValueError, ["Voids.gaps"]),
    (lambda: BALLASTED.supports.hanging(gap=1e-3), ValueError, ["either at"]),
    (lambda: dc.replace(BALLASTED, supports=BALLASTED.supports.hanging(20.0, gap=1e-3)),
     ValueError, ["Supports.void: no support at X = 19.8 m for its void"]),
])
def test_presets_refuse_bad_input_by_name(make, exc, words):
    with pytest.raises(exc) as info:
        make()
    for w in words:
        assert w in str(info.value), (w, str(info.value))


def test_hanging_puts_the_void_under_the_nearest_sleeper():
    s = BALLASTED.supports.hanging([4.3, 6.0], gap=[1e-3, 2e-3])
    assert s.void == tw.Voids((4.2, 6.0), (1e-3, 2e-3))
    s = s.hanging(sleepers=2, gap=5e-4)  # adds X = 1.8 m
    scene = dc.replace(BALLASTED, supports=s)
    v = scene.support_values.void
    pos = np.asarray(scene.support_positions)
    assert pos[v > 0].tolist() == pytest.approx([1.8, 4.2, 6.0], rel=1e-12)
    assert v[v > 0].tolist() == [5e-4, 1e-3, 2e-3]
    assert scene.supports.unilateral and scene.support_values.unilateral
    assert not BALLASTED.supports.unilateral


def scatter_bed(cv=0.3, seed=7, n=20000):
    """k_b of ``n`` sleepers (X = j d, j = 1..n) of a scattered bed of mean 105 MN/m."""
    s = BALLASTED.supports.scattered(cv, seed=seed)
    return s.value_at("ballast_stiffness", 0.6 * np.arange(1, n + 1))


def test_a_scattered_bed_has_its_mean_and_coefficient_of_variation():
    """20000 sleepers, cv = 0.3: the sample mean of k_b / k_mean within 4 standard errors
    cv / sqrt(n) = 0.0021 of 1; the sample cv within 4 standard errors of a lognormal's sample
    standard deviation, std * sqrt((kurtosis - 1) / (4 n)) with kurtosis
    e^{4 s2} + 2 e^{3 s2} + 3 e^{2 s2} - 3 = 4.57 (s2 = ln(1 + cv^2)): 0.67 % of cv; ln k_b
    normal with mean ln k_mean - s2 / 2 and variance s2 (mean and standard deviation within 4
    standard errors); neighbouring sleepers uncorrelated (|r| < 4 / sqrt(n))."""
    cv, n = 0.3, 20000
    k = scatter_bed(cv, n=n) / 105e6
    s2 = np.log1p(cv * cv)
    assert abs(k.mean() - 1.0) < 4 * cv / np.sqrt(n)
    kurt = np.exp(4 * s2) + 2 * np.exp(3 * s2) + 3 * np.exp(2 * s2) - 3
    assert abs(k.std(ddof=1) / k.mean() / cv - 1.0) < 4 * np.sqrt((kurt - 1) / (4 * n))
    lk = np.log(k)
    assert abs(lk.mean() + s2 / 2) < 4 * np.sqrt(s2 / n)
    assert abs(lk.std(ddof=1) / np.sqrt(s2) - 1.0) < 4 / np.sqrt(2 * n)
    assert abs(np.corrcoef(lk[:-1], lk[1:])[0, 1]) < 4 / np.sqrt(n)


def test_a_scattered_bed_is_fixed_by_its_seed_and_the_sleepers_index():
    """The same seed gives the same bed in any process (a fixed SeedSequence), another seed
    another; a sleeper's value depends only on (seed, its absolute index): the same on a 9 m and
    a 30 m rail where they overlap, on either side of a block boundary, and read anywhere in its
    bay (X within d/2 of the sleeper)."""
    a, b = scatter_bed(seed=7, n=3000), scatter_bed(seed=7, n=3000)
    assert a.tobytes() == b.tobytes()
    assert not np.allclose(a, scatter_bed(seed=8, n=3000))
    short = dc.replace(BALLASTED, supports=BALLASTED.supports.scattered(0.3, seed=7))
    long = dc.replace(LONG, supports=LONG.supports.scattered(0.3, seed=7))
    n = len(short.support_positions)
    assert short.support_values.ballast_stiffness.tolist() == (
        long.support_values.ballast_stiffness[:n].tolist())
    assert short.support_values.ballast_stiffness.tolist() == a[:n].tolist()
    sup = short.supports
    assert sup.value_at("ballast_stiffness", 0.6 * 1024 + 0.29) == a[1023]  # j = 1024
    assert sup.value_at("ballast_stiffness", 0.6 * 1023 - 0.29) == a[1022]  # j = 1023
    # a window's sleepers behind X = 0 have their own values, fixed too
    behind = sup.value_at("ballast_stiffness", [-1.2, -0.6])
    assert behind.tolist() == sup.value_at("ballast_stiffness", [-1.2, -0.6]).tolist()
    assert np.all(behind > 0.0) and behind[0] != behind[1]


def test_reseeding_redraws_every_scattered_property_like_an_irregularity():
    s = BALLASTED.supports.scattered(0.3, seed=0).scattered(0.1, seed=0, property="stiffness")
    r = s.reseeded(5)
    assert r.stiffness.seed == 5  # the first scattered field (in field order) gets the seed
    assert r.ballast_stiffness.seed == tw.excitation.derived_seed(5, 1)
    assert r == s.reseeded(5) and r != s.reseeded(6)
    assert BALLASTED.supports.scattered(0.3, seed=3) == (
        BALLASTED.supports.scattered(0.3, seed=0).reseeded(3))
    with pytest.raises(ValueError, match="no property is scattered"):
        BALLASTED.supports.reseeded(1)


def test_a_sweep_over_seeds_redraws_the_bed(tmp_path):
    """sweep(seeds=...) on a scattered bed without an irregularity: each seed's case runs the
    bed of that seed (its record holds Scatter(seed=s)), seeds give different results, and a
    seed's row is the direct run of Supports.scattered(..., seed=s)."""
    base = with_supports(KATO, damping=2e4)
    scene = dc.replace(base, supports=base.supports.scattered(0.3, seed=0, property="stiffness"))
    kw = dict(x_start=0.25, x_end=0.75, dt=2e-5)
    df = tw.sweep(scene, [tw.kmh(100)], seeds=[1, 2], store=tmp_path, max_workers=1,
                  progress=False, **kw)
    assert list(df["seed"]) == [1, 2] and np.isnan(df["support_stiffness_N_m"]).all()
    assert df["amplitude_m"].iloc[0] != df["amplitude_m"].iloc[1]
    direct = dc.replace(base, supports=base.supports.scattered(0.3, seed=2, property="stiffness"))
    r = tw.simulate(direct, tw.kmh(100), progress=False, **kw)
    assert df["amplitude_m"].iloc[1] == tw.analyse(r).amplitude
    seeds = sorted(__import__("json").loads(p.read_text())["inputs"]["scene"]["supports"]
                   ["stiffness"]["seed"] for p in tmp_path.glob("case-*.json"))
    assert seeds == [1, 2]


# ---------------------------------------------------------------------------------------------
# the command line
def _cli_scene(argv, track="ballasted"):
    from trackwheel import cli
    from trackwheel.cli import scenes

    args = cli.build_parser().parse_args(["run", "--speed-kmh", "100", "--track", track, *argv])
    return scenes.track_scene(args, args.support_stiffness)


def test_the_command_line_builds_the_api_track():
    """--transition / --scatter / --void give the supports the API builds: the ballast stiffness
    of --track ballasted, the support stiffness of kato2005; a ramp is linear unless
    --transition-shape says cosine; the scatter's mean is the transition and its seed --seed."""
    base = tw.Scene.ballasted_track().supports
    assert _cli_scene(["--transition", "50e6,200e6,15"]).supports == base.transition(
        15.0, ballast_stiffness=(50e6, 200e6))
    assert _cli_scene(["--transition", "50e6,200e6,15,3", "--transition-shape", "cosine",
                       "--scatter", "0.2", "--seed", "4"]).supports == base.transition(
        15.0, ramp=3.0, shape="cosine", ballast_stiffness=(50e6, 200e6)).scattered(0.2, seed=4)
    assert _cli_scene(["--void", "15.1,1e-3", "--void", "3,2e-3"]).supports == base.hanging(
        [15.1, 3.0], gap=[1e-3, 2e-3])
    assert _cli_scene(["--transition", "1e8,2e8,2.5,1"], "kato2005").supports == (
        KATO.supports.transition(2.5, ramp=1.0, shape="linear", stiffness=(1e8, 2e8)))


@pytest.mark.parametrize("argv, words", [
    (["--transition", "1e8,2e8"], ["K1,K2,AT[,RAMP]"]),
    (["--transition", "1e8,-2e8,2.5"], ["--transition: Supports.stiffness at support 4 "
                                         "(X = 2.5 m) = -50000000.0", "(0, 1e+14] N/m"]),
    (["--transition-shape", "cosine"], ["--transition-shape needs --transition K1,K2,AT,RAMP"]),
    (["--transition", "1e8,2e8,2.5", "--support-stiffness", "1e8"],
     ["give them or --support-stiffness, not both"]),
    (["--scatter", "20"], ["--scatter: Scatter.cv = 20.0 is outside the allowed range"]),
    (["--void", "2,1e-3"], ["--void: a void lies between a sleeper and its ballast"]),
    (["--track", "ballasted", "--void", "15,0.5"], ["--void: Voids.gaps = 0.5",
                                                    "[0.0, 0.1] m"]),
    (["--seed", "3"], ["--seed need(s) a random --irregularity", "or --scatter"]),
])
def test_bad_track_options_are_one_line(argv, words, capsys):
    from trackwheel import cli

    cheap = ["--n-elements", "20", "--dt", "1e-5", "--x-end", "5.4"]
    assert cli.main(["run", "--speed-kmh", "100", *argv, *cheap]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "error:" in err
    for w in words:
        assert w in err, (w, err)


def test_run_prints_the_track_along_x(capsys):
    from trackwheel import cli

    argv = ["--transition", "100e6,180e6,2.5,1", "--support-damping", "2e4", "--n-elements",
            "20", "--dt", "2e-5", "--x-end", "1.0"]
    assert cli.main(["run", "--speed-kmh", "100", *argv]) == 0
    out = capsys.readouterr().out
    assert "k_s = 100..180 MN/m" in out
    assert "track along X  : k_s 100 -> 180 MN/m at X = 2.5 m over 1 m (linear)" in out
