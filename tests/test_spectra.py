"""Published spectra against hand arithmetic from the published constants (docs: Model § Irregularities)."""

import itertools
import math
import pickle

import numpy as np
import pytest
from scipy.integrate import quad

from trackwheel import spectra

# Round-off only: the code and the test evaluate the same closed forms in a different order.
RTOL = 1e-12


@pytest.mark.parametrize("omega", [0.05, 0.8245, 3.0])
def test_fra_class_5_against_published_formula(omega, validation):
    # Garg & Dukkipati: k A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)) [cm^2/(rad/m)], class 5
    # A_v = 0.2095 cm^2 rad/m, k = 0.25, Omega_c = 0.8245 rad/m; 1 cm^2 = 1e-4 m^2.
    cm2 = 0.25 * 0.2095 * 0.8245**2 / (omega**2 * (omega**2 + 0.8245**2))
    assert spectra.fra(5)(omega) == pytest.approx(cm2 * 1e-4, rel=RTOL)
    if omega == 0.8245:
        validation.record(
            "excitation.fra_class_5", level="excitation", kind="published",
            quantity="FRA class 5 PSD at Ω = Ω_c = 0.8245 rad/m",
            reference="Garg & Dukkipati (1984): k A_v Ω_c²/(Ω²(Ω² + Ω_c²)), the published "
                      "constants",
            measured=abs(spectra.fra(5)(omega) / (cm2 * 1e-4) - 1.0), tolerance=RTOL)


def test_fra_classes_order_and_band():
    # class 1 is the worst track, class 6 the best: S falls monotonically with the class
    values = [spectra.fra(c)(1.0) for c in range(1, 7)]
    assert all(a > b for a, b in itertools.pairwise(values))
    lo, hi = spectra.fra(3).band  # 1.524-304.8 m (5-1000 ft)
    assert lo == pytest.approx(2 * math.pi / 304.8, rel=RTOL)
    assert hi == pytest.approx(2 * math.pi / 1.524, rel=RTOL)


@pytest.mark.parametrize("level, av", [("low", 4.032e-7), ("high", 1.080e-6)])
def test_german_against_published_formula(level, av, validation):
    gaps = []
    for omega in (0.01, 0.5, 5.0):
        expected = av * 0.8246**2 / ((omega**2 + 0.0206**2) * (omega**2 + 0.8246**2))
        assert spectra.german(level)(omega) == pytest.approx(expected, rel=RTOL)
        gaps.append(abs(spectra.german(level)(omega) / expected - 1.0))
    if level == "high":
        validation.record(
            "excitation.german_high", level="excitation", kind="published",
            quantity="German high-speed spectrum, high disturbance, at 0.01, 0.5, 5 rad/m",
            reference="A_v Ω_c²/((Ω² + Ω_r²)(Ω² + Ω_c²)), the published constants",
            measured=max(gaps), tolerance=RTOL)


@pytest.mark.parametrize("f, a, n", [(0.01, 1.0544e-5, 3.3891), (0.03, 3.5588e-3, 1.9271),
                                     (0.1, 1.9784e-2, 1.3643), (0.3, 3.9488e-4, 3.4516)])
def test_china_pieces_against_published_formula(f, a, n):
    # S(f) = A / f^n [mm^2/(1/m)]; per rad/m: divide by 2 pi; mm^2 -> m^2: 1e-6
    omega = 2 * math.pi * f
    assert spectra.china_hsr()(omega) == pytest.approx(a / f**n * 1e-6 / (2 * math.pi),
                                                       rel=RTOL)


def test_china_variance_over_f_equals_variance_over_omega():
    # the conversion keeps the variance: integral S(f) df over 0.05..0.1 1/m (one piece,
    # closed form) equals the integral of S(Omega) over 2 pi x that band
    a, n = 1.9784e-2, 1.3643
    exact_mm2 = a / (1 - n) * (0.1 ** (1 - n) - 0.05 ** (1 - n))
    s = spectra.china_hsr()
    got, _ = quad(lambda w: s(w), 2 * math.pi * 0.05, 2 * math.pi * 0.1, epsrel=1e-12)
    assert got == pytest.approx(exact_mm2 * 1e-6, rel=1e-9)


def test_china_pieces_meet_at_the_splits():
    # the published fit is continuous to its printed digits (0.4 % at f = 0.0187 1/m)
    s = spectra.china_hsr()
    for f in (0.0187, 0.0474, 0.1533):
        w = 2 * math.pi * f
        assert s(w * (1 - 1e-9)) == pytest.approx(s(w * (1 + 1e-9)), rel=0.01)


def test_iso3095_band_variances_are_the_levels():
    # band level L [dB re 1 um] is a variance 1e-12 10^(L/10) m^2 in that band
    s = spectra.iso3095()
    edges = s.edges()
    assert len(edges) == 23
    levels = dict(zip(s.wavelengths, s.levels_db))
    assert levels[0.40] == 17.1 and levels[0.00315] == -11.0
    for i, (lam, level) in enumerate(zip(s.wavelengths, s.levels_db)):
        mid = math.sqrt(edges[i] * edges[i + 1])
        assert edges[i] < 2 * math.pi / lam < edges[i + 1]
        variance = s(mid) * (edges[i + 1] - edges[i])
        assert variance == pytest.approx(1e-12 * 10 ** (level / 10), rel=RTOL)
    # outer edges lie half a base-10 one-third octave (x 10^(1/20)) beyond the outer centres
    assert edges[0] == pytest.approx(2 * math.pi / 0.40 / 10**0.05, rel=RTOL)
    assert s(edges[0] * 0.99) == 0.0 and s(edges[-1] * 1.01) == 0.0


def test_third_octave_any_order_and_total_variance():
    s = spectra.third_octave([0.01, 0.04, 0.02], [0.0, 10.0, 3.0])
    assert s.wavelengths == (0.04, 0.02, 0.01)
    total, _ = quad(lambda w: s(w), *s.band, points=list(s.edges()), limit=200)
    assert total == pytest.approx(1e-12 * (1 + 10 + 10**0.3), rel=1e-9)


def test_spectra_pickle_and_hash():
    for s in (spectra.fra(2), spectra.german("low"), spectra.china_hsr(), spectra.iso3095()):
        back = pickle.loads(pickle.dumps(s))
        assert back == s and hash(back) == hash(s)
        assert np.array_equal(back(np.array([1.0, 10.0])), s(np.array([1.0, 10.0])))


@pytest.mark.parametrize("call, name", [
    (lambda: spectra.fra(7), "track_class"),
    (lambda: spectra.fra(0), "track_class"),
    (lambda: spectra.german("medium"), "level"),
    (lambda: spectra.third_octave([0.1, 0.2], [1.0]), "levels_db"),
    (lambda: spectra.third_octave([0.1, -0.2], [1.0, 2.0]), "wavelengths"),
    (lambda: spectra.fra(3)(-1.0), "Omega"),
])
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(ValueError, match=name):
        call()
