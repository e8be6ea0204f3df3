"""The support-force outputs of an analysis (max_ballast_force, its X, max_rail_seat_force):
the peaks of the run's envelope along the track over the sleepers of the measured stretch."""

import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel.study.columns import PERIODIC_OUTPUTS, label

SCENE = tw.Scene.ballasted_track(15.0)
SLEEPER_WEIGHT = 150.0 * 9.81  # the preset's half sleeper, m_s g [N]


@pytest.fixture(scope="module")
def slow_passage():
    """A passage at 4 m/s: sleeper passing at 6.7 Hz, far below the track's resonances
    (~100 Hz), so every force is its static value to O((f/f_0)^2) ~ 1e-3 and less."""
    r = tw.simulate(SCENE, 4.0, fidelity="linear/hertz", progress=False)
    return r, tw.analyse(r)


def test_a_slow_passage_peaks_at_the_static_ballast_force(slow_passage):
    """v -> 0: the largest ballast force over the stretch is the static one with the wheel
    over a sleeper (tw.static, solved independently on the ANCF rail: the two models' statics
    differ by ~3e-5 of the deflection) within 1e-3, at a sleeper of the stretch."""
    r, a = slow_passage
    X = np.asarray(r.support_envelope["x"])
    inside = X[(X >= a.x_range[0]) & (X <= a.x_range[1])]
    assert inside.size >= 5
    static = max(float(tw.static(SCENE, x).ballast_force.max()) for x in inside)
    assert a.max_ballast_force == pytest.approx(static, rel=1e-3)
    assert np.min(np.abs(inside - a.max_ballast_force_x)) < 1e-9


def test_the_ballast_carries_the_rail_seat_force_and_the_sleeper(slow_passage):
    """The sleeper's equilibrium at rest, F_b = F_p + m_s g: at quasi-static speed the two
    peaks (the same sleeper, the wheel above it) differ by the sleeper's weight, to the
    sleeper's inertia m_s z'' ~ 1e-4 of the force."""
    _, a = slow_passage
    assert a.max_ballast_force - a.max_rail_seat_force == pytest.approx(
        SLEEPER_WEIGHT, abs=1e-4 * a.max_ballast_force)


def test_the_peaks_leave_out_the_sleepers_outside_the_stretch(slow_passage):
    """Measured over the whole run the peak can only grow (more sleepers): the start-up's
    sleepers are left out of the default measure, not added."""
    r, a = slow_passage
    whole = tw.analyse(r, measure="run")
    assert whole.max_ballast_force >= a.max_ballast_force
    env = r.support_envelope
    X = np.asarray(env["x"])
    ran = (X >= whole.x_range[0]) & (X <= whole.x_range[1])
    assert whole.max_ballast_force == np.max(np.asarray(env["ballast_force_max"])[ran])


def test_outside_every_support_the_peaks_are_nan(slow_passage):
    """A stretch between two sleepers holds none: NaN, not a neighbour's force."""
    r, _ = slow_passage
    X = np.asarray(r.support_envelope["x"])
    mid = X[(X > 7.0)][:2].mean()  # half a bay from either sleeper
    a = tw.analyse(r, measure=(mid - 0.05, mid + 0.05))
    assert all(math.isnan(getattr(a, n)) for n in ("max_ballast_force", "max_ballast_force_x",
                                                    "max_rail_seat_force"))


def test_the_periodic_level_has_no_support_forces():
    for n in ("max_ballast_force", "max_ballast_force_x", "max_rail_seat_force"):
        assert n in PERIODIC_OUTPUTS and PERIODIC_OUTPUTS[n] is None
        assert label(n).startswith(n)
