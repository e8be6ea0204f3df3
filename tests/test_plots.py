"""trackwheel.plots: Figures with unit-labelled axes that show exactly the result's arrays,
drawn without pyplot's global state."""

from __future__ import annotations

import dataclasses as dc
import subprocess
import sys

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure

import trackwheel as tw
from trackwheel import plots

# plots needs no backend (Figure objects, no pyplot); Agg is for the pyplot check below, so
# that it never looks for a display.
matplotlib.use("Agg")


@pytest.fixture(scope="module")
def sweep():
    scene = tw.Scene.kato2005()
    return tw.eigen(scene, np.linspace(0.0, scene.rail.length, 21), n_modes=5)


def _mode_lines(ax):
    return [ln for ln in ax.get_lines() if ln.get_label().startswith("mode ")]


def test_eigen_figure_shows_the_frequencies(sweep):
    fig = plots.eigen(sweep)
    assert isinstance(fig, Figure)
    (ax,) = fig.axes
    assert "[m]" in ax.get_xlabel() and "[Hz]" in ax.get_ylabel()
    lines = _mode_lines(ax)
    assert [ln.get_label() for ln in lines] == ["mode 1", "mode 2", "mode 3", "mode 4"]
    for k, ln in enumerate(lines):
        np.testing.assert_array_equal(ln.get_xdata(), sweep.positions)
        np.testing.assert_array_equal(ln.get_ydata(), sweep.frequencies[:, k])
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend[-4:] == ["mode 1", "mode 2", "mode 3", "mode 4"]


def test_eigen_figure_marks_the_supports(sweep):
    ax = plots.eigen(sweep).axes[0]
    vertical = sorted(float(ln.get_xdata()[0]) for ln in ax.get_lines()
                      if not ln.get_label().startswith("mode ") and np.ptp(ln.get_xdata()) == 0)
    expected = sorted([*sweep.scene.support_positions, 0.0, sweep.scene.rail.length])
    assert vertical == expected  # drawn at exactly these X


def test_eigen_into_given_axes_and_no_pyplot_state(sweep):
    import matplotlib.pyplot as plt

    before = plt.get_fignums()
    fig = plots.eigen(sweep, n_modes=2)
    plots.mode_shapes(sweep, 3)
    assert plt.get_fignums() == before  # nothing registered with pyplot

    own = Figure()
    ax = own.add_subplot()
    assert plots.eigen(sweep, n_modes=3, ax=ax) is own
    assert len(_mode_lines(ax)) == 3
    assert len(_mode_lines(fig.axes[0])) == 2


def test_mode_shapes_show_rail_and_wheel(sweep):
    i_pos = 10  # X = 2.5 m
    modes = [0, 2, 3]
    fig = plots.mode_shapes(sweep, i_pos, modes=modes)
    assert isinstance(fig, Figure)
    assert len(fig.axes) == len(modes)
    assert "[m]" in fig.axes[-1].get_xlabel()
    x_wheel = sweep.positions[i_pos]
    for ax, m in zip(fig.axes, modes):
        assert "[-]" in ax.get_ylabel()
        assert f"{sweep.frequencies[i_pos, m]:.1f} Hz" in ax.get_title(loc="left")
        s, y, wheel = sweep.rail_mode_shape(i_pos, m)
        (rail,) = [ln for ln in ax.get_lines() if ln.get_label() == "rail y(s)"]
        (dot,) = [ln for ln in ax.get_lines() if ln.get_label() == "wheel"]
        np.testing.assert_array_equal(rail.get_xdata(), s)
        np.testing.assert_array_equal(rail.get_ydata(), y)
        np.testing.assert_array_equal(dot.get_xdata(), [x_wheel])
        np.testing.assert_array_equal(dot.get_ydata(), [wheel])


def test_default_mode_shapes_are_the_lowest_four(sweep):
    fig = plots.mode_shapes(sweep, 0)
    titles = [ax.get_title(loc="left") for ax in fig.axes]
    assert [t.split(":")[0] for t in titles] == ["mode 1", "mode 2", "mode 3", "mode 4"]


def test_figures_save_as_png(sweep, tmp_path):
    for name, fig in (("a.png", plots.eigen(sweep)), ("b.png", plots.mode_shapes(sweep, 0))):
        fig.savefig(tmp_path / name)
        assert (tmp_path / name).read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("call, exc, word", [
    (lambda r: plots.eigen("not a result"), TypeError, "EigenResult"),
    (lambda r: plots.eigen(r, n_modes=6), ValueError, "n_modes"),   # result has 5
    (lambda r: plots.eigen(r, n_modes=0), ValueError, "n_modes"),
    (lambda r: plots.mode_shapes(r, 21), ValueError, "i_pos"),       # 21 positions
    (lambda r: plots.mode_shapes(r, 0, modes=[5]), ValueError, "modes"),
    (lambda r: plots.mode_shapes(r, 0, modes=[]), ValueError, "modes"),
])
def test_bad_arguments(sweep, call, exc, word):
    with pytest.raises(exc, match=word):
        call(sweep)


def test_import_trackwheel_does_not_import_matplotlib():
    code = "import sys, trackwheel; sys.exit('matplotlib' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], check=False).returncode == 0


# ------------------------------------------------------------------------------------------
# time simulations and sweeps. Short, coarse runs: the figures must show exactly the arrays
# they are given, whatever their physics.
SHORT = {"n_elements": 20, "x_start": 0.25, "x_end": 0.30}


@pytest.fixture(scope="module")
def runs():
    """Two passages over 5 cm at 100 km/h (generalized-alpha at 1e-5 and 5e-6 s) and one at
    300 km/h on a 10-element mesh."""
    scene = tw.Scene.kato2005()
    a = tw.simulate(scene, tw.kmh(100), dt=1e-5, **SHORT)
    b = tw.simulate(scene, tw.kmh(100), dt=5e-6, **SHORT)
    c = tw.simulate(scene, tw.kmh(300), dt=1e-5, **dict(SHORT, n_elements=10))
    return a, b, c


def _labelled(ax, label):
    (line,) = [ln for ln in ax.get_lines() if ln.get_label() == label]
    return line


@pytest.mark.parametrize("func", [plots.time_step_convergence, plots.element_convergence])
def test_convergence_figures_show_each_run(runs, func):
    fig = func(list(runs))
    assert isinstance(fig, Figure)
    ax_y, ax_v, ax_a, ax_diff = fig.axes
    assert "[mm]" in ax_y.get_ylabel() and "[%]" in ax_v.get_ylabel()
    assert "[m/s²]" in ax_a.get_ylabel() and "[m/s²]" in ax_diff.get_ylabel()
    assert "[m]" in ax_diff.get_xlabel()
    legend = [t.get_text() for t in ax_y.get_legend().get_texts()]
    assert len(legend) == 3
    for r, label in zip(runs, legend):
        for ax, y in ((ax_y, r.y_contact * 1e3), (ax_v, r.v_error), (ax_a, r.acc_contact)):
            line = _labelled(ax, label)
            np.testing.assert_array_equal(line.get_xdata(), r.x_wheel)
            np.testing.assert_array_equal(line.get_ydata(), y)


def test_v_e_is_defined_on_the_convergence_figures(runs):
    """The velocity error's definition (the paper's eq. 28) is written on the figure."""
    for fig in (plots.time_step_convergence(runs), plots.element_convergence(runs[:2],
                                                                              acceleration=False)):
        title = fig.axes[1].get_title(loc="left")
        assert "v_e" in title and r"\dot{X}_A" in title and r"\rho\,\dot{\theta}" in title
        assert "100" in title and "eq. 28" in title


@pytest.mark.parametrize("func, finest", [(plots.time_step_convergence, 1),  # dt = 5e-6 s
                                          (plots.element_convergence, 1)])  # 20 el., 5e-6 s
def test_convergence_difference_panel_is_from_the_finest_run(runs, func, finest):
    """Bottom panel: each other run's acceleration minus the finest run's, the latter linearly
    interpolated at the run's wheel positions; the finest run itself is not drawn there."""
    fig = func(list(runs))
    ax_diff = fig.axes[3]
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels[finest] in ax_diff.get_title(loc="left")
    drawn = [ln for ln in ax_diff.get_lines() if ln.get_gid() == "difference"]
    assert [ln.get_label() for ln in drawn] == [lab for i, lab in enumerate(labels)
                                                if i != finest]
    ref = runs[finest]
    for ln in drawn:
        r = runs[labels.index(ln.get_label())]
        np.testing.assert_array_equal(ln.get_xdata(), r.x_wheel)
        # independent check of the interpolation at every sample inside the reference stretch:
        # between reference samples x0 <= x <= x1 the reference is the straight line through
        # them (exact up to round-off of the interpolation weights)
        inside = (r.x_wheel >= ref.x_wheel[0]) & (r.x_wheel <= ref.x_wheel[-1])
        j = np.clip(np.searchsorted(ref.x_wheel, r.x_wheel[inside]), 1, ref.x_wheel.size - 1)
        x0, x1 = ref.x_wheel[j - 1], ref.x_wheel[j]
        w = (r.x_wheel[inside] - x0) / (x1 - x0)
        a_ref = (1 - w) * ref.acc_contact[j - 1] + w * ref.acc_contact[j]
        scale = np.max(np.abs(ref.acc_contact))
        np.testing.assert_allclose(ln.get_ydata()[inside], r.acc_contact[inside] - a_ref,
                                   rtol=0, atol=1e-12 * scale)
        assert np.all(np.isnan(ln.get_ydata()[~inside]))
    # an explicit reference overrides the finest
    other = func(list(runs), reference=0)
    assert labels[0] in other.axes[3].get_title(loc="left")


def test_convergence_legends_name_the_setting(runs):
    ts = plots.time_step_convergence(runs[:2], acceleration=False)
    assert len(ts.axes) == 2  # no acceleration panel
    labels = [t.get_text() for t in ts.axes[0].get_legend().get_texts()]
    assert labels == ["generalized-α, dt = 1e-5 s", "generalized-α, dt = 5e-6 s"]
    el = plots.element_convergence([runs[0], runs[2]])
    labels = [t.get_text() for t in el.axes[0].get_legend().get_texts()]
    assert labels == ["20 elements", "10 elements"]  # same integrator and dt: mesh only
    mixed = plots.element_convergence([runs[1], runs[2]])
    labels = [t.get_text() for t in mixed.axes[0].get_legend().get_texts()]
    assert labels == ["20 elements, generalized-α, dt = 5e-6 s",
                      "10 elements, generalized-α, dt = 1e-5 s"]
    assert len(el.axes) == 4  # y_B, v_e, acceleration, difference from the finest
    own = plots.time_step_convergence(runs[:2], labels=["a", "b"], title="T")
    assert [t.get_text() for t in own.axes[0].get_legend().get_texts()] == ["a", "b"]
    assert own._suptitle.get_text() == "T"


def test_format_dt():
    assert [plots.format_dt(x) for x in (1e-7, 5e-6, 2.5e-5, 1.0)] == [
        "1e-7", "5e-6", "2.5e-5", "1e0"]


@pytest.mark.parametrize("against, scale", [("position", None), ("time", 1e3)])
def test_acceleration_terms_show_A_to_E(runs, against, scale):
    two = [runs[0], runs[2]]
    fig = plots.acceleration_terms(two, against=against)
    assert isinstance(fig, Figure)
    assert len(fig.axes) == 4  # (run, column)
    for i, r in enumerate(two):
        left, right = fig.axes[2 * i], fig.axes[2 * i + 1]
        x = r.x_wheel if scale is None else r.t * scale
        for ax, terms in ((left, "AB"), (right, "CDE")):
            assert "[m/s²]" in ax.get_ylabel()
            lines = ax.get_lines()[: len(terms)]  # the zero line is drawn after them
            assert [ln.get_label()[0] for ln in lines] == list(terms)
            for ln, term in zip(lines, terms):
                np.testing.assert_array_equal(ln.get_xdata(), x)
                np.testing.assert_array_equal(ln.get_ydata(), getattr(r, f"acc_{term}"))
        assert f"{r.settings['speed'] * 3.6:g} km/h" in left.get_title(loc="left")
    unit = "[m]" if against == "position" else "[ms]"
    assert unit in fig.axes[-1].get_xlabel()
    # one y scale per column, so the growth with speed is seen directly
    assert fig.axes[0].get_ylim() == fig.axes[2].get_ylim()
    assert fig.axes[1].get_ylim() == fig.axes[3].get_ylim()
    # C and D are nearly equal (D ~ C for a travelling bowl): C wide underneath, D thin on top
    c, d = _labelled_start(fig.axes[1], "C"), _labelled_start(fig.axes[1], "D")
    assert c.get_linewidth() >= 3 * d.get_linewidth() and c.get_zorder() < d.get_zorder()


def _labelled_start(ax, start):
    (line,) = [ln for ln in ax.get_lines() if ln.get_label().startswith(start)]
    return line


def test_dynamic_figure_shows_the_analysis(runs):
    r = runs[0]
    a = tw.analyse(r)
    eig = tw.eigen(r.scene, np.linspace(0.0, 5.0, 6), n_modes=4)
    fig = plots.dynamic(r, a, eigen=eig, n_modes=2)
    ax_y, ax_d, ax_f = fig.axes
    assert "[mm]" in ax_y.get_ylabel() and "[m]" in ax_y.get_xlabel()
    assert "[µm]" in ax_d.get_ylabel() and "[µm]" in ax_f.get_ylabel()
    assert "[Hz]" in ax_f.get_xlabel()
    np.testing.assert_array_equal(_labelled(ax_y, "y_B").get_ydata(), a.y_contact * 1e3)
    np.testing.assert_array_equal(_labelled(ax_y, "y_qs").get_ydata(), a.y_qs * 1e3)
    d = _labelled(ax_d, "d")
    np.testing.assert_array_equal(d.get_xdata(), a.x_wheel)
    np.testing.assert_array_equal(d.get_ydata(), a.dynamic * 1e6)
    (peak,) = [ln for ln in ax_d.get_lines() if ln.get_label().startswith("amplitude")]
    assert abs(peak.get_ydata()[0]) == pytest.approx(a.amplitude * 1e6, rel=1e-15)
    freqs, amps = a.spectrum
    spec = _labelled(ax_f, "|D(f)|")
    keep = freqs <= ax_f.get_xlim()[1]
    np.testing.assert_array_equal(spec.get_xdata(), freqs[keep])
    np.testing.assert_array_equal(spec.get_ydata(), amps[keep] * 1e6)
    (main,) = [ln for ln in ax_f.get_lines() if ln.get_gid() == "main frequency"]
    assert main.get_xdata()[0] == a.main_frequency
    assert f"{a.main_frequency:.1f} Hz" in main.get_label()
    bands = {ln.get_gid(): ln.get_xdata()[0] for ln in ax_f.get_lines()
             if (ln.get_gid() or "").startswith("eigen")}
    assert set(bands) == {f"eigen mode {k} {e}" for k in (1, 2) for e in ("min", "max")}
    assert bands["eigen mode 2 max"] == eig.frequencies[:, 1].max()
    # the analysis is computed when not given: the same figure data
    again = plots.dynamic(r)
    np.testing.assert_array_equal(_labelled(again.axes[1], "d").get_ydata(), a.dynamic * 1e6)


def _table():
    """A sweep table as trackwheel.sweep returns it (the columns the plots read), rows out of
    order, one failed case (NaN outputs)."""
    import pandas as pd

    rows = []
    for v in (300.0, 100.0):
        for k in (140e6, 20e6, 70e6):
            rows.append({"speed_m_s": v / 3.6, "speed_kmh": v, "support_stiffness_N_m": k,
                         "amplitude_m": 1e-6 * v / 100 * 140e6 / k,
                         "main_frequency_hz": 340.0 * np.sqrt(k / 140e6),
                         "frequency_resolution_hz": v / 16.0, "error": ""})
    rows[1].update(amplitude_m=np.nan, main_frequency_hz=np.nan, error="DivergenceError: x")
    return pd.DataFrame(rows)


def test_support_stiffness_figure_shows_the_table():
    df = _table()
    fig = plots.support_stiffness(df, frequency=True)
    ax_a, ax_f = fig.axes
    assert "[µm]" in ax_a.get_ylabel() and "[Hz]" in ax_f.get_ylabel()
    assert "[MN/m]" in ax_f.get_xlabel()
    span = (140e6 - 20e6) / 1e6  # the table's k_s range [MN/m]
    for i, v in enumerate((100.0, 300.0)):
        ref = df[df.speed_kmh == v].sort_values("support_stiffness_N_m")
        x = ref.support_stiffness_N_m.to_numpy() / 1e6
        shift = (i - 0.5) * plots.DODGE * span  # two series: half a dodge either side
        for ax, y, dx in ((ax_a, ref.amplitude_m * 1e6, 0.0), (ax_f, ref.main_frequency_hz, shift)):
            line = _labelled(ax, f"{v:g} km/h")
            np.testing.assert_allclose(line.get_xdata(), x + dx, rtol=1e-15)
            np.testing.assert_array_equal(line.get_ydata(), y)  # NaN where the case failed
    single = plots.support_stiffness(df)
    assert len(single.axes) == 1


def test_support_stiffness_error_bars_are_not_hidden_by_the_other_speed():
    """Fig. 6's frequency panel: at each stiffness the two speeds' points stand further apart
    than a marker's radius, so neither series' error bar runs through the other's marker; the
    markers are open and the bars drawn over them."""
    fig = plots.support_stiffness(_table(), frequency=True)
    fig.draw_without_rendering()
    ax_f = fig.axes[1]
    slow, fast = _labelled(ax_f, "100 km/h"), _labelled(ax_f, "300 km/h")
    radius_px = 0.5 * slow.get_markersize() * fig.dpi / 72.0
    to_px = ax_f.transData.transform
    xs = to_px(np.column_stack([slow.get_xdata(), slow.get_ydata()]))[:, 0]
    xf = to_px(np.column_stack([fast.get_xdata(), fast.get_ydata()]))[:, 0]
    both = np.isfinite(xs) & np.isfinite(xf)  # the failed case has no point
    assert both.sum() == 2 and np.all(np.abs(xf - xs)[both] > radius_px)
    for line in (slow, fast):
        assert line.get_markerfacecolor() == "none"
    bars = [c for c in ax_f.collections if len(c.get_segments()) > 0]
    assert len(bars) == 2 and all(c.get_zorder() > slow.get_zorder() for c in bars)


def test_speed_figure_shows_the_table_and_the_eigen_bands():
    df = _table()
    df = df[df.support_stiffness_N_m == 140e6]
    eig = tw.eigen(tw.Scene.kato2005(), np.linspace(0.0, 5.0, 11), n_modes=5)
    fig = plots.speed(df, eig)
    ax_a, ax_f = fig.axes
    assert "[µm]" in ax_a.get_ylabel() and "[Hz]" in ax_f.get_ylabel()
    assert "[km/h]" in ax_f.get_xlabel()
    ref = df.sort_values("speed_kmh")
    for ax, y in ((ax_a, ref.amplitude_m * 1e6), (ax_f, ref.main_frequency_hz)):
        line = _labelled(ax, "k_s = 140 MN/m")
        np.testing.assert_array_equal(line.get_xdata(), ref.speed_kmh)
        np.testing.assert_array_equal(line.get_ydata(), y)
    bands = {ln.get_gid(): ln.get_ydata()[0] for ln in ax_f.get_lines()
             if (ln.get_gid() or "").startswith("eigen")}
    assert len(bands) == 8  # 4 modes x (min, max)
    for k in range(4):
        assert bands[f"eigen mode {k + 1} min"] == eig.frequencies[:, k].min()
        assert bands[f"eigen mode {k + 1} max"] == eig.frequencies[:, k].max()
    legend = [t.get_text() for t in ax_f.get_legend().get_texts()]
    lo, hi = eig.frequencies[:, 0].min(), eig.frequencies[:, 0].max()
    assert f"mode 1: {lo:.0f}–{hi:.0f} Hz" in legend


def test_new_figures_leave_no_pyplot_state(runs):
    import matplotlib.pyplot as plt

    before = plt.get_fignums()
    plots.time_step_convergence(runs)
    plots.element_convergence(runs)
    plots.acceleration_terms(runs)
    plots.dynamic(runs[0])
    plots.support_stiffness(_table())
    plots.speed(_table())
    assert plt.get_fignums() == before


@pytest.mark.parametrize("call, exc, word", [
    (lambda r: plots.time_step_convergence([]), ValueError, "results"),
    (lambda r: plots.time_step_convergence(["x"]), TypeError, "Result"),
    (lambda r: plots.time_step_convergence(3), TypeError, "results"),
    (lambda r: plots.element_convergence(r, labels=["a"]), ValueError, "labels"),
    (lambda r: plots.element_convergence(r, labels="abc"), TypeError, "labels"),
    (lambda r: plots.acceleration_terms(r, against="speed"), ValueError, "against"),
    (lambda r: plots.dynamic(list(r)), TypeError, "Result"),
    (lambda r: plots.dynamic(r[0], "analysis"), TypeError, "Analysis"),
    (lambda r: plots.dynamic(r[0], tw.analyse(r[1])), ValueError, "analysis"),
    (lambda r: plots.dynamic(r[0], f_max=-1.0), ValueError, "f_max"),
    (lambda r: plots.support_stiffness(_table().drop(columns="amplitude_m")), TypeError,
     "amplitude_m"),
    (lambda r: plots.support_stiffness(_table().iloc[:0]), ValueError, "empty"),
    (lambda r: plots.support_stiffness(_table(), frequency=True, ax=Figure().add_subplot()),
     ValueError, "ax"),
    (lambda r: plots.speed({"speed_kmh": [1]}), TypeError, "sweep table"),
    (lambda r: plots.speed(_table(), tw.eigen(tw.Scene.kato2005(), [1.0])), ValueError,
     "k_s"),
    (lambda r: plots.speed(_table()[_table().support_stiffness_N_m == 140e6],
                           tw.eigen(tw.Scene.kato2005(), [1.0], n_modes=2)), ValueError,
     "n_modes"),
])
def test_bad_arguments_of_the_new_figures(runs, call, exc, word):
    with pytest.raises(exc, match=word):
        call(runs)


def _figures_with_legends(runs, sweep):
    df = _table()
    eig = tw.eigen(tw.Scene.kato2005(), np.linspace(0.0, 5.0, 11), n_modes=5)
    return {
        "fig3": plots.eigen(sweep),
        "mode shapes": plots.mode_shapes(sweep, 10),
        "fig4": plots.time_step_convergence(runs),
        "fig5": plots.element_convergence(runs),
        "fig6": plots.support_stiffness(df, frequency=True),
        "fig7": plots.speed(df[df.support_stiffness_N_m == 140e6], eig),
        "fig7 dynamic": plots.dynamic(runs[0], eigen=eig),
        "fig8": plots.acceleration_terms([runs[0], runs[2]]),
    }


def test_legends_hide_no_data(runs, sweep):
    """Every legend lies outside every axes of its figure (touching allowed), so it covers no
    data, whatever the data; the legends are in the figure (not clipped away)."""
    for name, fig in _figures_with_legends(runs, sweep).items():
        fig.draw_without_rendering()
        legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
        assert legends, name
        fig_box = fig.bbox
        for leg in legends:
            box = leg.get_window_extent()
            for ax in fig.axes:
                assert not box.overlaps(ax.get_window_extent()), (name, leg.get_texts()[0])
            assert fig_box.x0 <= box.x0 + 0.5 and box.x1 <= fig_box.x1 + 0.5, name
            assert fig_box.y0 <= box.y0 + 0.5 and box.y1 <= fig_box.y1 + 0.5, name


# ---- what a new user saw in the figures --------------------------------------------------------
def test_decay_rate_figure_has_a_title_and_readable_ticks():
    """decay.png: matplotlib labelled the minor ticks of the 250 Hz-5 kHz log axis and they ran
    into one string ('2x10^2 3x10^2 ...'); no title. Now plain octave ticks (250, 500, ...),
    unlabelled minor ticks, and a title naming the track."""
    s = tw.Scene.ballasted_track(60.0, elements_per_bay=2)
    fig = plots.decay_rate(s, np.geomspace(250.0, 5000.0, 12))
    fig.draw_without_rendering()
    ax = fig.axes[0]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["250", "500", "1000", "2000",
                                                            "4000"]
    assert all(t.get_text() == "" for t in ax.get_xticklabels(minor=True))
    assert "decay rate" in fig.get_suptitle() and "60 m rail" in fig.get_suptitle()


def test_receptance_figure_has_a_title_and_its_legend_takes_no_width():
    s = tw.Scene.kato2005()
    fig = plots.receptance(s, np.geomspace(50.0, 3000.0, 20))
    fig.draw_without_rendering()
    assert "Point receptance" in fig.get_suptitle() and "5 m rail" in fig.get_suptitle()
    assert _width_fraction(fig) > 0.8


def _width_fraction(fig) -> float:
    """The narrowest axes' width over the figure's (legends to the right squeezed it to 2/3)."""
    return min(ax.get_window_extent().width for ax in fig.axes) / fig.bbox.width


def test_run_figure_keeps_its_width_and_the_main_frequency_in_view(runs):
    """run.png / fig7_dynamic: the legends stood to the right (a third of the width) and four
    mode bands filled the spectrum around the main-frequency line. The legends stand above the
    axes; the bands fill a strip at the top only, the main frequency is drawn over them, full
    height, and the spectrum stays under the strip."""
    eig = tw.eigen(tw.Scene.kato2005(), np.linspace(0.0, 5.0, 11), n_modes=4)
    fig = plots.dynamic(runs[0], eigen=eig)
    fig.draw_without_rendering()
    assert _width_fraction(fig) > 0.8
    ax_f = fig.axes[2]
    (main,) = [ln for ln in ax_f.get_lines() if ln.get_gid() == "main frequency"]
    bands = [ln for ln in ax_f.get_lines() if (ln.get_gid() or "").startswith("eigen")]
    assert all(min(ln.get_ydata()) >= 0.85 for ln in bands)  # axes fraction: the top strip
    assert main.get_ydata()[0] == 0.0 and main.get_ydata()[1] == 1.0
    assert main.get_zorder() > max(p.get_zorder() for p in ax_f.patches)
    spec = _labelled(ax_f, "|D(f)|")
    assert np.max(spec.get_ydata()) < 0.85 * ax_f.get_ylim()[1]


def test_acceleration_terms_figure_leaves_no_empty_strip(runs):
    """fig8: the two legends to the right of the top row pushed the right column over and left
    a wide empty strip between the columns; above the top row, each over its column's title,
    they leave both columns their width (each over 40 % of the figure), and overlap no title."""
    fig = plots.acceleration_terms([runs[0], runs[2]])
    fig.draw_without_rendering()
    widths = [ax.get_window_extent().width / fig.bbox.width for ax in fig.axes]
    assert min(widths) > 0.4
    for ax in fig.axes[:2]:
        legend, title = ax.get_legend().get_window_extent(), ax.title.get_window_extent()
        assert not legend.overlaps(title) and legend.y0 >= title.y1 - 0.5


def test_convergence_figure_writes_the_v_e_scale_in_its_label(runs):
    """fig4: the v_e axis's offset text ('1e-5') sat at the axes' top left, squeezed under the
    subtitle; the scale is in the axis label and the offset text is empty."""
    fig = plots.time_step_convergence(runs)
    fig.draw_without_rendering()
    ax_v = fig.axes[1]
    assert ax_v.yaxis.get_offset_text().get_text() == ""
    scale = max(np.max(np.abs(r.v_error)) for r in runs)
    p = int(np.floor(np.log10(scale)))
    assert ax_v.get_ylabel() == f"velocity error v_e [%] (× 1e{p})"


def test_vehicle_run_figure_is_against_the_wheel_position_as_for_one_wheel():
    """plots.dynamic drew one wheel against X and a vehicle's wheels against t; both against
    the wheel position X now (each wheel its own: a track defect shows at one X)."""
    s = tw.Scene(rail=tw.Rail(length=10.0, n_elements=40), vehicle=tw.Vehicle.bogie(
        wheelbase=2.0))
    r = tw.simulate(s, 20.0, fidelity="linear/hertz", x_start=0.5, x_end=1.5, dt=1e-4)
    fig = plots.dynamic(r)
    ax_n = fig.axes[0]
    assert ax_n.get_xlabel().startswith("wheel position X [m]")
    for i, line in enumerate(ax_n.get_lines()):
        np.testing.assert_array_equal(line.get_xdata(), r.wheel(i).x_wheel)


def test_sleeper_envelope_shows_the_envelope_beside_the_supports():
    """The figure's lines are the envelope's columns and the supports' values at the same X,
    read through Supports.values (a transition: the stiff side's k_b after it)."""
    sup = tw.Scene.ballasted_track().supports.transition(
        7.5, ramp=1.2, shape="linear", ballast_stiffness=(105e6, 210e6))
    scene = dc.replace(tw.Scene.ballasted_track(length=15.0), supports=sup)
    r = tw.simulate(scene, tw.kmh(100), x_start=6.0, x_end=9.0, fidelity="linear/hertz",
                    progress=False)
    fig = plots.sleeper_envelope(r)
    lines = {ln.get_gid(): ln for ax in fig.axes for ln in ax.get_lines()}
    df = r.sleeper_envelope()
    np.testing.assert_allclose(lines["ballast max"].get_ydata(), 1e-3 * df.ballast_force_max)
    np.testing.assert_allclose(lines["sleeper z min"].get_ydata(), 1e3 * df.sleeper_z_min)
    kb = lines["k_b"].get_ydata()
    assert kb[0] == pytest.approx(105.0) and kb[-1] == pytest.approx(210.0)
