"""What every figure shares: figure and axes set-up, argument checks, labels of runs, the
marks of supports and of eigenfrequency bands.

Every figure is a :class:`matplotlib.figure.Figure` built without ``pyplot``.
"""

from __future__ import annotations

from matplotlib.axes import Axes
from matplotlib.figure import Figure, SubFigure
from matplotlib.transforms import ScaledTranslation

from ..base import validate as v
from ..run.eigen import EigenResult
from ..run.results import Result

#: style of the marks at the support positions: faint, behind the data
SUPPORT_STYLE = {"color": "0.6", "linewidth": 0.8, "linestyle": ":", "zorder": 0}


def legend_outside(ax: Axes, **kw) -> None:
    """The legend to the right of the axes, outside them, so that it hides no data (the
    constrained layout makes room for it)."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              fontsize="small", **kw)


def legend_above(ax: Axes, ncols: int = 2, *, over_title: bool = False, **kw) -> None:
    """The legend above the axes, outside them, in ``ncols`` columns from the axes' left edge:
    it hides no data and takes height, not the width of the plot (the constrained layout
    makes room for it). ``over_title``: above the axes' title (TITLE_ROOM points higher)."""
    shift = ScaledTranslation(0.0, (TITLE_ROOM if over_title else 2.0) / 72.0,
                              root_figure(ax).dpi_scale_trans)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), borderaxespad=0.0,
              bbox_transform=ax.transAxes + shift, fontsize="small", ncols=ncols, **kw)


#: room for an axes title under a legend above it [points]: a medium title and its pad
TITLE_ROOM = 22.0


def root_figure(ax: Axes) -> Figure:
    fig = ax.figure
    while isinstance(fig, SubFigure):
        fig = fig.figure
    return fig


def figure_and_axes(ax: Axes | None, figsize: tuple[float, float]) -> tuple[Figure, Axes]:
    """A new one-axes figure of ``figsize`` [in], or ``ax`` (checked) and its figure."""
    if ax is None:
        fig = Figure(figsize=figsize, layout="constrained")
        return fig, fig.add_subplot()
    if not isinstance(ax, Axes):
        raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    return root_figure(ax), ax


def check_eigen_result(result) -> EigenResult:
    if not isinstance(result, EigenResult):
        raise TypeError(
            f"result must be a trackwheel.EigenResult (from trackwheel.eigen), "
            f"got {type(result).__name__}")
    return result


def mark_supports(ax: Axes, result: EigenResult, label: str | None = "supports") -> None:
    """Faint vertical lines at the elastic supports (dotted) and the rigid end supports."""
    for j, x in enumerate(result.scene.support_positions):
        ax.axvline(x, label=label if j == 0 else None, **SUPPORT_STYLE)
    for x in (0.0, result.scene.rail.length):
        ax.axvline(x, color="0.4", linewidth=1.2, zorder=0)



#: display names of the integrators
INTEGRATOR_NAMES = {"explicit": "explicit RK4", "generalized_alpha": "generalized-α"}


def check_results(name: str, results) -> list:
    if isinstance(results, Result):
        results = [results]
    try:
        results = list(results)
    except TypeError:
        raise TypeError(f"{name} must be a sequence of trackwheel.Result (from "
                        f"trackwheel.simulate), got {type(results).__name__}") from None
    if not results:
        raise ValueError(f"{name} is empty: give at least one trackwheel.Result")
    for r in results:
        if not isinstance(r, Result):
            raise TypeError(f"{name} must hold trackwheel.Result objects (from "
                            f"trackwheel.simulate), got {type(r).__name__}")
    return results


def check_labels(name: str, labels, n: int) -> list[str] | None:
    if labels is None:
        return None
    if isinstance(labels, str):
        raise TypeError(f"{name} must be a sequence of strings, not one string")
    labels = [str(s) for s in labels]
    if len(labels) != n:
        raise ValueError(f"{name} has {len(labels)} entries for {n} results")
    return labels


def format_dt(dt: float) -> str:
    """A time step [s] written compactly: 1e-07 -> "1e-7", 5e-06 -> "5e-6", 2.5e-5 -> "2.5e-5"."""
    mant, exp = f"{dt:.3e}".split("e")
    mant = mant.rstrip("0").rstrip(".")
    return f"{mant}e{int(exp)}"


def speed_kmh(result) -> float:
    return result.settings["speed"] * 3.6


def stretch_text(results) -> str:
    x0 = min(float(r.x_wheel[0]) for r in results)
    x1 = max(float(r.x_wheel[-1]) for r in results)
    return f"X = {x0:.3g}–{x1:.3g} m"


def same_setting(results, key) -> bool:
    return len({r.settings[key] for r in results}) == 1


def run_label(r, *, dt: bool, n_elements: bool) -> str:
    s = r.settings
    parts = []
    if n_elements:
        parts.append(f"{s['n_elements']} elements")
    name = INTEGRATOR_NAMES.get(s["integrator"], s["integrator"])
    parts.append(f"{name}, dt = {format_dt(s['dt'])} s" if dt else name)
    if s.get("fidelity", "full") != "full":
        parts.append(s["fidelity"])
    return ", ".join(parts)




#: height of the strip of eigenfrequency bands at the top of a spectrum, a fraction of the axes
BAND_STRIP = 0.1


def eigen_bands(ax: Axes, eigen: EigenResult, n_modes: int, *, horizontal: bool) -> None:
    """Each of the lowest ``n_modes`` modes as a band from its lowest to its highest frequency
    over the wheel positions of ``eigen``: two thin lines (gid "eigen mode k min/max") and a
    faint fill between them, labelled "mode k: lo–hi Hz". Horizontal bands (frequency on the
    y axis) span the plot; vertical ones (a spectrum) fill only a strip at the top of the axes,
    numbered, so that they do not hide the spectrum and its main-frequency line."""
    f = eigen.frequencies[:, :n_modes]
    for k in range(n_modes):
        lo, hi = float(f[:, k].min()), float(f[:, k].max())
        style = {"color": f"C{(k + 5) % 10}", "linewidth": 0.8, "linestyle": "--", "zorder": 0}
        label = f"mode {k + 1}: {lo:.0f}–{hi:.0f} Hz"
        if horizontal:
            ax.axhline(lo, gid=f"eigen mode {k + 1} min", **style)
            ax.axhline(hi, gid=f"eigen mode {k + 1} max", **style)
            ax.axhspan(lo, hi, color=style["color"], alpha=0.15, zorder=0, label=label)
            continue
        strip = {"ymin": 1.0 - BAND_STRIP, "ymax": 1.0}
        style.update(linestyle="-", zorder=1)
        ax.axvline(lo, gid=f"eigen mode {k + 1} min", **strip, **style)
        ax.axvline(hi, gid=f"eigen mode {k + 1} max", **strip, **style)
        ax.axvspan(lo, hi, color=style["color"], alpha=0.5, zorder=1, label=label, **strip)
        # the mode's number under the strip (modes a few Hz apart: the legend tells them)
        ax.annotate(f"{k + 1}", xy=(0.5 * (lo + hi), 1.0 - BAND_STRIP), xycoords=("data",
                    "axes fraction"), xytext=(0, -2), textcoords="offset points",
                    ha="center", va="top", fontsize="x-small", color=style["color"])


def check_n_modes(eigen, n_modes) -> int:
    check_eigen_result(eigen)
    return v.integer("n_modes", n_modes, low=1, high=eigen.frequencies.shape[1])

