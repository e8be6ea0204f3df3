"""Per-support outputs (docs: Model § Outputs): each support's rail-seat force, ballast force and
sleeper displacement per kept sample (``simulate(..., support_forces=True)``), and each
support's envelope along the track (``Result.sleeper_envelope()``), which every run keeps.

Checks: the force balance of the track in static equilibrium (the supports carry the wheel
load), the recorded forces against the pad and ballast laws evaluated on the recorded state,
the kernel's envelope against the one derived from the histories, the statics' ballast forces
at the start, determinism, and the refusals.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest

import trackwheel as tw
from trackwheel.run.results import ENVELOPE_FIELDS, SUPPORT_FIELDS


def _track(length: float = 18.0, rail_gravity: bool = True) -> tw.Scene:
    scene = tw.Scene.ballasted_track(length=length)
    return dc.replace(scene, rail_gravity=rail_gravity)


def test_support_forces_carry_the_wheel_load_in_static_equilibrium():
    """Without the track's weight (rail_gravity=False) the supports carry the wheel load alone:
    sum_j F_b,j = sum_j F_p,j = P less the reactions of the rail's two pinned ends. With the
    wheel 9 m from either end of the 18 m rail those decay as exp(-beta x) with beta =
    (k / 4 EI)^(1/4) ~ 1.2 /m for the preset's bed (k = series k_p k_b/(k_p + k_b) per 0.6 m),
    e^(-10) of P: the sums equal P within 1e-6 P at the static start (sample 0, no rates).
    A slow passage (1 m/s over 0.6 m: one bay) stays quasi-static: its inertia and damping
    forces are O((v / v_cr)^2) and O(c v / (k lambda)) of P, below 1e-3 P, measured 4e-6."""
    scene = _track(rail_gravity=False)
    P = scene.static_load
    r = tw.simulate(scene, 1.0, x_start=8.7, x_end=9.3, fidelity="linear/hertz",
                    support_forces=True, progress=False)
    fb, fp = r.ballast_force, r.rail_seat_force
    assert fb.shape == (r.t.size, len(scene.support_positions)) == fp.shape
    assert abs(fb[0].sum() - P) < 1e-5 * P and abs(fp[0].sum() - P) < 1e-5 * P
    assert np.abs(fb.sum(axis=1) - P).max() < 1e-3 * P
    assert np.abs(fp.sum(axis=1) - P).max() < 1e-3 * P


def test_ballast_forces_with_weight_are_the_statics():
    """With gravity the start (sample 0) is the static equilibrium that trackwheel.static
    solves: each sleeper's ballast force -k_b z_j equals the statics' ballast force, and the
    ballast forces exceed the rail-seat forces by the sleepers' weight m_s g each (the sleeper
    at rest: F_b - F_p = m_s g), both to round-off of the statics' Newton tolerance, 1e-9 of P."""
    scene = _track()
    P = scene.static_load
    r = tw.simulate(scene, 10.0, x_start=9.0, x_end=9.1, support_forces=True, progress=False)
    st = tw.static(scene, 9.0, n_elements=r.settings.n_elements)
    np.testing.assert_allclose(r.ballast_force[0], st.ballast_force, rtol=0, atol=1e-9 * P)
    m_g = scene.supports.sleeper_mass * scene.gravity
    np.testing.assert_allclose(r.ballast_force[0] - r.rail_seat_force[0], m_g, rtol=0,
                               atol=1e-9 * P)


def test_recorded_forces_are_the_pad_and_ballast_laws_on_the_recorded_state():
    """The last sample (output_every = 1) is the run's final state: its rail at each support
    y_j = s_j . e and rate y_j' = s_j . e', and the sleepers' z_j, z_j'. The recorded forces
    equal -(k_p (y_j - z_j) + c_p (y_j' - z_j')) and -(k_b z_j + c_b z_j') evaluated here on
    that state, and sleeper_z equals z, to round-off (1e-9 of the largest force)."""
    scene = _track()
    r = tw.simulate(scene, tw.kmh(200), x_start=8.0, x_end=9.0, dt=2e-5, output_every=1,
                    n_elements=scene.rail.n_elements, support_forces=True, progress=False)
    fs = r.final_state
    model = tw.run.kernel.rail_model(scene, r.settings.n_elements)
    x = scene.support_positions
    y = model.positions(np.asarray(fs.e), x)[:, 1]
    # r(s) = sum h_a e_a is linear in e: the same map takes e' to the point's velocity
    ydot = model.positions(np.asarray(fs.edot), x)[:, 1]
    z, zdot = np.asarray(fs.z), np.asarray(fs.zdot)
    sp = scene.supports
    fp = -(sp.stiffness * (y - z) + sp.damping * (ydot - zdot))
    fb = -(sp.ballast_stiffness * z + sp.ballast_damping * zdot)
    scale = np.abs(r.ballast_force).max()
    assert np.abs(zdot).max() > 1e-4  # the sleepers move: the damping terms are tested
    np.testing.assert_allclose(r.rail_seat_force[-1], fp, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(r.ballast_force[-1], fb, rtol=0, atol=1e-9 * scale)
    np.testing.assert_array_equal(r.sleeper_z[-1], z)


@pytest.mark.parametrize("fidelity", ["full", "linear/hertz"])
def test_envelope_is_the_histories_extremes(fidelity):
    """On a fixed rail the kernel's envelope, accumulated over the kept samples, is the
    extremes of the recorded histories exactly (the same numbers, max/min taken in the same
    order), at the supports' X; contact_time counts the samples with F_b > 0, each
    output_every x dt long."""
    scene = _track()
    r = tw.simulate(scene, tw.kmh(150), x_start=8.0, x_end=9.5, output_every=3,
                    support_forces=True, fidelity=fidelity, progress=False)
    df = r.sleeper_envelope()
    assert list(df.columns) == [f[0] for f in ENVELOPE_FIELDS]
    assert df.attrs["units"]["ballast_force_max"] == "N"
    np.testing.assert_array_equal(df.x, scene.support_positions)
    fb, fp, z = r.ballast_force, r.rail_seat_force, r.sleeper_z
    np.testing.assert_array_equal(df.ballast_force_max, fb.max(axis=0))
    np.testing.assert_array_equal(df.ballast_force_min, fb.min(axis=0))
    np.testing.assert_array_equal(df.rail_seat_force_max, fp.max(axis=0))
    np.testing.assert_array_equal(df.rail_seat_force_min, fp.min(axis=0))
    np.testing.assert_array_equal(df.sleeper_z_min, z.min(axis=0))
    ds = r.settings.output_every * r.settings.dt
    np.testing.assert_allclose(df.contact_time, (fb > 0).sum(axis=0) * ds, rtol=1e-12)
    np.testing.assert_allclose(df.observed_time, r.t.size * ds, rtol=1e-12)
    # under the wheel's passage the ballast force rises well above its rest value
    assert df.ballast_force_max.max() > 0.2 * scene.static_load


@pytest.mark.parametrize("fidelity", ["full", "linear/hertz"])
def test_a_voided_sleeper_records_its_unilateral_ballast(fidelity):
    """A sleeper over a void (docs: Model § Supports varying along the track) records the
    unilateral law, not the linear one: its ballast force is never negative (the bed pushes
    only) and exactly 0 wherever the sleeper is clear of its bed, d = -z - g < 0. A 0.3 mm
    void under the sleeper the wheel passes is closed under the wheel (the static fall is about
    0.8 mm) and open before and after it: the envelope's contact_time (kept samples with
    F_b > 0, output_every = 1) equals the kernel's own ballast_contact_time (steps on the
    bed) within one sample per state change. A 5 mm void, deeper than any motion here, keeps
    the bed's force exactly 0 throughout."""
    scene = _track()
    j = int(np.argmin(np.abs(np.asarray(scene.support_positions) - 9.0)))
    for gap, closes in ((3e-4, True), (5e-3, False)):
        voided = dc.replace(scene, supports=scene.supports.hanging(9.0, gap=gap))
        r = tw.simulate(voided, tw.kmh(150), x_start=8.0, x_end=10.0, output_every=1,
                        support_forces=True, fidelity=fidelity, progress=False)
        fb = r.ballast_force[:, j]
        assert fb.min() >= 0.0
        assert np.all(fb[-r.sleeper_z[:, j] - gap < 0.0] == 0.0)
        env = r.sleeper_envelope()
        ds = r.settings.output_every * r.settings.dt
        assert abs(env.contact_time[j] - r.ballast_contact_time[j]) <= (r.ballast_events + 1) * ds
        if closes:
            assert r.ballast_events >= 2 and fb.max() > 0.05 * scene.static_load
            assert 0.0 < env.contact_time[j] < env.observed_time[j]
        else:
            assert r.ballast_events == 0 and fb.max() == 0.0 and env.contact_time[j] == 0.0


def test_support_outputs_are_deterministic_and_on_request():
    scene = _track()
    kw = dict(x_start=8.0, x_end=8.6, fidelity="linear/hertz", progress=False)
    a = tw.simulate(scene, tw.kmh(250), support_forces=True, **kw)
    b = tw.simulate(scene, tw.kmh(250), support_forces=True, **kw)
    for name, _u, _d in SUPPORT_FIELDS:
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    for name, _u, _d in ENVELOPE_FIELDS:
        np.testing.assert_array_equal(a.support_envelope[name], b.support_envelope[name])
    c = tw.simulate(scene, tw.kmh(250), **kw)
    assert all(getattr(c, name) is None for name, _u, _d in SUPPORT_FIELDS)
    np.testing.assert_array_equal(c.normal_force, a.normal_force)  # recording changes nothing
    np.testing.assert_array_equal(c.sleeper_envelope().ballast_force_max,
                                  a.sleeper_envelope().ballast_force_max)


def test_single_springs_report_the_spring_force():
    """Single-spring supports (the paper's scene): the rail-seat and ballast forces are both
    the spring's -(k_s y + c_s y'), and there is no sleeper (z = 0)."""
    scene = tw.Scene.kato2005()
    r = tw.simulate(scene, tw.kmh(100), x_end=0.6, dt=1e-5, n_elements=20, support_forces=True,
                    progress=False)
    np.testing.assert_array_equal(r.ballast_force, r.rail_seat_force)
    assert not np.any(r.sleeper_z)
    assert r.rail_seat_force.max() > 0.1 * scene.static_load


def test_support_forces_refused_on_a_window():
    scene = tw.Scene.ballasted_track(window=tw.Window(10, 10))
    with pytest.raises(ValueError, match="support_forces=True needs a fixed rail"):
        tw.simulate(scene, tw.kmh(100), support_forces=True, progress=False)
