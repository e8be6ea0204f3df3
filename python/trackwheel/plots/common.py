"""What every figure shares: figure and axes set-up, argument checks, labels of runs, the
marks of supports and of eigenfrequency bands.

Every figure is a :class:`matplotlib.figure.Figure` built without ``pyplot``.
"""

from __future__ import annotations

from matplotlib.axes import Axes
from matplotlib.figure import Figure, SubFigure

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




def eigen_bands(ax: Axes, eigen: EigenResult, n_modes: int, *, horizontal: bool) -> None:
    """Each of the lowest ``n_modes`` modes as a band from its lowest to its highest frequency
    over the wheel positions of ``eigen``: two thin lines (gid "eigen mode k min/max") and a
    faint fill between them, labelled "mode k: lo–hi Hz"."""
    f = eigen.frequencies[:, :n_modes]
    for k in range(n_modes):
        lo, hi = float(f[:, k].min()), float(f[:, k].max())
        style = {"color": f"C{(k + 5) % 10}", "linewidth": 0.8, "linestyle": "--", "zorder": 0}
        line = ax.axhline if horizontal else ax.axvline
        span = ax.axhspan if horizontal else ax.axvspan
        line(lo, gid=f"eigen mode {k + 1} min", **style)
        line(hi, gid=f"eigen mode {k + 1} max", **style)
        span(lo, hi, color=style["color"], alpha=0.15, zorder=0,
             label=f"mode {k + 1}: {lo:.0f}–{hi:.0f} Hz")


def check_n_modes(eigen, n_modes) -> int:
    check_eigen_result(eigen)
    return v.integer("n_modes", n_modes, low=1, high=eigen.frequencies.shape[1])

