"""The ``trackwheel`` command: ``run``, ``sweep`` and ``eigen`` print what the library computes;
bad arguments and unusable output paths are one-line errors (exit code 2) found before anything
is computed, in the command line's units. (``reproduce``: tests/test_reproduce.py.)"""

from __future__ import annotations

import dataclasses
import importlib
import subprocess
import sys

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import cli
from trackwheel.base.limits import MAX_ELEMENTS
from trackwheel.cli import commands, options, scenes
from trackwheel.simulate import FIDELITY_LEVELS

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _csv(path):
    import pandas as pd

    # the python engine parses with float(): the shortest repr written by to_csv round-trips
    return pd.read_csv(path, engine="python", keep_default_na=False, na_values=[""])


def test_eigen_command_prints_the_frequencies(capsys):
    assert cli.main(["eigen", "--position", "1.3", "--n-modes", "5"]) == 0
    printed = capsys.readouterr().out
    f = tw.eigen(tw.Scene.kato2005(), [1.3], n_modes=5).frequencies[0]
    rows = [line.split() for line in printed.splitlines() if line.strip().endswith("Hz")
            and line.split()[0].isdigit()]
    assert [int(r[0]) for r in rows] == [1, 2, 3, 4, 5]
    np.testing.assert_allclose([float(r[1]) for r in rows], f, atol=0.006)  # printed to 0.01


# ---- run and sweep ----------------------------------------------------------------------
#: a cheap passage: the paper's 20 elements at 1e-5 s over the first two bays
CHEAP = ["--n-elements", "20", "--dt", "1e-5", "--x-end", "0.75"]


def _value(printed: str, key: str) -> float:
    (line,) = [ln for ln in printed.splitlines() if ln.strip().startswith(key)]
    return float(line.split(":", 1)[1].split()[0])


def test_run_prints_the_headline_outputs(tmp_path, capsys):
    png = tmp_path / "run.png"
    assert cli.main(["run", "--speed-kmh", "300", "--support-stiffness", "70e6", *CHEAP,
                     "--plot", str(png)]) == 0
    printed = capsys.readouterr().out
    scene = tw.Scene.kato2005()
    scene = scene.__class__(rail=scene.rail, wheel=scene.wheel, contact=scene.contact,
                            supports=scene.supports.__class__(stiffness=70e6))
    a = tw.analyse(tw.simulate(scene, tw.kmh(300), n_elements=20, dt=1e-5, x_end=0.75))
    assert _value(printed, "amplitude") == pytest.approx(a.amplitude * 1e6, abs=5e-4)  # µm
    assert _value(printed, "main frequency") == pytest.approx(a.main_frequency, abs=0.05)
    assert f"resolution {a.frequency_resolution:.2g} Hz" in printed
    assert f"{a.min_contact_force:.1f} .. {a.max_contact_force:.1f} N" in printed
    assert "lost contact   : no" in printed
    assert "k_s = 70 MN/m" in printed
    assert png.read_bytes()[:8] == PNG_MAGIC


def test_run_reports_divergence_with_exit_1(capsys):
    # explicit RK4 far above its stability limit (about 1e-5 s for 20 elements): the warning is
    # printed, one line, before the divergence
    code = cli.main(["run", "--speed-kmh", "100", "--integrator", "explicit", "--dt", "1e-4",
                     "--n-elements", "20", "--x-end", "0.75"])
    assert code == 1
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("trackwheel run: warning: --dt = 0.0001 s is above the predicted "
                             "stability limit")
    assert "diverged" in err[1] and len(err) == 2


def test_run_fidelity_option(capsys):
    assert cli.main(["run", "--speed-kmh", "100", "--fidelity", "linear/sprung", *CHEAP]) == 0
    assert "fidelity linear/sprung" in capsys.readouterr().out


def test_sweep_command_writes_store_and_table(tmp_path, capsys):
    store, csv = tmp_path / "store", tmp_path / "table.csv"
    argv = ["sweep", "--speeds-kmh", "100", "300", "--support-stiffness", "40e6", "140e6",
            "--store", str(store), "--out", str(csv), "--workers", "1", "--no-progress", *CHEAP]
    assert cli.main(argv) == 0
    assert "4 cases: 4 computed, 0 from the store" in capsys.readouterr().out
    table = _csv(csv)
    assert sorted(zip(table.speed_kmh, table.support_stiffness_N_m)) == [
        (100.0, 40e6), (100.0, 140e6), (300.0, 40e6), (300.0, 140e6)]
    stored = tw.load_sweep(store)
    assert sorted(stored.amplitude_m) == sorted(table.amplitude_m)
    # one case against the API, exactly
    row = table[(table.speed_kmh == 300.0) & (table.support_stiffness_N_m == 140e6)].iloc[0]
    a = tw.analyse(tw.simulate(tw.Scene.kato2005(), tw.kmh(300), n_elements=20, dt=1e-5,
                               x_end=0.75))
    assert row.amplitude_m == a.amplitude and row.main_frequency_hz == a.main_frequency
    # again: everything comes from the store
    assert cli.main(argv) == 0
    assert "4 cases: 0 computed, 4 from the store" in capsys.readouterr().out


def test_sweep_command_fidelity_auto(tmp_path, capsys):
    argv = ["sweep", "--speeds-kmh", "100", "--store", str(tmp_path / "s"), "--workers", "1",
            "--no-progress", "--fidelity", "auto", "--fidelity-tol", "0.05", *CHEAP]
    assert cli.main(argv) == 0
    (line,) = [ln for ln in capsys.readouterr().out.splitlines()
               if ln.startswith("--fidelity auto:")]
    chosen = line.split(":")[1].split()[0]
    assert chosen in FIDELITY_LEVELS
    assert "within 0.05 on 100 km/h, 140 MN/m" in line


@pytest.mark.parametrize("argv, word", [
    (["sweep", "--speeds-kmh", "100", "--store", "{tmp}", "--fidelity-tol", "0.1"],
     "--fidelity auto"),
    (["run", "--speed-kmh", "100", "--fidelity", "auto"], "fidelity"),  # sweep only
    (["run"], "--speed-kmh"),
    (["run", "--speed-kmh", "0"], "must be above 0"),
    (["run", "--speed-kmh", "100", "--dt", "-1e-5"], "--dt = -1e-05 is outside"),
    # no abbreviations: --speed is not --speed-kmh, nor --support --support-stiffness
    (["run", "--speed", "300"], "the following arguments are required: --speed-kmh"),
    (["run", "--speed-kmh", "100", "--support", "1e8"], "unrecognized arguments: --support"),
    (["sweep", "--speeds", "100", "--store", "{tmp}"], "required: --speeds-kmh"),
    (["run", "--speed-kmh", "100", "--dt", "1"], "dt"),                # longer than the run
    (["run", "--speed-kmh", "100", "--x-end", "9"], "--x-end"),        # beyond the rail
    (["run", "--speed-kmh", "100", "--fidelity", "bogus"], "fidelity"),
    (["run", "--speed-kmh", "100", "--integrator", "euler"], "integrator"),
    (["sweep", "--speeds-kmh", "100"], "--store"),
    (["sweep", "--speeds-kmh", "2000", "--store", "{tmp}"],
     "--speeds-kmh 2000: the speed must be above 0 and at most 1080 km/h"),
    (["sweep", "--speeds-kmh", "100", "100", "--store", "{tmp}"],
     "--speeds-kmh: 100 km/h is given twice"),
    (["sweep", "--speeds-kmh", "100", "--support-stiffness", "1e8", "1e8", "--store", "{tmp}"],
     "--support-stiffness: 1e+08 N/m is given twice"),
    (["reproduce", "--out", "{tmp}", "--only", "fig9"], "fig9"),
])
def test_bad_run_sweep_arguments_exit_2(argv, word, tmp_path, capsys):
    argv = [a.replace("{tmp}", str(tmp_path / "x")) for a in argv]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert "error:" in err and word in err
    assert len(err.splitlines()) == 1  # one line, no usage block


@pytest.mark.parametrize("argv", [
    ["eigen", "--position", "7"],          # outside the 5 m rail
    ["eigen", "--position", "-0.1"],
    ["eigen", "--position", "nan"],
    ["eigen", "--position", "abc"],
    ["eigen", "--n-modes", "0"],
    ["eigen", "--n-modes", "1000"],        # more than the 20-element mesh has
    ["reproduce"],                          # --out is required
    ["fly"],                                # no such command
    [],
])
def test_bad_arguments_exit_2(argv, capsys):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert "error:" in err and len(err.splitlines()) == 1


def test_out_must_be_a_folder(tmp_path, capsys):
    f = tmp_path / "file.txt"
    f.write_text("x", encoding="utf-8")
    assert cli.main(["reproduce", "--quick", "--out", str(f)]) == 2
    assert "not a folder" in capsys.readouterr().err


@pytest.mark.parametrize("argv", [["--help"], ["reproduce", "--help"], ["eigen", "--help"],
                                  ["run", "--help"], ["sweep", "--help"]])
def test_help(argv, capsys):
    assert cli.main(argv) == 0
    assert "usage: trackwheel" in capsys.readouterr().out


def test_version(capsys):
    assert cli.main(["--version"]) == 0
    assert capsys.readouterr().out.strip() == f"trackwheel {tw.__version__}"


def test_module_entry_point_exit_code():
    """``python -m trackwheel.cli`` passes main's exit code to the shell."""
    run = subprocess.run([sys.executable, "-m", "trackwheel.cli", "eigen", "--position", "9"],
                         capture_output=True, text=True, check=False)
    assert run.returncode == 2
    assert "outside the rail" in run.stderr


# ---- issue 16: what a new user met ----------------------------------------------------------
@pytest.mark.parametrize("speed", ["5000", "0"])
def test_speed_error_in_km_h(speed, capsys):
    """The speed's range in km/h, its lower end open (0 is not a speed a wheel passes at)."""
    assert cli.main(["run", "--speed-kmh", speed]) == 2
    err = capsys.readouterr().err
    assert err == (f"trackwheel run: error: --speed-kmh {speed}: the speed must be above 0 and "
                   "at most 1080 km/h\n")


@pytest.mark.parametrize("value", ["-1e6", "-1E+6", "-2.5e7", "-.5e3", "-1000000"])
def test_negative_numbers_reach_validation(value, capsys):
    """argparse reads -1e6 as a value, and the library's range check answers, in one line."""
    assert cli.main(["run", "--speed-kmh", "100", "--support-stiffness", value, *CHEAP]) == 2
    err = capsys.readouterr().err
    assert err.startswith("trackwheel run: error: --support-stiffness = -")
    assert "is outside the allowed range (0, 1e+14] N/m" in err and len(err.splitlines()) == 1


def test_negative_x_start_reaches_validation(capsys):
    assert cli.main(["run", "--speed-kmh", "100", "--x-start", "-1e-1", *CHEAP]) == 2
    assert "--x-start = -0.1 is outside the allowed range [0.0, 5.0] m" in capsys.readouterr().err


@pytest.mark.parametrize("argv, words", [
    (["run", "--speed-kmh", "300", "--plot", "run.xyz"], "unknown file format 'xyz'"),
    (["run", "--speed-kmh", "300", "--plot", "run"], "unknown file format '(none)'"),
    (["run", "--speed-kmh", "300", "--plot", "{tmp}/missing/run.png"], "does not exist"),
    (["run", "--speed-kmh", "300", "--plot", "/proc/run.png"], "cannot write in this folder"),
    (["run", "--speed-kmh", "300", "--plot", "{tmp}"], "is a folder"),
    (["reproduce", "--out", "/proc"], "cannot write in this folder"),
    (["reproduce", "--out", "/proc/x/y"], "cannot create the folder"),
    (["sweep", "--speeds-kmh", "100", "--store", "/proc"], "cannot write in this folder"),
    (["sweep", "--speeds-kmh", "100", "--store", "{tmp}/s", "--out", "/proc/t.csv"],
     "cannot write in this folder"),
    (["sweep", "--speeds-kmh", "100", "--store", "{tmp}/s", "--out", "{tmp}/no/t.csv"],
     "does not exist"),
])
def test_output_paths_are_checked_before_computing(argv, words, tmp_path, capsys, monkeypatch):
    """Each bad path is a one-line error, exit code 2, and nothing was computed."""
    calls = []
    monkeypatch.setattr(commands.run, "simulate", lambda *a, **k: calls.append(a))
    monkeypatch.setattr(commands.sweep, "sweep", lambda *a, **k: calls.append(a))
    monkeypatch.setattr(commands.reproduce, "reproduce", lambda *a, **k: calls.append(a))
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and len(err.splitlines()) == 1
    assert calls == []


def test_no_traceback_from_the_shell():
    """The console entry point: one line on stderr, exit code 2, no traceback."""
    run = subprocess.run([sys.executable, "-m", "trackwheel.cli", "run", "--speed-kmh", "300",
                          "--plot", "run.xyz"], capture_output=True, text=True, check=False)
    assert run.returncode == 2
    lines = [ln for ln in run.stderr.splitlines() if ln.startswith("trackwheel")]
    assert len(lines) == 1 and "Traceback" not in run.stderr


def test_mesh_warning_is_printed(capsys):
    assert cli.main(["run", "--speed-kmh", "300", "--n-elements", "5", "--dt", "1e-5",
                     "--x-end", "0.75"]) == 0
    captured = capsys.readouterr()
    assert captured.err.startswith("trackwheel run: warning: --n-elements = 5 cannot resolve "
                                   "the 10 support bays")
    assert "5 elements" in captured.out


@pytest.mark.parametrize("speed_kmh", ["100", "300"])
def test_linear_sprung_uses_the_full_models_settings(speed_kmh, capsys):
    """issue 16, item 1: every level uses the derived mesh and step; with them linear/sprung
    reproduces the full model within the README's 0.03 % on the amplitude."""
    printed = {}
    for level in ("full", "linear/sprung"):
        assert cli.main(["run", "--speed-kmh", speed_kmh, "--fidelity", level]) == 0
        printed[level] = capsys.readouterr().out
    d = tw.default_settings(tw.Scene.kato2005())
    for out in printed.values():
        (line,) = [ln for ln in out.splitlines() if "settings" in ln]
        assert f"dt = {d['dt']:.3g} s, {d['n_elements']} elements" in line
    full, lin = (_value(printed[k], "amplitude") for k in ("full", "linear/sprung"))
    assert abs(lin / full - 1.0) < 3e-4


def test_version_is_written_once():
    """pyproject.toml takes the version from _version.py (scikit-build-core's regex provider)
    and declares none of its own; the installed metadata agrees with the package."""
    import importlib.metadata
    import re
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    project = (root / "pyproject.toml").read_text(encoding="utf-8")
    table = project.split("[project]", 1)[1].split("\n[", 1)[0]
    assert re.search(r'^dynamic = \["version"\]', table, re.M)
    assert not re.search(r"^version\s*=", table, re.M)
    assert 'metadata.version.input = "python/trackwheel/_version.py"' in project
    source = (root / "python" / "trackwheel" / "_version.py").read_text(encoding="utf-8")
    assert re.findall(r'__version__ = "([^"]+)"', source) == [tw.__version__]
    assert importlib.metadata.version("trackwheel") == tw.__version__


def test_a_failed_static_solve_at_the_start_is_one_line(capsys, monkeypatch):
    """The kernel's static solve failing at the start (forced here: the loads that made it
    fail, 2e7 N on 1 MN/m supports, sag the track metres and Scene refuses them) is exit code 1
    and one line, not a traceback."""
    plan = importlib.import_module("trackwheel.run.plan")

    def fail(*args, **kwargs):
        raise RuntimeError("static solve: the wheel lost contact with the rail")

    monkeypatch.setattr(plan, "initial_state", fail)
    assert cli.main(["run", "--speed-kmh", "100", *CHEAP]) == 1
    message = "the simulation could not start: static solve: the wheel lost contact with the rail"
    assert capsys.readouterr().err == f"trackwheel run: {message}\n"


def test_a_failed_static_solve_in_the_analysis_is_one_line(capsys, monkeypatch):
    """The kernel's static solve failing on the quasi-static line of the analysis (forced here:
    which loads make it fail depends on the solver's start, not on anything the CLI does) is
    exit code 1 and one line, not a traceback."""
    line = importlib.import_module("trackwheel.study.static_line")

    def fail(*args, **kwargs):
        raise RuntimeError("static solve: the wheel lost contact with the rail")

    monkeypatch.setattr(line, "quasi_static", fail)
    line.qs_series.cache_clear()  # nothing cached may hide the failing solver
    assert cli.main(["run", "--speed-kmh", "100", *CHEAP]) == 1
    message = "the analysis failed: static solve: the wheel lost contact with the rail"
    assert capsys.readouterr().err == f"trackwheel run: {message}\n"


@pytest.mark.parametrize("command", ["reproduce", "run", "sweep"])
def test_help_has_no_hand_typed_timings(command, capsys):
    """issue 16, item 9: timings come from the run or from benchmarks/, never the help text."""
    import re

    assert cli.main([command, "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert not re.search(r"\b(minutes?|hours?|seconds)\b|about \d+ ?s\b|µs", text), text


# --------------------------------------------------------------------------------------------
# excitation options (issue 13)
def _scene_of(argv):
    """The scene a `run` command line builds (and its notes)."""
    args = cli.build_parser().parse_args(["run", "--speed-kmh", "100", *argv])
    return scenes.excited_scene(tw.Scene.kato2005(), args)


def test_excitation_options_build_the_api_scene():
    """--irregularity/--seed/--wavelengths/--joint/--wheel-flat give exactly the scene the API
    builds: the random part drawn with --seed, a second random part with the seed derived from
    it (Irregularity.reseeded), the joint added, a new flat half a revolution from the mark."""
    scene, _ = _scene_of(["--irregularity", "fra:5", "--irregularity", "german:high",
                          "--seed", "3", "--wavelengths", "2", "50",
                          "--joint", "0.002,0.5,2.0", "--wheel-flat", "0.05"])
    spec = tw.spectra
    irr = (tw.Irregularity.random(spec.fra(5), seed=3, wavelengths=(2.0, 50.0))
           + tw.Irregularity.random(spec.german("high"), seed=0, wavelengths=(2.0, 50.0))
           ).reseeded(3) + tw.Irregularity.dipped_joint(0.002, 0.5, 2.0)
    assert scene.irregularity == irr
    assert scene.wheel.defects == (tw.WheelFlat(0.05, at_angle=np.pi),)
    sine, _ = _scene_of(["--irregularity", "sine:0.5,1e-5", "--irregularity", "china"])
    assert sine.irregularity.parts[0] == tw.Irregularity.sine(0.5, 1e-5).parts[0]
    assert sine.irregularity.parts[1].seed == 0  # --seed defaults to 0
    iso, _ = _scene_of(["--irregularity", "iso3095"])
    assert iso.irregularity.parts[0].spectrum == spec.iso3095()
    assert _scene_of([])[0] == tw.Scene.kato2005()


def test_joint_turns_the_contact_filter_on():
    """--joint sets Contact.patch_filter (the Kabo cusp curves more sharply than any wheel) and
    says so; --patch-filter alone sets it too."""
    scene, notes = _scene_of(["--joint", "0.002,0.5,2.0"])
    assert scene.contact.patch_filter is True and "contact filter on" in notes[0]
    assert _scene_of(["--patch-filter"])[0].contact.patch_filter is True


def test_run_prints_the_force_statistics(capsys):
    """`run` with an excitation prints it and the force statistics of analyse(run,
    defect_at=joint middle) on the scene the API builds: dynamic factor and P1/P2 to the
    printed digits."""
    argv = ["--irregularity", "fra:5", "--seed", "3", "--wavelengths", "2", "50",
            "--joint", "0.0005,0.2,0.4"]
    assert cli.main(["run", "--speed-kmh", "300", *argv, *CHEAP]) == 0
    printed = capsys.readouterr().out
    scene, _ = _scene_of(argv)
    a = tw.analyse(tw.simulate(scene, tw.kmh(300), n_elements=20, dt=1e-5, x_end=0.75),
                   defect_at=0.5)
    assert "FRA class 5 (seed 3, 2-50 m), dipped joint 0.5 mm over 0.2 m at X = 0.4 m" in printed
    assert _value(printed, "dynamic factor") == pytest.approx(a.dynamic_factor, abs=5e-5)
    assert f"{a.forces.p1 / 1e3:.2f} / {a.forces.p2 / 1e3:.2f} kN" in printed
    assert "force bands" in printed


@pytest.mark.parametrize("argv, words", [
    (["--irregularity", "fra:7"], ["fra:7", "track_class = 7", "[1, 6]"]),
    (["--irregularity", "fra:x"], ["fra:x", "integer 1..6"]),
    (["--irregularity", "german:mid"], ["german:mid", "'low'"]),
    (["--irregularity", "bumpy"], ["unknown irregularity 'bumpy'", "fra:N"]),
    (["--irregularity", "sine:0.5"], ["WAVELENGTH,AMPLITUDE"]),
    (["--irregularity", "fra:5", "--wavelengths", "0.5", "50"],
     ["--wavelengths (0.5, 50) m is outside the validity band of FRA class 5",
      "[1.524, 304.8] m"]),
    (["--irregularity", "fra:5", "--wavelengths", "0", "50"], ["positive"]),
    (["--seed", "3"], ["--seed", "random --irregularity"]),
    (["--irregularity", "fra:5", "--seed", "-1"], ["--seed -1", "allowed range"]),
    (["--joint", "-0.002,0.5,2"], ["--joint", "DEPTH = -0.002", "allowed range"]),
    (["--joint", "1,600,1950"], ["--joint", "DEPTH = 1.0", "(0, 0.1] m", "1 mm is 1e-3"]),
    (["--joint", "0.001,6,0"], ["--joint", "LENGTH 6 m is longer than the rail (5 m)"]),
    (["--joint", "0.01,0.05,1"], ["--joint", "slope of 0.628", "allowed at most 0.1"]),
    (["--irregularity", "sine:0.5,1"], ["AMPLITUDE = 1.0", "[0, 0.1] m", "1 mm is 1e-3"]),
    (["--irregularity", "fra:5", "--wavelengths", "50", "1.5"],
     ["--wavelengths (50, 1.5) m must be (lambda_min, lambda_max)"]),
    (["--wheel-flat", "20"], ["--wheel-flat = 20.0", "20 mm is 0.02"]),
    (["--joint", "0.002,0.5"], ["DEPTH,LENGTH,AT"]),
    (["--joint", "0.002,0.5,4.8"], ["--joint", "leaves the rail", "[0, 4.5] m"]),
    (["--wheel-flat", "-0.05"], ["--wheel-flat", "> 0 m"]),
    (["--wheel-flat", "0.3"], ["--wheel-flat", "shorter than the wheel's diameter"]),
])
def test_bad_excitation_values_are_one_line(argv, words, capsys):
    assert cli.main(["run", "--speed-kmh", "100", *argv, *CHEAP]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and "error:" in err
    for w in words:
        assert w in err, (w, err)


def test_seed_lists_and_ranges(tmp_path, capsys):
    """--seeds takes ranges and lists (0-2,5 is 0, 1, 2, 5); bad ones are one-line errors."""
    assert options.seed_list("0-2,5") == [0, 1, 2, 5] and options.seed_list("7") == [7]
    store = str(tmp_path / "s")
    for bad, word in (("5-3", "empty seed range"), ("a", "0-19"), ("-1", "0-19")):
        assert cli.main(["sweep", "--speeds-kmh", "100", "--store", store,
                         "--irregularity", "fra:5", "--seeds", bad]) == 2
        err = capsys.readouterr().err
        assert len(err.splitlines()) == 1 and word in err, err
    assert cli.main(["sweep", "--speeds-kmh", "100", "--store", store, "--seeds", "0-2"]) == 2
    assert "random --irregularity" in capsys.readouterr().err
    assert cli.main(["sweep", "--speeds-kmh", "100", "--store", store, "--irregularity",
                     "fra:5", "--seeds", "1", "0-2"]) == 2
    assert "twice" in capsys.readouterr().err
    assert cli.main(["sweep", "--speeds-kmh", "100", "--store", store, "--irregularity",
                     "fra:5", "--seeds", "0-2", "--seed", "4"]) == 2
    assert "not both" in capsys.readouterr().err


def test_sweep_over_seeds(tmp_path, capsys):
    """`sweep --seeds 0-2` runs one case per (speed, seed) of the reseeded scene, writes the
    seed and force columns, and prints the percentiles over the seeds per speed (those of
    summarise_seeds on the written table)."""
    csv = tmp_path / "t.csv"
    argv = ["sweep", "--speeds-kmh", "200", "300", "--irregularity", "fra:5", "--wavelengths",
            "2", "50", "--seeds", "0-2", "--store", str(tmp_path / "s"), "--out", str(csv),
            "--workers", "1", "--no-progress", *CHEAP]
    assert cli.main(argv) == 0
    printed = capsys.readouterr().out
    table = _csv(csv)
    assert list(table.seed) == [0, 1, 2, 0, 1, 2] and list(table.speed_kmh) == [200.0] * 3 + [
        300.0] * 3
    assert "dynamic_factor" in table.columns and "loss_duration_s" in table.columns
    s = tw.summarise_seeds(table, ["max_contact_force_N", "dynamic_factor"])
    p = s.loc[tw.kmh(300)]
    line = [ln for ln in printed.splitlines() if ln.strip().startswith("300 km/h")][0]
    assert (f"max N {p[('max_contact_force_N', 'p5')] / 1e3:.4g} / "
            f"{p[('max_contact_force_N', 'p50')] / 1e3:.4g}") in line and "(3 seeds)" in line
    # the header names the realisations swept, not the scene's seed 0
    assert "excitation: FRA class 5 (seeds 0-2, 2-50 m)" in printed


def test_a_sweep_whose_every_case_fails_is_one_line_and_exit_1(tmp_path, capsys):
    """Every case diverges (explicit RK4 at ten times its stability limit): the table of errors,
    then one line naming the count and the first error, exit code 1; no traceback."""
    argv = ["sweep", "--speeds-kmh", "100", "150", "--store", str(tmp_path / "s"),
            "--integrator", "explicit", "--dt", "1e-4", "--x-end", "0.5", "--n-elements", "20",
            "--workers", "1", "--no-progress"]
    assert cli.main(argv) == 1
    captured = capsys.readouterr()
    err = [ln for ln in captured.err.splitlines() if "warning" not in ln]
    assert len(err) == 1 and err[0].startswith("trackwheel sweep: every case of the sweep failed "
                                               "(2); the first (v = 27.78 m/s")
    assert captured.out.count("DivergenceError") == 2


# --------------------------------------------------------------------------------------------
# the track: beam theory, receptance and decay rate (issue 12)
def _timoshenko(scene, kappa=0.4):
    return dataclasses.replace(scene, rail=dataclasses.replace(
        scene.rail, beam="timoshenko", shear_coefficient=kappa))


def test_run_with_a_timoshenko_rail_on_the_ancf_level(capsys):
    """`run --beam timoshenko --fidelity ancf/sprung` (refused while the ANCF rail was
    Euler-Bernoulli only) is the API's run of that scene on the shear-deformable ANCF rail
    (amplitude to the printed 1e-3 µm)."""
    argv = ["run", "--speed-kmh", "300", "--fidelity", "ancf/sprung", "--beam", "timoshenko",
            *CHEAP]
    assert cli.main(argv) == 0
    printed = capsys.readouterr().out
    a = tw.analyse(tw.simulate(_timoshenko(tw.Scene.kato2005()), tw.kmh(300), n_elements=20,
                               dt=1e-5, x_end=0.75, fidelity="ancf/sprung"))
    assert _value(printed, "amplitude") == pytest.approx(a.amplitude * 1e6, abs=5e-4)


def test_run_with_a_timoshenko_rail_simulates_that_scene(capsys):
    """`run --beam timoshenko --shear-coefficient 0.3 --fidelity linear/hertz` is the API's run
    of the scene with that rail (amplitude to the printed 1e-3 µm), and it differs from the
    Euler-Bernoulli run by more than the print resolution (the options reach the kernel)."""
    argv = ["run", "--speed-kmh", "300", "--fidelity", "linear/hertz", *CHEAP]
    assert cli.main([*argv, "--beam", "timoshenko", "--shear-coefficient", "0.3"]) == 0
    printed = capsys.readouterr().out
    assert "Scene.kato2005() with a Timoshenko rail (kappa = 0.3)" in printed
    kw = dict(n_elements=20, dt=1e-5, x_end=0.75, fidelity="linear/hertz")
    scene = _timoshenko(tw.Scene.kato2005(), 0.3)
    a = tw.analyse(tw.simulate(scene, tw.kmh(300), **kw))
    assert _value(printed, "amplitude") == pytest.approx(a.amplitude * 1e6, abs=5e-4)
    e = tw.analyse(tw.simulate(tw.Scene.kato2005(), tw.kmh(300), **kw))
    assert abs(e.amplitude - a.amplitude) * 1e6 > 2e-3


def test_sweep_with_a_timoshenko_rail_runs_that_scene(tmp_path, capsys):
    """`sweep --beam timoshenko --fidelity linear/hertz`: the case is the API's run of the
    Timoshenko scene, exactly (same inputs, bit-identical outputs)."""
    csv = tmp_path / "t.csv"
    assert cli.main(["sweep", "--speeds-kmh", "300", "--beam", "timoshenko", "--fidelity",
                     "linear/hertz", "--store", str(tmp_path / "s"), "--out", str(csv),
                     "--workers", "1", "--no-progress", *CHEAP]) == 0
    row = _csv(csv).iloc[0]
    a = tw.analyse(tw.simulate(_timoshenko(tw.Scene.kato2005()), tw.kmh(300), n_elements=20,
                               dt=1e-5, x_end=0.75, fidelity="linear/hertz"))
    assert row.amplitude_m == a.amplitude and row.main_frequency_hz == a.main_frequency


def test_eigen_with_a_timoshenko_rail(capsys):
    assert cli.main(["eigen", "--beam", "timoshenko", "--shear-coefficient", "0.3",
                     "--n-modes", "4"]) == 0
    printed = capsys.readouterr().out
    f = tw.eigen(_timoshenko(tw.Scene.kato2005(), 0.3), [2.5], 4).frequencies[0]
    for k, fk in enumerate(f, start=1):
        assert f"  {k:>3}  {fk:10.2f} Hz\n" in printed


def test_receptance_command_writes_the_api_receptance(tmp_path, capsys):
    """The CSV holds trackwheel.receptance at the mid-span of the bay right of the middle
    support (15.3 m on the 30 m ballasted track) on --n log-spaced frequencies; abs and phase are
    those of re + i im; the printed peak lies within 1 % of the Timoshenko pinned-pinned
    frequency of a 0.6 m bay when the search starts above the track resonances."""
    out, png = tmp_path / "r.csv", tmp_path / "r.png"
    assert cli.main(["receptance", "--track", "ballasted", "--beam", "timoshenko", "--fmin",
                     "700", "--fmax", "2000", "--n", "300", "--n-elements", "400", "--out",
                     str(out), "--plot", str(png)]) == 0
    printed = capsys.readouterr().out
    t = np.loadtxt(out, delimiter=",", skiprows=1)
    assert t.shape == (300, 5)
    np.testing.assert_allclose(t[:, 0], np.geomspace(700.0, 2000.0, 300), rtol=1e-9)
    scene = _timoshenko(tw.Scene.ballasted_track())
    a = tw.receptance(scene, 15.3, t[:, 0], n_elements=400)
    np.testing.assert_allclose(t[:, 1] + 1j * t[:, 2], a, rtol=1e-9)
    np.testing.assert_allclose(t[:, 3], np.abs(a), rtol=1e-9)
    np.testing.assert_allclose(t[:, 4], np.degrees(np.angle(a)), rtol=1e-9, atol=1e-9)
    assert "X = 15.3 m (mid-span)" in printed
    f_peak = float(printed.split("largest |alpha|:")[1].split(" at ")[1].split()[0])
    f_t = tw.fidelity.pinned_pinned_frequencies(scene)[1]
    assert f_peak == pytest.approx(f_t, rel=0.01)
    assert png.read_bytes()[:8] == PNG_MAGIC


def test_receptance_above_a_support_and_from_zero(tmp_path, capsys):
    """--at support is the support nearest the middle (15 m); --fmin 0 spaces linearly and the
    0 Hz receptance is the static flexibility, real and positive."""
    out = tmp_path / "r.csv"
    assert cli.main(["receptance", "--at", "support", "--track", "ballasted", "--fmin", "0",
                     "--fmax", "100", "--n", "11", "--out", str(out)]) == 0
    assert "X = 15 m (above a support)" in capsys.readouterr().out
    t = np.loadtxt(out, delimiter=",", skiprows=1)
    np.testing.assert_allclose(t[:, 0], np.linspace(0.0, 100.0, 11))
    assert t[0, 1] > 0.0 and t[0, 2] == 0.0


def test_band_decay_rate_with_one_frequency_is_the_centre_value():
    """With one frequency per band, the band's geometric centre, the band rate is the EN 15461
    rate of trackwheel.decay_rate there (sqrt(lo hi) is the exact base-2 centre)."""
    from trackwheel.frequency import iso3095_band_edges

    scene = tw.Scene.ballasted_track(60.0)
    e = iso3095_band_edges()
    centres = np.sqrt(e[:-1] * e[1:])
    # rtol: np.geomspace's middle point and sqrt(lo hi) differ by an ulp or two, which the sharp
    # resonances of the 60 m rail on its default 1200 elements turn into ~4e-12 of the rate
    np.testing.assert_allclose(tw.frequency.band_decay_rates(scene, 1), tw.decay_rate(scene, centres),
                               rtol=1e-10)


def test_decay_rate_command_prints_and_writes_the_bands(tmp_path, capsys):
    out, png = tmp_path / "d.csv", tmp_path / "d.png"
    assert cli.main(["decay-rate", "--track", "ballasted", "--per-band", "3", "--n-elements",
                     "400", "--out", str(out), "--plot", str(png)]) == 0
    printed = capsys.readouterr().out
    t = np.loadtxt(out, delimiter=",", skiprows=1)
    np.testing.assert_array_equal(t[:, 0], tw.frequency.ISO3095_BANDS)
    np.testing.assert_array_equal(t[:, 2], tw.frequency.ISO3095_VERTICAL_LIMIT)
    dr = tw.frequency.band_decay_rates(tw.Scene.ballasted_track(60.0), 3, 400)
    np.testing.assert_allclose(t[:, 1], dr, rtol=1e-9)
    n_ok = int(np.sum(dr >= t[:, 2]))
    assert f"{n_ok} of 14 bands at or above the limit" in printed
    assert printed.count("below the limit") == 14 - n_ok
    assert "60 m" in printed and png.read_bytes()[:8] == PNG_MAGIC


@pytest.mark.parametrize("argv, words", [
    (["receptance", "--at", "top"], "expected midspan, support or a position"),
    (["receptance", "--at", "7"], "allowed range [0, 5] m"),
    (["receptance", "--fmin", "100", "--fmax", "50"], "0 <= fmin < fmax"),
    (["receptance", "--fmin", "-1"], "0 <= fmin < fmax"),
    (["receptance", "--n", "0"], "positive integer"),
    (["receptance", "--length", "60"], "--length is only for --track ballasted"),
    (["receptance", "--track", "ballasted", "--length", "31"], "--length 31"),
    (["decay-rate", "--track", "ballasted", "--length", f"{0.6 * (MAX_ELEMENTS + 1):g}"],
     "is too long; allowed: at most"),
    (["receptance", "--shear-coefficient", "0.3"], "only used with --beam timoshenko"),
    (["receptance", "--beam", "timoshenko", "--shear-coefficient", "2"],
     "--shear-coefficient = 2.0 is outside the allowed range (0, 1]"),
    (["receptance", "--beam", "bernoulli"], "invalid choice"),
    (["receptance", "--out", "/proc/r.csv"], "cannot write in this folder"),
    (["decay-rate"], "need a rail longer than 33.5 m"),
    (["decay-rate"], "use --track ballasted"),
    (["decay-rate", "--track", "ballasted", "--length", "39.6"], "longer than 40.2 m"),
    (["decay-rate", "--track", "ballasted", "--length", "30"], "give a --length of at least 40.2 m"),
    (["decay-rate", "--track", "ballasted", "--plot", "d.xyz"], "unknown file format"),
    (["eigen", "--beam", "timoshenko", "--shear-coefficient", "0"], "positive number"),
])
def test_bad_track_arguments_are_one_line(argv, words, capsys, monkeypatch):
    calls = []
    monkeypatch.setattr(tw.frequency, "band_decay_rates", lambda *a, **k: calls.append(a))
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and words in err, err
    assert calls == []


@pytest.mark.parametrize("command", ["receptance", "decay-rate"])
def test_track_commands_have_help_without_timings(command, capsys):
    import re

    assert cli.main([command, "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "usage: trackwheel" in text and "--beam" in text
    assert not re.search(r"\b(minutes?|hours?|seconds)\b|about \d+ ?s\b|µs", text), text


def test_a_reader_leaving_the_pipe_ends_the_command_quietly():
    """`trackwheel ... | head` closes the pipe while the command still writes: the command stops
    with exit code 1 and no traceback (Python ignores SIGPIPE, so the write raises
    BrokenPipeError, and the interpreter's final flush of stdout would raise it again)."""
    code = ("import sys, time; from trackwheel.cli import main; time.sleep(0.5); "
            "sys.exit(main(['eigen', '--n-modes', '6']))")
    with subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE) as p:
        p.stdout.close()  # the reader leaves before the first line
        err = p.stderr.read().decode()
        assert p.wait(timeout=120) == 1
    assert "Traceback" not in err and "BrokenPipe" not in err, err


def test_half_car_on_the_paper_track_says_it_lengthens_the_rail(capsys):
    """run --vehicle half-car on the 5 m track ran on a 25 m rail without saying so: a note
    gives the new length: the rail is lengthened by the car's 20 m of wheels in whole bays, so
    that its wheels run on the stretch one wheel has (5 m -> 25 m, 30 m -> 50.4 m)."""
    fast = ["--fidelity", "linear/hertz", "--dt", "1e-4", "--n-elements", "100", "--x-end", "1"]
    assert cli.main(["run", "--speed-kmh", "100", "--vehicle", "half-car", *fast]) == 0
    out = capsys.readouterr().out
    assert ("note: --vehicle half-car: the rail is lengthened from 5 m to 25 m for the half "
            "car's 20 m of wheels") in out
    scene, notes = scenes.vehicle_scene(tw.Scene.ballasted_track(), "half-car")
    assert scene.rail.length == pytest.approx(50.4) and "from 30 m to 50.4 m" in notes[0]
    assert scene.rail.n_elements == 84 * 4  # the preset's elements per bay kept


@pytest.mark.parametrize("command", ["eigen", "decay-rate", "receptance"])
def test_help_mentions_only_options_the_command_has(command, capsys):
    """eigen, decay-rate and receptance have no --fidelity; their help does not send the
    reader to it (the --beam help did)."""
    assert cli.main([command, "--help"]) == 0
    assert "--fidelity" not in capsys.readouterr().out


@pytest.mark.parametrize("command", ["run", "sweep", "eigen"])
def test_descriptions_name_the_track_option_not_only_the_paper_scene(command, capsys):
    """The descriptions said 'Scene.kato2005()' even with --track ballasted."""
    assert cli.main([command, "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "the --track scene (default Scene.kato2005())" in text


def test_eigen_on_the_ballasted_track_starts_mid_rail_and_explains_its_cluster(capsys):
    """eigen --track ballasted took the paper's 2.5 m, near the 30 m rail's rigid end; its
    default is the mid-bay nearest the middle, 15.3 m. Its modes 2-6 lie within 1 % of each
    other: the note names the track's lowest resonance, the lower root of one bay of rail
    (m d) on the pad k_p on the sleeper m_s on the ballast k_b, which the finite rail's
    long-wave modes approach (within 0.5 % here: they bend a little, the wheel sits on one)."""
    from trackwheel.cli.commands import eigen as command

    assert cli.main(["eigen", "--track", "ballasted"]) == 0
    out = capsys.readouterr().out
    assert "wheel at X = 15.3 m" in out
    note = [ln for ln in out.splitlines() if ln.startswith("note: modes 2-6")]
    assert note and "the track's lowest resonance" in note[0]
    scene = tw.Scene.ballasted_track()
    f0, _ = command.cut_on_frequency(scene)
    s = scene.supports
    m_r = scene.rail.mass_per_length * s.spacing
    M = np.diag([m_r, s.sleeper_mass])
    K = np.array([[s.stiffness, -s.stiffness], [-s.stiffness, s.stiffness + s.ballast_stiffness]])
    lowest = np.sqrt(np.min(np.linalg.eigvals(np.linalg.solve(M, K)).real)) / (2 * np.pi)
    assert f0 == pytest.approx(lowest, rel=1e-12)
    modes = tw.eigen(scene, [15.3], n_modes=6).frequencies[0, 1:]
    assert np.all(np.abs(modes / f0 - 1.0) < 5e-3)
    assert f"near {f0:.2f} Hz" in note[0]
    # the paper's track keeps the paper's position and has no such cluster
    assert cli.main(["eigen"]) == 0
    out = capsys.readouterr().out
    assert "wheel at X = 2.5 m" in out and "note:" not in out


@pytest.mark.parametrize("argv, group", [
    (["run", "--track", "ballasted", "--distance", "100000", "--speed-kmh", "100"], False),
    (["sweep", "--track", "ballasted", "--length", "120", "--speeds-kmh", "100", "150", "200",
      "250", "--workers", "2", "--no-progress"], True),  # minutes of work: interrupted before
])
def test_ctrl_c_is_one_line_and_exit_130(argv, group, tmp_path):
    """Ctrl-C during a long run, or a sweep on two workers (the terminal signals the whole
    process group: the workers too), printed a 20-line traceback; it is one line,
    'trackwheel <command>: interrupted (Ctrl-C)', and exit code 130 (128 + SIGINT), the
    sweep's workers gone."""
    import os
    import signal
    import time

    import psutil

    if argv[0] == "sweep":
        argv = [*argv, "--store", str(tmp_path / "s")]
    env = dict(os.environ, PYTHONPATH=str(tw.__path__[0].rsplit(os.sep, 1)[0]))
    # a process started by a non-interactive shell may inherit SIGINT ignored: restore it
    proc = subprocess.Popen(
        [sys.executable, "-m", "trackwheel.cli", *argv], env=env, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, start_new_session=group,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        # imported, and running: on a loaded machine the imports and the sweep's pool take
        # seconds, so wait (up to 60 s) until the sweep's workers are up, then a little more
        deadline = time.monotonic() + 60.0
        time.sleep(5.0)
        while (group and time.monotonic() < deadline and proc.poll() is None
               and len(psutil.Process(proc.pid).children(recursive=True)) < 3):
            time.sleep(0.5)
        time.sleep(2.0)
        assert proc.poll() is None, proc.communicate()
        children = psutil.Process(proc.pid).children(recursive=True)
        if group:
            os.killpg(proc.pid, signal.SIGINT)
        else:
            proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30.0)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    text = err.decode()
    assert proc.returncode == 130 and "Traceback" not in text, text[-2000:]
    assert text.replace("\r", "\n").splitlines()[-1] == (
        f"trackwheel {argv[0]}: interrupted (Ctrl-C)")
    _, alive = psutil.wait_procs(children, timeout=10.0)  # workers and forkserver
    assert not alive


def test_the_wall_time_printed_is_the_whole_commands():
    """'wall time' was the simulation's alone (4.3 s printed of 10.2 s taken). It is the whole
    command's, from the process's start (Python's start-up and imports included) to the
    print: at most the time the process took as measured from outside, and within its exit
    and spawn (a fraction of a second) of it; the simulation's share is beside it."""
    import os
    import re
    import time

    env = dict(os.environ, PYTHONPATH=str(tw.__path__[0].rsplit(os.sep, 1)[0]))
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-m", "trackwheel.cli", "run", "--speed-kmh", "100",
                          *CHEAP], env=env, capture_output=True, text=True, check=True).stdout
    outside = time.perf_counter() - t0
    m = re.search(r"wall time +: ([\d.]+) s for the whole command \(the simulation ([\d.]+) s, "
                  r"(\d+) steps\)", out)
    assert m, out
    whole, sim = float(m.group(1)), float(m.group(2))
    assert sim < whole <= outside + 0.02 and whole > outside - 1.0, (whole, sim, outside)


def test_a_flat_on_the_undamped_track_is_explained_and_damping_can_be_set(capsys):
    """A 20 mm flat at 100 km/h on the paper's undamped track: a note says why its forces and
    contact losses pile up and how to damp it; --support-damping and --contact-damping set
    Supports.damping and Contact.damping (and the note goes). The physics behind the note:
    the first strike is the same with and without damping (nothing has had time to
    dissipate), while on the undamped track later strikes meet a bouncing wheel and a ringing
    rail and exceed it by far, with several times more contact-loss intervals."""
    import math

    argv = ["run", "--speed-kmh", "100", "--wheel-flat", "0.02", *CHEAP[:4]]
    assert cli.main(argv) == 0
    out = capsys.readouterr().out
    assert "note: --wheel-flat on an undamped track" in out and "--support-damping" in out
    assert cli.main([*argv, "--support-damping", "2e4", "--contact-damping", "1e3"]) == 0
    assert "undamped" not in capsys.readouterr().out
    args = cli.build_parser().parse_args([*argv, "--support-damping", "2e4",
                                          "--contact-damping", "1e3"])
    scene = scenes.track_scene(args)
    assert scene.supports.damping == 2e4 and scene.contact.damping == 1e3
    assert cli.main([*argv, "--support-damping", "-1"]) == 2
    assert "--support-damping = -1.0 is outside" in capsys.readouterr().err

    base = tw.Scene.kato2005()
    flat = (tw.WheelFlat(0.02, at_angle=math.pi),)
    v, runs = tw.kmh(100), {}
    for c in (0.0, 2e4):
        s = dataclasses.replace(base, supports=dataclasses.replace(base.supports, damping=c),
                                wheel=dataclasses.replace(base.wheel, defects=flat))
        runs[c] = tw.simulate(s, v, n_elements=20, dt=1e-5, progress=False)
    first = math.pi * base.wheel.radius / v + 0.3 * 2 * math.pi * base.wheel.radius / v
    peak = {c: r.normal_force[r.t < first].max() for c, r in runs.items()}
    assert peak[0.0] == pytest.approx(peak[2e4], rel=0.05)
    assert runs[0.0].normal_force.max() > 1.3 * runs[2e4].normal_force.max()
    assert runs[2e4].normal_force.max() < 1.1 * peak[2e4]
    assert len(runs[0.0].contact_free_intervals()) > 2 * len(runs[2e4].contact_free_intervals())
