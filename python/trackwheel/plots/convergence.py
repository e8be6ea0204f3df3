"""Convergence of a passage in the time step and the mesh: the paper's Figs. 4 and 5."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter

from ..base import validate as v
from .common import check_labels, check_results, run_label, same_setting, speed_kmh, stretch_text

#: the paper's eq. 28 as drawn on Figs. 4-5
_V_E_DEFINITION = (r"$v_e = (\dot{X}_A - \rho\,\dot{\theta})\,/\,\dot{X}_A \cdot 100\,\%$"
                   " (the paper's eq. 28: slip of the rolling contact)")


def _difference(r, ref, field: str) -> np.ndarray:
    """``r.field - ref.field`` at r's wheel positions, ``ref`` interpolated linearly (the
    reference is the finest run, so its samples are the densest); NaN outside ref's stretch."""
    x, xr = r.x_wheel, ref.x_wheel
    diff = getattr(r, field) - np.interp(x, xr, getattr(ref, field))
    return np.where((x >= xr[0]) & (x <= xr[-1]), diff, np.nan)


def _scale_in_label(ax, values: np.ndarray) -> str:
    """Ticks of ``values`` far from 1 written as mantissas, their power of ten returned for the
    axis label (" (x 1e-05)"), not shown at the axes' top left, where matplotlib's offset text
    ran into the axes' title; "" for values between 1e-2 and 1e4 in magnitude (or none)."""
    top = float(np.nanmax(np.abs(values))) if np.any(np.isfinite(values)) else 0.0
    if top == 0.0 or 1e-2 <= top < 1e4:
        return ""
    p = int(np.floor(np.log10(top)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda y, _pos: f"{y / 10.0**p:g}"))
    return f" (× 1e{p})"


def _convergence(results, labels, acceleration: bool, title: str, reference: int) -> Figure:
    n_rows = 4 if acceleration else 2
    fig = Figure(figsize=(8.0, 2.4 + 2.2 * n_rows), layout="constrained")
    axes = fig.subplots(n_rows, 1, sharex=True, squeeze=False)[:, 0]
    styles = ["-", "--", "-.", ":"]
    ref = results[reference]
    for i, (r, label) in enumerate(zip(results, labels)):
        # the first run drawn widest, so that curves lying on top of each other stay visible
        kw = {"label": label, "color": f"C{i % 10}", "linestyle": styles[i % len(styles)],
              "linewidth": max(0.8, 2.4 - 0.4 * i)}
        axes[0].plot(r.x_wheel, r.y_contact * 1e3, **kw)
        axes[1].plot(r.x_wheel, r.v_error, **kw)
        if acceleration:
            axes[2].plot(r.x_wheel, r.acc_contact, **kw)
            if i != reference:
                axes[3].plot(r.x_wheel, _difference(r, ref, "acc_contact"), gid="difference",
                             **kw)
    axes[0].set_ylabel("contact point y_B [mm]")
    axes[1].set_ylabel("velocity error v_e [%]" + _scale_in_label(
        axes[1], np.concatenate([r.v_error for r in results])))
    axes[1].set_title(_V_E_DEFINITION, loc="left", fontsize="small")
    if acceleration:
        axes[2].set_ylabel("d²y_B/dt² [m/s²]")
        axes[2].set_title("vertical acceleration of the contact point", loc="left",
                          fontsize="small")
        axes[3].set_ylabel("difference [m/s²]")
        axes[3].set_title(f"acceleration minus that of the finest run ({labels[reference]})",
                          loc="left", fontsize="small")
        axes[3].axhline(0.0, color="0.5", linewidth=0.8, zorder=0)
    axes[-1].set_xlabel("wheel position X [m]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    # above the panels, outside them: the traces fill the axes
    axes[0].legend(loc="lower left", bbox_to_anchor=(0.0, 1.02), borderaxespad=0.0,
                   ncols=2, fontsize="small")
    fig.suptitle(title)
    return fig


def _reference(name: str, reference, results, finest) -> int:
    """Index of the run the differences are taken from: ``reference`` or the finest run."""
    if reference is None:
        return min(range(len(results)), key=lambda i: finest(results[i].settings))
    return v.integer(name, reference, low=-len(results), high=len(results) - 1) % len(results)


def time_step_convergence(results, *, labels=None, acceleration: bool = True,
                          title: str | None = None, reference: int | None = None) -> Figure:
    """The paper's Fig. 4, effect of the time step: the contact-point displacement y_B [mm],
    the velocity error v_e = (dX_A/dt - rho dtheta/dt) / (dX_A/dt) x 100 [%] (the paper's
    "calculation error", eq. 28) and, with ``acceleration``, the contact-point vertical
    acceleration [m/s²] and its difference from the finest run's (whose traces would otherwise
    lie on top of each other), against the wheel position X [m], one line per run.

    Parameters
    ----------
    results : sequence of Result
        Runs of :func:`trackwheel.simulate` that differ in time step (and integrator).
    labels : sequence of str, optional
        Legend entries; default "<integrator>, dt = <dt> s" (plus the mesh if it differs
        between the runs).
    acceleration : bool
        Add the acceleration panel (the quantity the paper says needs 1e-7 s).
    title : str, optional
        Figure title; default names the figure, the speed(s) and the stretch of track.
    reference : int, optional
        Index of the run the acceleration differences are taken from; default the finest run
        (the smallest dt here; the most elements, then the smallest dt, in
        :func:`element_convergence`).

    Returns
    -------
    matplotlib.figure.Figure
        Axes from top: y_B [mm] (``y_contact * 1e3``), v_e [%], acceleration [m/s²] and the
        difference ``acc_contact`` minus the reference's, interpolated linearly at the run's
        wheel positions (lines with gid "difference"; the reference itself is not drawn
        there), each line against ``x_wheel`` and labelled as in the legend above the panels.
    """
    results = check_results("results", results)
    labels = check_labels("labels", labels, len(results)) or [
        run_label(r, dt=True, n_elements=not same_setting(results, "n_elements")) for r in results]
    if title is None:
        speeds = ", ".join(sorted({f"{speed_kmh(r):g}" for r in results}, key=float))
        title = (f"Effect of the time step (Kato et al. 2005, Fig. 4): {speeds} km/h, "
                 f"{stretch_text(results)}")
    ref = _reference("reference", reference, results, lambda s: s["dt"])
    return _convergence(results, labels, v.boolean("acceleration", acceleration), title, ref)


def element_convergence(results, *, labels=None, acceleration: bool = True,
                        title: str | None = None, reference: int | None = None) -> Figure:
    """The paper's Fig. 5, effect of the number of elements: as
    :func:`time_step_convergence`, with the legend naming the mesh of each run
    ("<n> elements", plus integrator and dt if they differ between the runs)."""
    results = check_results("results", results)
    same_int = same_setting(results, "integrator") and same_setting(results, "dt")
    labels = check_labels("labels", labels, len(results)) or [
        run_label(r, dt=True, n_elements=True) if not same_int
        else f"{r.settings['n_elements']} elements" for r in results]
    if title is None:
        speeds = ", ".join(sorted({f"{speed_kmh(r):g}" for r in results}, key=float))
        how = ""
        if same_int:
            how = ", " + run_label(results[0], dt=True, n_elements=False)
        title = (f"Effect of the number of elements (Kato et al. 2005, Fig. 5): {speeds} km/h"
                 f"{how}, {stretch_text(results)}")
    ref = _reference("reference", reference, results, lambda s: (-s["n_elements"], s["dt"]))
    return _convergence(results, labels, v.boolean("acceleration", acceleration), title, ref)

