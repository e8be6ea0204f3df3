"""The ``trackwheel`` command: what ``reproduce`` writes is what the library computes, and bad
arguments are argparse errors (exit code 2)."""

from __future__ import annotations

import io
import math
import shutil
import subprocess
import sys

import numpy as np
import pytest

import trackwheel as tw
from trackwheel import cli
from trackwheel.simulate import FIDELITY_LEVELS

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


#: what `reproduce` writes, figure by figure
FILES = {
    "fig3": ["fig3_eigen.csv", "fig3_eigen.png", "fig3_mode_shapes_x2.5m.png"],
    "fig4": ["fig4_time_step.csv", "fig4_time_step.png"],
    "fig5": ["fig5_elements.csv", "fig5_elements.png"],
    "fig6": ["fig6_support_stiffness.csv", "fig6_support_stiffness.png"],
    "fig7": ["fig7_speed.csv", "fig7_speed.png", "fig7_dynamic_300kmh.png"],
    "fig8": ["fig8_acceleration_terms.csv", "fig8_acceleration_terms.png"],
}


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    """The whole ``trackwheel reproduce --quick`` (about 20 s on two cores), run once."""
    out = tmp_path_factory.mktemp("paper-figures")
    code = cli.main(["reproduce", "--quick", "--out", str(out)])
    return code, out


def _csv(path):
    import pandas as pd

    # the python engine parses with float(): the shortest repr written by to_csv round-trips
    return pd.read_csv(path, engine="python", keep_default_na=False, na_values=[""])


def test_reproduce_writes_the_files(quick_run):
    code, out = quick_run
    assert code == 0
    for names in FILES.values():
        for name in names:
            if name.endswith(".png"):
                assert (out / name).read_bytes()[:8] == PNG_MAGIC, name
            else:
                assert len((out / name).read_text(encoding="utf-8").splitlines()) > 1, name
    text = (out / "summary.txt").read_text(encoding="utf-8")
    for fig in range(3, 9):
        assert f"Fig. {fig} --" in text
    assert "FAILED" not in text
    assert (out / cli.STORE_NAME).is_dir()


def test_reproduce_sweep_tables_cover_the_plan(quick_run):
    _, out = quick_run
    plan = cli.QUICK
    fig6 = _csv(out / "fig6_support_stiffness.csv")
    assert sorted(zip(fig6.speed_kmh, fig6.support_stiffness)) == sorted(
        (v, k) for v in plan.fig6_speeds_kmh for k in plan.stiffness)
    fig7 = _csv(out / "fig7_speed.csv")
    assert list(fig7.speed_kmh) == list(plan.speeds_kmh)
    assert set(fig7.support_stiffness) == {tw.Scene.kato2005().supports.stiffness}
    for df in (fig6, fig7):
        assert (df.error.isna() | (df.error == "")).all()
        assert set(df.n_elements) == {plan.simulate["n_elements"]}
        assert set(df.dt) == {plan.simulate["dt"]}


def test_reproduce_sweep_csv_equals_api(quick_run):
    """A row of the written table is exactly what simulate + analyse give for that case."""
    _, out = quick_run
    fig7 = _csv(out / "fig7_speed.csv")
    row = fig7[fig7.speed_kmh == 300.0].iloc[0]
    a = tw.analyse(tw.simulate(tw.Scene.kato2005(), tw.kmh(300), **cli.QUICK.simulate))
    assert row.amplitude == a.amplitude  # CSV floats are written to round-trip exactly
    assert row.main_frequency == a.main_frequency
    assert row.frequency_resolution == a.frequency_resolution
    assert row.max_contact_force == a.max_contact_force


def test_reproduce_convergence_tables(quick_run):
    _, out = quick_run
    plan = cli.QUICK
    fig4 = _csv(out / "fig4_time_step.csv")
    assert list(fig4.dt) == [*plan.fig4_explicit_dt, *plan.fig4_alpha_dt]
    assert list(fig4.integrator) == (["explicit"] * len(plan.fig4_explicit_dt)
                                     + ["generalized_alpha"] * len(plan.fig4_alpha_dt))
    v = tw.kmh(plan.fig4_speed_kmh)
    np.testing.assert_array_equal(fig4.steps, np.round(plan.fig4_stretch / v / fig4.dt))
    ref = fig4.dt == min(plan.fig4_explicit_dt)  # the reference: zero difference from itself
    assert (fig4.loc[ref, ["diff_y_contact", "diff_acc_contact"]].to_numpy() == 0.0).all()
    assert (fig4.loc[~ref, "diff_y_contact"] > 0.0).all()
    fig5 = _csv(out / "fig5_elements.csv")
    assert list(fig5.n_elements) == [*plan.fig5_n_elements] * 2
    finest = fig5.n_elements == max(plan.fig5_n_elements)
    assert (fig5.loc[finest, "diff_dynamic"] == 0.0).all()


def test_reproduce_acceleration_table_equals_api(quick_run):
    _, out = quick_run
    fig8 = _csv(out / "fig8_acceleration_terms.csv")
    assert sorted(set(fig8.speed_kmh)) == sorted(cli.QUICK.fig8_speeds_kmh)
    r = tw.simulate(tw.Scene.kato2005(), tw.kmh(100), **cli.QUICK.simulate)
    for term in "ABCDE":
        row = fig8[(fig8.speed_kmh == 100.0) & (fig8.term == term)].iloc[0]
        x = getattr(r, f"acc_{term}")
        assert row.max_abs == np.max(np.abs(x))
        assert row.rms == np.sqrt(np.mean(x**2))


def test_reproduce_resumes_from_the_store(quick_run, tmp_path):
    """A second run finds every sweep case in OUT/sweep-store and computes none."""
    _, out = quick_run
    again = tmp_path / "again"  # a copy of the store: the first run's files stay as they are
    shutil.copytree(out / cli.STORE_NAME, again / cli.STORE_NAME)
    log = io.StringIO()
    ctx = cli.reproduce(again, quick=True, only=["fig7"], stream=log)
    n = len(cli.QUICK.speeds_kmh)
    assert f"{n} cases (0 computed, {n} from" in log.getvalue()
    assert [p.name for p in ctx.written] == FILES["fig7"] + ["summary.txt"]


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
    # docs: Model § Validation, computed here from the formulas, printed to 0.1 Hz
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
    # explicit RK4 far above its stability limit (about 1e-5 s for 20 elements)
    with pytest.warns(tw.StabilityWarning):
        code = cli.main(["run", "--speed-kmh", "100", "--integrator", "explicit", "--dt", "1e-4",
                         "--n-elements", "20", "--x-end", "0.75"])
    assert code == 1
    assert "diverged" in capsys.readouterr().err


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
    (["run", "--speed-kmh", "0"], "positive"),
    (["run", "--speed-kmh", "100", "--dt", "1"], "dt"),                # longer than the run
    (["run", "--speed-kmh", "100", "--x-end", "9"], "--x-end"),        # beyond the rail
    (["run", "--speed-kmh", "100", "--fidelity", "bogus"], "fidelity"),
    (["run", "--speed-kmh", "100", "--integrator", "euler"], "integrator"),
    (["sweep", "--speeds-kmh", "100"], "--store"),
    (["sweep", "--speeds-kmh", "2000", "--store", "{tmp}"], "km/h"),
    (["sweep", "--speeds-kmh", "100", "100", "--store", "{tmp}"], "duplicate"),
    (["reproduce", "--out", "{tmp}", "--only", "fig9"], "fig9"),
])
def test_bad_run_sweep_arguments_exit_2(argv, word, tmp_path, capsys):
    argv = [a.replace("{tmp}", str(tmp_path / "x")) for a in argv]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err
    assert "error:" in err and word in err


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
