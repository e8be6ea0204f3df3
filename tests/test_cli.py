"""The ``trackwheel`` command: what ``reproduce`` writes is what the library computes, and bad
arguments are argparse errors (exit code 2)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import cli

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("paper-figures")
    code = cli.main(["reproduce", "--quick", "--out", str(out)])
    return code, out


def test_reproduce_writes_the_files(quick_run):
    code, out = quick_run
    assert code == 0
    for name in ("fig3_eigen.png", "fig3_mode_shapes_x2.5m.png"):
        data = (out / name).read_bytes()
        assert data[:8] == PNG_MAGIC, name
    assert (out / "summary.txt").read_text(encoding="utf-8").strip()


def test_reproduce_csv_equals_library(quick_run):
    _, out = quick_run
    csv = out / "fig3_eigen.csv"
    header = csv.read_text(encoding="utf-8").splitlines()[0]
    assert header == "position_m,f1_hz,f2_hz,f3_hz,f4_hz"
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    scene = tw.Scene.kato2005()
    x = table[:, 0]
    # the sweep covers the whole rail, evenly
    assert x[0] == 0.0 and x[-1] == pytest.approx(scene.rail.length, abs=1e-12)
    np.testing.assert_allclose(np.diff(x), x[1] - x[0], rtol=1e-9)
    ref = tw.eigen(scene, x, n_modes=4).frequencies
    # written with 12 significant digits: relative rounding <= 5e-13
    np.testing.assert_allclose(table[:, 1:], ref, rtol=1e-11)
    assert np.all(np.diff(table[:, 1:], axis=1) >= 0.0)  # ascending modes in every row


def test_reproduce_summary_numbers(quick_run):
    _, out = quick_run
    text = (out / "summary.txt").read_text(encoding="utf-8")
    scene = tw.Scene.kato2005()
    f = tw.eigen(scene, [2.5], n_modes=4).frequencies[0]
    for fk in f:
        assert f"{fk:.1f} Hz" in text
    # MODEL.md §9, computed here from the formulas, printed to 0.1 Hz
    m, ei = scene.rail.mass_per_length, scene.rail.bending_stiffness
    cut_on = math.sqrt(scene.supports.stiffness / scene.supports.spacing / m) / (2 * math.pi)
    f_pp = math.pi / (2 * scene.supports.spacing**2) * math.sqrt(ei / m)
    f_1 = math.pi / (2 * scene.rail.length**2) * math.sqrt(ei / m)
    for ref in (cut_on, f_pp, f_1):
        assert f"{ref:.1f} Hz" in text


def test_eigen_command_prints_the_frequencies(capsys):
    assert cli.main(["eigen", "--position", "1.3", "--n-modes", "5"]) == 0
    printed = capsys.readouterr().out
    f = tw.eigen(tw.Scene.kato2005(), [1.3], n_modes=5).frequencies[0]
    rows = [line.split() for line in printed.splitlines() if line.strip().endswith("Hz")
            and line.split()[0].isdigit()]
    assert [int(r[0]) for r in rows] == [1, 2, 3, 4, 5]
    np.testing.assert_allclose([float(r[1]) for r in rows], f, atol=0.006)  # printed to 0.01


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
    assert "error:" in capsys.readouterr().err


def test_out_must_be_a_folder(tmp_path, capsys):
    f = tmp_path / "file.txt"
    f.write_text("x", encoding="utf-8")
    assert cli.main(["reproduce", "--quick", "--out", str(f)]) == 2
    assert "not a folder" in capsys.readouterr().err


@pytest.mark.parametrize("argv", [["--help"], ["reproduce", "--help"], ["eigen", "--help"]])
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
