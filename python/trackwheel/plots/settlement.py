"""The settlement loop drawn (:func:`trackwheel.settle`): the settlement along X as it grows,
beside the support stiffness, and the dynamic factor against the cycles."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..study.settlement.history import SettlementHistory
from .common import legend_outside, root_figure


def _check(history) -> SettlementHistory:
    if not isinstance(history, SettlementHistory):
        raise TypeError(f"history must be a SettlementHistory (trackwheel.settle), got "
                        f"{type(history).__name__}")
    return history


def _picked(history: SettlementHistory, n_curves: int) -> np.ndarray:
    """About ``n_curves`` states of the bed, evenly spread in log(cycles), the last included."""
    m = len(history.cycles)
    if m <= n_curves:
        return np.arange(m)
    logc = np.log10(np.maximum(history.cycles, 1))
    targets = np.linspace(logc[1], logc[-1], n_curves)
    return np.unique(np.r_[0, [int(np.argmin(np.abs(logc - t))) for t in targets[1:]], m - 1])


def settlement_profile(history, *, n_curves: int = 6, voids: bool = False,
                       ax: Axes | None = None) -> Figure:
    """The settlement along X [mm] at about ``n_curves`` states of the bed (evenly spread in
    log cycles, the last included), over a panel of each sleeper's static support stiffness
    [MN/m] (pad and ballast in series) and its largest peak ballast force [kN] on the intact
    and the last bed. ``voids=True`` draws the voids instead of the settlement. With ``ax``
    only the settlement panel is drawn, into it."""
    h = _check(history)
    if ax is None:
        fig = Figure(figsize=(8.0, 6.0), layout="constrained")
        top, bottom = fig.subplots(2, 1, sharex=True, height_ratios=(2, 1))
    else:
        top, bottom, fig = ax, None, root_figure(ax)
    x = h.sleepers
    values = h.voids if voids else h.settlement
    cmap = fig.colormaps["viridis"] if hasattr(fig, "colormaps") else None
    picked = _picked(h, int(n_curves))
    for i, k in enumerate(picked):
        color = None if cmap is None else cmap(i / max(1, len(picked) - 1))
        top.plot(x, 1e3 * values[k], marker=".", color=color,
                 label=f"{h.cycles[k]:.3g} cycles")
    top.set_ylabel(("void" if voids else "settlement") + " [mm]")
    top.invert_yaxis()  # down is down
    top.set_title("voids of the settled bed" if voids else "ballast settlement along the track")
    legend_outside(top)
    if bottom is None:
        top.set_xlabel("X [m]")
        return fig
    bottom.plot(x, 1e-6 * h.support_stiffness, color="0.3", drawstyle="steps-mid",
                label="support stiffness")
    bottom.set_ylabel("stiffness [MN/m]")
    bottom.set_xlabel("X [m]")
    force = bottom.twinx()
    force.plot(x, 1e-3 * h.peak_force[0], color="C0", linestyle="--", label="peak force, intact")
    force.plot(x, 1e-3 * h.peak_force[-1], color="C3", label="peak force, last bed")
    force.set_ylabel("peak ballast force [kN]")
    lines = bottom.get_lines() + force.get_lines()
    force.legend(lines, [ln.get_label() for ln in lines], fontsize="small", loc="best")
    return fig


def dynamic_factor_cycles(history, *, ax: Axes | None = None) -> Figure:
    """The dynamic factor (largest wheel force over its static load) [-] and the differential
    settlement (largest minus smallest) [mm] against the axle passes, log scale: how the bed's
    unevenness and the dynamic load grow together."""
    h = _check(history)
    if ax is None:
        fig = Figure(figsize=(7.0, 4.0), layout="constrained")
        ax = fig.add_subplot()
    else:
        fig = root_figure(ax)
    cycles = np.maximum(h.cycles, 1)
    ax.semilogx(cycles, h.dynamic_factor, marker="o", color="C0", label="dynamic factor")
    ax.set_xlabel("axle passes [-]")
    ax.set_ylabel("dynamic factor [-]")
    ax.set_title("open loop (intact bed's forces)" if not h.feedback else "settled bed fed back")
    diff = ax.twinx()
    diff.semilogx(cycles, 1e3 * h.differential, marker=".", color="C3",
                  label="differential settlement")
    diff.set_ylabel("differential settlement [mm]")
    lines = ax.get_lines() + diff.get_lines()
    ax.legend(lines, [ln.get_label() for ln in lines], fontsize="small", loc="upper left")
    return fig
