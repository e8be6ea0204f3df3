"""Receptance and decay rate of the linear track (docs: Model § Receptance and decay rate)."""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel as _kernel
from trackwheel.eigen import rail_frequencies
from trackwheel.frequency import decay_rate_limit, decay_rate_positions, en15461_decay

#: support spacing of the "continuous" track [m]: 20 supports per bending wavelength at 2 kHz
#: (lambda ~ 1 m), so the discrete supports act as the foundation k_f = k_s/d, c_f = c_s/d
D = 0.05
#: foundation damping per metre [N s/m^2]: the waves decay by more than 60 dB over the 30 m
#: from the receiver to either end and back (the slowest, near the 360 Hz cut-on, still ~2 dB/m),
#: so the finite rail's end reflections are below 0.01 dB at the receiver
C_F = 1e5


def _long_track() -> tw.Scene:
    s = tw.Scene.kato2005()
    return dc.replace(s, rail=dc.replace(s.rail, length=60.0, n_elements=1200),
                      supports=dc.replace(s.supports, spacing=D, stiffness=s.winkler_modulus * D,
                                          damping=C_F * D), rail_gravity=False)


def _infinite_beam(scene: tw.Scene, f: np.ndarray):
    """beta (the root with Re > 0 of beta^4 = (k_f + i w c_f - m w^2)/(4 EI)) and the point
    receptance 1/(8 EI beta^3) of the infinite Euler-Bernoulli beam on the foundation."""
    w = 2 * np.pi * f
    r = scene.rail
    s = scene.winkler_modulus + 1j * w * C_F
    beta = ((s - r.mass_per_length * w**2) / (4 * r.bending_stiffness)) ** 0.25
    return beta, 1.0 / (8 * r.bending_stiffness * beta**3)


def _infinite_beam_transfer(beta, x):
    """alpha(x)/alpha(0) = exp(-beta x)(cos beta x + sin beta x) = ((1 - i) exp(-k1 x)
    + (1 + i) exp(-k2 x))/2, k1,2 = (1 -+ i) beta: the two decaying waves."""
    k1, k2 = (1 - 1j) * beta, (1 + 1j) * beta
    return 0.5 * ((1 - 1j) * np.exp(-np.outer(k1, x)) + (1 + 1j) * np.exp(-np.outer(k2, x)))


def test_point_receptance_of_a_long_closely_supported_rail_is_the_infinite_beam(validation):
    """Within 0.1 dB and 0.01 rad over 20-2000 Hz at mid-rail (the issue asks 1 dB; measured
    ~1e-4 dB: the smeared supports and the 20 elements per wavelength are that close)."""
    s = _long_track()
    f = np.geomspace(20.0, 2000.0, 40)
    a = tw.receptance(s, 30.0, f)
    _, a_inf = _infinite_beam(s, f)
    assert np.max(np.abs(20 * np.log10(np.abs(a / a_inf)))) < 0.1
    assert np.max(np.abs(np.angle(a / a_inf))) < 0.01
    validation.record(
        "frequency.infinite_beam_receptance", level="frequency domain", kind="closed form",
        quantity="point receptance of a 60 m rail on damped supports every 5 cm, 20-2000 Hz: "
                 "magnitude",
        reference="infinite Euler-Bernoulli beam on a viscoelastic foundation: 1/(8 EI β³)",
        measured=np.max(np.abs(20 * np.log10(np.abs(a / a_inf)))), tolerance=0.1, metric="dB")


def test_static_limit_equals_static(validation):
    """f = 0: -P alpha(x, x, 0) is static's deflection under the wheel (rail weight off): the
    nonlinear ANCF statics and the linear track agree to 1e-6 (the contact point's shift
    off the load point is ~1e-6 m)."""
    s = dc.replace(tw.Scene.kato2005(), rail_gravity=False)
    gaps = []
    for x in (2.25, 2.5, 1.3):
        a0 = tw.receptance(s, x, [0.0], n_elements=s.rail.n_elements)[0]  # static's mesh
        assert a0.imag == 0.0
        assert -s.static_load * a0.real == pytest.approx(tw.static(s, x).y_contact, rel=1e-6)
        gaps.append(abs(-s.static_load * a0.real / tw.static(s, x).y_contact - 1.0))
    validation.record(
        "frequency.static_limit", level="frequency domain", kind="path agreement",
        quantity="paper's track: receptance at 0 Hz times the load, at three positions",
        reference="the nonlinear ANCF statics (tw.static)",
        measured=max(gaps), tolerance=1e-6)


def test_undamped_receptance_has_its_poles_at_the_eigenfrequencies(validation):
    """Near a simple pole alpha ~ A/(f_k - f): |alpha| at f_k (1 + 1e-7) is 100 times that at
    f_k (1 + 1e-5) for every mode (within 2 %, the regular part of alpha), so the peaks sit at
    the eigen analysis' frequencies to 1e-7."""
    s = tw.Scene.kato2005()
    for beam in ("euler", "timoshenko"):
        sb = dc.replace(s, rail=dc.replace(s.rail, beam=beam))
        ne = sb.rail.n_elements  # the same mesh for both
        fk = rail_frequencies(sb, 5, n_elements=ne)
        near = np.abs(tw.receptance(sb, 1.3, fk * (1 + 1e-7), n_elements=ne))
        far = np.abs(tw.receptance(sb, 1.3, fk * (1 + 1e-5), n_elements=ne))
        np.testing.assert_allclose(near / far, 100.0, rtol=0.02)
        if beam == "timoshenko":
            validation.record(
                "frequency.poles_are_eigenfrequencies", level="frequency domain",
                kind="path agreement",
                quantity="undamped Timoshenko track: |α| at f_k (1 + 1e-7) over |α| at "
                         "f_k (1 + 1e-5), five modes",
                reference="a simple pole at the eigen analysis' f_k: ratio 100",
                measured=np.abs(near / far / 100.0 - 1.0).max(), tolerance=0.02)


def test_transfer_receptance_is_reciprocal():
    """Maxwell-Betti: alpha(x_r, x_e) = alpha(x_e, x_r) (Z symmetric), to round-off."""
    s = tw.Scene.kato2005()
    s = dc.replace(s, supports=dc.replace(s.supports, damping=2e4))
    f = [0.0, 300.0, 1500.0]
    np.testing.assert_allclose(tw.receptance(s, 1.1, f, 3.7), tw.receptance(s, 3.7, f, 1.1),
                               rtol=1e-9)
    both = tw.receptance(s, 1.1, f, [1.1, 3.7])
    assert both.shape == (3, 2)
    np.testing.assert_allclose(both[:, 0], tw.receptance(s, 1.1, f), rtol=0)


def test_decay_rate_equals_the_en15461_sum_of_the_infinite_beam(validation):
    """The track's EN 15461 decay rate equals the same estimate from the infinite beam's closed
    form transfer receptances at the same positions within 0.5 % (the receptances agree to
    ~1e-4 dB)."""
    s = _long_track()
    f = np.array([50.0, 300.0, 1000.0, 2000.0])
    x = decay_rate_positions(s)
    beta, _ = _infinite_beam(s, f)
    got = tw.decay_rate(s, f)
    expected = en15461_decay(x, _infinite_beam_transfer(beta, x - x[0]))
    np.testing.assert_allclose(got, expected, rtol=5e-3)
    validation.record(
        "frequency.decay_rate_infinite_beam", level="frequency domain", kind="closed form",
        quantity="EN 15461 decay rate of a 60 m rail on damped supports every 5 cm, "
                 "50-2000 Hz",
        reference="the same EN 15461 sum over the infinite beam's closed-form transfer "
                  "receptances",
        measured=np.abs(got / expected - 1.0).max(), tolerance=5e-3)


def test_en15461_sum_is_the_decay_integral():
    """Where the waves have decayed by more than 30 dB over the 66-spacing grid (here below
    the cut-on), the EN sum is the integral 4.343 / int |alpha(x)/alpha(0)|^2 dx of the two
    decaying waves, in closed form 1/4 (1/Re k1 + 1/Re k2 + 2 Re(-2i/(k1 + conj k2))), within
    2 % (trapezoid rule on the standard's coarsening grid)."""
    s = _long_track()
    f = np.array([50.0, 100.0, 300.0])
    beta, _ = _infinite_beam(s, f)
    k1, k2 = (1 - 1j) * beta, (1 + 1j) * beta
    integral = 0.25 * (1 / k1.real + 1 / k2.real + 2 * np.real(-2j / (k1 + np.conj(k2))))
    np.testing.assert_allclose(tw.decay_rate(s, f), 10 * math.log10(math.e) / integral,
                               rtol=0.02)


def test_en15461_of_a_single_wave_is_its_decay():
    """|A| = exp(-delta x) on the standard grid of a 0.6 m track: DR = 8.686 delta within 3 %
    for 1-5 dB/m (truncation at 39.6 m and the trapezoid rule on the 7.2 m outer steps)."""
    x = 0.3 + 0.6 * np.asarray(tw.frequency.EN15461_SPANS)
    dr = np.array([1.0, 2.0, 5.0])
    delta = dr / (20 * math.log10(math.e))
    a = np.exp(-np.outer(delta, x - x[0])) * np.exp(-1j * np.outer(3 * delta, x))
    np.testing.assert_allclose(en15461_decay(x, a), dr, rtol=0.03)


def test_layered_support_with_a_stiff_ballast_and_light_sleeper_is_the_single_spring():
    """The sleeper correction built through the binding: m_s -> 0 with k_b -> inf gives the pad
    alone (k_dyn -> s_p, to 1e-6), and m_s -> 0 with k_b = k_p the two springs in series, k_p/2."""
    s = tw.Scene.kato2005()
    s = dc.replace(s, supports=dc.replace(s.supports, damping=1e4))
    f = [0.0, 200.0, 800.0, 1800.0]
    beam = _kernel.beam_params(s)
    n = len(s.support_positions)

    def layered(ms, kb, cb):
        p = _core.RailParams()
        p.length, p.EA, p.EI = s.rail.length, s.rail.axial_stiffness, s.rail.bending_stiffness
        p.rhoA, p.n_elements, p.n_gauss = s.rail.mass_per_length, s.rail.n_elements, 5
        p.gravity = s.gravity
        sp = _core.SupportParams()
        sp.position = list(s.support_positions)
        sp.stiffness = [s.supports.stiffness] * n
        sp.damping = [s.supports.damping] * n
        sp.sleeper_mass, sp.ballast_stiffness, sp.ballast_damping = [ms] * n, [kb] * n, [cb] * n
        return np.asarray(_core.receptance(_core.RailModel(p, sp), beam, [2.25], [2.25], f))[:, 0]

    single = tw.receptance(s, 2.25, f, n_elements=s.rail.n_elements)
    np.testing.assert_allclose(layered(1e-9, 1e16, 0.0), single, rtol=1e-6)
    half = dc.replace(s, supports=dc.replace(s.supports, stiffness=s.supports.stiffness / 2,
                                             damping=0.0))
    np.testing.assert_allclose(layered(1e-9, s.supports.stiffness, 0.0)[:1],
                               tw.receptance(half, 2.25, f, n_elements=s.rail.n_elements)[:1],
                               rtol=1e-9)


def test_decay_rate_limit_is_the_iso3095_band_value():
    """Each frequency takes its one-third-octave band's limit; the bands tile 223-5623 Hz."""
    lim = decay_rate_limit([224.0, 400.0, 1000.0, 1100.0, 5000.0, 5600.0, 100.0, 6000.0])
    np.testing.assert_array_equal(lim[:6], [2.0, 6.0, 0.8, 0.8, 0.8, 0.8])
    assert np.isnan(lim[6:]).all()
    edges = tw.frequency.iso3095_band_edges()
    np.testing.assert_allclose(np.sqrt(edges[:-1] * edges[1:]), tw.frequency.ISO3095_BANDS,
                               rtol=0.03)  # nominal centres are rounded exact ones


def test_en15461_grid_and_intervals():
    """29 positions to 66 spacings; the A.2 intervals add up to the grid's length plus half the
    last step (the last position stands for rail symmetric about itself)."""
    spans = np.asarray(tw.frequency.EN15461_SPANS)
    assert spans.size == 29 and spans[-1] == 66.0
    x = 0.6 * spans
    flat = np.ones((1, x.size))
    total = x[-1] + 0.5 * (x[-1] - x[-2])
    assert en15461_decay(x, flat)[0] == pytest.approx(10 * math.log10(math.e) / total)


@pytest.mark.parametrize("kw, match", [
    (dict(x=2.0, freqs=[-1.0]), "freqs"),
    (dict(x=2.0, freqs=[math.nan]), "freqs"),
    (dict(x=6.0, freqs=[10.0]), "x = 6.0"),
    (dict(x=2.0, freqs=[10.0], x_response=[1.0, 7.0]), "x_response"),
    (dict(x=2.0, freqs=[]), "freqs"),
])
def test_bad_input(kw, match):
    with pytest.raises(ValueError, match=match):
        tw.receptance(tw.Scene.kato2005(), **kw)


@pytest.mark.parametrize("scene, least", [(tw.Scene.kato2005(), 33.25),
                                          (tw.Scene.ballasted_track(), 39.9),
                                          (tw.Scene.ballasted_track(12.0), 39.9)])
def test_decay_rate_needs_room_for_the_standard_positions(scene, least):
    """A rail too short for the 66 spacings of EN 15461 is told the length it needs (66 d
    beyond the first mid-span, d / 2 from the end), never an empty range of x0."""
    with pytest.raises(ValueError, match="EN 15461 positions") as info:
        tw.decay_rate(scene, [500.0])
    msg = str(info.value)
    assert "Rail.length" in msg and f"at least {least:g} m" in msg and "x0 in" not in msg


def test_decay_rate_x0_is_inside_the_rail():
    """x0 = 0 is the rigid end (zero response, so no ratio: NaN rates before) and the rail
    hardly moves just beside it (1e-185 m: NaN too): x0 is at least a quarter bay from the end;
    an x0 beyond L - 66 d gets its allowed range."""
    s = tw.Scene.ballasted_track(60.0)
    for x0 in (0.0, 1e-185):
        with pytest.raises(ValueError, match=r"x0 = .* is outside the allowed range "
                           r"\[0.15, 60.0\]"):
            tw.decay_rate(s, [0.0, 500.0], x0=x0)
    with pytest.raises(ValueError, match=r"x0 = 30 m .* allowed range \[0.15, 20.4\] m"):
        tw.decay_rate(s, [500.0], x0=30.0)
    assert np.isfinite(tw.decay_rate(s, [0.0, 500.0], x0=0.15)).all()


def test_plots():
    from trackwheel import plots

    s = tw.Scene.kato2005()
    f = np.geomspace(50.0, 3000.0, 30)
    fig = plots.receptance(s, f)
    mag = {ln.get_gid(): ln for ax in fig.axes for ln in ax.get_lines()}
    np.testing.assert_allclose(mag["magnitude: mid-span"].get_ydata(),
                               np.abs(tw.receptance(s, 2.25, f)))
    assert "magnitude: above a support" in mag
    long = _long_track()
    fig = plots.decay_rate(long, f)
    gids = {a.get_gid() for a in fig.axes[0].get_children()}
    assert {"decay rate", "ISO 3095 limit"} <= gids


@pytest.mark.parametrize("beam", ["euler", "timoshenko"])
def test_pinned_pinned_peak_of_the_midspan_receptance(beam, validation):
    """On a long track on 0.5 m supports the mid-span point receptance peaks at the pinned-pinned
    frequency of one span (the rail bends between supports that hardly move, k_s >> the span's
    modal stiffness): within 1 % of (pi/(2 d^2)) sqrt(EI/m), 2147 Hz, as an Euler-Bernoulli beam,
    of the Timoshenko frequency equation's root, 1438 Hz, with shear (1 Hz steps)."""
    from trackwheel.fidelity import pinned_pinned_frequencies

    s = tw.Scene.kato2005()
    s = dc.replace(s, rail=dc.replace(s.rail, length=30.0, n_elements=600, beam=beam),
                   supports=dc.replace(s.supports, damping=2e3), rail_gravity=False)
    f = np.arange(1000.0, 3000.0, 1.0)
    peak = f[np.argmax(np.abs(tw.receptance(s, 15.25, f)))]
    expected = pinned_pinned_frequencies(s)[0 if beam == "euler" else 1]
    assert peak == pytest.approx(expected, rel=0.01)
    validation.record(
        f"frequency.pinned_pinned_peak[{beam}]", level="frequency domain", kind="closed form",
        quantity=f"{'Euler-Bernoulli' if beam == 'euler' else 'Timoshenko'} rail, 30 m on "
                 "0.5 m supports: frequency of the mid-span receptance peak (1 Hz steps)",
        reference=("π/(2 d²) √(EI/m)" if beam == "euler"
                   else "root of the Timoshenko frequency equation of one span"),
        measured=abs(peak / expected - 1.0), tolerance=0.01)


@pytest.mark.parametrize("f_max", [500.0, 2000.0, 5000.0])
def test_frequency_mesh_resolves_the_bending_wavelength(f_max):
    """The frequency-domain mesh (what `receptance` and `decay-rate` use): whole elements per
    quarter bay, at least ten per Euler-Bernoulli bending wavelength 2 pi (EI / (m w^2))^(1/4)
    at f_max, and the fewest such (one element per quarter bay less would miss it), never fewer
    than the scene's own."""
    from trackwheel.run.defaults import frequency_mesh

    scene = tw.Scene.ballasted_track()
    r, d = scene.rail, scene.supports.spacing
    n_bays = round(r.length / d)
    w = 2.0 * np.pi * f_max
    wavelength = 2.0 * np.pi * (r.bending_stiffness / (r.mass_per_length * w * w)) ** 0.25
    n = frequency_mesh(scene, f_max)
    assert n % (4 * n_bays) == 0 and n >= r.n_elements  # whole quarter bays
    assert r.length / n <= wavelength / 10.0
    assert n == r.n_elements or r.length / (n - 4 * n_bays) > wavelength / 10.0


def test_frequency_mesh_capped_by_the_element_limit_warns():
    from trackwheel.base.limits import MAX_ELEMENTS
    from trackwheel.run.defaults import frequency_mesh

    scene = tw.Scene.ballasted_track(3000.0, elements_per_bay=1)
    with pytest.warns(tw.MeshWarning, match="per bay that resolve the bending wavelength"):
        n = frequency_mesh(scene, 5000.0)
    assert n == MAX_ELEMENTS  # 5000 bays, 4 elements each


def test_frequencies_above_the_beam_models_range_are_refused_by_name():
    """receptance(kato, 2.25, [1e155]) raised the kernel's 'singular at 1000...000 Hz' (a
    155-digit number); the frequencies are bounded by MAX_FREQUENCY (100 kHz), named, and the
    bound itself gives a finite receptance, below the mass line 1 / (m omega^2 L) of the
    whole rail moving as one (the mesh cannot resolve 100 kHz, the magnitude still holds)."""
    s = tw.Scene.kato2005()
    with pytest.raises(ValueError, match=r"freqs = 1e\+155 Hz is outside the allowed range "
                       r"\[0, 100000\] Hz"):
        tw.receptance(s, 2.25, [1e155])
    a = tw.receptance(s, 2.25, [1e5])
    assert np.all(np.isfinite(a)) and 0.0 < abs(a[0])
