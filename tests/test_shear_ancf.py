"""The shear-deformable planar ANCF element of the full model (docs: Model, section
"Shear-deformable rail (Timoshenko)"): its force and tangent against central differences, rigid
motions, the Euler-Bernoulli limit, the linearised element against the IIE Timoshenko beam,
statics and eigenfrequencies against closed forms, a passage against the linear Timoshenko
track, the iteration matrix, the energy balance, and the linear path left as it was.

Element vector e = [x1, y1, d1x, d1y, x2, y2, d2x, d2y]: positions [m], directors [-].
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest
from test_ancf import (H_FD, H_FD_ENERGY, L_EL, TOL_CEILING, TOL_CEILING_ENERGY,
                       fd_with_tolerance, reference_element, rigid)
from test_invariants import cumulative_trapezoid
from test_system import central_difference_error

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel
from trackwheel.eigen import rail_frequencies

TIMO = tw.Rail(beam="timoshenko")  # the paper's rail, shear coefficient 0.4
Y_DOFS = [1, 3, 5, 7]
#: damped supports, as tests/test_paths_agree.py: the trace tolerance is that file's TOL_TRACE
TOL_TRACE = 5e-3


def shear_section(kga=TIMO.shear_stiffness, rho_i=TIMO.rotary_inertia, exact=True,
                  length=L_EL, n_gauss=5):
    c = _core.testing.ShearSection()
    c.length, c.EA, c.EI, c.kGA = length, TIMO.axial_stiffness, TIMO.bending_stiffness, kga
    c.rhoA, c.rhoI, c.exact_curvature, c.n_gauss = TIMO.mass_per_length, rho_i, exact, n_gauss
    return c


def cable_section(exact=True, length=L_EL):
    c = _core.testing.CableSection()
    c.length, c.EA, c.EI, c.rhoA = length, TIMO.axial_stiffness, TIMO.bending_stiffness, \
        TIMO.mass_per_length
    c.exact_curvature, c.n_gauss = exact, 5
    return c


def sheared_states(seed=20260101):
    """The straight element perturbed by 1e-3..1e-2 of l in the positions and of 1 in the
    directors, independently (so the section shears: d differs from r_s), and one such state
    stretched by 2 %, rotated by 1.1 rad and translated."""
    rng = np.random.default_rng(seed)
    scale = np.array([L_EL, L_EL, 1.0, 1.0] * 2)
    states = []
    for _ in range(3):
        amp = 10.0 ** rng.uniform(-3.0, -2.0)
        states.append(reference_element() + amp * scale * rng.uniform(-1.0, 1.0, 8))
    bent = reference_element() + 5e-3 * scale * rng.uniform(-1.0, 1.0, 8)
    states.append(rigid(bent, angle=1.1, shift=(1.3, -0.4), stretch=1.02))
    return states


STATES = sheared_states()


def rel(a, b):
    return np.linalg.norm(np.asarray(a) - np.asarray(b)) / np.linalg.norm(b)


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize("i_state", range(len(STATES)))
def test_force_is_the_gradient_of_the_energy(exact, i_state):
    """Q = dU/de by central differences of U, tolerance from the differences' own truncation
    and round-off estimate (test_ancf.fd_with_tolerance), below the ceiling that would let a
    term of 1e-7 of Q go unseen."""
    c = shear_section(exact=exact)
    e = STATES[i_state]
    Q = _core.testing.shear_elastic(c, e)[0]
    Q_fd, tol = fd_with_tolerance(lambda x: _core.testing.shear_elastic(c, x)[2], e, H_FD_ENERGY, Q)
    assert tol < TOL_CEILING_ENERGY
    assert rel(Q_fd, Q) < tol


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize("i_state", range(len(STATES)))
def test_tangent_matches_central_differences(exact, i_state, validation):
    """K = dQ/de by central differences of Q (same tolerance logic); K is symmetric (the
    Hessian of U)."""
    c = shear_section(exact=exact)
    e = STATES[i_state]
    K = _core.testing.shear_elastic(c, e)[1]
    K_fd, tol = fd_with_tolerance(lambda x: _core.testing.shear_elastic(c, x)[0], e, H_FD, K)
    assert tol < TOL_CEILING
    assert rel(K_fd, K) < tol
    if exact and i_state == 3:
        validation.record(
            "element.shear_tangent", level="element", kind="finite differences",
            quantity="shear-deformable ANCF element: tangent stiffness of a sheared, "
                     "stretched and rotated element",
            reference="central differences of the elastic force (K = dQ/de)",
            measured=rel(K_fd, K), tolerance=tol, metric="relative")
    assert np.linalg.norm(K - K.T) < 1e-12 * np.linalg.norm(K)


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize("i_state", range(len(STATES)))
def test_time_loop_force_equals_the_checked_force(exact, i_state):
    """The rail's internal force (the time loop's force-only pass, written out through r_s, d
    and d_s) is the force checked above: a one-element bare rail against shear_elastic, to
    round-off (1e-12 of |Q|; same formulas, other order of operations)."""
    c = shear_section(exact=exact)
    p = _core.RailParams()
    p.length, p.EA, p.EI, p.rhoA, p.n_elements = L_EL, c.EA, c.EI, c.rhoA, 1
    p.exact_curvature, p.n_gauss = exact, c.n_gauss
    p.shear_stiffness, p.rotary_inertia = c.kGA, c.rhoI
    model = _core.RailModel(p, _core.SupportParams())
    Q, U = model.internal_force(STATES[i_state])
    Q_ref, _, U_ref = _core.testing.shear_elastic(c, STATES[i_state])
    assert rel(Q, Q_ref) < 1e-12
    assert U == pytest.approx(U_ref, rel=1e-12)
    np.testing.assert_array_equal(model.mass_dense(), _core.testing.shear_mass(c))


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize("angle, shift", [(0.0, (3.0, -1.0)), (0.7, (0.0, 0.0)),
                                          (-2.1, (1.7, 0.4)), (math.pi, (5.0, 0.0))])
def test_rigid_motion_gives_zero_force_and_energy(exact, angle, shift):
    """Translated and rotated straight element: eps = kappa = gamma = 0 up to round-off (~1e-16
    in the strains), against the force and energy of an end deflected by 1e-4 m (shear and
    bending strains ~1e-4..1e-3): 1e-9 and 1e-12 leave wide margins, while a frame-dependent
    strain (e.g. gamma = d_y - r_s,y) would give O(1) of the scale."""
    c = shear_section(exact=exact)
    Q, _, U = _core.testing.shear_elastic(c, rigid(reference_element(), angle, shift))
    bent = reference_element()
    bent[5] -= 1e-4
    q_scale, _, u_scale = _core.testing.shear_elastic(c, bent)
    assert np.linalg.norm(Q) < 1e-9 * np.linalg.norm(q_scale)
    assert abs(U) < 1e-12 * u_scale


@pytest.mark.parametrize("exact", [True, False])
@pytest.mark.parametrize("i_state", range(len(STATES)))
def test_euler_bernoulli_limit_is_the_cable(exact, i_state):
    """kGA -> infinity (phi = 12 EI/(kGA l^2) = 1e-9) and rhoI = 0: the IIE functions differ from
    the Hermite ones by O(phi) (psi -> dN/ds) and the shear energy is kGA O(phi)^2 = O(phi) EI/l^2,
    so Q, K and M equal the cable element's to O(phi); tolerance 10 phi (round-off ~1e-13)."""
    phi = 1e-9
    kga = 12.0 * TIMO.bending_stiffness / (phi * L_EL**2)
    s, cab = shear_section(kga=kga, rho_i=0.0, exact=exact), cable_section(exact)
    e = STATES[i_state]
    Qs, Ks, Us = _core.testing.shear_elastic(s, e)
    Qc, Kc, Uc = _core.testing.cable_elastic(cab, e)
    assert rel(Qs, Qc) < 10 * phi
    assert rel(Ks, Kc) < 10 * phi
    assert Us == pytest.approx(Uc, rel=10 * phi)
    assert rel(_core.testing.shear_mass(s), _core.testing.cable_mass(cab)) < 10 * phi


def test_linearised_element_is_the_iie_timoshenko_beam(validation):
    """At the straight reference the y block of K is the IIE stiffness EI mu/l^3 [12 6l ...]
    (closed form, exact with n_gauss >= 3: psi'^2 has degree 2, gamma is constant), the y block
    of M the IIE mass with rotary inertia, and y does not couple with x; to round-off (1e-12)."""
    c = shear_section()
    K = _core.testing.shear_elastic(c, reference_element())[1]
    M = _core.testing.shear_mass(c)
    iy, ix = np.ix_(Y_DOFS, Y_DOFS), np.ix_(Y_DOFS, [0, 2, 4, 6])
    k_ref = _core.testing.timoshenko_stiffness(c.EI, c.kGA, L_EL)
    m_ref = _core.testing.timoshenko_mass(c.rhoA, c.rhoI, c.EI, c.kGA, L_EL)
    np.testing.assert_allclose(K[iy], k_ref, rtol=0, atol=1e-12 * np.abs(k_ref).max())
    validation.record(
        "element.shear_linearised_is_iie_timoshenko", level="element", kind="closed form",
        quantity="shear-deformable ANCF element linearised at the straight rail: vertical "
                 "stiffness",
        reference="interdependent-interpolation (IIE) Timoshenko beam element EI μ/l³ "
                  "[12 6l ...]",
        measured=np.abs(K[iy] - k_ref).max() / np.abs(k_ref).max(), tolerance=1e-12,
        metric="of max |K|")
    np.testing.assert_allclose(M[iy], m_ref, rtol=0, atol=1e-13 * np.abs(m_ref).max())
    assert np.abs(K[ix]).max() < 1e-12 * np.abs(K).max()
    assert np.abs(M[ix]).max() < 1e-13 * np.abs(M).max()


def test_mass_of_rigid_motions():
    """Translation: rhoA l; rotation of the straight element about its centre (r = (s - l/2) t,
    d = t): rhoA l^3/12 + rhoI l, the section's rotary inertia (exact quadrature, 1e-13)."""
    c = shear_section()
    M = _core.testing.shear_mass(c)
    t = np.array([0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0])  # rigid vertical velocity
    w = np.array([0.0, -L_EL / 2, 0.0, 1.0, 0.0, L_EL / 2, 0.0, 1.0])  # angular velocity 1
    assert t @ M @ t == pytest.approx(c.rhoA * L_EL, rel=1e-13)
    assert w @ M @ w == pytest.approx(c.rhoA * L_EL**3 / 12 + c.rhoI * L_EL, rel=1e-13)


def _span(beam: str, length: float, n_elements: int, load: float | None = None) -> tw.Scene:
    """The paper's rail as one bare simply supported span, no rail weight."""
    s = tw.Scene.kato2005()
    wheel = s.wheel if load is None else dc.replace(s.wheel, load=load)
    return dc.replace(s, rail=dc.replace(s.rail, length=length, n_elements=n_elements, beam=beam),
                      supports=dc.replace(s.supports, positions=()), rail_gravity=False,
                      wheel=wheel)


def test_static_midspan_deflection_with_shear():
    """A 1 m simply supported span under the wheel at midspan, P = 1 kN + M g: w = P L^3/(48 EI)
    + P L/(4 kGA) (the shear part is 23 % of it). The IIE element is nodally exact in linear
    statics, so what remains is the nonlinearity: the slope^2 of the geometry (~1e-9 relative)
    and the kink of the centre line under the load (the shear angle jumps by P/kGA there, which
    tilts the contact normal and moves the contact point by rho0 P/(2 kGA): ~1e-7 of w,
    measured 4e-8). Tolerance 1e-6; without shear the result is 23 % off."""
    s = _span("timoshenko", 1.0, 8, load=1e3)
    st = tw.static(s, 0.5)
    P, r = st.normal_force, s.rail
    bending = P / (48 * r.bending_stiffness)
    shear = P / (4 * r.shear_stiffness)
    assert -st.y_contact == pytest.approx(bending + shear, rel=1e-6)
    assert shear > 0.2 * (bending + shear)


def _dense_vertical_frequencies(scene: tw.Scene) -> np.ndarray:
    """The full model's rail: eigenfrequencies [Hz] of its tangent and mass at the straight
    reference over the free vertical coordinates (y, d_y; x decouples there)."""
    from scipy.linalg import eigh

    m = _kernel.rail_model(scene)
    free = np.asarray(m.free_to_full)
    vert = free[free % 2 == 1]
    K = np.asarray(m.tangent_dense(m.reference()))[np.ix_(vert, vert)]
    M = np.asarray(m.mass_dense())[np.ix_(vert, vert)]
    return np.sqrt(eigh(K, M, eigvals_only=True)) / (2 * math.pi)


def test_pinned_pinned_frequency_of_the_full_model():
    """The first bending mode of a bare 0.5 m span of the full model's rail: within 0.5 % of the
    lower root of the Timoshenko frequency equation (docs: Model, section "Shear-deformable rail
    (Timoshenko)"; 20 elements, FE error ~1e-3),
    and far from the Euler-Bernoulli 2.15 kHz."""
    from trackwheel.fidelity import pinned_pinned_frequencies

    s = _span("timoshenko", 0.5, 20)
    f_e, f_t = pinned_pinned_frequencies(s)
    f = _dense_vertical_frequencies(s)[0]
    assert f == pytest.approx(f_t, rel=5e-3)
    assert f < 0.8 * f_e


def test_full_model_frequencies_equal_the_linear_timoshenko_track():
    """The paper's track: the full model's vertical frequencies (dense tangent and mass, and
    rail_frequencies, dense and sparse) equal the linear Timoshenko track's (its own IIE
    matrices); the linearised element is that beam (above), so to round-off: 1e-9 (sparse:
    eigen.SPARSE_TOL 1e-12 plus the conditioning, measured 1e-13)."""
    s = tw.Scene.kato2005()
    s = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko"))
    model = _kernel.rail_model(s)
    lin = np.asarray(_core.testing.track_modes(model, _kernel.beam_params(s), 0.0, 0.0, [0.0],
                                       8)[0]).ravel()
    np.testing.assert_allclose(_dense_vertical_frequencies(s)[:8], lin, rtol=1e-9)
    ne = s.rail.n_elements  # the mesh of the model above
    np.testing.assert_allclose(rail_frequencies(s, 8, method="dense", n_elements=ne), lin,
                               rtol=1e-9)
    np.testing.assert_allclose(rail_frequencies(s, 8, method="sparse", n_elements=ne), lin,
                               rtol=1e-9)
    # with the wheel on its contact spring: the coupled modes of both methods agree as well
    d = tw.eigen(s, [2.25], 6, method="dense").frequencies
    sp = tw.eigen(s, [2.25], 6, method="sparse").frequencies
    np.testing.assert_allclose(sp, d, rtol=1e-9)


def test_linearised_full_rail_has_the_linear_tracks_receptance():
    """The full model's rail linearised at the straight reference (eigen.vertical_matrices: its
    band M, C, K over the vertical coordinates, with support dampers and graded absorbing end
    zones through the w functions) gives the linear Timoshenko track's receptance
    (tw.receptance, its own IIE matrices), point and transfer, to round-off (1e-9; the solves
    differ: dense here, banded there)."""
    from trackwheel.eigen import vertical_matrices

    s = tw.Scene.kato2005()
    s = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko",
                                      absorbing_ends=tw.AbsorbingEnds(1.0)),
                   supports=dc.replace(s.supports, damping=2e5))
    M, C, K, dofs = (x.toarray() if hasattr(x, "toarray") else x for x in vertical_matrices(s))
    model = _kernel.rail_model(s)

    def coupling(x):
        out = np.zeros(len(dofs))
        for j, i in enumerate(dofs):
            unit = np.zeros(model.n_dof)
            unit[i] = 1.0
            out[j] = model.positions(unit, [x])[0, 1]
        return out

    se, sr = coupling(2.1), coupling(3.3)
    freqs = np.array([50.0, 800.0, 1500.0])
    w = 2 * np.pi * freqs
    full = np.array([[sr_ @ np.linalg.solve(K + 1j * wi * C - wi**2 * M, se)
                      for sr_ in (se, sr)] for wi in w])
    ne = s.rail.n_elements  # the mesh of vertical_matrices
    lin = np.stack([tw.receptance(s, 2.1, freqs, n_elements=ne),
                    tw.receptance(s, 2.1, freqs, 3.3, n_elements=ne)], axis=1)
    np.testing.assert_allclose(full, lin, rtol=1e-9)


def _damped(beam: str) -> tw.Scene:
    s = tw.Scene.kato2005()
    return dc.replace(s, supports=dc.replace(s.supports, damping=2e5),
                      rail=dc.replace(s.rail, beam=beam))


@pytest.mark.parametrize("level", ["sprung", "hertz"])
def test_full_timoshenko_passage_matches_the_linear_timoshenko_track(level):
    """300 km/h over the damped paper's track (as test_paths_agree's Euler-Bernoulli check):
    the ANCF level with the shear-deformable rail agrees with the linear level on the
    Timoshenko beam within TOL_TRACE of the amplitude (measured 0.004 % amplitude, 0.02 % trace
    with the element compliance of both paths, 0.09 % without: 2x and 8x the Euler-Bernoulli
    difference, growing with P and with 1/kGA -- the centre line's slope, which sets the full
    model's contact normal and point, carries the shear angle) and the normal force within 1e-3
    of the static load (measured 7e-5). Shear matters here: the
    Euler-Bernoulli amplitude is 16 % lower, 30x the tolerance."""
    kw = {"n_elements": 20, "dt": 1e-5}
    v = tw.kmh(300)
    s = _damped("timoshenko")
    a = tw.simulate(s, v, fidelity=f"ancf/{level}", **kw)
    b = tw.simulate(s, v, fidelity=f"linear/{level}", **kw)
    full, lin = tw.analyse(a), tw.analyse(b)
    assert abs(lin.amplitude / full.amplitude - 1.0) < TOL_TRACE
    assert np.max(np.abs(lin.dynamic - full.dynamic)) < TOL_TRACE * full.amplitude
    assert np.max(np.abs(a.normal_force - b.normal_force)) < 1e-3 * s.static_load
    euler = tw.analyse(tw.simulate(_damped("euler"), v, fidelity=f"ancf/{level}", **kw))
    assert abs(euler.amplitude / full.amplitude - 1.0) > 20 * TOL_TRACE


@pytest.mark.parametrize("law, slide", [("linear", False), ("hertz", True)])
def test_iteration_matrix_matches_central_differences(law, slide):
    """generalized-alpha's iteration matrix on the Timoshenko scene (wheel at its static state on
    the shear-deformable rail, one step of 1e-5 s) against central differences of the residual,
    as tests/test_system.py's Euler-Bernoulli cases: every column within 1e-6 of its largest
    entry (FD truncation and round-off ~1e-8 at steps of 1e3 in these units)."""
    scene = tw.Scene.kato2005()
    scene = dc.replace(scene, rail=dc.replace(scene.rail, beam="timoshenko"),
                       contact=dc.replace(scene.contact, law=law))
    dt, v = 1e-5, tw.kmh(300)
    model = _kernel.rail_model(scene, 20)
    contact = _kernel.contact_params(scene)
    wheel = _kernel.wheel_params(scene)
    d = _core.static_solve(model, wheel, contact, 1.3)
    w = _core.WheelState()
    w.y, w.s, w.thetadot = d["y_wheel"], d["contact_s"], v / scene.wheel.radius
    w.state = _core.SlipState.slip if slide else _core.SlipState.stick
    w.sigma = -1.0
    st = _core.SimState()
    st.e = np.asarray(d["e"])
    st.edot, st.wheels = np.zeros_like(st.e), [w]
    s = _core.SimSettings()
    s.speed, s.x_start, s.dt, s.t_end = v, 1.3, dt, dt

    def R(x=None):
        return _core.testing.ga_probe(model, [wheel], contact, s, st, dt, x)

    p0 = R()
    x0, J = p0["start"], p0["matrix"]
    assert J.shape == (model.n_free + 3, model.n_free + 3)
    h = np.full(len(x0), 1e3)
    h[model.n_free + 2] = 1.0  # the multiplier lambda [N]
    err = central_difference_error(R, x0, J, h)
    assert np.max(err) < 1e-6, (int(np.argmax(err)), float(np.max(err)))


def test_energy_balance_with_the_shear_deformable_rail():
    """Undamped passage at 100 km/h (as test_invariants' Euler-Bernoulli check): the total
    energy, now with the shear strain energy and the rotary inertia, changes only by the work of
    the driving reaction R; generalized-alpha with rho_inf = 1 (trapezoidal) keeps that balance
    to the Newton tolerance. Between node crossings the tolerance is test_invariants' 1e-6 of
    max |W| (measured 2e-9).

    At a node the IIE centre line has a kink (its shear angle is constant per element and jumps
    by the nodal shear force over kGA, ~P/kGA = 2e-4 rad under the wheel), so the contact normal
    and R jump there (by ~9 N), and the step across the jump integrates the work with an error
    of up to |R jump| v dt (the trapezoid across a discontinuity; measured 0.5 of it, and it
    falls with dt: 3.4e-4, 1.5e-4, 5e-5 J at dt = 5, 2.5, 1.25 us)."""
    s = tw.Scene.kato2005()
    s = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko"))
    v, dt, ne = tw.kmh(100), 2.5e-6, 20
    r = tw.simulate(s, v, x_end=1.0, dt=dt, n_elements=ne, rho_inf=1.0, energy=True)
    work = cumulative_trapezoid(r.reaction * v, r.t)
    assert np.max(np.abs(work)) > 1.0
    step = np.diff(r.energy - work)  # the balance's error made in each step
    element = np.floor(r.contact_s / (s.rail.length / ne))
    crossing = np.diff(element) != 0
    assert np.count_nonzero(crossing) == 3  # x = 0.25 .. 1.0 m: nodes at 0.25, 0.5, 0.75 m
    assert abs(np.sum(step[~crossing])) < 1e-6 * np.max(np.abs(work))
    assert np.max(np.abs(step[~crossing])) < 1e-6 * np.max(np.abs(work))
    jump_r = np.abs(np.diff(r.reaction))[crossing]
    assert np.all(np.abs(step[crossing]) <= jump_r * v * dt)


def _linear_outputs(scene):
    _kernel.rail_model.cache_clear()
    r = tw.simulate(scene, 30.0, fidelity="linear/hertz", x_start=2.0, x_end=2.4, dt=2e-5)
    model = _kernel.rail_model(scene)
    modes = [] if scene.supports.layered else _core.testing.track_modes(
        model, _kernel.beam_params(scene), scene.wheel.mass, scene.contact_stiffness, [2.1], 6)[0]
    rec = tw.receptance(scene, 2.1, [10.0, 500.0, 1500.0])
    return [r.y_contact, r.normal_force, r.y_wheel, np.asarray(modes), rec,
            np.asarray(model.mass_dense())]


@pytest.mark.parametrize("layered", [False, True])
def test_linear_path_does_not_see_the_shear_element(layered, monkeypatch):
    """The linear Timoshenko track takes its own IIE matrices: with single springs a run, its
    modes and its receptance are bit-identical whether or not the kernel's RailModel carries kGA
    and rhoI, while the RailModel's own (full-model) mass does change. With sleepers the
    sleepers' rail weights come from RailModel.locate: now the IIE w functions (those the linear
    beam's pads use) instead of the Hermite ones, equal at the nodes where these supports sit up
    to the rounding of mu (1 + phi) = 1, so the results agree to round-off (1e-12; measured
    7e-14) -- and between nodes the sleepers now couple consistently with the pads. The Hertz
    force N = C_H delta^1.5 sees that rounding of the rail height y relative to the compression
    delta, amplified by 1.5 |y| / delta ~ 15 (measured 1.0e-12; 8.6e-13 without the element
    compliance): 1e-11 for it."""
    s = tw.Scene.kato2005()
    s = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko"))
    if layered:
        s = dc.replace(s, supports=dc.replace(s.supports, sleeper_mass=150.0,
                                               ballast_stiffness=105e6, ballast_damping=5e4))
    with_shear = _linear_outputs(s)
    original = _core.RailModel

    def without_shear(p, *args):
        p.shear_stiffness, p.rotary_inertia = 0.0, 0.0
        return original(p, *args)

    monkeypatch.setattr(_core, "RailModel", without_shear)
    try:
        euler = _linear_outputs(s)
    finally:
        monkeypatch.undo()
        _kernel.rail_model.cache_clear()
    for i, (a, b) in enumerate(zip(with_shear[:-1], euler[:-1])):
        if layered:
            np.testing.assert_allclose(a, b, rtol=1e-11 if i == 1 else 1e-12, atol=0)
        else:
            np.testing.assert_array_equal(a, b)
    assert not np.array_equal(with_shear[-1], euler[-1])


@pytest.mark.parametrize("field, value, match", [
    ("shear_stiffness", -1.0, "shear_stiffness must be >= 0"),
    ("shear_stiffness", math.nan, "shear_stiffness must be >= 0"),
    ("rotary_inertia", -1.0, "rotary_inertia must be >= 0"),
    ("rotary_inertia", 0.24, "rotary_inertia must be 0 kg m with shear_stiffness = 0"),
])
def test_rail_params_validation(field, value, match):
    p = _core.RailParams()
    p.length, p.EA, p.EI, p.rhoA, p.n_elements, p.n_gauss = 5.0, 1.6e9, 6.4e6, 60.0, 20, 5
    setattr(p, field, value)
    with pytest.raises(ValueError, match=match):
        _core.RailModel(p, _core.SupportParams())


def test_full_paths_take_the_timoshenko_rail():
    """static, simulate's full level and the vehicle eigen run with the shear-deformable rail
    (they refused Rail(beam='timoshenko') before). The static deflection under the wheel, and
    its shear part (Timoshenko minus Euler-Bernoulli), equal the linear track's own statics
    with the linear path's IIE beam (an independent element, linear_beam.cpp) within 3e-4 of
    the deflection: the tolerance of the Euler-Bernoulli comparison in test_statics.py
    (rho0 theta^2 of the contact point's offset, ~2e-4; measured 3.4e-6, the shear part 9 % of
    the deflection). The vehicle eigen of a single-wheel
    vehicle equals the single-wheel eigen (same matrices, different assembly: 1e-9)."""
    from trackwheel.vehicle import Vehicle

    s = tw.Scene.kato2005()
    st = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko"))
    ye, yt = tw.static(s, 2.5).y_contact, tw.static(st, 2.5).y_contact
    le, lt = (tw.linear_quasi_static(x, [2.5])[0] for x in (s, st))
    assert abs(yt - lt) < 3e-4 * abs(lt)
    assert abs((yt - ye) - (lt - le)) < 3e-4 * abs(lt)
    assert abs(lt - le) > 10 * 3e-4 * abs(lt)  # the shear part is resolved by the check
    r = tw.simulate(st, 30.0, x_start=2.0, x_end=2.1)
    assert np.all(r.normal_force > 0)
    sv = dc.replace(st, vehicle=Vehicle.single_wheel())
    np.testing.assert_allclose(tw.eigen(sv, [2.5], 6).frequencies,
                               tw.eigen(st, [2.5], 6).frequencies, rtol=1e-9)


@pytest.mark.parametrize("per_bay", [4, 16, 64])
def test_axial_frequencies_do_not_depend_on_the_mesh(per_bay):
    """The axial modes of the full model's shear-deformable rail (6 m of the ballasted preset,
    x held at X = 0, the far end a roller) are those of the rod whose kinetic energy is the
    element's, rho A u_t^2 + rho I u_st^2 (the director follows u_s):
    f_n = c k_n / (2 pi) / sqrt(1 + r_g^2 k_n^2), k_n = (2n - 1) pi / (2L), c = sqrt(E / rho),
    r_g^2 = I / A, at 0.15 m to 9.4 mm elements. Tolerance 5e-4: the cubic elements' error is
    below 1e-8 at these wavelengths; the director's stretch is held by kappa G A, not rigidly,
    which adds rho I omega^2 / (kappa G A) of the correction (4 % of it at the third mode:
    measured 1.5e-4). The director's length had no stiffness of its own before: its modes fell
    as l^2 (106 Hz at 8 elements per bay, 1.7 Hz at 64) below the rod's 215 Hz."""
    base = tw.Scene.ballasted_track(length=6.0, elements_per_bay=per_bay)
    s = dc.replace(base, rail=dc.replace(base.rail, beam="timoshenko"))
    rail = s.rail
    c = math.sqrt(rail.youngs_modulus / rail.density)
    k = (2 * np.arange(1, 4) - 1) * math.pi / (2 * rail.length)
    f = c * k / (2 * math.pi) / np.sqrt(1.0 + rail.second_moment / rail.area * k**2)
    got = tw.eigen(s, [3.0], n_modes=1, n_axial=3, n_elements=rail.n_elements)
    np.testing.assert_allclose(got.axial_frequencies, f, rtol=5e-4)
