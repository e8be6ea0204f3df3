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


def test_the_window_refuses_supports_that_vary():
    scene = tw.Scene.ballasted_track(window=tw.Window(bays_behind=4, bays_ahead=4))
    with pytest.raises(ValueError, match="Scene.window needs supports that repeat every bay"):
        with_supports(scene, ballast_stiffness=lambda x: np.full_like(x, 105e6))


def test_voids_wait_for_the_kernels_unilateral_ballast():
    for sup in (dc.replace(BALLASTED.supports, void=1e-3),
                dc.replace(BALLASTED.supports, ballast_tensionless=True),
                BALLASTED.supports.hanging(4.5, gap=1e-3)):
        scene = dc.replace(BALLASTED, supports=sup)  # the scene is valid...
        with pytest.raises(ValueError, match="need the kernel's unilateral ballast"):
            tw.static(scene, 4.5)  # ...the kernel does not have the law yet
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
