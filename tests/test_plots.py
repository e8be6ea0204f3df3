"""trackwheel.plots: Figures with unit-labelled axes that show exactly the result's arrays,
drawn without pyplot's global state."""

from __future__ import annotations

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
