"""The rail under the load between nodes: the element's fixed-end compliance in series with the
contact law (docs: Model § Contact, "The rail under the load between nodes";
``Contact.element_compliance``).

The element's w functions are exact homogeneous static solutions (the IIE Timoshenko
functions; the Hermite cubics for Euler-Bernoulli), so a static point load P at a between the
nodes, applied through the work-equivalent nodal loads S(a)^T P, gives exact nodal values; the
exact deflection under the load is the interpolation plus the element's clamped-clamped
Green's function G(a) P. These tests check G(a) and the statics against the closed form of a
simply supported span, the series law and every new Jacobian against central differences, and
the moving contact on the shear-deformable rail against mesh refinement.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest
from conftest import EA, EI, RHO_A
from test_ancf import fd_with_tolerance
from test_contact import RHO0, bent_rail
from test_system import central_difference_error

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel

KGA = tw.Rail(beam="timoshenko").shear_stiffness  # the paper's rail, kappa 0.4 [N]
RHO_I = tw.Rail().rotary_inertia  # [kg m]
K_LIN = tw.Scene.kato2005().contact_stiffness  # [N/m]
C_HERTZ = tw.Scene.kato2005().hertz_constant  # [N/m^1.5]
LAWS = {"linear": K_LIN, "hertz": C_HERTZ}


def shear_rail(length=5.0, n_elements=20, shear=True, profile=None):
    """The paper's section on ``n_elements`` (shear-deformable with ``shear``), simply supported
    at its ends only, no gravity."""
    p = _core.RailParams()
    p.length, p.EA, p.EI, p.rhoA, p.n_elements, p.n_gauss, p.gravity = (
        length, EA, EI, RHO_A, n_elements, 5, 0.0)
    if shear:
        p.shear_stiffness, p.rotary_inertia = KGA, RHO_I
    args = (p, _core.SupportParams()) + (() if profile is None else (profile,))
    return _core.RailModel(*args)


def contact(law, stiffness, compliance=True, damping=0.0):
    cp = _core.ContactParams()
    cp.law = getattr(_core.ContactLaw, law)
    cp.stiffness, cp.damping, cp.radius = stiffness, damping, RHO0
    cp.element_compliance = compliance
    return cp


def simply_supported(P, a, L, kga=KGA):
    """Deflection under a point load P at a on a simply supported span L [m]: bending
    P a^2 b^2 / (3 EI L) plus shear P a b / (L kGA) (statically determinate: the shear force is
    P b / L left of the load) [m]."""
    b = L - a
    return P * a * a * b * b / (3.0 * EI * L) + (P * a * b / (L * kga) if kga else 0.0)


# --------------------------------------------------------------------------------------------
# the fixed-end compliance and the statics under a load between nodes

def test_fixed_end_compliance_limits_and_symmetry():
    """G(a) of the kernel: l^3 / (192 EI) + l / (4 kGA) at mid-element (the clamped-clamped
    beam's centre deflections, additive there by symmetry), a^3 b^3 / (3 EI l^3) for
    Euler-Bernoulli (shear compliance 0), symmetric in a <-> l - a, zero at the nodes; its
    derivatives against central differences (G is a polynomial of degree 6 in a: the
    difference quotient's error ~h^2 G''', h = 1e-5 l, far below 1e-7)."""
    le = 0.075
    g_mid = _core.testing.fixed_end_compliance(EI, 1.0 / KGA, le, 0.5 * le)[0]
    assert g_mid == pytest.approx(le**3 / (192 * EI) + le / (4 * KGA), rel=1e-14, abs=0)
    for a in (0.0, 0.013, 0.031, le):
        g = _core.testing.fixed_end_compliance(EI, 0.0, le, a)[0]
        assert g == pytest.approx(a**3 * (le - a) ** 3 / (3 * EI * le**3), rel=1e-14, abs=0)
        assert _core.testing.fixed_end_compliance(EI, 1.0 / KGA, le, le - a)[0] == pytest.approx(
            _core.testing.fixed_end_compliance(EI, 1.0 / KGA, le, a)[0], rel=1e-13, abs=1e-30)
    h = 1e-5 * le
    for a in (0.011, 0.029, 0.052):
        G = [_core.testing.fixed_end_compliance(EI, 1.0 / KGA, le, a + k * h) for k in (-1, 0, 1)]
        assert (G[2][0] - G[0][0]) / (2 * h) == pytest.approx(G[1][1], rel=1e-7, abs=0)
        assert (G[2][1] - G[0][1]) / (2 * h) == pytest.approx(G[1][2], rel=1e-7, abs=0)


@pytest.mark.parametrize("beam", ["timoshenko", "euler"])
@pytest.mark.parametrize("a", [0.37, 0.5, 0.8125])
def test_linear_static_deflection_under_a_load_between_nodes(beam, a, validation):
    """Linear track, a 1 m simply supported span on 3 elements (nodes at 1/3, 2/3 m), the load
    between nodes: with the element compliance the deflection under the load is the closed
    form to round-off (1e-12: the IIE and Hermite elements are nodally exact, G(a) exact);
    without it the interpolated rail misses exactly G(a) P -- the 'kick' term, which moves
    with the load inside each element: 4-21 % of the deflection here with shear (0.06-2.4 %
    without; 1e-9 of it against the closed form's difference, the round-off of G P)."""
    P, L, n = 5e4, 1.0, 3
    shear = beam == "timoshenko"
    model = shear_rail(L, n, shear)
    b = _core.BeamParams()
    if shear:
        b.shear_stiffness, b.rotary_inertia = KGA, RHO_I
    exact = -simply_supported(P, a, L, KGA if shear else 0.0)
    with_g = _core.linear_static_line(model, b, P, [a], 0, True)[0]
    plain = _core.linear_static_line(model, b, P, [a], 0, False)[0]
    assert with_g == pytest.approx(exact, rel=1e-12, abs=0)
    if a == 0.37:
        validation.record(
            f"contact.element_compliance_linear_static_{beam}", level="statics",
            kind="closed form",
            quantity=f"linear {beam} rail, 3 elements, element compliance: deflection under a "
                     "load between nodes",
            reference="simply supported span: P a² b²/(3 EI L) + P a b/(L κGA)",
            measured=abs(with_g / exact - 1.0), tolerance=1e-12)
    le = L / n
    g = _core.testing.fixed_end_compliance(EI, 1.0 / KGA if shear else 0.0, le, a - le * math.floor(a / le))
    assert plain - with_g == pytest.approx(g[0] * P, rel=1e-9, abs=1e-12 * abs(exact))
    if a != 1.0 / 3.0 and shear:
        assert abs(plain / exact - 1.0) > 0.02


@pytest.mark.parametrize("law", ["linear", "hertz"])
def test_full_static_deflection_under_a_load_between_nodes(law, validation):
    """Full model (shear-deformable ANCF rail), the same span and a wheel of 1 kN standing
    between nodes: y_contact (the rail under the load, the element's own deflection included)
    equals the closed form at the contact point a = s* within 1e-6 (measured 4e-8 and 2.9e-7;
    without the compliance the full model equals the linear track's interpolation to 1e-10
    here). The remainder grows like P (2.9e-6 at 10 kN): the climbing force (N^2/2) G' ds*/dq
    acts on the rail's rotations too, since a rotation moves the foot of the normal by rho0
    times it -- a moment of order N (N G') rho0, the price of the conservative form; 2e-5 at
    the 80 kN of a real wheel. Without the compliance the deflection misses the closed form
    by G(a) P (measured 7 % and 14 %)."""
    L, n, P = 1.0, 3, 1e3
    model = shear_rail(L, n)
    w = _core.WheelParams()
    w.mass, w.inertia, w.radius, w.load, w.gravity = 0.0, 1.0, RHO0, P, 0.0
    worst = 0.0
    for x in (0.41, 0.77):
        d = _core.static_solve(model, w, contact(law, LAWS[law]), x)
        exact = -simply_supported(d["normal_force"], d["contact_s"], L)
        worst = max(worst, abs(d["y_contact"] / exact - 1.0))
        assert worst < 1e-6
        plain = _core.static_solve(model, w, contact(law, LAWS[law], compliance=False), x)
        assert abs(plain["y_contact"] / exact - 1.0) > 0.02
    validation.record(
        f"contact.element_compliance_full_static_{law}", level="statics", kind="closed form",
        quantity=f"shear-deformable ANCF rail, 3 elements, {law} contact with element "
                 "compliance: deflection under a wheel between nodes",
        reference="simply supported span: P a² b²/(3 EI L) + P a b/(L κGA)",
        measured=worst, tolerance=1e-6)


# --------------------------------------------------------------------------------------------
# the series law

@pytest.mark.parametrize("law", ["linear", "hertz"])
@pytest.mark.parametrize("G", [0.0, 1.5e-10, 2e-9])
def test_series_law(law, G):
    """N = N_law(delta - G N) to round-off, dN/d(delta) and the energy's derivative N against
    central differences (relative steps 1e-4: the error ~(h/delta)^2 ~ 1e-8), and G = 0 is the
    law itself."""
    k = LAWS[law]
    for delta in (2e-5, 1e-4):
        N, slope, comp, energy = _core.testing.series_contact(getattr(_core.ContactLaw, law), k, G, delta)
        law_n = k * comp if law == "linear" else k * comp**1.5
        assert N == pytest.approx(law_n, rel=1e-14, abs=0)
        assert comp + G * N == pytest.approx(delta, rel=1e-14, abs=0)
        h = 1e-4 * delta
        up = _core.testing.series_contact(getattr(_core.ContactLaw, law), k, G, delta + h)
        dn = _core.testing.series_contact(getattr(_core.ContactLaw, law), k, G, delta - h)
        assert (up[0] - dn[0]) / (2 * h) == pytest.approx(slope, rel=1e-7, abs=0)
        assert (up[3] - dn[3]) / (2 * h) == pytest.approx(N, rel=1e-7, abs=0)
        if G == 0.0:
            assert N == (k * delta if law == "linear" else k * delta * math.sqrt(delta))


# --------------------------------------------------------------------------------------------
# the full model's contact force and its Jacobian

def corrugated(length=5.0, n_elements=20):
    """The shear rail with a 0.3 mm, 0.1 m corrugation (R'' up to 1.2 1/m, R''' up to 75 1/m^2:
    the profile's terms of d2 s*/dq2)."""
    from scipy.interpolate import CubicSpline

    dx = 1e-3
    x = np.arange(0.0, length + dx / 2, dx)
    spline = CubicSpline(x, 3e-4 * np.sin(2 * math.pi * x / 0.1))
    return shear_rail(length, n_elements, profile=_core.Profile(0.0, dx, spline.c))


class Compliant:
    """F(q) with q = [X_A, Y_A, e_el] on a copy of the rail state ``e``, wheel near ``x``."""

    def __init__(self, model, e, cp, x):
        self.model, self.e, self.cp, self.x = model, e, cp, x

    def at_penetration(self, delta):
        above = _core.contact_eval(self.model, self.e, self.x, self.model.positions(
            self.e, [self.x])[0, 1] + RHO0 + 1e-3, self.x, self.cp, np.zeros(10))
        ya = above["surface"][1] + RHO0 - delta
        self.el = _core.contact_eval(self.model, self.e, self.x, ya, self.x, self.cp,
                                     np.zeros(10))["element"]
        return np.concatenate([[self.x, ya], self.e[4 * self.el:4 * self.el + 8]])

    def __call__(self, q):
        e = self.e.copy()
        e[4 * self.el:4 * self.el + 8] = q[2:]
        d = _core.contact_eval(self.model, e, q[0], q[1], self.x, self.cp, np.zeros(10))
        assert d["element"] == self.el  # the stencil stays in one element
        return d


# FD steps 1e-4 of the penetration (test_contact.py: truncation ~1e-8 of the force's scale);
# the tolerance is estimated from the steps h and 2h and must stay below TOL_CEILING. The
# compliance's terms are small beside N grad rho and its Jacobian: the climbing force
# (N^2/2) G' ds*/dq ~1e-4 of the force, its Jacobian's (N^2/2) G' d2s*/dq2 ~1e-8 of K (dropping
# it fails 5 of the 8 cases below by up to 4x their tolerance), so d2s*/dq2 has its own check.
H_REL = 1e-4
TOL_CEILING = 1e-7


@pytest.mark.parametrize("xi", [0.2, 0.85])
@pytest.mark.parametrize("profile", [False, True])
def test_contact_parameter_hessian_matches_central_differences(rel, xi, profile):
    """d s*/dq and d2 s*/dq2 of the foot of the normal (the implicit-function theorem on
    f(s, q) = (R_A - p(s)).p_s(s) = 0, with p_sss and the profile's R''') against central
    differences of s* and of d s*/dq, steps 1e-6 m / 1e-6 (s* varies on the scale of the
    element, ~0.1 m, and of rho0: truncation ~(h/0.1)^2 ~ 1e-10), tolerance from the steps h
    and 2h below 1e-6."""
    model = corrugated() if profile else shear_rail()
    f = Compliant(model, bent_rail(model), contact("linear", K_LIN), (9 + xi) * 0.25)
    q0 = f.at_penetration(5e-5)
    d = f(q0)
    g_fd, tol = fd_with_tolerance(lambda q: np.array([f(q)["s"]]), q0, 1e-6, d["ds_dq"][None, :])
    assert tol < 1e-6 and rel(g_fd[0], d["ds_dq"]) < tol
    h_fd, tol = fd_with_tolerance(lambda q: f(q)["ds_dq"], q0, 1e-6, d["d2s_dq2"])
    assert tol < 1e-6 and rel(h_fd, d["d2s_dq2"]) < tol


@pytest.mark.parametrize("law", ["linear", "hertz"])
@pytest.mark.parametrize("xi", [0.2, 0.85])
@pytest.mark.parametrize("profile", [False, True])
def test_compliant_contact_stiffness_matches_central_differences(rel, law, xi, profile,
                                                                validation):
    """K = -dF/dq with the element compliance (its G, G' and G'' at s*, the climbing force and
    d2 s*/dq2) against central differences, on a bent shear rail, plain or corrugated; K is the
    Hessian of the series spring's energy Phi (symmetric), and F = -grad Phi."""
    model = corrugated() if profile else shear_rail()
    f = Compliant(model, bent_rail(model), contact(law, LAWS[law]), (9 + xi) * 0.25)
    q0 = f.at_penetration(5e-5)
    d = f(q0)
    assert d["active"] and d["compliance"] > 0.0
    K_fd, tol = fd_with_tolerance(lambda q: -f(q)["F"], q0, H_REL * 5e-5, d["K"])
    assert tol < TOL_CEILING
    assert rel(K_fd, d["K"]) < tol
    if xi == 0.2:
        validation.record(
            f"contact.element_compliance_stiffness_{law}_{'profile' if profile else 'plain'}",
            level="contact", kind="finite differences",
            quantity=f"{law} contact with element compliance on a bent shear rail"
                     f"{' with a corrugation' if profile else ''}: stiffness K = -dF/dq",
            reference="central differences of the contact force",
            measured=rel(K_fd, d["K"]), tolerance=TOL_CEILING)
    assert np.linalg.norm(d["K"] - d["K"].T) < 1e-12 * np.linalg.norm(d["K"])
    dphi, tol = fd_with_tolerance(lambda q: np.array([f(q)["energy"]]), q0, H_REL * 5e-5,
                                  d["F"][None, :])
    assert tol < TOL_CEILING
    assert rel(-dphi[0], d["F"]) < tol
    # the series law at the point: N = k delta / (1 + k G) for the linear law
    if law == "linear":
        assert d["N"] == pytest.approx(K_LIN * (RHO0 - d["rho"]) / (1 + K_LIN * d["compliance"]),
                                       rel=1e-13)


def test_the_climbing_force_is_the_horizontal_part():
    """On the straight rail the contact normal is vertical, so the only horizontal force on the
    wheel centre is the climbing term (N_e^2 / 2) G'(a) ds*/dX_A = (N^2 / 2) G'(a) (ds*/dX_A = 1
    there): it pushes the wheel back where the compliance rises ahead (a < l/2) and forward
    beyond the middle, and is the same work G N^2 / 2 the element's deflection stores."""
    model = shear_rail()
    e = np.asarray(model.reference())
    le = model.element_length
    for xi in (0.2, 0.5, 0.8):
        x = (9 + xi) * le
        d = _core.contact_eval(model, e, x, RHO0 - 5e-5, x, contact("linear", K_LIN),
                               np.zeros(10))
        G, Ga, _ = _core.testing.fixed_end_compliance(EI, 1.0 / KGA, le, xi * le)
        assert d["compliance"] == pytest.approx(G, rel=1e-13, abs=0)
        assert d["F"][0] == pytest.approx(0.5 * d["N"] ** 2 * Ga, rel=1e-10, abs=1e-9)
        assert d["F"][1] == pytest.approx(d["N"], rel=1e-13, abs=0)


# --------------------------------------------------------------------------------------------
# the iteration matrices

def _ballasted_probe(law, slide, polygon=None, compliance=True, theta=0.3, dt=2.8e-5):
    """The ballasted preset with the Timoshenko rail on 8 elements per bay, a wheel standing at
    its static state between nodes (xi = 0.3 of its element), generalized-alpha at 2.8e-5 s;
    ``polygon`` = (order, amplitude [m]) turns the wheel to ``theta`` [rad] of that defect."""
    scene = tw.Scene.ballasted_track(length=6.0, elements_per_bay=8)
    scene = dc.replace(scene, rail=dc.replace(scene.rail, beam="timoshenko"),
                       contact=dc.replace(scene.contact, law=law, element_compliance=compliance))
    if polygon:
        scene = dc.replace(scene, wheel=dc.replace(scene.wheel,
                                                   defects=(tw.Polygon(*polygon),)))
    v, x = tw.kmh(200), 3.0 + 0.3 * 0.075
    model = _kernel.rail_model(scene)
    cp = _kernel.contact_params(scene)
    wheel = _kernel.wheel_params(scene)
    d = _core.static_solve(model, wheel, cp, x)
    w = _core.WheelState()
    w.y, w.s, w.thetadot = d["y_wheel"], d["contact_s"], v / scene.wheel.radius
    w.theta = theta if polygon else 0.0
    w.state = _core.SlipState.slip if slide else _core.SlipState.stick
    w.sigma = -1.0
    st = _core.SimState()
    st.e = np.asarray(d["e"])
    st.edot, st.wheels = np.zeros_like(st.e), [w]
    st.z = np.asarray(d["sleeper_z"])
    st.zdot = np.zeros_like(st.z)
    s = _core.SimSettings()
    s.speed, s.x_start, s.dt, s.t_end = v, x, dt, dt
    return model, [wheel], cp, s, st, dt


@pytest.mark.parametrize("law, slide, polygon", [
    ("linear", False, None), ("hertz", True, None), ("hertz", False, (8, 5e-5)),
    ("linear", True, (8, 5e-5))])
def test_full_iteration_matrix_with_compliance_matches_central_differences(law, slide, polygon):
    """generalized-alpha's iteration matrix on the ballasted Timoshenko track with the element
    compliance (contact K, the slide row's dN_e/dq = -k_t u, the out-of-round block) against
    central differences of the residual, as tests/test_system.py: every column within 1e-6
    of its largest entry (measured below 1e-7)."""
    model, wheels, cp, s, st, dt = _ballasted_probe(law, slide, polygon)

    def R(x=None):
        return _core.testing.ga_probe(model, wheels, cp, s, st, dt, x)

    p0 = R()
    x0, J = p0["start"], p0["matrix"]
    h = np.full(len(x0), 1e3)
    h[model.n_free + 2] = 1.0  # the multiplier lambda [N]
    err = central_difference_error(R, x0, J, h)
    assert np.max(err) < 1e-6, (int(np.argmax(err)), float(np.max(err)))


# --------------------------------------------------------------------------------------------
# the moving contact on the shear-deformable rail against the mesh

WHEEL_LOAD, K_QUARTER = 80e3, 1.3374e9


def quarter_car(elements_per_bay, compliance=None, window=True, length=30.0):
    """The issue's quarter car (benchmarks/contact_ripple.py): a 600 kg wheel under a 996 kg
    one-wheel bogie on a 1.2 MN/m primary spring, 80 kN static load, linear contact
    1.3374e9 N/m, on the ballasted UIC60 track with the Timoshenko rail (kappa 0.4); on a
    travelling window of 20 + 20 bays, or a fixed rail of ``length``."""
    from trackwheel import Bogie, Vehicle

    base = tw.Scene.ballasted_track(length=length, elements_per_bay=elements_per_bay)
    g = base.gravity
    wheel = tw.Wheel(mass=600.0, radius=0.46, load=0.0, youngs_modulus=210e9, poisson_ratio=0.3)
    bogie = Bogie(wheels=(0,), centre=0.0, mass=996.0, pitch_inertia=1.0,
                  primary_stiffness=1.2e6, primary_damping=0.0,
                  load=WHEEL_LOAD - (600.0 + 996.0) * g)
    s = dc.replace(base, rail=dc.replace(base.rail, beam="timoshenko", shear_coefficient=0.4),
                   vehicle=Vehicle(wheels=(wheel,), positions=(0.0,), bogies=(bogie,)),
                   contact=tw.Contact(law="linear", stiffness=K_QUARTER,
                                      element_compliance=compliance))
    return s.windowed(tw.Window(20, 20)) if window else s


def _steady(scene, speed, fidelity="linear/sprung", tangential=False, **kw):
    """(bay profile max, min [N], ripple above 1 kHz rms [N]) over the steady part (whole
    bays); with ``tangential`` also the tangential force's amplitude at the element-passing
    frequency v / l_e [N]."""
    r = tw.simulate(scene, speed, dt=tw.default_settings(scene)["dt"],
                    n_elements=scene.rail.n_elements, fidelity=fidelity, progress=False, **kw)
    ss = tw.steady_state(r, tol=2e-3)
    t, f = np.asarray(r.t), np.asarray(r.normal_force)
    keep = (t >= ss.t_from) & (t < ss.t_from + ss.n_bays * scene.supports.spacing / speed
                               - 0.5 * (t[1] - t[0]))
    freq = np.fft.rfftfreq(keep.sum(), t[1] - t[0])
    c = np.fft.rfft(f[keep] - f[keep].mean())
    c[freq < 1000.0] = 0.0
    ripple = float(np.sqrt(np.mean(np.fft.irfft(c, keep.sum()) ** 2)))
    out = (float(ss.bay_profile.max()), float(ss.bay_profile.min()), ripple)
    if not tangential:
        return out
    lam = np.asarray(r.tangential_force)[keep]
    a = 2.0 * np.abs(np.fft.rfft(lam - lam.mean())) / lam.size
    fe = speed * scene.rail.n_elements / scene.rail.length
    return out + (float(a[np.abs(freq - fe) < 3 * freq[1]].max()),)


def test_moving_contact_converges_to_the_fine_mesh_at_the_default_mesh(validation):
    """The quarter car at 200 km/h, linear level (the same contact model as the full one, which
    the next check compares), default step 2.81e-5 s: with the element compliance the
    bay-averaged contact-force profile at the default 8 elements per bay is within 0.5 % of the
    32-element one (the issue's target; measured max 0.06 %, min 0.27 %: at 8/16/32/64
    elements the min is 77.74/77.89/77.94/77.94 kN, the max 82.89/82.88/82.84/82.83 kN, so 32
    is converged to 0.01 %), and the force's content above 1 kHz is below 150 N rms (measured
    123 N, and 111/95/91 N at 16/32/64: what remains is the track's own, the sleeper-passing
    harmonics near the pinned-pinned resonance). Without it the same mesh overstates the peak
    by 3.4 % and rings with 660 N rms (the node-crossing kicks at v/l_e = 741 Hz and
    harmonics)."""
    v = tw.kmh(200)
    mx8, mn8, rip8 = _steady(quarter_car(8), v, distance=18.0)
    mx32, mn32, rip32 = _steady(quarter_car(32), v, distance=18.0)
    assert abs(mx8 / mx32 - 1.0) < 5e-3 and abs(mn8 / mn32 - 1.0) < 5e-3
    validation.record(
        "contact.element_compliance_default_mesh", level="contact", kind="path agreement",
        quantity="quarter car at 200 km/h, Timoshenko rail, element compliance, 8 elements "
                 "per bay: bay-averaged contact-force profile max and min",
        reference="the same on 32 elements per bay (converged to 0.01 %)",
        measured=max(abs(mx8 / mx32 - 1.0), abs(mn8 / mn32 - 1.0)), tolerance=5e-3)
    assert rip8 < 150.0 and rip8 < 1.5 * rip32
    px8, pn8, prip8 = _steady(quarter_car(8, compliance=False), v, distance=18.0)
    assert px8 / mx32 - 1.0 > 0.02 and prip8 > 4.0 * rip8


def test_full_model_takes_the_same_compliance():
    """The full model (shear-deformable ANCF rail, foot-of-normal contact, rolling) on the same
    quarter car and default mesh: its bay profile equals the linear level's within 1e-3
    (measured 7e-5) and its ripple within 5 % (measured 1 %): the element compliance acts
    alike on both paths. The wheel rolls on the rail under the load (rolling radius
    rho + G N_e), so the tangential force has no element-passing content either: below 15 N
    at v / l_e = 741 Hz (measured 6 N; 75 N without the compliance, and 138 N with it but the
    rolling radius of the interpolated rail, rho, which varies by G N ~ 6 um per element)."""
    v = tw.kmh(200)
    full = _steady(quarter_car(8), v, fidelity="full", tangential=True, distance=12.0)
    lin = _steady(quarter_car(8), v, distance=12.0)
    assert abs(full[0] / lin[0] - 1.0) < 1e-3 and abs(full[1] / lin[1] - 1.0) < 1e-3
    assert abs(full[2] / lin[2] - 1.0) < 0.05
    assert full[3] < 15.0


# --------------------------------------------------------------------------------------------
# full and linear at fine meshes: the director's length

def test_director_length_follows_the_centre_line_on_fine_meshes():
    """The shear-deformable ANCF rail at 64 elements per bay (l = 9.4 mm, phi = 12 EI /
    (kGA l^2) = 3500), static under the wheel on the ballasted track: the nodal director's
    length equals |r_s| within 1e-6 (its departure is of the order of the squared strains,
    measured 1e-8; it was 2.8 % before the director's stretch had its EA term, which made the
    rail 5 % softer on fine meshes), and the deflection under the wheel equals the linear IIE
    track's (independent element, with the same element compliance) within 3e-4 (measured
    1.4e-6), as test_shear_ancf.py's coarse-mesh check."""
    s = dc.replace(tw.Scene.ballasted_track(length=7.2, elements_per_bay=64),
                   rail=dc.replace(tw.Scene.ballasted_track().rail, length=7.2,
                                   n_elements=12 * 64, beam="timoshenko"))
    x = 3.6 + 0.3 * 0.6 / 64
    st = tw.static(s, x)
    e = np.asarray(st.rail_coordinates).reshape(-1, 4)
    le = s.rail.length / s.rail.n_elements
    phi = 12.0 * s.rail.bending_stiffness / (s.rail.shear_stiffness * le * le)
    ws = _core.testing.timoshenko_shapes(0.0, le, phi)[1]  # r_s at each element's first node
    rs = (ws[0] * e[:-1, :2] + ws[1] * e[:-1, 2:] + ws[2] * e[1:, :2] + ws[3] * e[1:, 2:])
    stretch = np.hypot(e[:-1, 2], e[:-1, 3]) - np.hypot(rs[:, 0], rs[:, 1])
    assert np.max(np.abs(stretch)) < 1e-6
    lin = tw.linear_quasi_static(s, [x])[0]
    assert abs(st.y_contact / lin - 1.0) < 3e-4


@pytest.mark.parametrize("level", ["sprung", "hertz", "moving_mass"])
def test_linear_newton_satisfies_the_series_law(level):
    """The linear levels with the element compliance: the Newton iterate each step accepts
    satisfies the contact law at the recorded state -- N = k delta_c (sprung: the level takes one
    Newton step, exact for its linear system only if the iteration matrix holds the series
    slope k / (1 + k G); to 1e-9 of P, measured 5e-13: round-off), N = C_H delta_c^1.5 (Hertz:
    within Newton's force tolerance 1e-6 P, measured 9e-13), and the moving mass rides on the
    rail under the load, Y_A = y_contact + rho0 with y_contact the interpolated rail minus G N
    (1e-12 m, measured 6e-17 m) -- and the Hertz level needs no more Newton iterations than
    without the compliance (+2 %; measured +0.2 %): the matrix is the derivative of the
    residual. (With the law's slope k in place of k / (1 + k G) the first two fail.)"""
    v, kw = tw.kmh(200), dict(distance=3.0, progress=False)
    s = quarter_car(8)
    fid = {"sprung": "linear/sprung", "hertz": "linear/hertz", "moving_mass": "linear/moving_mass"}
    r = tw.simulate(s, v, fidelity=fid[level], **kw)
    P = WHEEL_LOAD
    if level == "sprung":
        assert np.max(np.abs(r.normal_force - K_QUARTER * r.penetration)) < 1e-9 * P
    elif level == "hertz":
        ch = (K_QUARTER / (1.5 * P ** (1 / 3))) ** 1.5
        assert np.max(np.abs(r.normal_force - ch * np.maximum(r.penetration, 0) ** 1.5)) < 1e-6 * P
        plain = tw.simulate(quarter_car(8, compliance=False), v, fidelity=fid[level], **kw)
        assert r.newton_iterations <= 1.02 * plain.newton_iterations
    else:
        assert np.max(np.abs(r.y_wheel - r.y_contact - 0.46)) < 1e-12


def _bay_harmonics(r, x0, x1, d=0.6, n=128):
    """Amplitudes of the first three sleeper-passing harmonics of the contact force averaged
    over the bays in [x0, x1] [N]."""
    nb = round((x1 - x0) / d)
    xs = x0 + d * np.arange(nb * n) / n
    f = np.interp(xs, r.x_wheel, r.normal_force).reshape(nb, n).mean(axis=0)
    return 2.0 * np.abs(np.fft.rfft(f)[1:4]) / n


def test_full_and_linear_agree_on_sleeper_passing_harmonics_at_64_elements_per_bay(validation):
    """The quarter car at 200 km/h on a 9.6 m fixed rail at 64 elements per bay (l = 9.4 mm):
    the full model's and the linear level's first three sleeper-passing harmonics, over the
    same three bays of the same passage (both start from their static state at X = 2.7 m, so the
    start-up's share is common), agree within 0.5 % (the issue's target; measured 0.05 %).
    Before the shear element's director was held to the centre line's stretch they differed by
    12-14 % here (5-7 % on a 14.4 m rail, 0.5 % at 32 elements per bay): the director stretched
    on fine meshes and softened the full model's rail."""
    s = quarter_car(64, window=False, length=9.6)
    kw = dict(x_start=2.7, x_end=6.3, dt=tw.default_settings(s)["dt"],
              n_elements=s.rail.n_elements, progress=False)
    full = _bay_harmonics(tw.simulate(s, tw.kmh(200), **kw), 4.2, 6.0)
    lin = _bay_harmonics(tw.simulate(s, tw.kmh(200), fidelity="linear/sprung", **kw), 4.2, 6.0)
    np.testing.assert_allclose(full, lin, rtol=5e-3)
    assert lin[0] > 1e3
    validation.record(
        "paths.full_linear_sleeper_harmonics_64", level="paths agree", kind="path agreement",
        quantity="quarter car at 200 km/h on the ballasted Timoshenko track, 64 elements per "
                 "bay: first three sleeper-passing harmonics of the contact force",
        reference="the linear level (IIE Timoshenko beam) on the same mesh",
        measured=float(np.max(np.abs(full / lin - 1.0))), tolerance=5e-3)  # the harmonics are the sleepers' (1.8 kN), not noise


def test_rolling_radius_terms_of_an_out_of_round_wheel():
    """With the element compliance the wheel rolls on the rail under the load, radius
    rho_r = rho + G N_e, and N_e depends on theta through an out-of-round wheel's radius: the
    rolling row's and the torque's theta'' entries gain -cq theta' d rho_r/d theta / cv and
    lambda d rho_r/d theta cq (d rho_r/d theta = G k_t dDelta rho/dpsi). They are tiny beside
    the entries, so they are checked alone, where they are large: a 0.1 mm, 8th-order polygon
    turning through theta = pi/16 at the step's end (Delta rho = 0, dDelta rho/dpsi =
    -0.8 mm), a step of 0.1 ms and an iterate with lambda = 1e8 N (an iterate, not a state:
    it scales the torque's term): central differences of the residual with steps 1e4 rad/s^2
    are exact there to ~1e-14 of the entry (the residual is smooth in theta''), tolerance
    1e-10 of the entry (measured 2.5e-13); the terms are 1.8e-7 and 8.8e-7 of their entries,
    so dropping either fails by 1e3 x the tolerance."""
    dt = 1e-4
    theta = math.pi / 16 - tw.kmh(200) / 0.46 * dt
    model, wheels, cp, s, st, dt = _ballasted_probe("hertz", False, polygon=(8, 1e-4),
                                                    theta=theta, dt=dt)
    c = _core.ContactParams()
    c.law, c.stiffness, c.radius, c.element_compliance = cp.law, cp.stiffness, 0.46, True
    c.radius += tw.Polygon(8, 1e-4).delta_rho(theta, 0.46)
    d = _core.contact_eval(model, st.e, s.x_start, st.wheels[0].y, st.wheels[0].s, c,
                           np.zeros(10))
    assert d["N"] > 0.0 and d["compliance"] > 0.0  # the contact is closed, between nodes

    def R(x=None):
        return _core.testing.ga_probe(model, wheels, cp, s, st, dt, x)

    x0 = R()["start"].copy()
    th, lam = model.n_free + 1, model.n_free + 2
    x0[lam] = 1e8
    J = R(x0)["matrix"]
    h = 1e4
    xp, xm = x0.copy(), x0.copy()
    xp[th] += h
    xm[th] -= h
    col = -(R(xp)["residual"] - R(xm)["residual"]) / (2.0 * h)
    for row in (th, lam):
        assert abs(J[row, th] - col[row]) < 1e-10 * abs(J[row, th])
