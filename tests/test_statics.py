"""Statics (docs: Model § Outputs): the wheel resting on the rail, y_qs(X), against analytic references."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel

KATO = tw.Scene.kato2005()


def no_gravity(scene):
    return dataclasses.replace(scene, gravity=0.0, rail_gravity=False)


def winkler_scene(spacing, stiffness, length=30.0):
    rail = dataclasses.replace(KATO.rail, length=length,
                               n_elements=round(length / spacing))
    return no_gravity(dataclasses.replace(
        KATO, rail=rail, supports=tw.Supports(stiffness=stiffness, spacing=spacing)))


def winkler_deflection(scene):
    """P beta / (2 k_f), beta = (k_f / (4 EI))^(1/4) (docs: Model § Validation) [m], and beta [1/m]."""
    kf = scene.winkler_modulus
    beta = (kf / (4.0 * scene.rail.bending_stiffness)) ** 0.25
    return scene.static_load * beta / (2.0 * kf), beta


@pytest.mark.parametrize("x_offset", [0.0, 0.5], ids=["on_support", "mid_bay"])
def test_long_rail_on_dense_supports_matches_winkler(x_offset, validation):
    """A 30 m rail on supports every 0.1 m with the paper's foundation modulus
    k_f = 140 MN/m / 0.5 m = 280 MN/m^2: beta = 1.82 /m, so beta L = 55 (the ends, where the
    deflection decays like exp(-beta x), are exp(-27) away from the load: an infinite beam)
    and beta d_s = 0.18 (a wavelength 2 pi / beta = 3.5 m spans 35 supports: a continuous
    foundation). Nodes on every support, wheel load P = F = 47040 N, no gravity."""
    d = 0.1
    scene = winkler_scene(d, stiffness=280e6 * d)
    w, beta = winkler_deflection(scene)
    assert beta * scene.rail.length > 50 and beta * d < 0.2
    res = tw.static(scene, 15.0 + x_offset * d)
    assert res.normal_force == pytest.approx(scene.static_load, rel=1e-9)
    err = abs(-res.y_contact / w - 1.0)
    assert err < 0.03  # the criterion (measured: 8e-6 on a support, 2.4e-4 mid-bay)
    where = "above a support" if x_offset == 0.0 else "mid-bay"
    validation.record(
        f"statics.winkler_beam[{'on_support' if x_offset == 0.0 else 'mid_bay'}]",
        level="statics", kind="closed form",
        quantity=f"deflection under the wheel, 30 m rail on supports every 0.1 m, {where}",
        reference="beam on a Winkler foundation: P β/(2 k_f), β = (k_f/4EI)^(1/4)",
        measured=err, tolerance=0.03)
    # the discrete-support error is what remains: it falls as the supports get denser at the
    # same k_f (measured 2.4e-4 -> 1.8e-5 mid-bay for d = 0.1 -> 0.05)
    finer = winkler_scene(d / 2, stiffness=280e6 * d / 2)
    res2 = tw.static(finer, 15.0 + x_offset * d / 2)
    err2 = abs(-res2.y_contact / w - 1.0)
    assert err2 < err


def scene_with_supports(positions):
    return no_gravity(dataclasses.replace(KATO, supports=tw.Supports(positions=positions)))


#: the paper's supports with the third one moved from 1.5 m to 1.3 m
SHIFTED = (0.5, 1.0, 1.3, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5)


def test_support_between_nodes_statics_converges_to_node_aligned_mesh():
    """Without rail weight and with the wheel on a node (X = 1.5 m), the exact deflection of an
    Euler-Bernoulli beam with point forces at nodes is piecewise cubic, so a mesh with a node
    at every support reproduces it (only the geometric nonlinearity, ~1e-8, separates meshes).
    A support at 1.3 m between the nodes of the 0.25 m mesh must converge to that answer."""
    scene = scene_with_supports(SHIFTED)
    aligned = {ne: tw.static(scene, 1.5, n_elements=ne).y_contact for ne in (50, 100)}
    assert aligned[50] == pytest.approx(aligned[100], rel=1e-9)
    ref = aligned[100]
    err = {ne: abs(tw.static(scene, 1.5, n_elements=ne).y_contact / ref - 1.0)
           for ne in (20, 40, 80)}  # 1.3 m sits at xi = 0.2, 0.4, 0.8 of an element
    # measured 1.7e-4, 7.0e-5, 2.6e-6: the 0.25 m mesh is already within 0.05 %
    assert err[20] < 5e-4
    assert err[80] < err[40] < err[20]
    assert err[80] < err[20] / 30  # about third-to-fourth order in h


def test_static_equilibrium_balances_forces():
    """The paper's scene with rail weight, wheel at 1.6 m (between nodes). Support forces
    -k_s y(X_j), the end reactions (the residual at the fixed coordinates) and the loads must
    balance; the wheel's own equilibrium gives N n_y = F + M g."""
    scene = KATO
    res = tw.static(scene, 1.6)
    model = _kernel.rail_model(scene)
    e = res.rail_coordinates
    Q, _ = model.internal_force(e)
    Qg = np.array(model.gravity_force())
    d = _core.contact_eval(model, e, res.x_wheel, res.y_wheel, res.contact_s,
                           _kernel.contact_params(scene), np.zeros(10))
    Qc = np.zeros(model.n_dof)
    Qc[4 * d["element"]:4 * d["element"] + 8] = d["F"][2:]
    R = np.array(Q) - Qg - Qc  # = reaction forces at the fixed coordinates, 0 elsewhere
    P = scene.static_load
    free = np.array(model.free_to_full)
    assert np.abs(R[free]).max() < 1e-9 * P  # Newton converged
    weight = scene.rail.mass_per_length * scene.gravity * scene.rail.length
    y_sup = model.positions(e, list(scene.support_positions))[:, 1]
    support_forces = -scene.supports.stiffness * y_sup  # upward on the rail [N]
    end_reactions = R[1] + R[model.n_dof - 3]
    assert support_forces.sum() + end_reactions == pytest.approx(P + weight, rel=1e-10)
    assert R[0] + Qc[0::4].sum() == pytest.approx(0.0, abs=1e-9 * P)  # horizontal: pinned end
    # the wheel
    assert d["N"] * d["normal"][1] == pytest.approx(P, rel=1e-10)
    assert res.normal_force == pytest.approx(d["N"], rel=1e-12)
    assert res.contact_s == pytest.approx(1.6, abs=1e-6)  # nearly vertical normal
    # the wheel sits k-compressed on the rail: Y_A - y_B = rho0 - P/k (to the tilt, ~1e-8)
    assert res.y_wheel - res.y_contact == pytest.approx(
        scene.wheel.radius - P / scene.contact_stiffness, abs=1e-9)


def test_static_matches_linear_finite_element_solution(validation):
    """The deflection is ~1e-4 m on 5 m: geometric nonlinearity is ~(w/d_s)^2 ~ 1e-7, so the
    Newton solution equals the linear Euler-Bernoulli FE solution (tangent at the straight rail,
    wheel on a spring k at a node) to ~1e-6."""
    scene = KATO
    X = 2.5
    model = _kernel.rail_model(scene)
    K = np.array(model.tangent_dense(model.reference()))
    free = [i for i in model.free_to_full if i % 2 == 1]  # y, y_s
    n = len(free)
    node_y = 4 * round(X / model.element_length) + 1
    k = scene.contact_stiffness
    A = np.zeros((n + 1, n + 1))
    A[:n, :n] = K[np.ix_(free, free)]
    i = free.index(node_y)
    A[i, i] += k
    A[i, n] -= k
    A[n, i] -= k
    A[n, n] += k
    b = np.zeros(n + 1)
    b[:n] = np.array(model.gravity_force())[free]
    b[n] = -scene.static_load
    u = np.linalg.solve(A, b)
    res = tw.static(scene, X)
    assert res.y_contact == pytest.approx(u[i], rel=1e-6)
    validation.record(
        "statics.nonlinear_equals_linear_fe", level="statics", kind="path agreement",
        quantity="paper's scene, wheel at rest at 2.5 m: rail deflection under the wheel "
                 "(Newton on the nonlinear ANCF rail)",
        reference="linear Euler-Bernoulli finite elements, a dense solve in the test",
        measured=abs(res.y_contact / u[i] - 1.0), tolerance=1e-6)
    # the wheel centre moves by u_wheel from rest, where it touched the undeformed rail
    assert res.y_wheel - scene.wheel.radius == pytest.approx(u[n], rel=1e-6)


def test_hertz_and_linearised_contact_give_the_same_rail_deflection(validation):
    """Both laws carry N = P at equilibrium, so the rail is loaded identically; only the wheel's
    approach differs: delta = P/k (linear) or (P/C_H)^(2/3) (Hertz)."""
    hertz = dataclasses.replace(KATO, contact=tw.Contact(law="hertz"))
    P = KATO.static_load
    lin = tw.static(KATO, 1.6)
    her = tw.static(hertz, 1.6)
    assert her.normal_force == pytest.approx(P, rel=1e-9)
    assert her.y_contact == pytest.approx(lin.y_contact, rel=1e-9)
    # the linearisation k = 1.5 C_H^(2/3) P^(1/3) is the tangent, so delta_lin = 2/3 delta_H
    d_hertz = (P / KATO.hertz_constant) ** (2.0 / 3.0)
    assert her.y_wheel - her.y_contact == pytest.approx(KATO.wheel.radius - d_hertz, abs=1e-9)
    validation.record(
        "contact.hertz_approach", level="contact", kind="closed form",
        quantity="Hertzian contact at rest under P = F + Mg: approach of wheel and rail",
        reference="Hertz: δ = (P/C_H)^(2/3), C_H = 4/3 E* √ρ0",
        measured=abs(her.y_wheel - her.y_contact - (KATO.wheel.radius - d_hertz)),
        tolerance=1e-9, metric="m")
    assert KATO.wheel.radius - (lin.y_wheel - lin.y_contact) == pytest.approx(
        2.0 / 3.0 * d_hertz, rel=1e-6)


def test_quasi_static_equals_static_at_each_position():
    X = np.array([0.3, 0.8, 1.6, 2.2, 2.5, 3.9])
    qs = tw.quasi_static(KATO, X)
    for j, x in enumerate(X):
        st = tw.static(KATO, x)
        # both are Newton solutions converged to steps of 1e-13 L; the warm start only changes
        # the path
        assert qs.y_contact[j] == pytest.approx(st.y_contact, rel=1e-9)
        assert qs.y_wheel[j] == pytest.approx(st.y_wheel, rel=1e-12, abs=1e-13)
        assert qs.contact_s[j] == pytest.approx(st.contact_s, abs=1e-10)
        assert qs.normal_force[j] == pytest.approx(st.normal_force, rel=1e-9)
    assert np.all(qs.y_contact < 0)  # pressed down


def test_quasi_static_line_is_symmetric():
    """The scene is symmetric about L/2 except for the axial end condition (x fixed at 0, a
    roller at L). With the far end pinned the problem is exactly symmetric; with the roller
    the rail's end slides by ~int w'^2/2 ds ~ 1e-7 m, which shifts y_qs by a relative ~1e-8
    (measured 2e-8): 1e-6 bounds it."""
    X = np.array([0.3, 0.75, 1.6, 2.2, 2.5])
    L = KATO.rail.length
    qs = tw.quasi_static(KATO, X)
    mirror = tw.quasi_static(KATO, L - X)
    np.testing.assert_allclose(mirror.y_contact, qs.y_contact, rtol=1e-6)
    pinned = dataclasses.replace(KATO, rail=dataclasses.replace(KATO.rail, far_end="pinned"))
    qp = tw.quasi_static(pinned, X)
    qp_mirror = tw.quasi_static(pinned, L - X)
    np.testing.assert_allclose(qp_mirror.y_contact, qp.y_contact, rtol=1e-12)
    np.testing.assert_allclose(qp.y_contact, qs.y_contact, rtol=1e-6)
    # the line dips between supports and is stiffest over them
    on_support = tw.static(KATO, 1.5).y_contact
    mid_bay = tw.static(KATO, 1.75).y_contact
    assert mid_bay < on_support < 0


def test_linear_quasi_static_is_the_point_load_deflection_of_a_simply_supported_beam(
        validation):
    """Bare simply supported rail, no rail weight: y(a) = -P a^2 b^2 / (3 EI L) under the load
    at a, b = L - a (beam tables). Hermite cubics reproduce a beam under nodal point loads
    exactly, so at nodes only round-off remains (a band solve of ~80 unknowns whose stiffness
    entries span l_e^-3 .. l_e^-1: relative error ~1e-12; tolerance 1e-9)."""
    scene = dataclasses.replace(tw.Scene.kato2005(), supports=tw.Supports(positions=()),
                                rail_gravity=False)
    ne, L, ei, P = 40, scene.rail.length, scene.rail.bending_stiffness, scene.static_load
    a = L / ne * np.arange(3, ne - 2, 4)
    y = tw.linear_quasi_static(scene, a, n_elements=ne)
    exact = -P * a**2 * (L - a) ** 2 / (3.0 * ei * L)
    np.testing.assert_allclose(y, exact, rtol=1e-9)
    validation.record(
        "statics.point_load_on_a_simply_supported_beam", level="statics", kind="closed form",
        quantity="linear track, bare 5 m rail: deflection under a point load at nine positions",
        reference="beam tables: P a² b²/(3 EI L)",
        measured=np.max(np.abs(y / exact - 1.0)), tolerance=1e-9)


def test_linear_quasi_static_is_the_ancf_line_linearised():
    """The linear track is the ANCF rail linearised about the straight rail, loaded at X_A
    instead of at the contact point. The ANCF contact point sits rho0 theta behind or ahead of
    X_A on a rail of slope theta, which moves y_B by ~rho0 theta^2: with theta up to 6e-4 under
    the paper's wheel (deflection 0.16 mm over a quarter bay), rho0 theta^2 ~ 4e-8 m, 2e-4 of
    the deflection; the geometric nonlinearity ((y/l)^2 ~ 1e-7) is far smaller. Tolerance 3e-4
    of the largest deflection (measured: 3e-5)."""
    scene = tw.Scene.kato2005()
    x = np.linspace(0.3, 4.7, 23)
    ancf = tw.quasi_static(scene, x, n_elements=80).y_contact
    lin = tw.linear_quasi_static(scene, x, n_elements=80)
    assert np.max(np.abs(lin - ancf)) < 3e-4 * np.max(np.abs(ancf))


@pytest.mark.parametrize("fidelity, layered", [("linear/hertz", False),
                                               ("linear/moving_force", False),
                                               ("linear/hertz", True)])
def test_linear_runs_start_on_their_quasi_static_line(fidelity, layered):
    """analyse measures a linear run against the linear track's own static line, on which the
    run starts (static equilibrium, N = P): d(0) is round-off, ~1e-16 m against a deflection
    of ~1e-4 m, also on an irregular rail (the profile lifts the wheel, not the rail) and on
    pad-sleeper-ballast supports (the sleepers condensed at rest, with their weight)."""
    scene = dataclasses.replace(tw.Scene.kato2005(),
                                irregularity=tw.Irregularity.sine(1.0, 1e-4))
    if layered:
        scene = dataclasses.replace(scene, supports=dataclasses.replace(
            scene.supports, sleeper_mass=150.0, ballast_stiffness=105e6))
    r = tw.simulate(scene, tw.kmh(200), fidelity=fidelity, x_end=1.2, progress=False)
    a = tw.analyse(r)
    assert abs(a.dynamic[0]) < 1e-12 * np.max(np.abs(a.y_qs))
    assert a.amplitude > 1e-8  # and the run does move off it


def test_linear_quasi_static_rejects_bad_input():
    scene = tw.Scene.kato2005()
    with pytest.raises(ValueError, match="positions"):
        tw.linear_quasi_static(scene, [6.0])
    with pytest.raises(ValueError, match="n_modes"):
        tw.linear_quasi_static(scene, [1.0], n_modes=0)


def test_the_static_fields_are_the_kernels():
    """The static result classes come from one table (run.results.STATIC_FIELDS): every field of
    it is in the kernel's static solution, and StaticResult carries each of them, with the
    kernel's values."""
    from trackwheel.run.results import STATIC_FIELDS, static_from_kernel

    scene = tw.Scene.ballasted_track()
    model = _kernel.rail_model(scene)
    d = _core.static_solve(model, _kernel.wheel_params(scene), _kernel.contact_params(scene),
                           15.3)
    names = [q.name for q in STATIC_FIELDS]
    values = static_from_kernel(d, names)
    res = tw.static(scene, 15.3)
    for name in names:
        np.testing.assert_array_equal(getattr(res, name), values[name])
        assert f"``{name}``" in tw.StaticResult.__doc__
    assert res.sleeper_z.size == len(scene.support_positions)
