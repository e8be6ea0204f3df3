"""``trackwheel reproduce``: what it writes is what the library computes, every CSV column carries
its unit, ``--only`` keeps the other figures' summary sections, and every concluding sentence of
the summary follows the data (checked with synthetic inputs that flip each conclusion)."""

from __future__ import annotations

import io
import math
import shutil

import numpy as np
import pandas as pd
import pytest

import trackwheel as tw
from trackwheel import cli
from trackwheel import reproduce as rp

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
#: column-name endings that state a unit; the other columns are counts, labels or flags
UNIT_SUFFIXES = ("_m", "_s", "_hz", "_N", "_N_m", "_m_s", "_m_s2", "_kmh", "_percent", "_1_s")
UNITLESS = {"run", "reference", "integrator", "n_elements", "steps", "term", "lost_contact",
            "error", "output_every", "rho_inf", "rolling", "start", "fidelity", "n_modes",
            "version", "case", "seed", "dynamic_factor", "wheel", "worst"}


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    """The whole ``trackwheel reproduce --quick``, through the command, run once."""
    out = tmp_path_factory.mktemp("paper-figures")
    code = cli.main(["reproduce", "--quick", "--out", str(out)])
    return code, out


def _csv(path):
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
        assert text.count(f"Fig. {fig} --") == 1
        assert (out / rp.SECTIONS_NAME / f"fig{fig}.txt").is_file()
    assert "FAILED" not in text
    assert (out / rp.STORE_NAME).is_dir()


def test_every_csv_column_carries_its_unit(quick_run):
    _, out = quick_run
    for names in FILES.values():
        for name in (n for n in names if n.endswith(".csv")):
            for col in _csv(out / name).columns:
                assert col in UNITLESS or col.endswith(UNIT_SUFFIXES), (name, col)


def test_reproduce_sweep_tables_cover_the_plan(quick_run):
    _, out = quick_run
    plan = rp.QUICK
    fig6 = _csv(out / "fig6_support_stiffness.csv")
    assert sorted(zip(fig6.speed_kmh, fig6.support_stiffness_N_m)) == sorted(
        (v, k) for v in plan.fig6_speeds_kmh for k in plan.stiffness)
    fig7 = _csv(out / "fig7_speed.csv")
    assert list(fig7.speed_kmh) == list(plan.speeds_kmh)
    np.testing.assert_allclose(fig7.speed_m_s, fig7.speed_kmh / 3.6, rtol=1e-15)
    assert set(fig7.support_stiffness_N_m) == {tw.Scene.kato2005().supports.stiffness}
    for df in (fig6, fig7):
        assert (df.error.isna() | (df.error == "")).all()
        assert set(df.n_elements) == {plan.simulate["n_elements"]}
        assert set(df.dt_s) == {plan.simulate["dt"]}


def test_reproduce_sweep_csv_equals_api(quick_run):
    """A row of the written table is exactly what simulate + analyse give for that case."""
    _, out = quick_run
    fig7 = _csv(out / "fig7_speed.csv")
    row = fig7[fig7.speed_kmh == 300.0].iloc[0]
    a = tw.analyse(tw.simulate(tw.Scene.kato2005(), tw.kmh(300), **rp.QUICK.simulate))
    assert row.amplitude_m == a.amplitude  # CSV floats are written to round-trip exactly
    assert row.main_frequency_hz == a.main_frequency
    assert row.frequency_resolution_hz == a.frequency_resolution
    assert row.max_contact_force_N == a.max_contact_force


def test_reproduce_convergence_tables(quick_run):
    _, out = quick_run
    plan = rp.QUICK
    fig4 = _csv(out / "fig4_time_step.csv")
    assert list(fig4.dt_s) == [*plan.fig4_explicit_dt, *plan.fig4_alpha_dt]
    assert list(fig4.integrator) == (["explicit"] * len(plan.fig4_explicit_dt)
                                     + ["generalized_alpha"] * len(plan.fig4_alpha_dt))
    v = tw.kmh(plan.fig4_speed_kmh)
    np.testing.assert_array_equal(fig4.steps, np.round(plan.fig4_stretch / v / fig4.dt_s))
    ref = fig4.dt_s == min(plan.fig4_explicit_dt)  # the reference: zero difference from itself
    assert (fig4.loc[ref, ["diff_y_contact_m", "diff_acc_contact_m_s2"]].to_numpy() == 0).all()
    assert (fig4.loc[~ref, "diff_y_contact_m"] > 0.0).all()
    fig5 = _csv(out / "fig5_elements.csv")
    assert list(fig5.n_elements) == [*plan.fig5_n_elements] * 2
    finest = fig5.n_elements == max(plan.fig5_n_elements)
    assert (fig5.loc[finest, "diff_dynamic_m"] == 0.0).all()


def test_reproduce_acceleration_table_equals_api(quick_run):
    _, out = quick_run
    fig8 = _csv(out / "fig8_acceleration_terms.csv")
    assert sorted(set(fig8.speed_kmh)) == sorted(rp.QUICK.fig8_speeds_kmh)
    r = tw.simulate(tw.Scene.kato2005(), tw.kmh(100), **rp.QUICK.simulate)
    for term in "ABCDE":
        row = fig8[(fig8.speed_kmh == 100.0) & (fig8.term == term)].iloc[0]
        x = getattr(r, f"acc_{term}")
        assert row.max_abs_m_s2 == np.max(np.abs(x))
        assert row.rms_m_s2 == np.sqrt(np.mean(x**2))


def test_reproduce_resumes_from_the_store(quick_run, tmp_path):
    """A second run finds every sweep case in OUT/sweep-store and computes none."""
    _, out = quick_run
    again = tmp_path / "again"  # a copy of the store: the first run's files stay as they are
    shutil.copytree(out / rp.STORE_NAME, again / rp.STORE_NAME)
    log = io.StringIO()
    ctx = rp.reproduce(again, quick=True, only=["fig7"], stream=log)
    n = len(rp.QUICK.speeds_kmh)
    assert f"{n} cases (0 computed, {n} from" in log.getvalue()
    assert [p.name for p in ctx.written] == FILES["fig7"] + ["fig7.txt", "summary.txt"]


def _sections(text: str) -> dict[str, str]:
    """summary.txt split at its "Fig. N --" headings, without the timing line of each."""
    out, key = {}, None
    for line in text.splitlines():
        if line.startswith("Fig. "):
            key = line.split(" --")[0]
            out[key] = []
        elif key is not None and not line.strip().startswith("("):
            out[key].append(line)
    return {k: "\n".join(v) for k, v in out.items()}


def test_only_keeps_the_other_sections(quick_run, tmp_path):
    """--only fig8 refreshes the Fig. 8 section and keeps Figs. 3-7 from the earlier run."""
    _, out = quick_run
    again = tmp_path / "again"
    shutil.copytree(out, again)
    before = (again / "summary.txt").read_text(encoding="utf-8")
    assert cli.main(["reproduce", "--quick", "--out", str(again), "--only", "fig8"]) == 0
    after = (again / "summary.txt").read_text(encoding="utf-8")
    old, new = _sections(before), _sections(after)
    assert list(new) == [f"Fig. {k}" for k in range(3, 9)]
    for k in range(3, 8):  # untouched, byte for byte, timing line included
        assert (again / rp.SECTIONS_NAME / f"fig{k}.txt").read_bytes() == (
            out / rp.SECTIONS_NAME / f"fig{k}.txt").read_bytes()
    assert new == old  # fig8 recomputed: deterministic, so the same numbers


def test_only_in_a_fresh_folder_accumulates_sections(tmp_path):
    log = io.StringIO()
    rp.reproduce(tmp_path, quick=True, only=["fig3"], stream=log)
    assert list(_sections((tmp_path / "summary.txt").read_text(encoding="utf-8"))) == ["Fig. 3"]
    rp.reproduce(tmp_path, quick=True, only=["fig8"], stream=log)
    text = (tmp_path / "summary.txt").read_text(encoding="utf-8")
    assert list(_sections(text)) == ["Fig. 3", "Fig. 8"]
    assert text.count("quick plan; computed in") == 2


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
    ref = tw.eigen(scene, x, n_modes=4, n_elements=scene.rail.n_elements).frequencies  # Fig. 3
    # written with 12 significant digits: relative rounding <= 5e-13
    np.testing.assert_allclose(table[:, 1:], ref, rtol=1e-11)
    assert np.all(np.diff(table[:, 1:], axis=1) >= 0.0)  # ascending modes in every row


def test_reproduce_summary_numbers(quick_run):
    _, out = quick_run
    text = (out / "summary.txt").read_text(encoding="utf-8")
    scene = tw.Scene.kato2005()
    f = tw.eigen(scene, [2.5], n_modes=4, n_elements=scene.rail.n_elements).frequencies[0]
    for fk in f:
        assert f"{fk:.1f} Hz" in text
    # docs: Model § Validation, computed here from the formulas, printed to 0.1 Hz
    m, ei = scene.rail.mass_per_length, scene.rail.bending_stiffness
    cut_on = math.sqrt(scene.supports.stiffness / scene.supports.spacing / m) / (2 * math.pi)
    f_pp = math.pi / (2 * scene.supports.spacing**2) * math.sqrt(ei / m)
    f_1 = math.pi / (2 * scene.rail.length**2) * math.sqrt(ei / m)
    for ref in (cut_on, f_pp, f_1):
        assert f"{ref:.1f} Hz" in text


def test_summary_states_no_hand_typed_timing(quick_run):
    """Timings in the summary are measured in the run (per step, per section), never typed."""
    _, out = quick_run
    text = (out / "summary.txt").read_text(encoding="utf-8")
    assert "~70" not in text and "hours" not in text
    assert "µs per step here" in text


# ---- the conclusions follow the data ----------------------------------------------------------
LO = np.array([300.0, 380.0, 420.0, 600.0])  #: mode bands [Hz] over the wheel positions
HI = np.array([350.0, 400.0, 480.0, 700.0])


def test_fig7_conclusion_names_the_mode_the_data_follow():
    amp = [1e-6, 2e-6, 3e-6]
    lowest = " ".join(rp.fig7_conclusions(amp, [340.0, 342.0, 345.0], LO, HI))
    assert "follows mode 1 at every speed, the first mode (300-350 Hz)" in lowest
    assert "not the paper's third mode (420-480 Hz)" in lowest
    third = " ".join(rp.fig7_conclusions(amp, [430.0, 440.0, 450.0], LO, HI))
    assert "follows mode 3" in third and "as in the paper, the third mode" in third
    mixed = " ".join(rp.fig7_conclusions(amp, [340.0, 390.0, 450.0], LO, HI))
    assert "moves between modes 1, 2, 3" in mixed
    assert "increasing with speed -- yes (1.00 to 3.00 µm)" in lowest
    assert "increasing with speed -- NO" in " ".join(
        rp.fig7_conclusions([3e-6, 2e-6, 1e-6], [340.0] * 3, LO, HI))


def test_fig8_conclusion_states_the_measured_size_of_c_d_e():
    def rms(c):
        return pd.DataFrame({100.0: [1.0, 2.0, c, c, c], 300.0: [9.0, 18.0, 9 * c, 9 * c, 9 * c]},
                            index=list("ABCDE"))

    small = rp.fig8_conclusions(rms(1e-4))[0]
    assert "C, D, E are at most 0.0001 of the smaller of A, B (order 1e-4)" in small
    assert "rms ratio 300/100 km/h = 9.0..9.0 (v² ratio 9.0)" in small
    assert "order 1e-2" in rp.fig8_conclusions(rms(3e-2))[0]
    assert "C, D, E reach 2 times the smaller of A, B" in rp.fig8_conclusions(rms(2.0))[0]


def test_fig6_conclusions_follow_the_tables():
    k = [20e6, 70e6, 140e6]
    amp = pd.DataFrame({100.0: [3e-6, 2e-6, 1e-6], 300.0: [6e-6, 5e-6, 1.5e-6]}, index=k)
    freq = pd.DataFrame({100.0: [300.0, 320.0, 340.0], 300.0: [300.0, 330.0, 320.0]}, index=k)
    text = " ".join(rp.fig6_conclusions(amp, freq))
    assert "amplitude decreasing with k_s -- 100 km/h: yes, 300 km/h: yes" in text
    assert "main frequency rising with k_s -- 100 km/h: yes, 300 km/h: NO" in text
    assert "ratio 300/100 km/h 1.50..2.50, largest at k_s = 70 MN/m" in text
    amp[300.0] = [6e-6, 7e-6, 1.5e-6]
    assert "300 km/h: NO" in rp.fig6_conclusions(amp, freq)[0]


def test_convergence_conclusion_finds_the_coarsest_agreeing_run():
    rows = [  # dt [s], largest d difference [m], largest acceleration difference [m/s^2]
        ("explicit", 1e-6, 0.5e-8, 50.0), ("explicit", 1e-7, 1e-10, 5.0),
        ("explicit", 1e-8, 0.0, 0.0), ("generalized_alpha", 1e-5, 5e-8, 200.0)]
    table = pd.DataFrame([{"integrator": i, "dt_s": dt, "run": f"{i} {dt}",
                           "reference": "explicit 1e-08", "diff_dynamic_m": dd,
                           "diff_acc_contact_m_s2": da, "ref_amplitude_m": 1e-6,
                           "ref_max_abs_acc_contact_m_s2": 1000.0} for i, dt, dd, da in rows])
    lines = rp.convergence_conclusions(table, "dt")
    assert lines[0].endswith("(explicit): coarsest run within 1% of its reference -- "
                             "d from dt = 1e-06 s; acceleration from dt = 1e-07 s.")
    assert lines[1].endswith("-- d at none of the runs; acceleration at none of the runs.")


def test_passage_cost_sentence_is_computed():
    # 1 ms per step; 4.5 m at 12.5 m/s with dt = 1e-8 s is 3.6e7 steps: 3.6e4 s = 10 h
    text = rp.passage_cost_sentence(1.0, 1000, 1e-8, 4.5, 12.5)
    assert "cost 1000 µs per step here" in text and "about 10 h" in text
    assert "about 36 s" in rp.passage_cost_sentence(1.0, 1000, 1e-5, 4.5, 12.5)
