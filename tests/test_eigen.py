"""Eigenvalue analysis (docs: Model § Eigen analysis) against the analytic references of docs: Model § Validation."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel
from trackwheel.eigen import rail_frequencies

KATO = tw.Scene.kato2005()
L = KATO.rail.length  # 5 m
EI = KATO.rail.bending_stiffness  # [N m^2]
M_RAIL = KATO.rail.mass_per_length  # [kg/m]


def bare_frequencies(make_rail, n_elements, n_modes=5, **kw):
    """Vertical frequencies [Hz] of the rail without wheel (wheel mass 0)."""
    f, _ = _core.vertical_modes(make_rail(length=L, n_elements=n_elements, **kw), 0.0, 0.0,
                                [0.0], n_modes)
    return np.asarray(f).ravel()


def simply_supported(n):
    """f_n = n^2 pi / (2 L^2) sqrt(EI / m) [Hz]."""
    return n**2 * math.pi / (2.0 * L**2) * math.sqrt(EI / M_RAIL)


def test_simply_supported_beam_frequencies_and_convergence(make_rail, validation):
    """Bare rail, no supports, no wheel: the pinned-pinned Euler-Bernoulli beam."""
    exact = simply_supported(np.arange(1, 6))
    err = {ne: bare_frequencies(make_rail, ne) / exact - 1.0 for ne in (10, 20, 40)}
    # measured at 20 elements: 4e-7, 7e-6, 3.4e-5, 1.1e-4, 2.6e-4
    assert np.all(np.abs(err[20]) < 0.005)
    validation.record(
        "eigen.simply_supported_beam", level="eigen analysis", kind="closed form",
        quantity="bare 5 m rail, 20 elements: the five lowest bending frequencies",
        reference="simply supported beam: f_n = n²π/(2L²) √(EI/m)",
        measured=np.abs(err[20]).max(), tolerance=0.005)
    # Rayleigh-Ritz with a conforming mesh: the FE frequencies are upper bounds
    assert np.all(err[20] > 0)
    # cubic Hermite beam: eigenvalue error O(h^4); observed order log2(err_h / err_h/2)
    # measured 3.93..4.00 for every mode and both refinements
    for coarse, fine in ((10, 20), (20, 40)):
        order = np.log2(err[coarse] / err[fine])
        assert np.all(order > 3.5), (coarse, fine, order)


def test_simply_supported_mode_shapes_are_sines(make_rail):
    model = make_rail(length=L, n_elements=20)
    _, shapes = _core.vertical_modes(model, 0.0, 0.0, [0.0], 4)
    s = np.linspace(0.0, L, 201)
    for n in range(1, 5):
        y = model.positions(shapes[0, :-1, n - 1], s)[:, 1]
        sine = np.sin(n * math.pi * s / L)
        mac = (y @ sine) ** 2 / ((y @ y) * (sine @ sine))
        assert mac > 1 - 1e-6


@pytest.mark.parametrize("far_end", ["roller", "pinned"])
def test_axial_frequencies_of_the_bar(make_rail, far_end, validation):
    """x fixed at 0 and a roller at L: fixed-free bar, f = (2n - 1)/(4L) sqrt(E/rho);
    pinned at L: fixed-fixed, f = n/(2L) sqrt(E/rho)."""
    c = math.sqrt(KATO.rail.youngs_modulus / KATO.rail.density)
    n = np.arange(1, 4)
    exact = (2 * n - 1) / (4 * L) * c if far_end == "roller" else n / (2 * L) * c
    pin = far_end == "pinned"
    err = {ne: np.asarray(_core.axial_modes(make_rail(length=L, n_elements=ne, pin_far_end=pin),
                                            3)[0]).ravel() / exact - 1.0
           for ne in (10, 20)}
    # C1 cubic elements for a second-order problem: eigenvalue error O(h^6); measured
    # <= 5.5e-8 at 20 elements
    assert np.all(np.abs(err[20]) < 1e-6)
    validation.record(
        f"eigen.axial_bar[{far_end}]", level="eigen analysis", kind="closed form",
        quantity=f"bare 5 m rail, 20 elements, far end {far_end}: three lowest axial "
                 "frequencies",
        reference=("fixed-free bar: (2n - 1)/(4L) √(E/ϱ)" if far_end == "roller"
                   else "fixed-fixed bar: n/(2L) √(E/ϱ)"),
        measured=np.abs(err[20]).max(), tolerance=1e-6)
    assert np.all(err[20] > -1e-12)  # upper bounds (up to round-off)
    order = np.log2(err[10][1:] / err[20][1:])  # mode 1 is already at round-off at 20
    assert np.all(order > 5.0), order
    # the public API reports the same, apart from the vertical list
    scene = dataclasses.replace(KATO, rail=dataclasses.replace(KATO.rail, far_end=far_end))
    np.testing.assert_allclose(tw.eigen(scene, [2.5]).axial_frequencies, exact, rtol=1e-6)


def test_stiff_supports_give_the_pinned_pinned_span_mode(make_rail, validation):
    """Nine supports every d_s = 0.5 m (ends rigid). The pinned-pinned frequency
    f_pp = pi/(2 d_s^2) sqrt(EI/m) = 2147 Hz belongs to y = sin(pi x/d_s), which is still at
    rest at every support, so for stiff enough supports (k_s >~ 4e9 N/m, when the foundation's
    cut-on sqrt(k_f/m)/2pi exceeds f_pp) it is the lowest mode; softer supports let the rail
    bounce on them below f_pp. The rest of the span band converges to its rigid-support values
    like 1/k_s."""
    d = 0.5
    sup = [d * j for j in range(1, 10)]
    f_pp = math.pi / (2 * d**2) * math.sqrt(EI / M_RAIL)
    ne = 40  # 4 elements per span: the discretisation error of f_pp is 2.6e-4
    freqs = {}
    for ks in (1e8, 1e9, 1e10, 1e11, 1e12, 1e14):
        freqs[ks] = bare_frequencies(make_rail, ne, n_modes=10, supports=sup, stiffness=ks)
    lowest = np.array([freqs[k][0] for k in sorted(freqs)])
    assert np.all(np.diff(lowest) >= -1e-9 * f_pp)  # stiffer supports, higher frequency
    assert lowest[0] < 0.5 * f_pp  # 100 MN/m: the rail bounces on its supports well below
    # at 1e11 N/m the lowest mode is the span mode, within the mesh's discretisation error
    # (measured 2.6e-4), and closer than at 1e9 N/m (where it is 56 % below)
    assert freqs[1e11][0] == pytest.approx(f_pp, rel=1e-3)
    validation.record(
        "eigen.pinned_pinned_span", level="eigen analysis", kind="closed form",
        quantity="5 m rail on nine 1e11 N/m supports every 0.5 m: lowest frequency",
        reference="pinned-pinned span: f_pp = π/(2 d²) √(EI/m) = 2147 Hz",
        measured=abs(freqs[1e11][0] / f_pp - 1.0), tolerance=1e-3)
    assert abs(freqs[1e11][0] / f_pp - 1) < abs(freqs[1e9][0] / f_pp - 1)
    # the other modes of the span band (2..10: neighbouring spans out of phase, supports
    # moving a little) converge to their rigid-support values like 1/k_s; 1e14 N/m stands in
    # for rigid (its own gap is ~1e-4). Measured max gap over the band: 0.44, 0.078, 0.0082
    # at 1e10, 1e11, 1e12 N/m.
    gap = [np.abs(freqs[k] / freqs[1e14] - 1).max() for k in (1e10, 1e11, 1e12)]
    assert gap[2] < gap[1] < gap[0]
    assert gap[1] < 0.1
    assert 8 < gap[1] / gap[2] < 12  # first order in 1/k_s


def test_support_between_nodes_frequencies_as_accurate_as_on_nodes():
    """Support at 1.3 m (between nodes of the 0.25 m and 0.125 m meshes) against a 200-element
    mesh with a node there: the error is the ordinary discretisation error, as large as that of
    the paper's scene (supports on nodes) at the same element size."""
    shifted = dataclasses.replace(KATO, supports=tw.Supports(
        positions=(0.5, 1.0, 1.3, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5)))
    X = 1.5
    ref_shift = tw.eigen(shifted, [X], n_elements=200).frequencies[0]
    ref_kato = tw.eigen(KATO, [X], n_elements=200).frequencies[0]
    for ne in (20, 40):
        err_shift = np.abs(tw.eigen(shifted, [X], n_elements=ne).frequencies[0] / ref_shift - 1)
        err_kato = np.abs(tw.eigen(KATO, [X], n_elements=ne).frequencies[0] / ref_kato - 1)
        # measured max over six modes: 6.0e-4 vs 6.1e-4 (20), 3.9e-5 vs 3.9e-5 (40)
        assert err_shift.max() < 2 * err_kato.max()
    assert err_shift.max() < 1e-4  # 40 elements


def test_paper_scene_frequencies():
    res = tw.eigen(tw.Scene.kato2005(), [2.5])
    f = res.frequencies
    assert f.shape == (1, 6)
    assert np.all(np.isfinite(f)) and np.all(f > 0)
    assert np.all(np.diff(f[0]) > 0)
    np.testing.assert_array_equal(res.positions, [2.5])
    # the wheel on its contact spring alone would ring at sqrt(k/M)/2pi = 1.34 kHz; the rail
    # on the paper's supports starts near its foundation's cut-on sqrt(k_f/m)/2pi = 361 Hz
    cut_on = math.sqrt(KATO.winkler_modulus / M_RAIL) / (2 * math.pi)
    assert 0.8 * cut_on < f[0, 0] < 1.2 * cut_on


def test_mode_shapes_are_mass_normalised():
    scene = KATO
    X = 1.6
    res = tw.eigen(scene, [X], n_modes=6, n_elements=scene.rail.n_elements)
    model = _kernel.rail_model(scene)
    M = np.array(model.mass_dense())
    K = np.array(model.tangent_dense(model.reference()))
    phi = res.shapes[0]  # (n_dof + 1, n_modes)
    rail, wheel = phi[:-1], phi[-1]
    mass = rail.T @ M @ rail + scene.wheel.mass * np.outer(wheel, wheel)
    np.testing.assert_allclose(mass, np.eye(6), atol=1e-9)
    # stiffness: rail + contact spring k (Y_w - y_rail(X))^2 / 2
    y_at_x = np.array([model.positions(rail[:, j], [X])[0, 1] for j in range(6)])
    stretch = wheel - y_at_x
    stiff = rail.T @ K @ rail + scene.contact_stiffness * np.outer(stretch, stretch)
    omega2 = (2 * math.pi * res.frequencies[0]) ** 2
    np.testing.assert_allclose(stiff, np.diag(omega2), atol=1e-9 * omega2.max())


@pytest.mark.parametrize("node", [1.75, 1.5])  # a node between supports, a node on a support
def test_frequencies_are_continuous_across_a_node(node):
    """The wheel is attached through the shape functions, so moving it off a node changes the
    frequencies continuously: the change is proportional to the distance (measured ~0.1 per mm,
    relative), from either side."""
    changes = []
    for dx in (1e-3, 1e-4, 1e-5):
        f = tw.eigen(KATO, [node, node + dx, node - dx]).frequencies
        changes.append(max(np.abs(f[1] / f[0] - 1).max(), np.abs(f[2] / f[0] - 1).max()))
    changes = np.array(changes)
    assert changes[0] < 1e-3
    np.testing.assert_allclose(changes[1:] / changes[:-1], 0.1, rtol=0.3)


@pytest.mark.parametrize("X", [0.0, L])
def test_wheel_over_an_end_support_decouples(X, validation):
    """Over a rigid end support the rail does not move under the wheel: the spectrum is the
    bare rail's plus the wheel bouncing on its contact spring, sqrt(k/M)/2pi = 1343 Hz."""
    res = tw.eigen(KATO, [X], n_modes=12)
    wheel = math.sqrt(KATO.contact_stiffness / KATO.wheel.mass) / (2 * math.pi)
    expected = np.sort(np.append(rail_frequencies(KATO, 12), wheel))[:12]
    np.testing.assert_allclose(res.frequencies[0], expected, rtol=1e-10)
    if X == 0.0:
        validation.record(
            "eigen.wheel_over_a_rigid_support", level="eigen analysis", kind="closed form",
            quantity="paper's scene, wheel above the rigid end support: 12 lowest frequencies",
            reference="the bare track's frequencies plus the wheel on its contact spring, "
                      "√(k/M)/2π = 1343 Hz",
            measured=np.abs(res.frequencies[0] / expected - 1.0).max(), tolerance=1e-10)


def test_stiff_contact_with_tiny_wheel_recovers_the_bare_rail():
    """A massless wheel on a spring adds no stiffness to the rail: with M -> 0 the wheel's own
    mode sqrt(k/M)/2pi leaves the band and the rail modes approach the bare rail's, the change
    being proportional to the added mass M (measured 3.3e-5 relative per 0.01 kg)."""
    bare = rail_frequencies(KATO, 6)
    errs = []
    for mass in (1e-1, 1e-2, 1e-3):
        scene = dataclasses.replace(KATO, wheel=dataclasses.replace(KATO.wheel, mass=mass),
                                    contact=tw.Contact(stiffness=1e10))
        f = tw.eigen(scene, [1.6]).frequencies[0]
        errs.append(np.abs(f / bare - 1).max())
    assert errs[-1] < 1e-5
    np.testing.assert_allclose(np.array(errs[1:]) / errs[:-1], 0.1, rtol=0.05)


def test_rail_mode_shape_is_normalised():
    res = tw.eigen(KATO, [1.6])
    for mode in range(3):
        s, y, wheel = res.rail_mode_shape(0, mode)
        assert s[0] == 0.0 and s[-1] == L
        assert max(np.abs(y).max(), abs(wheel)) == pytest.approx(1.0)
        assert y[0] == pytest.approx(0.0, abs=1e-12) and y[-1] == pytest.approx(0.0, abs=1e-12)


def test_repr_counts_positions_and_modes_in_words():
    """One position: 'at one wheel position X = 2.5 m' and one frequency per mode (it said
    '1 wheel positions' and '343.8-343.8'); several: the count and the bands."""
    s = tw.Scene.kato2005()
    one = repr(tw.eigen(s, [2.5], n_modes=2))
    assert "2 vertical modes at one wheel position X = 2.5 m" in one
    assert "wheel positions" not in one and "-" not in one.split("vertical [Hz]: ")[1].split()[0]
    two = repr(tw.eigen(s, [2.5, 3.0], n_modes=1))
    assert "1 vertical mode at 2 wheel positions X = 2.5..3 m" in two


def test_pyproject_lists_each_dependency_once():
    import re
    from pathlib import Path

    text = (Path(__file__).parents[1] / "pyproject.toml").read_text()
    deps = text.split("dependencies = [")[1].split("]")[0]
    names = re.findall(r'"([A-Za-z0-9_.\-]+)', deps)
    assert len(names) == len(set(names)) and "scipy" in names, names
