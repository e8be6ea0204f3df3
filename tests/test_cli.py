"""The ``trackwheel`` command: ``run``, ``sweep`` and ``eigen`` print what the library computes;
bad arguments and unusable output paths are one-line errors (exit code 2) found before anything
is computed, in the command line's units. (``reproduce``: tests/test_reproduce.py.)"""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import cli
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
    assert err[0].startswith("trackwheel run: warning: dt = 0.0001 s is above the predicted "
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
    assert sorted(zip(table.speed_kmh, table.support_stiffness)) == [
        (100.0, 40e6), (100.0, 140e6), (300.0, 40e6), (300.0, 140e6)]
    stored = tw.load_sweep(store)
    assert sorted(stored.amplitude) == sorted(table.amplitude)
    # one case against the API, exactly
    row = table[(table.speed_kmh == 300.0) & (table.support_stiffness == 140e6)].iloc[0]
    a = tw.analyse(tw.simulate(tw.Scene.kato2005(), tw.kmh(300), n_elements=20, dt=1e-5,
                               x_end=0.75))
    assert row.amplitude == a.amplitude and row.main_frequency == a.main_frequency
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
    (["run", "--speed-kmh", "0"], "positive speed"),
    (["run", "--speed-kmh", "100", "--dt", "1"], "dt"),                # longer than the run
    (["run", "--speed-kmh", "100", "--x-end", "9"], "--x-end"),        # beyond the rail
    (["run", "--speed-kmh", "100", "--fidelity", "bogus"], "fidelity"),
    (["run", "--speed-kmh", "100", "--integrator", "euler"], "integrator"),
    (["sweep", "--speeds-kmh", "100"], "--store"),
    (["sweep", "--speeds-kmh", "2000", "--store", "{tmp}"],
     "speed 2000 km/h is outside the allowed range 0–1080 km/h"),
    (["sweep", "--speeds-kmh", "100", "100", "--store", "{tmp}"], "duplicate"),
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
def test_speed_error_in_km_h(capsys):
    assert cli.main(["run", "--speed-kmh", "5000"]) == 2
    err = capsys.readouterr().err
    assert err == ("trackwheel run: error: --speed-kmh: speed 5000 km/h is outside the allowed "
                   "range 0–1080 km/h (a passage needs a positive speed)\n")


@pytest.mark.parametrize("value", ["-1e6", "-1E+6", "-2.5e7", "-.5e3", "-1000000"])
def test_negative_numbers_reach_validation(value, capsys):
    """argparse reads -1e6 as a value, and the library's range check answers, in one line."""
    assert cli.main(["run", "--speed-kmh", "100", "--support-stiffness", value, *CHEAP]) == 2
    err = capsys.readouterr().err
    assert err.startswith("trackwheel run: error: --support-stiffness = -")
    assert "is outside the allowed range (0.0, inf] N/m" in err and len(err.splitlines()) == 1


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
    monkeypatch.setattr(cli, "simulate", lambda *a, **k: calls.append(a))
    monkeypatch.setattr(cli, "sweep", lambda *a, **k: calls.append(a))
    monkeypatch.setattr(cli, "reproduce", lambda *a, **k: calls.append(a))
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


@pytest.mark.parametrize("stiffness, message", [
    (1e6, "the simulation could not start: static solve: the wheel lost contact with the rail"),
    (140e6, "the analysis failed: static solve: the wheel lost contact with the rail"),
])
def test_a_failed_static_solve_is_one_line(stiffness, message, capsys, monkeypatch):
    """A wheel load of 2e7 N pushes the rail through 1 MN/m supports at the start (the kernel's
    static solve fails), and through 140 MN/m ones somewhere along the quasi-static line of the
    analysis: exit code 1 and one line, not a traceback."""
    scene = tw.Scene.kato2005()
    heavy = dataclasses.replace(scene, wheel=dataclasses.replace(scene.wheel, load=2e7),
                                supports=dataclasses.replace(scene.supports, stiffness=stiffness))
    monkeypatch.setattr(cli, "_scene", lambda stiffness=None: heavy)
    assert cli.main(["run", "--speed-kmh", "100", *CHEAP]) == 1
    assert capsys.readouterr().err == f"trackwheel run: {message}\n"


@pytest.mark.parametrize("command", ["reproduce", "run", "sweep"])
def test_help_has_no_hand_typed_timings(command, capsys):
    """issue 16, item 9: timings come from the run or from benchmarks/, never the help text."""
    import re

    assert cli.main([command, "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert not re.search(r"\b(minutes?|hours?|seconds)\b|about \d+ ?s\b|µs", text), text
