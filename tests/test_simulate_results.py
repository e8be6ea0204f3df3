"""What a run returns: the typed RunSettings, the compact reprs of the result objects (a few
lines with the key numbers, never the arrays), and the derived defaults shared by every level."""

from __future__ import annotations

import dataclasses as dc
import importlib
import warnings

import numpy as np
import pytest

import trackwheel as tw

SCENE = tw.Scene.kato2005()
#: most characters and lines a repr may take: a few lines, like pandas/xarray summaries (the
#: former dataclass reprs printed whole arrays: thousands of characters)
MAX_CHARS, MAX_LINES = 400, 4


@pytest.fixture(scope="module")
def run():
    return tw.simulate(SCENE, tw.kmh(300), n_elements=20, dt=1e-5, x_end=1.0)


def _compact(obj) -> str:
    text = repr(obj)
    assert len(text) <= MAX_CHARS and len(text.splitlines()) <= MAX_LINES, text
    assert "array" not in text and "[" not in text.split(">")[0]
    return text


def test_run_settings_are_typed_and_dict_readable(run):
    s = run.settings
    assert isinstance(s, tw.RunSettings)
    assert (s.integrator, s.dt, s.n_elements, s.fidelity) == ("generalized_alpha", 1e-5, 20,
                                                               "full")
    assert s.speed == tw.kmh(300) and s.x_start == 0.25
    # 0.75 m at 83.3 m/s is 9e-3 s, 900 steps of 1e-5 s; x_end follows from them
    assert s.t_end == pytest.approx(0.009, rel=1e-12) and run.steps == 900
    assert s.x_end == pytest.approx(1.0, rel=1e-12)
    assert s["dt"] == s.dt and s.get("n_modes", 0) is None and s.get("bogus", 7) == 7
    with pytest.raises(KeyError):
        s["bogus"]
    with pytest.raises(dc.FrozenInstanceError):
        s.dt = 1.0
    assert s.asdict()["n_elements"] == 20 and set(s.keys()) == set(s.asdict())


def test_result_repr(run):
    text = _compact(run)
    assert f"{run.t.size} samples" in text and f"{run.steps} steps" in text
    assert "generalized_alpha, dt = 1e-05 s, 20 elements" in text
    assert f"{run.normal_force.min():.4g} .. {run.normal_force.max():.4g} N" in text


def test_analysis_repr(run):
    a = tw.analyse(run)
    text = _compact(a)
    assert f"max|d| = {a.amplitude:.4g} m" in text
    assert f"{a.main_frequency:.1f} Hz" in text


def test_eigen_repr():
    e = tw.eigen(SCENE, np.linspace(0.0, 5.0, 11), n_modes=6)
    text = _compact(e)
    assert "6 vertical modes at 11 wheel positions" in text and "(+2 more)" in text
    f = e.frequencies
    assert f"{f[:, 0].min():.1f}-{f[:, 0].max():.1f}" in text


def test_static_and_quasi_static_repr():
    st = tw.static(SCENE, 2.5)
    text = _compact(st)
    assert f"y_contact = {st.y_contact:.6g} m" in text and f"N = {st.normal_force:.6g} N" in text
    qs = tw.quasi_static(SCENE, np.linspace(0.5, 4.5, 9))
    text = _compact(qs)
    assert "9 wheel positions" in text and f"{qs.y_contact.min():.6g}" in text


def test_convergence_repr():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tw.ConvergenceWarning)
        c = tw.converged(SCENE, tw.kmh(300), tol=0.2, dt=1e-5, n_elements=20, x_end=0.75,
                         max_refinements=0)
    text = _compact(c)
    assert f"dt = {c.dt:.3g} s, {c.n_elements} elements" in text
    assert f"after {len(c.history)} runs" in text


def test_every_level_uses_the_derived_settings():
    """issue 16, item 1: no level silently changes the mesh or the step."""
    d = tw.default_settings(SCENE)
    for level in ("full", "ancf/sprung", "linear/sprung", "linear/moving_force"):
        r = tw.simulate(SCENE, tw.kmh(300), fidelity=level, x_end=0.5)
        assert (r.settings.n_elements, r.settings.dt) == (d["n_elements"], d["dt"]), level


def test_fewer_elements_than_bays_warn():
    """10 bays of 0.5 m on the 5 m rail: 9 elements leave a bay without a node."""
    with pytest.warns(tw.MeshWarning, match="n_elements = 9 cannot resolve the 10 support bays"):
        tw.simulate(SCENE, tw.kmh(100), n_elements=9, dt=1e-5, x_end=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tw.simulate(SCENE, tw.kmh(100), n_elements=10, dt=1e-5, x_end=0.5)


def test_the_output_size_check_counts_every_recorded_array():
    """simulate refuses outputs above MAX_OUTPUT_BYTES before running, counting _N_FIELDS
    float64 arrays per sample: exactly the arrays a run with energy=True returns."""
    sim = importlib.import_module("trackwheel.simulate")  # (tw.simulate is the function)
    r = tw.simulate(SCENE, tw.kmh(300), n_elements=20, dt=1e-5, x_end=0.5, energy=True)
    arrays = [f.name for f in dc.fields(tw.Result)
              if isinstance(getattr(r, f.name), np.ndarray)]
    assert len(arrays) == sim._N_FIELDS
    assert all(getattr(r, name).shape == r.t.shape for name in arrays)
