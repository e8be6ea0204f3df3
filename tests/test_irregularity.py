"""Rail profiles, wheel defects and the contact filter (docs: Model § Irregularities, issue 13)."""

import math
import multiprocessing
import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest
from scipy.integrate import quad

from trackwheel import spectra
from trackwheel.irregularity import (
    Irregularity,
    Polygon,
    WheelFlat,
    contact_filter,
    contact_half_width,
    filter_attenuation,
    filter_matters,
    hertz_half_width,
)

BAND = (2.0, 40.0)  # generated wavelengths [m]


def _fd(f, x, h):
    """Central differences of f at x: (f', f'') with O(h^2) error."""
    return (f(x + h) - f(x - h)) / (2 * h), (f(x + h) - 2 * f(x) + f(x - h)) / h**2


def _third_octave_omega_bands(lam_min, lam_max):
    """Base-10 one-third-octave bands in f = 1/lambda lying inside the band, as Omega edges."""
    half = 10**0.05
    ks = range(math.ceil(10 * math.log10(half / lam_max)), math.floor(
        10 * math.log10(1 / (lam_min * half))) + 1)
    return [(2 * math.pi * 10 ** (k / 10) / half, 2 * math.pi * 10 ** (k / 10) * half)
            for k in ks]


# ---------------------------------------------------------------------------------------------
# random profiles
def test_spectral_sum_variance_matches_integral_of_the_spectrum():
    # sum a_n^2 / 2 is the profile's variance (each cosine contributes a^2/2). With Omega_n
    # drawn uniformly in each of n log sub-bands it is an unbiased stratified estimate of
    # integral S over the band; S ~ Omega^-4 changes by at most (10^0.01)^4 - 1 = 9.6 % in a
    # sub-band at 100 per decade, so each of the ~130 independent band errors is below 10 % of
    # its band's share and the total is within ~10 % / sqrt(130) ~ 1 % (1 sigma): 3 % is 3 sigma.
    s = spectra.fra(5)
    exact, _ = quad(s, 2 * math.pi / BAND[1], 2 * math.pi / BAND[0], epsrel=1e-12)
    # closed form: k A Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)) = kA (1/Omega^2 - 1/(..))
    kA, wc = 0.25 * 0.2095e-4, 0.8245
    def prim(w):
        return kA * (-1 / w - math.atan(w / wc) / wc)

    assert exact == pytest.approx(prim(2 * math.pi / 2) - prim(2 * math.pi / 40), rel=1e-10)
    for seed in range(5):
        part = Irregularity.random(s, seed=seed, wavelengths=BAND).parts[0]
        _, a, _ = part.components()
        assert 0.5 * np.sum(a**2) == pytest.approx(exact, rel=0.03)


def test_sampled_variance_matches_spectral_sum():
    # over a record of 20 km the sample variance of r equals sum a^2/2 up to the cross terms
    # of neighbouring components, each ~ 1/(dOmega L): averaged over 10 seeds within 3 %
    s = spectra.fra(5)
    ratios = []
    x = np.arange(0.0, 20_000.0, 0.5)
    for seed in range(10):
        irr = Irregularity.random(s, seed=seed, wavelengths=BAND)
        _, a, _ = irr.parts[0].components()
        ratios.append(np.var(irr(x)) / (0.5 * np.sum(a**2)))
    assert np.mean(ratios) == pytest.approx(1.0, abs=0.03)


def test_welch_psd_matches_target_in_every_third_octave_band():
    # 20 seeds x 15 half-overlapping Hann segments of 2048 m: the relative standard error of
    # the averaged Welch estimate is ~ 1/sqrt(15 x 20) = 6 % (0.25 dB) per bin, less after
    # averaging the >= 13 bins of a band; +-1 dB is more than 4 standard errors. The lowest
    # band (0.028-0.036 1/m) holds 15 bins of 1/2048 1/m, so the Hann leakage of the band
    # edges (+-2 bins) stays small.
    s = spectra.fra(4)
    dx, length, nseg = 0.25, 16_384.0, 8192
    est = None
    for seed in range(20):
        irr = Irregularity.random(s, seed=seed, wavelengths=BAND)
        omega, p = irr.psd(0.0, length, dx, nperseg=nseg)
        est = p if est is None else est + p
    est /= 20
    bands = _third_octave_omega_bands(*BAND)
    assert len(bands) >= 10
    for lo, hi in bands:
        sel = (omega >= lo) & (omega < hi)
        target = quad(s, lo, hi)[0] / (hi - lo)
        got = np.mean(est[sel])
        assert abs(10 * math.log10(got / target)) < 1.0, (lo, hi)


def test_same_seed_same_profile_bit_for_bit_and_different_seeds_differ():
    x = np.linspace(-3.0, 50.0, 1001)
    a = Irregularity.random(spectra.german("high"), seed=7, wavelengths=(1.0, 50.0))
    b = Irregularity.random(spectra.german("high"), seed=7, wavelengths=(1.0, 50.0))
    c = Irregularity.random(spectra.german("high"), seed=8, wavelengths=(1.0, 50.0))
    assert a == b and hash(a) == hash(b)
    assert np.array_equal(a(x), b(x))
    back = pickle.loads(pickle.dumps(a))
    assert back == a and np.array_equal(back(x), a(x))
    assert not np.array_equal(a(x), c(x))


def _evaluate(irr, x):
    return irr(x), irr.slope(x), irr.curvature(x)


def test_same_profile_in_a_worker_process():
    irr = Irregularity.random(spectra.fra(3), seed=11, wavelengths=(1.6, 100.0)) + \
        Irregularity.dipped_joint(2e-3, 0.4, 3.0)
    x = np.linspace(0.0, 10.0, 501)
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=1, mp_context=ctx) as pool:
        remote = pool.submit(_evaluate, irr, x).result()
    for got, here in zip(remote, _evaluate(irr, x)):
        assert np.array_equal(got, here)


def test_random_derivatives_against_finite_differences():
    irr = Irregularity.random(spectra.iso3095(), seed=1)
    x = np.linspace(0.0, 1.0, 37)
    h = 1e-5  # shortest wavelength 2.8 mm: (Omega h)^2 ~ 5e-4 relative truncation
    d1, d2 = _fd(irr, x, h)
    scale1 = np.max(np.abs(irr.slope(x)))
    scale2 = np.max(np.abs(irr.curvature(x)))
    assert np.max(np.abs(irr.slope(x) - d1)) < 1e-3 * scale1
    assert np.max(np.abs(irr.curvature(x) - d2)) < 1e-3 * scale2


def test_random_band_defaults_to_validity_and_repr_shows_recipe():
    irr = Irregularity.random(spectra.china_hsr(), seed=3)
    part = irr.parts[0]
    assert part.wavelengths == pytest.approx((2.0, 200.0), rel=1e-12)
    assert part.n == math.ceil(100 * 2)  # 100 per decade over two decades
    text = repr(irr)
    assert "seed=3" in text and "China" in text and len(text) < 200


# ---------------------------------------------------------------------------------------------
# deterministic shapes
def test_sine_values_and_derivatives():
    irr = Irregularity.sine(0.08, 5e-5, phase=0.3)
    x = np.linspace(0.0, 0.3, 31)
    assert np.allclose(irr(x), 5e-5 * np.sin(2 * math.pi * x / 0.08 + 0.3), rtol=0, atol=1e-18)
    d1, d2 = _fd(irr, x, 1e-6)
    assert np.allclose(irr.slope(x), d1, rtol=1e-6, atol=1e-12)
    assert np.allclose(irr.curvature(x), d2, rtol=1e-4, atol=1e-5)


def test_dipped_joint_shape():
    d, length, at = 3e-3, 0.5, 2.0
    irr = Irregularity.dipped_joint(d, length, at)
    assert irr(at + length / 2) == pytest.approx(-d, rel=1e-15)  # deepest at the middle
    assert irr(np.array([at, at + length, at - 1, at + 2])).tolist() == \
        pytest.approx([0, 0, 0, 0], abs=1e-18)
    assert np.all(irr(np.linspace(at, at + length, 101)) <= 0.0)  # a dip, never a bump
    # cusp: slope -pi d / l just before the middle, +pi d / l just after
    assert irr.slope(at + length / 2 - 1e-12) == pytest.approx(-math.pi * d / length, rel=1e-9)
    assert irr.slope(at + length / 2 + 1e-12) == pytest.approx(math.pi * d / length, rel=1e-9)
    # smooth elsewhere inside: analytic derivatives against differences
    x = np.concatenate((np.linspace(at + 0.01, at + 0.24, 10), np.linspace(at + 0.26, at + 0.49,
                                                                           10)))
    d1, d2 = _fd(irr, x, 1e-6)
    assert np.allclose(irr.slope(x), d1, rtol=1e-7, atol=1e-12)
    assert np.allclose(irr.curvature(x), d2, rtol=1e-4, atol=1e-6)


def test_samples_reproduce_a_cubic_and_refuse_outside():
    x = np.linspace(0.0, 4.0, 21)
    def cubic(s):
        return 1e-3 * (s**3 - 2 * s**2 + 0.5 * s - 1)

    irr = Irregularity.samples(x, cubic(x))
    xq = np.linspace(0.0, 4.0, 77)
    # a not-a-knot cubic spline reproduces a cubic exactly (round-off only)
    assert np.allclose(irr(xq), cubic(xq), rtol=0, atol=1e-15)
    assert np.allclose(irr.slope(xq), 1e-3 * (3 * xq**2 - 4 * xq + 0.5), rtol=0, atol=1e-13)
    assert np.allclose(irr.curvature(xq), 1e-3 * (6 * xq - 4), rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match=r"\[0.0, 4.0\] m"):
        irr(np.array([1.0, 4.5]))
    pchip = Irregularity.samples(x, cubic(x), method="pchip")
    assert np.allclose(pchip(x), cubic(x), rtol=0, atol=1e-18)  # interpolates the samples
    assert "21 samples" in repr(pchip)


def test_profiles_add():
    a = Irregularity.sine(1.0, 1e-3)
    b = Irregularity.dipped_joint(1e-3, 0.3, 0.2)
    x = np.linspace(0.0, 1.0, 51)
    s = a + b
    assert len(s.parts) == 2
    assert sum([a, b]) == s  # sum() starts from 0, a smooth rail
    for m in ("__call__", "slope", "curvature"):
        assert np.array_equal(getattr(s, m)(x), getattr(a, m)(x) + getattr(b, m)(x))


def test_table_is_the_profile_on_a_uniform_grid():
    irr = Irregularity.sine(0.7, 1e-4)
    x0, dx, r = irr.table(1.0, 6.0, 0.03)
    assert x0 == 1.0 and dx <= 0.03
    assert x0 + (r.size - 1) * dx == pytest.approx(6.0, rel=1e-14)
    assert np.array_equal(r, irr(np.linspace(1.0, 6.0, r.size)))


@pytest.mark.parametrize("call, name", [
    (lambda: Irregularity.dipped_joint(-1e-3, 0.5, 0.0), "depth"),
    (lambda: Irregularity.dipped_joint(1e-3, 0.0, 0.0), "length"),
    (lambda: Irregularity.sine(0.0, 1e-3), "wavelength"),
    (lambda: Irregularity.random(spectra.fra(5), seed=1, wavelengths=(0.5, 50.0)),
     "wavelengths"),
    (lambda: Irregularity.random(spectra.fra(5), seed=1, wavelengths=(5.0, 2.0)),
     "wavelengths"),
    (lambda: Irregularity.random(spectra.fra(5), seed=-1), "seed"),
    (lambda: Irregularity.samples([0, 1, 1, 2], [0, 0, 0, 0]), "increasing"),
    (lambda: Irregularity.samples([0, 1, 2, 3], [0, 0, 0]), "same length"),
    (lambda: Irregularity.sine(1.0, 1e-3).table(0.0, 1.0, -0.1), "dx"),
])
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


# ---------------------------------------------------------------------------------------------
# wheel out-of-roundness
RHO0 = 0.46


def test_new_flat_depth_and_chord():
    lf = 0.05
    flat = WheelFlat(lf)
    phi = math.asin(lf / (2 * RHO0))
    depth = -float(flat.delta_rho(0.0, RHO0))
    # exact sagitta rho0 (1 - cos phi); the approximation L^2/(8 rho0) is good to (L/2rho0)^2
    assert depth == pytest.approx(RHO0 * (1 - math.cos(phi)), rel=1e-12)
    assert depth == pytest.approx(lf**2 / (8 * RHO0), rel=(lf / (2 * RHO0)) ** 2)
    # the flat is a straight chord: the surface points lie on y = rho0 cos(phi), and its ends
    # (where Delta rho returns to 0) are L_f apart
    psi = np.linspace(-phi, phi, 41)
    rad = RHO0 + flat.delta_rho(psi, RHO0)
    assert np.allclose(rad * np.cos(psi), RHO0 * math.cos(phi), rtol=1e-14)
    assert float(flat.delta_rho(phi * (1 - 1e-12), RHO0)) == pytest.approx(0.0, abs=1e-14)
    assert 2 * RHO0 * math.sin(phi) == pytest.approx(lf, rel=1e-14)
    assert float(flat.delta_rho(phi * 1.01, RHO0)) == 0.0


def test_rounded_flat_depth_and_extent():
    lr = 0.1
    flat = WheelFlat(lr, rounded=True, at_angle=1.0)
    assert -float(flat.delta_rho(1.0, RHO0)) == pytest.approx(lr**2 / (16 * RHO0), rel=1e-14)
    edge = 1.0 + lr / 2 / RHO0
    assert float(flat.delta_rho(edge * (1 - 1e-12), RHO0)) == pytest.approx(0.0, abs=1e-15)
    assert float(flat.delta_rho(edge + 1e-3, RHO0)) == 0.0
    deep = WheelFlat(lr, rounded=True, depth=1e-3)
    assert -float(deep.delta_rho(0.0, RHO0)) == pytest.approx(1e-3, rel=1e-14)


@pytest.mark.parametrize("defect", [WheelFlat(0.06, at_angle=0.5),
                                    WheelFlat(0.08, rounded=True, at_angle=-2.0),
                                    Polygon(7, 3e-5, phase=0.4)])
def test_defect_derivatives_and_period(defect):
    psi = np.linspace(-math.pi, math.pi, 400)
    if isinstance(defect, WheelFlat):  # away from the edges, where a derivative jumps
        half = (math.asin(defect.length / (2 * RHO0)) if not defect.rounded
                else defect.length / (2 * RHO0))
        psi = psi[np.abs(np.abs(psi - defect.at_angle) - half) > 1e-3]
    def f(p):
        return defect.delta_rho(p, RHO0)

    # h = 1e-6 for the slope, 1e-4 for the second difference (its round-off eps rho0 / h^2
    # would be 5e-5 at 1e-6); the truncation h^2 |d3 rho| / 6 stays below 1e-9
    d1, _ = _fd(f, psi, 1e-6)
    _, d2 = _fd(f, psi, 1e-4)
    assert np.allclose(defect.delta_rho_dpsi(psi, RHO0), d1, rtol=1e-6, atol=1e-9)
    scale2 = np.max(np.abs(defect.delta_rho_dpsi2(psi, RHO0)))
    assert np.allclose(defect.delta_rho_dpsi2(psi, RHO0), d2, rtol=1e-4, atol=1e-5 * scale2)
    assert np.allclose(f(psi + 2 * math.pi), f(psi), rtol=0, atol=1e-15)
    psi0, dpsi, table = defect.table(RHO0, 720)
    assert psi0 == 0.0 and dpsi == pytest.approx(2 * math.pi / 720, rel=1e-15)
    assert np.array_equal(table, f(dpsi * np.arange(720)))


def test_polygon_formula():
    p = Polygon(3, 1e-4, phase=0.2)
    assert float(p.delta_rho(0.5, RHO0)) == pytest.approx(1e-4 * math.cos(1.5 + 0.2), rel=1e-14)


@pytest.mark.parametrize("call, name", [
    (lambda: WheelFlat(-0.01), "WheelFlat.length"),
    (lambda: WheelFlat(1.0).delta_rho(0.0, 0.46), "WheelFlat.length"),
    (lambda: WheelFlat(0.05, depth=1e-3), "WheelFlat.depth"),
    (lambda: Polygon(0, 1e-4), "Polygon.order"),
    (lambda: Polygon(3, -1e-4), "Polygon.amplitude"),
    (lambda: Polygon(3, 1e-4).table(0.46, 2), "n"),
])
def test_bad_defects_name_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()


# ---------------------------------------------------------------------------------------------
# contact filter
def test_hertz_half_width_circular_matches_the_contact_law():
    # sphere on a flat: approach delta = a^2 / R and P = 4/3 E* sqrt(R) delta^1.5 (the law
    # trackwheel's Hertz constant uses), so a must satisfy both
    p, r, e = 47138.0, 0.1, 2.058e11 / (2 * (1 - 0.3**2))
    a = hertz_half_width(p, r, e)
    delta = a**2 / r
    assert 4 / 3 * e * math.sqrt(r) * delta**1.5 == pytest.approx(p, rel=1e-12)
    # line contact: p0 = 2 P / (pi a b) and a^2 = 4 P R / (pi b E*): doubling the load
    # widens the patch by sqrt 2
    a1 = hertz_half_width(p, r, e, contact_length=0.02)
    assert hertz_half_width(2 * p, r, e, contact_length=0.02) == pytest.approx(
        math.sqrt(2) * a1, rel=1e-14)
    assert a1**2 == pytest.approx(4 * p * r / (math.pi * 0.02 * e), rel=1e-14)


@pytest.mark.parametrize("lam", [0.02, 0.05, 0.3])
def test_contact_filter_of_a_sine_is_sinc(lam):
    # the patch average of sin(Omega X) is sin(Omega a)/(Omega a) sin(Omega X); averaging the
    # piecewise-linear interpolant of samples dx apart errs by at most (Omega dx)^2 / 12
    a, dx = 0.006, 5e-5
    x = np.arange(0.0, 0.6 + dx / 2, dx)
    xf, rf = contact_filter(x, np.sin(2 * math.pi * x / lam), a)
    expected = filter_attenuation(lam, a)[0] * np.sin(2 * math.pi * xf / lam)
    assert xf[0] >= a - 1e-15 and xf[-1] <= 0.6 - a + 1e-12
    assert np.max(np.abs(rf - expected)) < (2 * math.pi / lam * dx) ** 2 / 12
    assert filter_attenuation(lam, a)[0] == pytest.approx(
        math.sin(2 * math.pi * a / lam) / (2 * math.pi * a / lam), rel=1e-14)


def test_filter_matters():
    a = 0.006
    assert filter_matters(2 * a, a)  # the first zero of the transfer function
    assert not filter_matters(1.0, a)  # 1 m waves: |H| = 1 - 6e-4
    # threshold: -20 log10 |H| = 1 dB where |H| = 0.891
    lam = 2 * math.pi * a / 0.8306  # Omega a = 0.8306: sin(u)/u = 0.8913
    assert filter_matters(lam * 0.98, a) and not filter_matters(lam * 1.02, a)


# ---------------------------------------------------------------------------------------------
# on the scene
def test_scene_with_excitation_pickles_and_keys_the_sweep_store():
    import dataclasses
    import hashlib

    import trackwheel
    from trackwheel.study.sweep.store import canonical, inputs

    def key(scene):
        return hashlib.sha256(canonical(inputs(scene, 50.0, 140e6, {}))).hexdigest()

    base = trackwheel.Scene()
    wheel = dataclasses.replace(base.wheel, defects=(WheelFlat(0.05, rounded=True),))
    scenes = [dataclasses.replace(base, irregularity=Irregularity.random(
        spectra.fra(5), seed=seed, wavelengths=(2.0, 50.0)), wheel=wheel) for seed in (0, 0, 1)]
    back = pickle.loads(pickle.dumps(scenes[0]))
    assert back == scenes[0]
    assert key(back) == key(scenes[0]) == key(scenes[1])  # same recipe, same store record
    assert key(scenes[2]) != key(scenes[0])  # another seed is another case
    assert key(base) != key(scenes[0])
    assert len(repr(scenes[0].irregularity)) < 200  # the recipe, not the samples


def test_scene_rejects_wrong_excitation_types():
    import trackwheel

    with pytest.raises(TypeError, match="Scene.irregularity"):
        trackwheel.Scene(irregularity=0.001)
    with pytest.raises(TypeError, match="Wheel.defects"):
        trackwheel.Wheel(defects=(0.05,))
    with pytest.raises(ValueError, match="WheelFlat.length"):
        trackwheel.Wheel(radius=0.1, defects=(WheelFlat(0.25),))


# ---------------------------------------------------------------------------------------------
# plots
def test_profile_figure_shows_the_profile_and_its_spectrum():
    from matplotlib.figure import Figure

    from trackwheel import plots

    irr = Irregularity.random(spectra.fra(5), seed=4, wavelengths=(2.0, 40.0))
    fig = plots.irregularity_profile(irr, 0.0, 2000.0, 0.25)
    assert isinstance(fig, Figure)
    ax_r, ax_s = fig.axes
    assert "[m]" in ax_r.get_xlabel() and "[mm]" in ax_r.get_ylabel()
    assert "[rad/m]" in ax_s.get_xlabel() and "[m^2/(rad/m)]" in ax_s.get_ylabel()
    (profile,) = [ln for ln in ax_r.get_lines() if ln.get_gid() == "profile"]
    x = np.asarray(profile.get_xdata())
    assert np.array_equal(profile.get_ydata(), irr(x) * 1e3)
    (target,) = [ln for ln in ax_s.get_lines() if ln.get_gid() == "target"]
    w = np.asarray(target.get_xdata())
    assert w[0] >= 2 * math.pi / 40.0 * (1 - 1e-12) and w[-1] <= math.pi * (1 + 1e-12)
    assert np.array_equal(target.get_ydata(), spectra.fra(5)(w))


def test_filtered_table_is_the_sinc_scaled_profile():
    # a sine of 3 cm under the paper's patch (a ~ 6 mm): the table is H sin(...) everywhere on
    # the requested grid, H = sin(Omega a)/(Omega a); sampling error (Omega dx)^2 / 12
    import trackwheel

    a = contact_half_width(trackwheel.Scene())
    assert 1e-3 < a < 1e-2  # millimetres, as for a 0.1 m wheel under 47 kN
    lam, dx, amp = 0.03, 1e-4, 1e-4
    irr = Irregularity.sine(lam, amp)
    x0, h, r = irr.table(0.0, 0.5, dx, half_width=a)
    x = x0 + h * np.arange(r.size)
    assert x[-1] == pytest.approx(0.5, rel=1e-12)
    expected = filter_attenuation(lam, a)[0] * irr(x)
    assert np.max(np.abs(r - expected)) < amp * (2 * math.pi / lam * dx) ** 2 / 12


def test_shortest_wavelength():
    irr = (Irregularity.random(spectra.fra(5), seed=0, wavelengths=(3.0, 30.0))
           + Irregularity.sine(0.05, 1e-5) + Irregularity.dipped_joint(1e-3, 0.4, 1.0))
    assert irr.shortest_wavelength() == 0.05
    assert Irregularity.samples([0, 0.01, 0.03, 0.04], [0, 0, 0, 0]).shortest_wavelength() == \
        pytest.approx(0.02, rel=1e-12)
    assert Irregularity().shortest_wavelength() == math.inf


# ---------------------------------------------------------------------------------------------
# the extremes: a clean ValueError naming the parameter, or finite values
@pytest.mark.parametrize("call, match", [
    # NaN values (2.2e-308) and OverflowError in curvature (1e-300, 1e-200) before
    (lambda: Irregularity.sine(2.2e-308, 0.0), r"Irregularity\.sine\.wavelength = 2\.2e-308"),
    (lambda: Irregularity.sine(1e-300, 0.0), r"sine\.wavelength .*\[0\.0001, 10000\] m"),
    (lambda: Irregularity.sine(1e-200, 1e-3), r"sine\.wavelength"),
    (lambda: Irregularity.sine(1e5, 1e-3), r"sine\.wavelength"),
    (lambda: Irregularity.sine(0.01, 1e-3), r"slope of 0\.628 \(2 pi a / lambda\)"),
    # curvature -9.9e297 at 1e-150, OverflowError at 1e-300 before
    (lambda: Irregularity.dipped_joint(1e-3, 1e-300, 2.0), r"dipped_joint\.length = 1e-300"),
    (lambda: Irregularity.dipped_joint(1e-3, 1e-150, 2.0), r"dipped_joint\.length"),
    (lambda: Irregularity.dipped_joint(0.5, 2.0, 2.0), r"dipped_joint\.depth = 0\.5"),
    (lambda: Irregularity.dipped_joint(1e-3, 2e-2, 2.0), r"slope of 0\.157 \(pi d / l\)"),
    (lambda: Irregularity.samples([0, 1, 2, 3], [0, 0, 1.0, 0]), r"samples\.r = 1\.0"),
    (lambda: Irregularity.samples([0, 1e-9, 1, 2], [0, 0, 0, 0]), r"1e-09 m apart"),
    # NaN Delta rho near psi = 0 before
    (lambda: WheelFlat(5e-324, rounded=True), r"WheelFlat\.length = 5e-324"),
    (lambda: WheelFlat(0.05, rounded=True, depth=1.0), r"WheelFlat\.depth = 1\.0"),
    (lambda: Polygon(5, 1.0), r"Polygon\.amplitude = 1\.0"),
])
def test_extreme_profiles_and_defects_are_refused_by_name(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_a_run_names_the_sine_wavelength_not_an_internal_grid():
    """sine(1e-6, 1e-3) in a run was refused by the profile table's 'dx = 2.5e-08 m gives
    200000001 points' and, at 1e-300, a 300-digit count; now by the wavelength at
    construction, before any run."""
    with pytest.raises(ValueError, match=r"Irregularity\.sine\.wavelength = 1e-06"):
        Irregularity.sine(1e-6, 1e-3)


@pytest.mark.parametrize("part", [
    Irregularity.sine(1e-4, 1.5e-6), Irregularity.sine(1e4, 0.1),
    Irregularity.dipped_joint(3e-5, 1e-3, 0.0), Irregularity.dipped_joint(0.1, 1e3, 0.0),
])
def test_profiles_at_the_ends_of_their_ranges_are_finite(part):
    """At the ends of the ranges (and the slope limit) r, r' and r'' are finite, and bounded
    by the closed forms: |r| <= a, |r'| <= MAX_PROFILE_SLOPE, |r''| <= a (2 pi / lambda)^2 or
    d (pi / l)^2."""
    from trackwheel.base.limits import MAX_PROFILE_SLOPE

    p = part.parts[0]
    scale = p.length if hasattr(p, "length") else p.wavelength
    x = np.linspace(-scale, 2.0 * scale, 3001)
    for f in (part, part.slope, part.curvature):
        assert np.all(np.isfinite(f(x)))
    assert np.max(np.abs(part.slope(x))) <= MAX_PROFILE_SLOPE * (1 + 1e-12)


@pytest.mark.parametrize("flat", [WheelFlat(1e-4, rounded=True), WheelFlat(1e-4),
                                  WheelFlat(0.9, rounded=True), Polygon(10_000, 0.1)])
def test_defects_at_the_ends_of_their_ranges_are_finite(flat):
    """The shortest flat (0.1 mm), one near the diameter, the finest polygon: Delta rho and
    its derivatives finite around the wheel, psi = 0 included (a 5e-324 m rounded flat gave
    NaN there)."""
    psi = np.concatenate([np.linspace(-np.pi, np.pi, 20001), [0.0, 1e-12, -1e-12]])
    for f in (flat.delta_rho, flat.delta_rho_dpsi, flat.delta_rho_dpsi2):
        assert np.all(np.isfinite(f(psi, RHO0)))


def test_the_finest_sine_on_a_long_rail_gets_the_curvature_message():
    """A 0.1 mm sine (the shortest wavelength allowed) filtered over the patch on the 30 m
    ballasted rail: the filter's grid of micron steps tens of metres from 0 has spacings equal
    to a few eps |X| only, and was refused as 'x must be uniformly spaced'; it is taken, and
    the run is refused by what matters, the filtered profile curving more than the wheel."""
    import dataclasses as dc

    import trackwheel as tw

    s = tw.Scene.ballasted_track()
    sc = dc.replace(s, irregularity=Irregularity.sine(1e-4, 1e-6),
                    contact=dc.replace(s.contact, patch_filter=True))
    with pytest.raises(ValueError, match="Scene.irregularity curves upwards by"):
        tw.simulate(sc, 30.0, x_start=10.0, x_end=10.5, progress=False)
