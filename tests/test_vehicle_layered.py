"""A vehicle on layered supports (issue 15 x the sleepers): where the two features meet.

The sleepers are condensed into the rail band and the vehicle's bodies out of the border; the
two condensations are independent (docs: Model § The vehicle, § Layered supports). Checks: the
multi-wheel statics with sleepers (lever-rule loads, ballast balance, the run's start), the
iteration matrix with both against central differences and the condensed solve against the
dense one, the linear path against the full one, generalized-alpha against RK4, the vehicle
eigen solver against the C++ one with sleepers, and the Timoshenko linear rail's thin-beam
limit with a vehicle.
"""

from __future__ import annotations

import dataclasses as dc

import numpy as np
import pytest
from test_system import central_difference_error
from test_vehicle import vehicle_probe

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel
from trackwheel.statics import vehicle_static
from trackwheel.vehicle import Vehicle

V = tw.kmh(300)
#: linear vs full: tests/test_paths_agree.py's TOL_TRACE (0.5 % of the dynamic amplitude, 5x
#: the undamped difference the ANCF nonlinearity makes)
TOL_TRACE = 5e-3


def _layered_kato(length: float = 10.0, n_elements: int = 40, vehicle=Vehicle.bogie()
                  ) -> tw.Scene:
    """tests/test_paths_agree.py's layered scene (pad 140 MN/m and 2e4 N s/m, half sleeper
    150 kg, ballast 105 MN/m and 5e4 N s/m) on a rail long enough for a bogie."""
    base = tw.Scene.kato2005()
    sup = dc.replace(base.supports, damping=2e4, sleeper_mass=150.0, ballast_stiffness=105e6,
                     ballast_damping=5e4)
    rail = dc.replace(base.rail, length=length, n_elements=n_elements)
    return dc.replace(base, rail=rail, supports=sup, vehicle=vehicle)


def test_bogie_statics_on_the_ballasted_track():
    """A bogie at mid-length of Scene.ballasted_track (30 m): the contact forces are the
    lever-rule loads (Newton tolerance 1e-13 L in displacement; measured 2e-10 relative,
    bound 1e-8), and the ballast carries the vehicle's weight: the ballast forces with the bogie
    less those of the bare track sum to the sum of the wheel loads. The wheels' share reaching
    the rail's rigid ends decays as exp(-beta x), beta = 1.4 1/m, x >= 13.75 m: e^-19 = 5e-9
    (measured 1.7e-9; tolerance 1e-8)."""
    scene = dc.replace(tw.Scene.ballasted_track(), vehicle=Vehicle.bogie())
    veh = scene.active_vehicle
    P = np.array(veh.static_loads(scene.gravity))
    vs = vehicle_static(scene, 15.0 - 1.25)
    np.testing.assert_allclose(vs.normal_force, P, rtol=1e-8)
    bare = np.asarray(_core.testing.track_static(_kernel.rail_model(scene))["ballast_force"])
    n = len(scene.support_positions)
    assert vs.ballast_force.shape == (n,) and vs.sleeper_z.shape == (n,)
    assert abs((vs.ballast_force - bare).sum() / P.sum() - 1.0) < 1e-8
    # the sleepers under the wheels sink most (one under each wheel's bay)
    deepest = sorted(np.argsort(vs.sleeper_z)[:2])
    xs = np.asarray(scene.support_positions)[deepest]
    assert np.all(np.abs(xs - vs.x_wheels) <= 0.3 + 1e-12)


def test_bogie_run_on_the_ballasted_track_starts_in_equilibrium():
    """The full path's static start with sleepers and a bogie: the first sample's contact
    forces are the lever-rule loads (rtol 1e-6 as tests/test_vehicle.py; measured 5e-10), and
    the bodies hardly move in the first millisecond (measured 2e-10 m; bound 1e-7 m, as for
    single springs)."""
    scene = dc.replace(tw.Scene.ballasted_track(), vehicle=Vehicle.bogie())
    r = tw.simulate(scene, tw.kmh(100), x_start=12.0, duration=1e-3, dt=1e-4)
    P = np.array(scene.active_vehicle.static_loads(scene.gravity))
    np.testing.assert_allclose(r.normal_force[0], P, rtol=1e-6)
    assert np.max(np.abs(r.body_z - r.body_z[0])) < 1e-7


@pytest.mark.parametrize("preset", ["bogie", "half_car"])
def test_iteration_matrix_with_sleepers_and_bodies_matches_central_differences(preset):
    """ga_probe's matrix over x = [e''_free, (Y'', theta'', lambda) per wheel, (z'', phi'') per
    body, z'' per sleeper] against central differences of its residual (steps and tolerance as
    tests/test_system.py: 1e3 m/s^2 on accelerations, 1 N on multipliers, 1e-6 of each
    column's largest entry; measured 2e-9 and 5e-9), with damped pads, ballast and
    suspensions moving. The kernel's Newton correction (sleepers condensed into the band,
    bodies out of the border) equals the dense solve to round-off: 1e-10 of max |dx| with
    cond(J) up to 8e7 (measured 6e-16). Bodies and sleepers share no entry."""
    veh = Vehicle.bogie() if preset == "bogie" else Vehicle.half_car()
    length = 6.0 if preset == "bogie" else 23.0
    scene = dc.replace(_layered_kato(length, int(length / 0.5)), vehicle=veh)
    probe, nf = vehicle_probe(scene, V)
    p0 = probe()
    x0, J = p0["start"], p0["matrix"]
    nw, nb = veh.n_wheels, veh.n_bodies
    ns = len(scene.support_positions)
    assert len(x0) == nf + 3 * nw + 2 * nb + ns
    h = np.full(len(x0), 1e3)
    h[nf + 2:nf + 3 * nw:3] = 1.0
    err = central_difference_error(probe, x0, J, h)
    assert np.max(err) < 1e-6, (int(np.argmax(err)), float(np.max(err)))
    dense = np.linalg.solve(J, p0["residual"])
    np.testing.assert_allclose(p0["solution"], dense, rtol=0,
                               atol=1e-10 * np.max(np.abs(dense)))
    ob, osl = nf + 3 * nw, nf + 3 * nw + 2 * nb
    assert np.count_nonzero(J[ob:osl, osl:]) == 0 and np.count_nonzero(J[osl:, ob:osl]) == 0
    assert np.count_nonzero(J[:nf, osl:]) >= ns  # every sleeper reaches the rail


@pytest.mark.parametrize("level", ["sprung", "hertz"])
def test_linear_matches_full_for_a_bogie_on_layered_supports(level):
    """A bogie on the layered scene at 300 km/h, both paths on the same mesh and step: each
    wheel's d(t) (analyse(r, wheel=i)) agrees within TOL_TRACE of its amplitude (measured
    0.04 % and 0.09 %), the amplitudes within TOL_TRACE (measured 0.03 %), the bogie's z(t)
    within 1 % of its range (measured 0.02 %). The sleepers matter: on single springs the
    leading wheel's amplitude is half as large."""
    scene = _layered_kato()
    kw = {"n_elements": 40, "dt": 1e-5}
    full = tw.simulate(scene, V, fidelity=f"ancf/{level}", **kw)
    lin = tw.simulate(scene, V, fidelity=f"linear/{level}", **kw)
    for i in range(2):
        af, al = tw.analyse(full, wheel=i), tw.analyse(lin, wheel=i)
        assert abs(al.amplitude / af.amplitude - 1.0) < TOL_TRACE
        assert np.max(np.abs(al.dynamic - af.dynamic)) < TOL_TRACE * af.amplitude
    assert np.max(np.abs(lin.body_z - full.body_z)) < 0.01 * np.ptp(full.body_z)
    single = dc.replace(scene, supports=dc.replace(tw.Scene.kato2005().supports, damping=2e4))
    a1 = tw.analyse(tw.simulate(single, V, fidelity=f"ancf/{level}", **kw), wheel=0).amplitude
    assert abs(a1 / tw.analyse(full, wheel=0).amplitude - 1.0) > 10 * TOL_TRACE


def test_integrators_agree_for_a_bogie_on_layered_supports():
    """Generalized-alpha (sleepers condensed in the Newton matrix, bodies out of its border)
    against RK4 (z'' = F/m_s, the bodies from the index-1 system) with a bogie on the layered
    scene: each wheel's y_B within 1 % of its dynamic amplitude (measured 0.03 %) and N within
    1 % of its range (measured 0.3 %), the tolerances of the one-wheel comparison in
    tests/test_paths_agree.py."""
    scene = _layered_kato(6.0, 24)
    kw = {"x_end": 1.5, "n_elements": 24}
    ga = tw.simulate(scene, V, dt=2.5e-6, **kw)
    ex = tw.simulate(scene, V, dt=2e-6, integrator="explicit", **kw)
    for i in range(2):
        amp = tw.analyse(ga, wheel=i).amplitude
        y_ex = np.interp(ga.t, ex.t, ex.y_contact[:, i])
        assert np.max(np.abs(y_ex - ga.y_contact[:, i])) < 0.01 * amp
        n_ex = np.interp(ga.t, ex.t, ex.normal_force[:, i])
        assert np.max(np.abs(n_ex - ga.normal_force[:, i])) < 0.01 * np.ptp(ga.normal_force[:, i])


def test_vehicle_eigen_with_sleepers_equals_the_kernel_eigen():
    """Two independent assemblies of the same problem: eigen with a one-wheel Vehicle (dense
    [rail, wheel, sleepers] in Python) against the C++ vertical_modes of the plain scene
    (rail, wheel, then sleepers) on layered supports: frequencies to 1e-9 (measured 3e-12),
    mode shapes equal up to sign to 1e-9 of their largest entry, the rows in the same order."""
    layered = _layered_kato(5.0, 20, vehicle=None)
    ne = layered.rail.n_elements  # the scene's own mesh: the dense assemblies stay well posed
    a = tw.eigen(layered, [1.3, 2.5], 8, n_elements=ne)
    b = tw.eigen(dc.replace(layered, vehicle=Vehicle.single_wheel()), [1.3, 2.5], 8,
                 n_elements=ne)
    n_dof = _kernel.rail_model(layered, a.n_elements).n_dof
    assert a.shapes.shape == b.shapes.shape == (2, n_dof + 1 + len(layered.support_positions), 8)
    np.testing.assert_allclose(b.frequencies, a.frequencies, rtol=1e-9)
    for p in range(2):
        for k in range(8):
            sa, sb = a.shapes[p, :, k], b.shapes[p, :, k]
            np.testing.assert_allclose(np.sign(sa @ sb) * sb, sa, rtol=0.0,
                                       atol=1e-9 * np.max(np.abs(sa)))


def test_vehicle_eigen_takes_the_timoshenko_rail():
    """The vehicle's eigen on layered supports with the shear-deformable rail: shear adds
    flexibility and rotary inertia, so no mode rises above its Euler-Bernoulli counterpart
    (measured: the track modes fall, the suspension's stay within 1e-9)."""
    scene = _layered_kato()
    timo = dc.replace(scene, rail=dc.replace(scene.rail, beam="timoshenko"))
    e, t = tw.eigen(scene, [4.0], 12), tw.eigen(timo, [4.0], 12)
    assert np.all(t.frequencies <= e.frequencies * (1 + 1e-9))
    assert np.any(t.frequencies < e.frequencies * (1 - 1e-3))


def test_timoshenko_thin_beam_limit_with_a_bogie_on_layered_supports(monkeypatch):
    """The linear path's Timoshenko rail with a huge kGA and no rotary inertia is the
    Euler-Bernoulli rail (phi = 12 EI/(kGA l^2) = 2e-6 here), with a bogie on layered supports:
    each wheel's N(t) and y_B(t) agree to phi of their ranges (measured 1e-7). With the rail's
    own kGA, shear softens the track: the mean deflection under each wheel is larger. Both
    runs take the element compliance (on by default for the Timoshenko rail only), whose
    thin-beam limit is the Euler-Bernoulli element's a^3 b^3 / (3 EI l^3)."""
    scene = _layered_kato()
    scene = dc.replace(scene, contact=dc.replace(scene.contact, element_compliance=True))
    timo = dc.replace(scene, rail=dc.replace(scene.rail, beam="timoshenko"))
    kw = dict(fidelity="linear/hertz", dt=1e-5)
    euler = tw.simulate(scene, V, **kw)
    shear = tw.simulate(timo, V, **kw)

    def thin(sc):
        b = _core.BeamParams()
        b.shear_stiffness = 1e10 * sc.rail.bending_stiffness / sc.rail.length**2
        b.rotary_inertia = 0.0
        return b

    monkeypatch.setattr(_kernel, "beam_params", thin)
    limit = tw.simulate(timo, V, **kw)
    for name in ("normal_force", "y_contact"):
        ref, got = getattr(euler, name), getattr(limit, name)
        assert np.all(np.max(np.abs(got - ref), axis=0) < 2e-6 * np.ptp(ref, axis=0)), name
    assert np.all(np.mean(shear.y_contact, axis=0) < np.mean(euler.y_contact, axis=0))


def test_cli_runs_a_bogie_on_the_ballasted_track(capsys):
    """`trackwheel run --vehicle bogie --track ballasted`: one line per wheel, the pad named
    k_p, and each wheel's static load the lever rule's (half the bogie's weight)."""
    from trackwheel import cli

    assert cli.main(["run", "--speed-kmh", "100", "--vehicle", "bogie", "--track", "ballasted",
                     "--x-start", "12.0", "--x-end", "13.0"]) == 0
    out = capsys.readouterr().out
    assert "k_p = 180 MN/m" in out
    P = Vehicle.bogie().static_loads(tw.Scene.ballasted_track().gravity)
    for i, x in enumerate(Vehicle.bogie().positions):
        assert f"wheel {i} (x = {x:g} m)" in out and f"(static {P[i] / 1e3:.2f} kN)" in out
