"""The rail profile streamed into the kernel (docs: Model § The travelling window).

Over hundreds of metres the kernel draws the profile's spline table chunk by chunk as the
vehicle advances and drops the chunks that lie more than a retention distance behind the
leading wheel. Checks: a streamed run is bit-identical to one on the whole table (linear and
full paths, and a second run on the same cached rail model, which reads the stream again from
the start); the most intervals held at once is a count fixed by the chunk length and the
retention, whatever the distance; a request behind the kept range of a one-pass stream raises;
a profile too sharp for the wheel far down the track still raises the curvature ValueError.
"""

from __future__ import annotations

import dataclasses as dc
import math

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import _core, spectra
from trackwheel.run import kernel as _kernel
from trackwheel.run import profile
from trackwheel.run.simulate import execute, plan_run

V = tw.kmh(300)


@pytest.fixture
def fresh_models():
    """The rail models are cached per scene: the runs here build their own, and leave none."""
    _kernel.rail_model.cache_clear()
    yield
    _kernel.rail_model.cache_clear()


def _scene():
    # wavelengths 3-50 m: the wheel keeps contact at 300 km/h (as in tests/test_window.py)
    irr = tw.Irregularity.random(spectra.fra(5), seed=3, wavelengths=(3.0, 50.0))
    return dc.replace(tw.Scene.ballasted_track(window=tw.Window(20, 20)), irregularity=irr)


def _run(scene, distance, **kw):
    """A window run and the kernel profile it read (the cached rail model's, whose stream
    state the run advanced)."""
    plan = plan_run(scene, V, distance=distance, x_start=0.3, **kw)
    return execute(plan, progress=False), plan.model.profile


def _assert_same_run(a, b):
    for f in ("normal_force", "y_wheel", "x_wheel", "y_contact"):
        np.testing.assert_array_equal(getattr(a, f), getattr(b, f))


def test_streamed_linear_run_is_bit_identical_to_the_whole_table(fresh_models, monkeypatch):
    """500 m of FRA class 5 on the linear path: the streamed table (525 m, 9 chunks of 65 536
    intervals, 200 m kept) holds the same coefficients as the whole one, so the run is the
    same bit for bit; the stream held at most 5 chunks (see the next test)."""
    scene = _scene()
    kw = dict(fidelity="linear/hertz", dt=1e-4, output_every=10)
    streamed, table = _run(scene, 500.0, **kw)
    assert table.streamed and table.n_intervals > 7 * profile.SPLINE_CHUNK
    assert table.peak_loaded_intervals == 5 * profile.SPLINE_CHUNK
    _kernel.rail_model.cache_clear()
    monkeypatch.setattr(profile, "STREAM_MIN_CHUNKS", 10**6)
    eager, whole = _run(scene, 500.0, **kw)
    assert not whole.streamed and whole.n_intervals == table.n_intervals
    _assert_same_run(streamed, eager)


def test_streamed_full_run_and_its_rerun_are_bit_identical_to_the_whole_table(fresh_models,
                                                                              monkeypatch):
    """The full path reads the profile in the window's rail coordinate: 12 m of FRA class 5
    with chunks shrunk to 2048 intervals (2 m) and 4 m kept, so the run crosses 6 chunks and
    drops 3; the same as on the whole table (same chunks), bit for bit.
    A second run on the same (cached) rail model starts behind the kept range: the stream
    re-opens once and the run repeats bit for bit."""
    monkeypatch.setattr(profile, "SPLINE_CHUNK", 2048)
    monkeypatch.setattr(profile, "STREAM_RETENTION", 4.0)
    scene = _scene()
    kw = dict(fidelity="full", output_every=10)
    streamed, table = _run(scene, 12.0, **kw)
    assert table.streamed and table.n_intervals > 17 * 2048
    # the chunks ending within 4 m behind the wheel where it loads the next, and that one: 3
    assert table.peak_loaded_intervals == (math.floor(4.0 / (2048 * 1e-3)) + 2) * 2048
    again = tw.simulate(scene, V, distance=12.0, x_start=0.3, progress=False, **kw)
    assert table.rewinds == 1
    _assert_same_run(streamed, again)
    _kernel.rail_model.cache_clear()
    monkeypatch.setattr(profile, "STREAM_MIN_CHUNKS", 10**6)
    eager, whole = _run(scene, 12.0, **kw)
    assert not whole.streamed
    _assert_same_run(streamed, eager)


@pytest.mark.parametrize("distance", [600.0, 1000.0])
def test_most_intervals_held_does_not_grow_with_the_distance(fresh_models, distance):
    """Chunks of L = 65.536 m (65 536 intervals of 1 mm), kept while they end less than R =
    200 m behind the leading wheel: when the wheel reaches a chunk's start the stream holds the
    floor(R / L) + 1 = 4 chunks ending within R behind it and loads the next, 5 chunks
    (327 680 intervals, 10 MiB) whether the run is 600 m or 1 km (their tables 625 and
    1025 m long, 10 and 16 chunks)."""
    _, table = _run(_scene(), distance, fidelity="linear/hertz", dt=2e-4, output_every=100)
    chunk = profile.SPLINE_CHUNK
    assert table.n_intervals > distance / 1e-3
    assert table.peak_loaded_intervals == (math.floor(200.0 / (chunk * 1e-3)) + 2) * chunk
    assert table.loaded_intervals <= table.peak_loaded_intervals


def _chunks(irr, end):
    return (c for _, c, _, _ in profile.spline_chunks(irr, 0.0, end, 1e-3, chunk=1000))


def test_request_behind_the_kept_range():
    """A one-pass stream (an iterator) raises behind its kept range, never a wrong value; a
    re-openable one (a callable) reads forwards again and gives the whole table's value."""
    irr = tw.Irregularity.sine(2.0, 1e-4)
    x0, h, n = profile.spline_grid(irr, 0.0, 10.0, 1e-3)
    whole = _core.Profile(x0, h, n - 1, _chunks(irr, 10.0))
    once = _core.Profile(x0, h, n - 1, _chunks(irr, 10.0), 2.5)
    again = _core.Profile(x0, h, n - 1, lambda: _chunks(irr, 10.0), 2.5)
    xs = np.linspace(0.0, 9.9, 991)
    for p in (once, again):
        assert [p(x) for x in xs] == [whole(x) for x in xs]
        # 1 m chunks, 2.5 m kept behind X = 9.9: those from X = 7 m on (4 where 9 m loads)
        assert p.loaded_intervals == 3000 and p.peak_loaded_intervals == 4000
    assert once(7.05) == whole(7.05)  # inside the kept range
    with pytest.raises(RuntimeError, match=r"X = 6\.9.* behind the streamed profile's kept "
                                           r"range \(from X = 7\.0"):
        once(6.9)
    assert again(1.234) == whole(1.234) and again.rewinds == 1
    with pytest.raises(ValueError, match="retention"):
        _core.Profile(x0, h, n - 1, _chunks(irr, 10.0), 0.0)
    with pytest.raises(TypeError, match="chunks must be an iterable or a callable"):
        _core.Profile(x0, h, n - 1, 3.0, 2.5)


def test_a_failed_reopening_is_retried_not_read_from_the_old_source():
    """An exception while re-opening surfaces; the next request opens afresh and gives the
    whole table's value (the old source, past the kept range, is never read on)."""
    irr = tw.Irregularity.sine(2.0, 1e-4)
    x0, h, n = profile.spline_grid(irr, 0.0, 10.0, 1e-3)
    whole = _core.Profile(x0, h, n - 1, _chunks(irr, 10.0))
    opened = []

    def opener():
        opened.append(1)
        if len(opened) == 2:
            raise ValueError("source unavailable")
        return _chunks(irr, 10.0)

    p = _core.Profile(x0, h, n - 1, opener, 2.5)
    assert p(6.5) == whole(6.5)  # chunks 0-2 dropped, the source at chunk 7
    with pytest.raises(ValueError, match="source unavailable"):
        p(0.5)
    assert p(0.5) == whole(0.5) and len(opened) == 3


def test_stream_shorter_than_its_intervals_raises():
    irr = tw.Irregularity.sine(2.0, 1e-4)
    x0, h, n = profile.spline_grid(irr, 0.0, 10.0, 1e-3)
    p = _core.Profile(x0, h, n, _chunks(irr, 10.0), 2.5)
    with pytest.raises(RuntimeError, match="profile stream ended after 10000 intervals"):
        p(10.0)


def test_too_sharp_a_profile_far_down_the_track_is_refused(fresh_models):
    """A Kabo dipped joint's cusp (r'' -> infinity, see tests/test_irregularity_response.py)
    at X = 450 m, in the 7th chunk of a streamed table: the stream checks each chunk as it
    draws it, and the run stops there with the curvature ValueError from Python."""
    scene = dc.replace(tw.Scene.ballasted_track(window=tw.Window(20, 20)),
                       irregularity=tw.Irregularity.dipped_joint(1e-3, 0.4, 450.0))
    with pytest.raises(ValueError, match=r"curves upwards .* X = 450\.2 m.*r'' < 1/rho0"):
        tw.simulate(scene, V, distance=460.0, x_start=0.3, progress=False,
                    fidelity="linear/hertz", dt=2e-4, output_every=100)


def test_threads_on_one_rail_model_read_their_own_passes(fresh_models, monkeypatch):
    """Runs in two threads on the same (cached) rail model, as a thread-pool sweep makes them:
    each thread reads the stream on its own pass, so neither drops the other's chunks or makes
    it read again from the start (no re-opening), and both equal the serial run bit for bit.
    Chunks of 2 m, 4 m kept, 30 m run on the linear path."""
    import threading

    monkeypatch.setattr(profile, "SPLINE_CHUNK", 2048)
    monkeypatch.setattr(profile, "STREAM_RETENTION", 4.0)
    scene = _scene()
    kw = dict(fidelity="linear/hertz", dt=1e-4, output_every=10)
    serial, table = _run(scene, 30.0, **kw)
    runs = [None, None]

    def run(k):
        runs[k] = tw.simulate(scene, V, distance=30.0, x_start=0.3, progress=False, **kw)

    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert table.rewinds == 0
    for r in runs:
        _assert_same_run(serial, r)
