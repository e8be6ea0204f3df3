"""Sweeps over speed and support stiffness: equality with single runs, executors, the store
(resume, corruption), failed cases, interruption (issue 5 part 2, issue 8).

Cases are tiny (0.25 -> 0.5 m, dt = 2e-5 s: 225-450 steps each) so that the file runs in seconds;
what is checked does not depend on the length of a run.
"""

from __future__ import annotations

import concurrent.futures as cf
import dataclasses as dc
import hashlib
import importlib
import json
import math
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import distributed
import numpy as np
import pandas as pd
import psutil
import pytest

import trackwheel as tw
from trackwheel.study.columns import label

sweep_mod = importlib.import_module("trackwheel.sweep")  # (tw.sweep is the function)
cases = importlib.import_module("trackwheel.study.sweep.cases")  # where the sweep runs a case

SCENE = tw.Scene.kato2005()
KW = {"x_start": 0.25, "x_end": 0.5, "dt": 2e-5}
SPEEDS = [tw.kmh(200), tw.kmh(300)]
STIFF = [70e6, 140e6]
#: the analysis outputs compared, by name (the table's column of each: its label)
OUTPUTS = ["amplitude", "main_frequency", "frequency_resolution", "min_contact_force",
           "max_contact_force"]
COLUMN = {name: label(name) for name in OUTPUTS}


def no_wall(df):
    return df.drop(columns=["wall_time_s"])


@pytest.fixture
def counted(monkeypatch):
    """Replace the case function by a wrapper recording (speed, stiffness) of each computed case
    (in-process execution only: max_workers=1 or a thread pool)."""
    calls = []
    real = cases.run_case

    def run(scene, speed, kwargs):
        calls.append((speed, scene.supports.stiffness))
        return real(scene, speed, kwargs)

    monkeypatch.setattr(cases, "run_case", run)
    return calls


@pytest.fixture(scope="module")
def reference():
    """The 2 x 2 sweep run serially, in this process."""
    return tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, progress=False, **KW)


# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("max_workers", [1, 2])
def test_rows_equal_single_runs_bit_for_bit(max_workers, reference):
    """Each row is simulate(scene with k_s replaced, v, **kw) + analyse, bit for bit, in the
    Cartesian product's order (speed major), whether run serially or on a 2-process pool."""
    df = reference if max_workers == 1 else tw.sweep(SCENE, SPEEDS, STIFF, max_workers=2,
                                                      progress=False, **KW)
    assert len(df) == 4 and list(df.columns) == list(sweep_mod.COLUMNS)
    for row, (v, k) in zip(df.itertuples(), [(v, k) for v in SPEEDS for k in STIFF]):
        scene = dc.replace(SCENE, supports=dc.replace(SCENE.supports, stiffness=k))
        r = tw.simulate(scene, v, **KW)
        a = tw.analyse(r)
        assert (row.speed_m_s, row.support_stiffness_N_m, row.speed_kmh) == (v, k, v * 3.6)
        for name in OUTPUTS:
            assert getattr(row, COLUMN[name]) == getattr(a, name), name
        assert row.lost_contact == a.lost_contact and row.error == ""
        assert row.steps == r.steps
        for name in ("integrator", "dt", "n_elements", "x_start", "t_end", "output_every",
                     "rho_inf", "rolling", "start"):
            assert getattr(row, label(name)) == getattr(r.settings, name), name
        assert row.x_end_m == pytest.approx(0.5, abs=1e-12)
        assert row.version == tw.__version__ and 0.0 < row.wall_time_s < 60.0
    assert np.all(df.amplitude_m > 0) and np.all(df.main_frequency_hz > 0)


#: distributed's in-process cluster can leave a socket to the garbage collector at teardown (a
#: ResourceWarning through pytest's unraisable-exception hook): third-party noise, not a result
DASK_NOISE = ("ignore::ResourceWarning", "ignore::pytest.PytestUnraisableExceptionWarning")


@pytest.mark.filterwarnings(*DASK_NOISE)
def test_same_table_whatever_the_executor(reference):
    """1 worker, 2 processes, a thread pool and a local Dask cluster give the same table (every
    case is a deterministic, independent run; only wall_time differs)."""
    two = tw.sweep(SCENE, SPEEDS, STIFF, max_workers=2, progress=False, **KW)
    pd.testing.assert_frame_equal(no_wall(two), no_wall(reference), check_exact=True)
    with cf.ThreadPoolExecutor(2) as ex:
        threads = tw.sweep(SCENE, SPEEDS, STIFF, executor=ex, progress=False, **KW)
    pd.testing.assert_frame_equal(no_wall(threads), no_wall(reference), check_exact=True)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        dask = tw.sweep(SCENE, SPEEDS, STIFF, executor=client.get_executor(), progress=False,
                        **KW)
    pd.testing.assert_frame_equal(no_wall(dask), no_wall(reference), check_exact=True)


def test_scalars_and_default_stiffness():
    """A scalar speed and no stiffness list: one case with the scene's support stiffness."""
    df = tw.sweep(SCENE, tw.kmh(300), max_workers=1, progress=False, **KW)
    assert len(df) == 1 and df.support_stiffness_N_m[0] == SCENE.supports.stiffness


# --------------------------------------------------------------------------------------------
# store
def records(store):
    return sorted(Path(store).glob("case-*.json"))


def test_store_round_trip_and_skip(tmp_path, reference, counted):
    """Every case is written to the store; load_sweep gives the same table; a re-run computes
    nothing and returns the stored rows exactly (wall_time included)."""
    store = tmp_path / "s"
    first = tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)
    assert len(counted) == 4 and len(records(store)) == 4
    pd.testing.assert_frame_equal(no_wall(first), no_wall(reference), check_exact=True)
    loaded = tw.load_sweep(store)
    pd.testing.assert_frame_equal(loaded, first, check_exact=True)
    again = tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)
    assert len(counted) == 4 and again.attrs == {"computed": 0, "from_store": 4}
    pd.testing.assert_frame_equal(again, first, check_exact=True)
    # other settings are other cases: nothing is reused
    tw.sweep(SCENE, SPEEDS[:1], STIFF[:1], max_workers=1, store=store, progress=False,
             **dict(KW, rho_inf=0.5))
    assert len(counted) == 5 and len(records(store)) == 5


def test_resume_after_a_worker_raises(tmp_path, monkeypatch, counted):
    """Serial sweep of 6 cases whose 3rd raises an unexpected error: the error propagates, the
    2 finished cases are in the store; the re-run computes exactly the 4 others."""
    store = tmp_path / "s"
    speeds = [tw.kmh(150), tw.kmh(200), tw.kmh(300)]
    real = cases.run_case

    def failing(scene, speed, kwargs):  # real counts the cases it runs
        if len(counted) == 2:
            raise RuntimeError("worker lost")
        return real(scene, speed, kwargs)

    monkeypatch.setattr(cases, "run_case", failing)
    with pytest.raises(RuntimeError, match="worker lost"):
        tw.sweep(SCENE, speeds, STIFF, max_workers=1, store=store, progress=False, **KW)
    assert len(records(store)) == 2
    done = set(counted)
    calls = []

    def count(scene, speed, kwargs):
        calls.append((speed, scene.supports.stiffness))
        return real(scene, speed, kwargs)

    monkeypatch.setattr(cases, "run_case", count)
    df = tw.sweep(SCENE, speeds, STIFF, max_workers=1, store=store, progress=False, **KW)
    assert df.attrs == {"computed": 4, "from_store": 2}
    assert set(calls) == {(v, k) for v in speeds for k in STIFF} - done
    fresh = tw.sweep(SCENE, speeds, STIFF, max_workers=1, progress=False, **KW)
    pd.testing.assert_frame_equal(no_wall(df), no_wall(fresh), check_exact=True)


def test_parallel_sweep_keeps_every_finished_case_when_one_raises(tmp_path, monkeypatch):
    """On a 2-thread executor one case raises: every other case that finished (including the
    ones still running at the time) is stored; the re-run recomputes only the missing ones."""
    store = tmp_path / "s"
    speeds = [tw.kmh(150), tw.kmh(200), tw.kmh(250), tw.kmh(300)]
    real = cases.run_case
    bad = (speeds[1], STIFF[0])

    def failing(scene, speed, kwargs):
        if (speed, scene.supports.stiffness) == bad:
            raise RuntimeError("worker lost")
        return real(scene, speed, kwargs)

    monkeypatch.setattr(cases, "run_case", failing)
    with cf.ThreadPoolExecutor(2) as ex, pytest.raises(RuntimeError, match="worker lost"):
        tw.sweep(SCENE, speeds, STIFF, executor=ex, store=store, progress=False, **KW)
    stored = {(r.speed_m_s, r.support_stiffness_N_m) for r in tw.load_sweep(store).itertuples()}
    assert bad not in stored and len(stored) >= 1
    calls = []

    def count(scene, speed, kwargs):
        calls.append((speed, scene.supports.stiffness))
        return real(scene, speed, kwargs)

    monkeypatch.setattr(cases, "run_case", count)
    with cf.ThreadPoolExecutor(2) as ex:
        df = tw.sweep(SCENE, speeds, STIFF, executor=ex, store=store, progress=False, **KW)
    assert set(calls) == {(v, k) for v in speeds for k in STIFF} - stored
    assert df.attrs["from_store"] == len(stored) and (df.error == "").all()


def test_corrupt_records_are_detected_and_recomputed(tmp_path, counted):
    """Four kinds of damage to 4 of 6 records -- truncated (a partial write), a value edited
    without its checksum, another case's record under this name, not JSON -- are each reported
    and recomputed; the 2 sound records are used; a leftover temporary file is ignored. The
    final table equals the original one."""
    store = tmp_path / "s"
    speeds = [tw.kmh(150), tw.kmh(200), tw.kmh(300)]
    first = tw.sweep(SCENE, speeds, STIFF, max_workers=1, store=store, progress=False, **KW)
    paths = records(store)
    assert len(paths) == 6 and len(counted) == 6
    text = paths[0].read_text()
    paths[0].write_text(text[: len(text) // 2])
    rec = json.loads(paths[1].read_text())
    rec["row"]["amplitude_m"] *= 1.0 + 1e-12
    paths[1].write_text(json.dumps(rec))
    paths[2].write_bytes(paths[3].read_bytes())
    paths[4].write_bytes(b"\x00\xff not json")
    (store / ".tmp-leftover.json").write_text("{")
    with pytest.warns(RuntimeWarning) as warned:
        df = tw.sweep(SCENE, speeds, STIFF, max_workers=1, store=store, progress=False, **KW)
    reasons = " ".join(str(w.message) for w in warned)
    assert len(warned) == 4
    for reason in ("unreadable", "checksum mismatch", "other inputs"):
        assert reason in reasons
    assert df.attrs == {"computed": 4, "from_store": 2} and len(counted) == 10
    pd.testing.assert_frame_equal(no_wall(df), no_wall(first), check_exact=True)
    pd.testing.assert_frame_equal(no_wall(tw.load_sweep(store)), no_wall(first),
                                  check_exact=True)


def test_a_store_written_before_the_columns_carried_units_is_read(tmp_path, counted):
    """Format-3 records (the same rows, columns named without their units: ``amplitude``,
    ``speed``) are read with today's names: a re-run computes nothing and gives the same table,
    and load_sweep reads them; a record of format 2 is recomputed with a warning naming it."""
    from trackwheel.study.sweep import store as records_module

    store = tmp_path / "s"
    first = tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)
    old = {new: old for old, new in records_module.RENAMED.items()}
    for p in records(store):
        rec = json.loads(p.read_text())
        rec.pop("checksum")
        rec["format_version"] = 3
        rec["row"] = {old.get(k, k): val for k, val in rec["row"].items()}
        assert "amplitude" in rec["row"] and "speed" in rec["row"]
        rec["checksum"] = hashlib.sha256(records_module.canonical(rec)).hexdigest()
        p.write_text(json.dumps(rec))
    n_runs = len(counted)
    again = tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)
    assert again.attrs["computed"] == 0 and len(counted) == n_runs
    pd.testing.assert_frame_equal(again, first, check_exact=True)
    pd.testing.assert_frame_equal(tw.load_sweep(store), first.sort_values(
        ["speed_m_s", "support_stiffness_N_m"], ignore_index=True), check_exact=True)
    p = records(store)[0]
    rec = json.loads(p.read_text())
    rec["format_version"] = 2
    p.write_text(json.dumps(rec))
    with pytest.warns(RuntimeWarning, match="format version 2"):
        tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)


def test_a_store_written_before_the_support_force_columns_is_read(tmp_path, counted):
    """Format-4 records (no support-force columns) resume without a run, NaN in those columns
    and every other column as computed."""
    from trackwheel.study.sweep import store as records_module

    store = tmp_path / "s"
    first = tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)
    added = list(records_module.ADDED_IN_5)
    assert first[added].notna().all().all()  # computed today (single springs: the spring's)
    for p in records(store):
        rec = json.loads(p.read_text())
        rec.pop("checksum")
        rec["format_version"] = 4
        rec["row"] = {k: val for k, val in rec["row"].items() if k not in added}
        rec["checksum"] = hashlib.sha256(records_module.canonical(rec)).hexdigest()
        p.write_text(json.dumps(rec))
    n_runs = len(counted)
    again = tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)
    assert again.attrs["computed"] == 0 and len(counted) == n_runs
    assert again[added].isna().all().all()
    pd.testing.assert_frame_equal(again.drop(columns=added), first.drop(columns=added),
                                  check_exact=True)


def test_the_sweep_documents_every_column():
    """The column table is the sweep's docs: every column with its unit in the docstring."""
    for c in sweep_mod.COLUMNS:
        assert f"``{c}``" in tw.sweep.__doc__, c


def test_load_sweep_leaves_out_corrupt_records(tmp_path):
    store = tmp_path / "s"
    tw.sweep(SCENE, SPEEDS, STIFF, max_workers=1, store=store, progress=False, **KW)
    p = records(store)[0]
    p.write_text(p.read_text().replace('"error": ""', '"error": "x"'))
    with pytest.warns(RuntimeWarning, match="checksum mismatch"):
        df = tw.load_sweep(store)
    assert len(df) == 3
    with pytest.raises(ValueError, match="path"):
        tw.load_sweep(tmp_path / "missing")


# --------------------------------------------------------------------------------------------
def test_diverging_and_rejected_cases_are_recorded(tmp_path):
    """Explicit RK4 at dt = 5e-6 s is stable on 140 MN/m supports (limit 1.03e-5 s) and diverges
    on 1e13 N/m ones (their own frequency pushes the limit to 2.4e-6 s); 400 m/s is above
    simulate's speed range (ValueError). Those rows carry the message and NaN outputs, the
    others complete; the failures are stored and not retried unless retry_errors=True.
    simulate's StabilityWarning for the stiff case is issued as usual (here, in this process)."""
    store = tmp_path / "s"
    kw = dict(KW, integrator="explicit", dt=5e-6)
    args = (SCENE, [tw.kmh(300), 400.0], [140e6, 1e13])
    with pytest.warns(tw.StabilityWarning, match="above the predicted stability limit"), \
            pytest.warns(tw.PlausibilityWarning, match=r"speed = 400 m/s is 1440 km/h"), \
            pytest.warns(tw.FailedCasesWarning, match="3 of 4 cases"):
        df = tw.sweep(*args, max_workers=1, store=store, progress=False, **kw)
    ok = df.error == ""
    assert ok.tolist() == [True, False, False, False]
    assert df.error[1].startswith("DivergenceError:") and "stability limit" in df.error[1]
    assert all(e.startswith("ValueError: speed = 400.0") for e in df.error[2:])
    assert np.isfinite(df.amplitude_m[0]) and df.lost_contact[0] in (False,)  # not None
    assert df.loc[~ok, list(COLUMN.values())].isna().all().all()
    assert df.lost_contact[~ok].isna().all()
    assert (df.integrator == "explicit").all() and (df.dt_s == 5e-6).all()
    with pytest.warns(tw.PlausibilityWarning), pytest.warns(tw.FailedCasesWarning):
        again = tw.sweep(*args, max_workers=1, store=store, progress=False, **kw)
    assert again.attrs == {"computed": 0, "from_store": 4}
    pd.testing.assert_frame_equal(again, df, check_exact=True)
    with pytest.warns(tw.StabilityWarning), pytest.warns(tw.PlausibilityWarning), \
            pytest.warns(tw.FailedCasesWarning):
        retried = tw.sweep(*args, max_workers=1, store=store, progress=False,
                           retry_errors=True, **kw)
    assert retried.attrs == {"computed": 3, "from_store": 1}
    pd.testing.assert_frame_equal(no_wall(retried), no_wall(df), check_exact=True)


def test_a_failed_static_solve_is_a_failed_case(tmp_path, monkeypatch):
    """The kernel's static solve failing at a case's start (forced for the 1e8 N/m case: the
    loads that made it fail, 2e7 N on 1 MN/m supports, sag the track metres, and the scene,
    hence the sweep, refuses them before anything runs: next test) is one row of the table,
    not the end of the sweep, warned about with the first error, and stored like a
    divergence."""
    kw = dict(KW, n_elements=20)
    real = cases.simulate

    def simulate(scene, *args, **kwargs):
        if scene.supports.stiffness == 1e8:
            raise RuntimeError("static solve: the wheel lost contact with the rail")
        return real(scene, *args, **kwargs)

    monkeypatch.setattr(cases, "simulate", simulate)
    with pytest.warns(tw.FailedCasesWarning, match=r"1 of 2 cases .* the first \(v = 55.56 m/s, "
                      r"k_s = 1e\+08 N/m\): RuntimeError: static solve"):
        df = tw.sweep(SCENE, tw.kmh(200), [1e8, 1e9], max_workers=1, store=tmp_path / "s",
                      progress=False, **kw)
    assert (df.error == "").tolist() == [False, True]
    assert df.error[0] == "RuntimeError: static solve: the wheel lost contact with the rail"
    assert df.loc[0, list(COLUMN.values())].isna().all() and np.isfinite(df.amplitude_m[1])
    # the case that ran is the single run, exactly
    stiff = dc.replace(SCENE, supports=dc.replace(SCENE.supports, stiffness=1e9))
    assert df.amplitude_m[1] == tw.analyse(tw.simulate(stiff, tw.kmh(200), **kw)).amplitude
    with pytest.warns(tw.FailedCasesWarning):
        again = tw.sweep(SCENE, tw.kmh(200), [1e8, 1e9], max_workers=1, store=tmp_path / "s",
                         progress=False, **kw)
    assert again.attrs == {"computed": 0, "from_store": 2}


def test_a_support_stiffness_the_scene_refuses_is_refused_before_anything_runs(tmp_path):
    """2e7 N on 1 MN/m supports sags the paper's track metres (Scene.static_sag): the sweep
    refuses that stiffness by name, before running (or storing) any case."""
    heavy = dc.replace(SCENE, wheel=dc.replace(SCENE.wheel, load=2e7))
    with pytest.raises(ValueError, match=r"support_stiffness = 1e\+06 N/m: the track sags"):
        tw.sweep(heavy, tw.kmh(200), [1e9, 1e6], max_workers=1, store=tmp_path / "s",
                 progress=False, **KW)
    assert not records(tmp_path / "s")


def test_a_sweep_whose_every_case_fails_raises_with_the_first_error(tmp_path):
    """Explicit RK4 at 1e-4 s, ten times its stability limit: every case diverges. The sweep
    raises SweepFailedError naming the count and the first error, its table attached; the
    failed cases are stored (a re-run with retry_errors=True recomputes them)."""
    kw = dict(KW, integrator="explicit", dt=1e-4)
    with pytest.warns(tw.StabilityWarning), pytest.raises(
            tw.SweepFailedError, match=r"every case of the sweep failed \(2\); the first "
            r"\(v = 55.56 m/s, k_s = 1.4e\+08 N/m, seed 0\): DivergenceError") as info:
        tw.sweep(ROUGH, tw.kmh(200), seeds=range(2), max_workers=1, store=tmp_path / "s",
                 progress=False, **kw)
    table = info.value.table
    assert len(table) == 2 and table.error.str.startswith("DivergenceError").all()
    assert len(records(tmp_path / "s")) == 2


@pytest.mark.parametrize("kwargs,exc,match", [
    ({"speed": []}, ValueError, "speed is empty"),
    ({"speed": [10.0, -1.0]}, ValueError, "speed = -1.0"),
    ({"speed": [0.0]}, ValueError, "speed"),
    ({"speed": [math.nan]}, ValueError, "speed contains NaN"),
    ({"speed": [10.0, 10.0]}, ValueError, "speed contains duplicate"),
    ({"speed": [[1.0, 2.0]]}, ValueError, "speed must be"),
    ({"speed": "fast"}, TypeError, "speed"),
    ({"speed": 10.0, "support_stiffness": []}, ValueError, "support_stiffness is empty"),
    ({"speed": 10.0, "support_stiffness": [1e8, -1e8]}, ValueError, "support_stiffness = -1"),
    ({"speed": 10.0, "support_stiffness": math.inf}, ValueError, "support_stiffness contains"),
    ({"speed": 10.0, "dtt": 1e-5}, TypeError, "dtt"),
    ({"speed": 10.0, "max_workers": 0}, ValueError, "max_workers"),
    ({"speed": 10.0, "executor": object()}, TypeError, "executor"),
    ({"speed": 10.0, "executor": cf.ThreadPoolExecutor(1), "max_workers": 2}, ValueError,
     "executor or max_workers"),
    ({"speed": 10.0, "x_end": np.array([1.0])}, TypeError, "cannot store"),
])
def test_bad_arguments(kwargs, exc, match, tmp_path):
    """Rejected before anything runs (and before the store is touched)."""
    with pytest.raises(exc, match=match):
        tw.sweep(SCENE, progress=False, store=tmp_path / "s", **kwargs)
    assert not records(tmp_path / "s")
    with pytest.raises(TypeError, match="scene"):
        tw.sweep("kato", 10.0)
    (tmp_path / "file").write_text("")
    with pytest.raises(ValueError, match="store"):
        tw.sweep(SCENE, 10.0, store=tmp_path / "file")


def test_progress_bar(capsys):
    """On by default (tqdm on stderr outside Jupyter), silenced by progress=False."""
    tw.sweep(SCENE, SPEEDS, STIFF[:1], max_workers=1, **KW)
    err = capsys.readouterr().err
    assert "sweep" in err and "2/2" in err
    tw.sweep(SCENE, SPEEDS, STIFF[:1], max_workers=1, progress=False, **KW)
    assert capsys.readouterr().err == ""


# --------------------------------------------------------------------------------------------
CTRL_C_SCRIPT = textwrap.dedent("""
    import signal
    import sys
    import trackwheel as tw

    # a process started in the background by a non-interactive shell (as CI may be) inherits
    # SIGINT ignored, and Python then leaves it ignored: restore Ctrl-C's KeyboardInterrupt
    signal.signal(signal.SIGINT, signal.default_int_handler)

    if __name__ == "__main__":  # the process pool re-imports the main module
        tw.sweep(tw.Scene.kato2005(), [tw.kmh(v) for v in (300, 250, 200, 150)], [1e8, 1.4e8],
                 store=sys.argv[1], max_workers=2, progress=False, x_start=0.25, x_end=2.25,
                 dt=2e-6)
""")


def test_ctrl_c_keeps_finished_cases_and_stops_the_workers(tmp_path):
    """SIGINT to a sweep running on its own 2-process pool (as Jupyter's interrupt does: the
    parent only) after the first 2 of 8 cases (0.3-0.7 s each, fastest first) are stored:
    KeyboardInterrupt within 10 s, every stored record sound, its worker processes gone."""
    store = tmp_path / "s"
    script = tmp_path / "run.py"
    script.write_text(CTRL_C_SCRIPT)
    env = dict(os.environ, PYTHONPATH=str(Path(tw.__file__).parent.parent))
    proc = subprocess.Popen([sys.executable, str(script), str(store)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 120.0
        while len(records(store)) < 2:
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline
            time.sleep(0.05)
        children = psutil.Process(proc.pid).children(recursive=True)
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=10.0)
        assert time.monotonic() - t0 < 10.0
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert b"KeyboardInterrupt" in err and proc.returncode != 0
    _, alive = psutil.wait_procs(children, timeout=10.0)
    assert not alive
    df = tw.load_sweep(store)  # warnings are errors: every record is sound
    assert 2 <= len(df) < 8 and (df.error == "").all()


# --------------------------------------------------------------------------------------------
# the seed axis (issue 13): these check the plumbing (which profile each case runs, rows,
# records, executors), not the physics of the profile
RANDOM = (tw.Irregularity.random(tw.spectra.fra(5), seed=0, wavelengths=(1.6, 50.0))
          + tw.Irregularity.sine(0.5, 1e-5)
          + tw.Irregularity.random(tw.spectra.german("low"), seed=0, wavelengths=(2.0, 40.0)))
ROUGH = dc.replace(SCENE, irregularity=RANDOM)


def test_reseeded_draws_every_random_part_afresh():
    """reseeded(s): the first random part takes seed s (the same profile as
    Irregularity.random(seed=s)), the second the derived seed of (s, 1), the sine is kept;
    different seeds give different profiles, the same seed the same one bit for bit."""
    from trackwheel.irregularity import derived_seed

    r3 = RANDOM.reseeded(3)
    assert [p.seed for p in r3.parts if p.kind == "random"] == [3, derived_seed(3, 1)]
    assert r3.parts[1] == RANDOM.parts[1] and RANDOM.n_random == 2
    assert derived_seed(3, 1) not in (3, derived_seed(4, 1), derived_seed(3, 2))
    x = np.linspace(0.0, 5.0, 501)
    alone = tw.Irregularity.random(tw.spectra.fra(5), seed=3, wavelengths=(1.6, 50.0))
    np.testing.assert_array_equal(r3.parts[0].value(x), alone(x))
    np.testing.assert_array_equal(RANDOM.reseeded(3)(x), r3(x))
    assert np.max(np.abs(RANDOM.reseeded(4)(x) - r3(x))) > 1e-4  # mm-scale profiles differ
    with pytest.raises(ValueError, match="no random part"):
        tw.Irregularity.sine(0.5, 1e-5).reseeded(1)
    with pytest.raises(ValueError, match="seed"):
        RANDOM.reseeded(-1)


def test_seed_axis_rows_records_and_resume(tmp_path):
    """One row per (speed, stiffness, seed), seed minor; each case runs the scene with
    irregularity.reseeded(seed) (its record's inputs say so); the seeds are distinct cases in
    the store, and a re-run with a subset of the seeds reads them back unchanged (same seed,
    identical row)."""
    store = tmp_path / "s"
    df = tw.sweep(ROUGH, SPEEDS, seeds=[0, 3], max_workers=1, store=store, progress=False,
                  **KW)
    assert list(df.seed) == [0, 3, 0, 3]
    assert list(df.speed_m_s) == [SPEEDS[0]] * 2 + [SPEEDS[1]] * 2
    assert df.case.nunique() == 4 and len(records(store)) == 4
    for p in records(store):
        rec = json.loads(p.read_text())
        seed = rec["inputs"]["seed"]
        parts = rec["inputs"]["scene"]["irregularity"]["parts"]
        expected = dc.asdict(RANDOM.reseeded(seed))["parts"]
        assert rec["row"]["seed"] == seed and parts == json.loads(json.dumps(expected))
    again = tw.sweep(ROUGH, SPEEDS, seeds=[3], max_workers=1, store=store, progress=False,
                     **KW)
    assert again.attrs == {"computed": 0, "from_store": 2}
    pd.testing.assert_frame_equal(again, df[df.seed == 3].reset_index(drop=True),
                                  check_exact=True)
    assert df.seed.dtype == "Int64" and tw.sweep(ROUGH, SPEEDS[0], max_workers=1,
                                                 progress=False, **KW).seed.isna().all()


@pytest.mark.filterwarnings(*DASK_NOISE)
def test_seed_axis_same_rows_whatever_the_executor():
    """The Monte Carlo rows are identical serially, on 2 processes, on threads and on a local
    Dask cluster (each case a deterministic run of its own reseeded scene)."""
    kw = dict(seeds=[1, 2, 5], progress=False, **KW)
    ref = tw.sweep(ROUGH, SPEEDS[1], max_workers=1, **kw)
    two = tw.sweep(ROUGH, SPEEDS[1], max_workers=2, **kw)
    pd.testing.assert_frame_equal(no_wall(two), no_wall(ref), check_exact=True)
    with cf.ThreadPoolExecutor(2) as ex:
        threads = tw.sweep(ROUGH, SPEEDS[1], executor=ex, **kw)
    pd.testing.assert_frame_equal(no_wall(threads), no_wall(ref), check_exact=True)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        dask = tw.sweep(ROUGH, SPEEDS[1], executor=client.get_executor(), **kw)
    pd.testing.assert_frame_equal(no_wall(dask), no_wall(ref), check_exact=True)


def _with_patch_filter(scene):
    """The Kabo joint's cusp needs the contact filter (Contact.patch_filter)."""
    return dc.replace(scene, contact=dc.replace(scene.contact, patch_filter=True))


def test_force_columns_are_the_analysis_of_each_case():
    """The force-statistics columns are analyse(run, defect_at=joint middle).forces of the
    case's own run, bit for bit; force_rms is the RMS of N - mean(N); with the joint's middle
    (0.35 m) inside the run, P1/P2 are there, without a joint they are NaN."""
    irr = RANDOM + tw.Irregularity.dipped_joint(1e-4, 0.1, at=0.3)
    scene = _with_patch_filter(dc.replace(SCENE, irregularity=irr))
    df = tw.sweep(scene, SPEEDS[1], seeds=[7], max_workers=1, progress=False, **KW)
    case = dc.replace(scene, irregularity=irr.reseeded(7))
    r = tw.simulate(case, SPEEDS[1], **KW)
    a = tw.analyse(r, defect_at=0.35)
    row = df.iloc[0]
    assert row.dynamic_factor == a.dynamic_factor and row.loss_duration_s == a.loss_duration
    assert (row.p1_N, row.p1_time_s, row.p2_N, row.p2_time_s) == (
        a.forces.p1, a.forces.p1_time, a.forces.p2, a.forces.p2_time)
    n = r.normal_force
    assert row.force_rms_N == pytest.approx(math.sqrt(np.mean((n - n.mean()) ** 2)), rel=1e-12)
    plain = tw.sweep(ROUGH, SPEEDS[1], seeds=[7], max_workers=1, progress=False, **KW)
    assert plain.p1_N.isna().all() and plain.p2_N.isna().all()


@pytest.mark.parametrize("scene, seeds, exc, match", [
    (SCENE, [0], ValueError, "no random part"),
    (dc.replace(SCENE, irregularity=tw.Irregularity.sine(0.5, 1e-5)), [0], ValueError,
     "no random part"),
    (ROUGH, [], ValueError, "seeds is empty"),
    (ROUGH, [1, 1], ValueError, "duplicate"),
    (ROUGH, [-2], ValueError, "seeds"),
    (ROUGH, [1.5], TypeError, "seeds"),
])
def test_bad_seeds(scene, seeds, exc, match, tmp_path):
    with pytest.raises(exc, match=match):
        tw.sweep(scene, 10.0, seeds=seeds, store=tmp_path / "s", progress=False)
    assert not records(tmp_path / "s")


def test_summarise_seeds_percentiles_per_speed():
    """Per speed, numpy's percentiles of each column over the seeds that ran (a failed row is
    left out and not counted); a table mixing support stiffnesses must say how to group."""
    rng = np.random.default_rng(0)
    rows = [{"speed_m_s": sp, "support_stiffness_N_m": 1e8, "seed": s, "error": "",
             "max_contact_force_N": 5e4 + 1e3 * rng.random(),
             "dynamic_factor": 1 + rng.random()}
            for sp in (10.0, 20.0) for s in range(7)]
    rows[3]["error"], rows[3]["max_contact_force_N"] = "DivergenceError: x", 1e9
    df = pd.DataFrame(rows)
    out = tw.summarise_seeds(df, ["max_contact_force_N", "dynamic_factor"], q=(5, 50, 95))
    assert list(out.index) == [10.0, 20.0] and list(out[("n_seeds", "")]) == [6, 7]
    for sp in (10.0, 20.0):
        ok = df[(df.speed_m_s == sp) & (df.error == "")]
        for col in ("max_contact_force_N", "dynamic_factor"):
            for q in (5, 50, 95):
                assert out.loc[sp, (col, f"p{q}")] == np.percentile(ok[col], q)
    mixed = pd.concat([df, df.assign(support_stiffness_N_m=2e8)])
    with pytest.raises(ValueError, match="support_stiffness"):
        tw.summarise_seeds(mixed, ["dynamic_factor"])
    by = ["speed_m_s", "support_stiffness_N_m"]
    both = tw.summarise_seeds(mixed, ["dynamic_factor"], by=by)
    assert both.index.names == by and len(both) == 4
    with pytest.raises(ValueError, match="seed"):
        tw.summarise_seeds(df.drop(columns="seed"), ["dynamic_factor"])
