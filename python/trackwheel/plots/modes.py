"""The natural frequencies of the coupled system: the paper's Fig. 3 and the mode shapes."""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..base import validate as v
from ..run.eigen import EigenResult
from .common import check_eigen_result, figure_and_axes, legend_outside, mark_supports


def eigen(result: EigenResult, n_modes: int = 4, ax: Axes | None = None) -> Figure:
    """The paper's Fig. 3: the lowest ``n_modes`` vertical natural frequencies [Hz] of the
    wheel/rail/support system against the wheel position X [m] (docs: Model § Eigen analysis).

    Parameters
    ----------
    result : EigenResult
        From :func:`trackwheel.eigen` over a range of positions.
    n_modes : int
        Number of modes drawn, 1 <= n_modes <= ``result.frequencies.shape[1]``.
    ax : matplotlib Axes, optional
        Draw here instead of on a new figure.

    Returns
    -------
    matplotlib.figure.Figure
        One line per mode, labelled ``"mode k"`` (k = 1, 2, ...); the elastic supports are
        marked by faint dotted lines, the rigid end supports by grey lines.
    """
    result = check_eigen_result(result)
    n_modes = v.integer("n_modes", n_modes, low=1, high=result.frequencies.shape[1])
    fig, ax = figure_and_axes(ax, (7.0, 4.5))
    x = result.positions
    mark_supports(ax, result)
    for k in range(n_modes):
        ax.plot(x, result.frequencies[:, k], marker="." if x.size < 60 else None,
                label=f"mode {k + 1}")
    ax.set_xlabel("wheel position X [m]")
    ax.set_ylabel("natural frequency [Hz]")
    ax.set_xlim(0.0, result.scene.rail.length)
    ax.set_title("Natural frequencies against wheel position (Kato et al. 2005, Fig. 3)")
    legend_outside(ax)
    ax.grid(True, axis="y", alpha=0.3)
    return fig


def mode_shapes(result: EigenResult, i_pos: int, modes: Iterable[int] = range(4)) -> Figure:
    """Vertical mode shapes with the wheel at ``result.positions[i_pos]``: one panel per mode,
    the rail deflection y(s) along the rail [-] and the wheel's vertical displacement [-]
    (a dot above the wheel position), each mode scaled by
    :meth:`EigenResult.rail_mode_shape` (largest |value| = 1, wheel positive).

    Parameters
    ----------
    result : EigenResult
    i_pos : int
        Index into ``result.positions``.
    modes : iterable of int
        0-based mode indices (``range(4)`` = the lowest four).

    Returns
    -------
    matplotlib.figure.Figure
        In each panel the rail line is labelled ``"rail y(s)"`` and the wheel dot ``"wheel"``.
    """
    result = check_eigen_result(result)
    n_pos, n_avail = result.frequencies.shape
    i_pos = v.integer("i_pos", i_pos, low=-n_pos, high=n_pos - 1)
    if isinstance(modes, (int, np.integer)):
        modes = [modes]
    if isinstance(modes, (str, bytes)) or not isinstance(modes, Iterable):
        raise TypeError(f"modes must be an int or an iterable of ints (0-based mode indices), "
                        f"got {type(modes).__name__}")
    modes = [v.integer("modes[]", m, low=0, high=n_avail - 1) for m in modes]
    if not modes:
        raise ValueError("modes must name at least one mode (0-based indices)")
    x_wheel = float(result.positions[i_pos])
    fig = Figure(figsize=(7.0, 1.2 + 1.6 * len(modes)), layout="constrained")
    axes = fig.subplots(len(modes), 1, sharex=True, squeeze=False)[:, 0]
    for ax, m in zip(axes, modes):
        s, y, wheel = result.rail_mode_shape(i_pos, m)
        mark_supports(ax, result, label=None)
        ax.axhline(0.0, color="0.8", linewidth=0.8, zorder=0)
        ax.plot(s, y, color="C0", label="rail y(s)")
        ax.plot([x_wheel], [wheel], marker="o", markersize=8, linestyle="none", color="C3",
                label="wheel")
        ax.set_ylim(-1.25, 1.25)
        ax.set_ylabel("deflection [-]")
        ax.set_title(f"mode {m + 1}: {result.frequencies[i_pos, m]:.1f} Hz", fontsize="medium",
                     loc="left")
    legend_outside(axes[0])
    axes[-1].set_xlabel("position along the rail s [m]")
    axes[-1].set_xlim(0.0, result.scene.rail.length)
    fig.suptitle(f"Vertical mode shapes, wheel at X = {x_wheel:g} m")
    return fig

