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
        def support_params(scene):
            s = original(scene)
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
