"""The Timoshenko rail of the linear track (docs: Model, section "Shear-deformable rail
(Timoshenko)"): the IIE element against its energy and closed forms, the pinned-pinned frequency
against the Timoshenko frequency equation and the thin-beam limit (the full model's
shear-deformable ANCF rail: tests/test_shear_ancf.py)."""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel
from trackwheel.eigen import rail_frequencies

EI, KGA, L_EL = 6.36e6, 2.2e8, 0.125  # a rail-like section and element [N m^2, N, m]


def _span(beam: str, length: float = 0.5, n_elements: int = 20) -> tw.Scene:
    """The paper's rail as one bare simply supported span (no intermediate supports)."""
    s = tw.Scene.kato2005()
    return dc.replace(s, rail=dc.replace(s.rail, length=length, n_elements=n_elements, beam=beam),
                      supports=dc.replace(s.supports, positions=()), rail_gravity=False)


def _timoshenko_pinned_pinned(rail: tw.Rail, d: float) -> float:
    """Lower root of (rhoI rho/(kG)) w^4 - (rhoA + rhoI k^2 + EI k^2 rho/(kG)) w^2 + EI k^4 = 0,
    k = pi/d [Hz]."""
    k = math.pi / d
    kg = rail.shear_coefficient * rail.modulus_of_rigidity
    a = rail.rotary_inertia * rail.density / kg
    b = rail.mass_per_length + rail.rotary_inertia * k**2 \
        + rail.bending_stiffness * k**2 * rail.density / kg
    c = rail.bending_stiffness * k**4
    return math.sqrt((b - math.sqrt(b * b - 4 * a * c)) / (2 * a)) / (2 * math.pi)


def test_stiffness_is_the_hessian_of_the_element_energy():
    """K_e = d2U/dq2 by central differences of U (quadratic: the differences are exact up to
    round-off, ~1e-8 of the largest entry at this step)."""
    K = _core.testing.timoshenko_stiffness(EI, KGA, L_EL)
    q0 = np.array([1e-3, -2e-3, 0.5e-3, 1e-3])
    h = 1e-4
    H = np.empty((4, 4))
    for i in range(4):
        for j in range(4):
            e_i, e_j = h * np.eye(4)[i], h * np.eye(4)[j]
            U = [_core.testing.timoshenko_energy(EI, KGA, L_EL, q0 + si * e_i + sj * e_j)
                 for si, sj in ((1, 1), (1, -1), (-1, 1), (-1, -1))]
            H[i, j] = (U[0] - U[1] - U[2] + U[3]) / (4 * h * h)
    np.testing.assert_allclose(H, K, atol=1e-7 * np.abs(K).max())


def test_shear_strain_is_constant_and_nodal_values_interpolate():
    """The IIE interpolation: gamma = w' - psi is constant in the element (it solves the static
    equations), and w, psi take their nodal values at the ends."""
    phi = 12 * EI / (KGA * L_EL**2)
    rows = [np.asarray(_core.testing.timoshenko_shapes(xi, L_EL, phi)) for xi in np.linspace(0, 1, 7)]
    gamma = np.array([r[1] - r[3] for r in rows])  # (n_xi, 4)
    np.testing.assert_allclose(gamma, np.broadcast_to(gamma[0], gamma.shape), atol=1e-12)
    np.testing.assert_allclose(rows[0][[0, 3]], [[1, 0, 0, 0], [0, 1, 0, 0]], atol=1e-15)
    np.testing.assert_allclose(rows[-1][[0, 3]], [[0, 0, 1, 0], [0, 0, 0, 1]], atol=1e-15)


def test_mass_of_rigid_motions():
    """q^T M q of a translation is rhoA l; of a rotation about the centre (w = s - l/2,
    psi = 1) rhoA l^3/12 + rhoI l: translational and rotary inertia (exact quadrature)."""
    rhoA, rhoI = 54.4, 2.43e-1
    M = _core.testing.timoshenko_mass(rhoA, rhoI, EI, KGA, L_EL)
    t = np.array([1.0, 0.0, 1.0, 0.0])
    r = np.array([-L_EL / 2, 1.0, L_EL / 2, 1.0])
    assert t @ M @ t == pytest.approx(rhoA * L_EL, rel=1e-13)
    assert r @ M @ r == pytest.approx(rhoA * L_EL**3 / 12 + rhoI * L_EL, rel=1e-13)
    np.testing.assert_allclose(M, M.T, rtol=0, atol=1e-15 * np.abs(M).max())


def test_thin_beam_limit_is_the_hermite_element():
    """kGA -> infinity: the IIE stiffness tends to the Hermite beam's EI/l^3 [12 6l ..] as
    1/(1 + phi), phi = 12 EI/(kGA l^2) = 1e-9 here."""
    h = L_EL
    kga = 12 * EI / (1e-9 * h * h)
    herm = EI / h**3 * np.array([[12, 6 * h, -12, 6 * h], [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                                 [-12, -6 * h, 12, -6 * h], [6 * h, 2 * h * h, -6 * h, 4 * h * h]])
    np.testing.assert_allclose(_core.testing.timoshenko_stiffness(EI, kga, h), herm, rtol=1e-8,
                               atol=1e-8 * np.abs(herm).max())


def test_thin_beam_limit_frequencies_equal_euler_bernoulli():
    """The linear track with a huge kGA and no rotary inertia has the Euler-Bernoulli rail's
    frequencies (the linearised ANCF rail), to 1e-7 (phi ~ 1e-10)."""
    s = tw.Scene.kato2005()
    model = _kernel.rail_model(s)
    b = _core.BeamParams()
    b.shear_stiffness = 1e10 * s.rail.bending_stiffness / s.rail.length**2
    b.rotary_inertia = 0.0
    f_t = np.asarray(_core.testing.track_modes(model, b, 0.0, 0.0, [0.0], 8)[0]).ravel()
    np.testing.assert_allclose(f_t, rail_frequencies(s, 8, n_elements=s.rail.n_elements),
                               rtol=1e-7)


def test_static_midspan_deflection_with_shear(validation):
    """Simply supported span under a central point load: w = P L^3/(48 EI) + P L/(4 kGA) (bending
    plus shear); the IIE element is exact for point loads at nodes, so to round-off."""
    s = _span("timoshenko", length=2.0, n_elements=8)
    r = s.rail
    a0 = tw.receptance(s, 1.0, [0.0])[0]
    expected = 2.0**3 / (48 * r.bending_stiffness) + 2.0 / (4 * r.shear_stiffness)
    assert a0.real == pytest.approx(expected, rel=1e-9)
    validation.record(
        "statics.timoshenko_span", level="statics", kind="closed form",
        quantity="linear Timoshenko rail, 2 m simply supported span: mid-span compliance",
        reference="P L³/(48 EI) + P L/(4 κGA) (bending plus shear)",
        measured=abs(a0.real / expected - 1.0), tolerance=1e-9)
    assert a0.imag == 0.0


def test_pinned_pinned_frequency_against_the_timoshenko_equation(validation):
    """First bending frequency of a simply supported 0.5 m span: within 0.5 % of the closed form
    (20 elements: the FE error is ~1e-3 of it); Euler-Bernoulli within 0.5 % of
    (pi/(2 d^2)) sqrt(EI/m). The paper's rail: ~2.15 kHz without, ~1.44 kHz with shear (issue 12)."""
    d = 0.5
    f_t = rail_frequencies(_span("timoshenko"), 1)[0]
    f_e = rail_frequencies(_span("euler"), 1)[0]
    r = _span("euler").rail
    assert f_t == pytest.approx(_timoshenko_pinned_pinned(r, d), rel=5e-3)
    assert f_e == pytest.approx(math.pi / (2 * d * d) * math.sqrt(r.bending_stiffness
                                                                 / r.mass_per_length), rel=5e-3)
    validation.record(
        "eigen.timoshenko_pinned_pinned", level="eigen analysis", kind="closed form",
        quantity="linear Timoshenko rail, bare 0.5 m span, 20 elements: first bending frequency",
        reference="lower root of the Timoshenko frequency equation of a simply supported span",
        measured=abs(f_t / _timoshenko_pinned_pinned(r, d) - 1.0), tolerance=5e-3)
    assert f_e == pytest.approx(2150, rel=0.01)
    assert f_t == pytest.approx(1440, rel=0.01)


def test_eigen_with_the_wheel_takes_the_beam_theory():
    """With shear the coupled wheel/track frequencies can only fall (a softer, heavier beam:
    Rayleigh quotient), and the mode shapes come back in the ANCF numbering."""
    s = tw.Scene.kato2005()
    st = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko"))
    ne = s.rail.n_elements  # one mesh for both (the defaults differ: 8 and 12 per bay)
    e, t = tw.eigen(s, [2.25], 6, n_elements=ne), tw.eigen(st, [2.25], 6, n_elements=ne)
    assert np.all(t.frequencies <= e.frequencies * (1 + 1e-9))
    assert t.shapes.shape == e.shapes.shape
    s_, y, wheel = t.rail_mode_shape(0, 0)
    assert np.max(np.abs(y)) <= 1.0 + 1e-12


def test_linear_simulation_takes_the_beam_theory():
    """The linear/hertz level runs with either beam; shear softens the track under the wheel, so
    the mean static deflection under the load is larger (by P/(kGA) bay-scale terms)."""
    s = tw.Scene.kato2005()
    st = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko"))
    kw = dict(fidelity="linear/hertz", x_start=2.0, x_end=2.6, dt=2e-5)
    re, rt = tw.simulate(s, 30.0, **kw), tw.simulate(st, 30.0, **kw)
    de, dt_ = np.mean(re.y_contact), np.mean(rt.y_contact)
    assert dt_ < de < 0


def test_rail_beam_validation():
    with pytest.raises(ValueError, match="Rail.beam"):
        tw.Rail(beam="rayleigh")
    for bad in (0.0, 1.5, math.nan):
        with pytest.raises(ValueError, match="Rail.shear_coefficient"):
            tw.Rail(shear_coefficient=bad)
    r = tw.Rail(beam="timoshenko", shear_coefficient=0.4)
    assert r.shear_modulus is None
    assert r.modulus_of_rigidity == pytest.approx(r.youngs_modulus / 2.6)
    assert r.shear_stiffness == pytest.approx(0.4 * r.modulus_of_rigidity * r.area)


def test_shear_judgement_compares_the_two_beams():
    """adequacy's shear column: the pinned-pinned closed forms (those of the span test above)
    and the relative differences of the linear/hertz runs with each beam, as separate runs give
    them; a Timoshenko scene's ANCF levels run on the shear-deformable ANCF rail."""
    from trackwheel.analysis import analyse
    from trackwheel.fidelity import shear_judgement

    s = tw.Scene.kato2005()
    kw = dict(x_start=2.0, x_end=2.6, dt=2e-5)
    j = shear_judgement(s, [30.0], tol=0.005, **kw)
    assert j["pinned_pinned_euler"] == pytest.approx(2147.16, rel=1e-4)
    assert j["pinned_pinned_timoshenko"] == pytest.approx(
        _timoshenko_pinned_pinned(s.rail, 0.5), rel=1e-12)
    runs = [analyse(tw.simulate(dc.replace(s, rail=dc.replace(s.rail, beam=b)), 30.0,
                                fidelity="linear/hertz", **kw)) for b in ("euler", "timoshenko")]
    d = abs(runs[1].max_contact_force / runs[0].max_contact_force - 1)
    assert j["d_peak_contact_force"] == pytest.approx(d, rel=1e-12)
    assert j["matters"] == any(j["d_" + k] > 0.005
                               for k in ("amplitude", "main_frequency", "peak_contact_force"))
    st = dc.replace(s, rail=dc.replace(s.rail, beam="timoshenko"))
    df = tw.adequacy(st, speeds=[30.0], levels=("ancf/sprung",), reference="ancf/sprung",
                     n_elements=20, **kw)
    assert (df.error == "").all()
    assert "shear" in df.attrs


def test_linear_static_line_of_the_euler_rail_is_the_ancf_quasi_static_line():
    """With the Euler-Bernoulli beam the linear track's static line (load P plus the rail's
    weight) equals the nonlinear ANCF quasi-static line to 1e-6 (geometric nonlinearity and
    the contact-point shift ~1e-6 of the deflection)."""
    s = tw.Scene.kato2005()
    x = [1.3, 2.25, 2.5]
    np.testing.assert_allclose(tw.linear_quasi_static(s, x), tw.quasi_static(s, x).y_contact,
                               rtol=1e-6)
