"""Figures of trackwheel results, drawn with matplotlib's object API.

Every function returns a :class:`matplotlib.figure.Figure` built without ``pyplot``, so nothing is
registered in pyplot's global figure list and no backend is needed: save it with
``fig.savefig("x.png")`` or let Jupyter show it (after ``%matplotlib inline``). Where a function
takes ``ax``, pass it to draw into an axes of your own figure instead. Every axis names its unit;
figures show SI quantities in the units a track engineer reads (mm and µm, MN/m, km/h).

The paper's figures (Kato et al. 2005): :func:`eigen` (Fig. 3), :func:`time_step_convergence`
(Fig. 4), :func:`element_convergence` (Fig. 5), :func:`support_stiffness` (Fig. 6),
:func:`speed` (Fig. 7), :func:`acceleration_terms` (Fig. 8); and :func:`mode_shapes` and
:func:`dynamic` (one run: y_B, y_qs, d(t) and its spectrum).

This module imports matplotlib; ``import trackwheel`` does not, until ``trackwheel.plots`` is
used.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure, SubFigure

from . import _validate as v
from .eigen import EigenResult

__all__ = [
    "acceleration_terms",
    "dynamic",
    "eigen",
    "element_convergence",
    "format_dt",
    "mode_shapes",
    "speed",
    "support_stiffness",
    "time_step_convergence",
]

#: style of the marks at the support positions: faint, behind the data
_SUPPORT_STYLE = {"color": "0.6", "linewidth": 0.8, "linestyle": ":", "zorder": 0}


def _legend_outside(ax: Axes, **kw) -> None:
    """The legend to the right of the axes, outside them, so that it hides no data (the
    constrained layout makes room for it)."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0,
              fontsize="small", **kw)


def _root_figure(ax: Axes) -> Figure:
    fig = ax.figure
    while isinstance(fig, SubFigure):
        fig = fig.figure
    return fig


def _figure_and_axes(ax: Axes | None, figsize: tuple[float, float]) -> tuple[Figure, Axes]:
    """A new one-axes figure of ``figsize`` [in], or ``ax`` (checked) and its figure."""
    if ax is None:
        fig = Figure(figsize=figsize, layout="constrained")
        return fig, fig.add_subplot()
    if not isinstance(ax, Axes):
        raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    return _root_figure(ax), ax


def _check_result(result) -> EigenResult:
    if not isinstance(result, EigenResult):
        raise TypeError(
            f"result must be a trackwheel.EigenResult (from trackwheel.eigen), "
            f"got {type(result).__name__}")
    return result


def _mark_supports(ax: Axes, result: EigenResult, label: str | None = "supports") -> None:
    """Faint vertical lines at the elastic supports (dotted) and the rigid end supports."""
    for j, x in enumerate(result.scene.support_positions):
        ax.axvline(x, label=label if j == 0 else None, **_SUPPORT_STYLE)
    for x in (0.0, result.scene.rail.length):
        ax.axvline(x, color="0.4", linewidth=1.2, zorder=0)


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
    result = _check_result(result)
    n_modes = v.integer("n_modes", n_modes, low=1, high=result.frequencies.shape[1])
    fig, ax = _figure_and_axes(ax, (7.0, 4.5))
    x = result.positions
    _mark_supports(ax, result)
    for k in range(n_modes):
        ax.plot(x, result.frequencies[:, k], marker="." if x.size < 60 else None,
                label=f"mode {k + 1}")
    ax.set_xlabel("wheel position X [m]")
    ax.set_ylabel("natural frequency [Hz]")
    ax.set_xlim(0.0, result.scene.rail.length)
    ax.set_title("Natural frequencies against wheel position (Kato et al. 2005, Fig. 3)")
    _legend_outside(ax)
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
    result = _check_result(result)
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
        _mark_supports(ax, result, label=None)
        ax.axhline(0.0, color="0.8", linewidth=0.8, zorder=0)
        ax.plot(s, y, color="C0", label="rail y(s)")
        ax.plot([x_wheel], [wheel], marker="o", markersize=8, linestyle="none", color="C3",
                label="wheel")
        ax.set_ylim(-1.25, 1.25)
        ax.set_ylabel("deflection [-]")
        ax.set_title(f"mode {m + 1}: {result.frequencies[i_pos, m]:.1f} Hz", fontsize="medium",
                     loc="left")
    _legend_outside(axes[0])
    axes[-1].set_xlabel("position along the rail s [m]")
    axes[-1].set_xlim(0.0, result.scene.rail.length)
    fig.suptitle(f"Vertical mode shapes, wheel at X = {x_wheel:g} m")
    return fig


# --------------------------------------------------------------------------------------------
# time simulations (docs: Model § Outputs): convergence, one run, acceleration terms
# --------------------------------------------------------------------------------------------
#: display names of the integrators
_INTEGRATOR_NAMES = {"explicit": "explicit RK4", "generalized_alpha": "generalized-α"}
#: the acceleration terms of docs: Model § Outputs (paper's eq. 21, Fig. 8): field, legend text
_ACC_TERMS = (
    ("acc_A", "A = ρ cosφ θ' v φ_s"),
    ("acc_B", "B = ρ cosφ θ' φ_t"),
    ("acc_C", "C = ρ cosφ v² φ_s²"),
    ("acc_D", "D = ρ cosφ φ_t²"),
    ("acc_E", "E = 2 ρ cosφ φ_t v φ_s"),
)


#: line style per term: C and D are nearly equal (for the deflection bowl travelling with the
#: wheel phi_t ~ -v phi_s, so D ~ C), so C is drawn wide and pale under a thin D
_ACC_STYLE = {
    "acc_A": {"linewidth": 1.0, "zorder": 2},
    "acc_B": {"linewidth": 1.0, "zorder": 2},
    "acc_C": {"linewidth": 3.0, "alpha": 0.45, "zorder": 2},
    "acc_D": {"linewidth": 0.8, "zorder": 3},
    "acc_E": {"linewidth": 1.0, "zorder": 2},
}


def _check_results(name: str, results) -> list:
    from .simulate import Result

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


def _labels(name: str, labels, n: int) -> list[str] | None:
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


def _speed_kmh(result) -> float:
    return result.settings["speed"] * 3.6


def _stretch(results) -> str:
    x0 = min(float(r.x_wheel[0]) for r in results)
    x1 = max(float(r.x_wheel[-1]) for r in results)
    return f"X = {x0:.3g}–{x1:.3g} m"


def _same(results, key) -> bool:
    return len({r.settings[key] for r in results}) == 1


def _run_label(r, *, dt: bool, n_elements: bool) -> str:
    s = r.settings
    parts = []
    if n_elements:
        parts.append(f"{s['n_elements']} elements")
    name = _INTEGRATOR_NAMES.get(s["integrator"], s["integrator"])
    parts.append(f"{name}, dt = {format_dt(s['dt'])} s" if dt else name)
    if s.get("fidelity", "full") != "full":
        parts.append(s["fidelity"])
    return ", ".join(parts)


#: the paper's eq. 28 as drawn on Figs. 4-5
_V_E_DEFINITION = (r"$v_e = (\dot{X}_A - \rho\,\dot{\theta})\,/\,\dot{X}_A \cdot 100\,\%$"
                   " (the paper's eq. 28: slip of the rolling contact)")


def _difference(r, ref, field: str) -> np.ndarray:
    """``r.field - ref.field`` at r's wheel positions, ``ref`` interpolated linearly (the
    reference is the finest run, so its samples are the densest); NaN outside ref's stretch."""
    x, xr = r.x_wheel, ref.x_wheel
    diff = getattr(r, field) - np.interp(x, xr, getattr(ref, field))
    return np.where((x >= xr[0]) & (x <= xr[-1]), diff, np.nan)


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
    axes[1].set_ylabel("velocity error v_e [%]")
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
    results = _check_results("results", results)
    labels = _labels("labels", labels, len(results)) or [
        _run_label(r, dt=True, n_elements=not _same(results, "n_elements")) for r in results]
    if title is None:
        speeds = ", ".join(sorted({f"{_speed_kmh(r):g}" for r in results}, key=float))
        title = (f"Effect of the time step (Kato et al. 2005, Fig. 4): {speeds} km/h, "
                 f"{_stretch(results)}")
    ref = _reference("reference", reference, results, lambda s: s["dt"])
    return _convergence(results, labels, v.boolean("acceleration", acceleration), title, ref)


def element_convergence(results, *, labels=None, acceleration: bool = True,
                        title: str | None = None, reference: int | None = None) -> Figure:
    """The paper's Fig. 5, effect of the number of elements: as
    :func:`time_step_convergence`, with the legend naming the mesh of each run
    ("<n> elements", plus integrator and dt if they differ between the runs)."""
    results = _check_results("results", results)
    same_int = _same(results, "integrator") and _same(results, "dt")
    labels = _labels("labels", labels, len(results)) or [
        _run_label(r, dt=True, n_elements=True) if not same_int
        else f"{r.settings['n_elements']} elements" for r in results]
    if title is None:
        speeds = ", ".join(sorted({f"{_speed_kmh(r):g}" for r in results}, key=float))
        how = ""
        if same_int:
            how = ", " + _run_label(results[0], dt=True, n_elements=False)
        title = (f"Effect of the number of elements (Kato et al. 2005, Fig. 5): {speeds} km/h"
                 f"{how}, {_stretch(results)}")
    ref = _reference("reference", reference, results, lambda s: (-s["n_elements"], s["dt"]))
    return _convergence(results, labels, v.boolean("acceleration", acceleration), title, ref)


def acceleration_terms(results, *, against: str = "position", title: str | None = None
                       ) -> Figure:
    """The paper's Fig. 8: the terms A–E of the contact-point vertical acceleration (docs:
    Model § Outputs, paper's eq. 21) for each run (the paper: 100 and 300 km/h), one row per run.

    Left column: A = ρ cosφ θ' v φ_s and B = ρ cosφ θ' φ_t (first order in the rail's slope);
    right column: C = ρ cosφ v² φ_s², D = ρ cosφ φ_t², E = 2 ρ cosφ φ_t v φ_s (second order,
    about 10⁻⁴ of A and B for the paper's scene, hence their own axes). Each column shares its
    y axis between the runs, so the growth with speed is seen directly. C and D are nearly equal
    (the deflection bowl travels with the wheel, so φ_t ≈ -v φ_s): C is drawn wide and pale
    under a thin D. The legends stand to the right of the top row, outside the data.

    Parameters
    ----------
    results : sequence of Result
    against : str
        The x axis: "position" (the wheel position X [m]) or "time" (the time [ms]).
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        Axes row by row (left, right); the lines are labelled as in the legend, their y data
        are ``result.acc_A`` ... ``result.acc_E`` [m/s²].
    """
    results = _check_results("results", results)
    v.choice("against", against, {"position", "time"})
    n = len(results)
    fig = Figure(figsize=(10.0, 1.4 + 2.6 * n), layout="constrained")
    axes = fig.subplots(n, 2, squeeze=False, sharey="col")
    for (ax_l, ax_r), r in zip(axes, results):
        x = r.x_wheel if against == "position" else r.t * 1e3
        for k, (name, text) in enumerate(_ACC_TERMS):
            ax = ax_l if k < 2 else ax_r
            if name == "acc_C":
                text += " (wide, under D)"
            ax.plot(x, getattr(r, name), color=f"C{k}", label=text, **_ACC_STYLE[name])
        head = (f"{_speed_kmh(r):g} km/h, k_s = {r.scene.supports.stiffness / 1e6:g} MN/m")
        ax_l.set_title(f"{head}: terms A, B", loc="left", fontsize="medium")
        ax_r.set_title(f"{head}: terms C, D, E", loc="left", fontsize="medium")
        for ax in (ax_l, ax_r):
            ax.set_ylabel("acceleration [m/s²]")
            ax.grid(True, alpha=0.3)
            ax.axhline(0.0, color="0.7", linewidth=0.8, zorder=0)
    xlabel = "wheel position X [m]" if against == "position" else "time t [ms]"
    for ax in axes[-1]:
        ax.set_xlabel(xlabel)
    _legend_outside(axes[0, 0])
    _legend_outside(axes[0, 1])
    fig.suptitle("Terms of the contact-point acceleration (Kato et al. 2005, Fig. 8)"
                 if title is None else title)
    return fig


def _eigen_bands(ax: Axes, eigen: EigenResult, n_modes: int, *, horizontal: bool) -> None:
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


def _check_eigen(eigen, n_modes) -> int:
    _check_result(eigen)
    return v.integer("n_modes", n_modes, low=1, high=eigen.frequencies.shape[1])


def dynamic(result, analysis=None, *, eigen: EigenResult | None = None, n_modes: int = 4,
            f_max: float | None = None) -> Figure:
    """One run measured as the paper measures it (docs: Model § Outputs): the contact-point
    displacement y_B and the quasi-static line y_qs [mm] against the wheel position, the
    dynamic part d = y_B - y_qs [µm] with its amplitude max |d| marked, and the amplitude
    spectrum of d [µm] with the main frequency marked.

    Parameters
    ----------
    result : Result
    analysis : Analysis, optional
        ``trackwheel.analyse(result)``; computed here if not given.
    eigen : EigenResult, optional
        Natural frequencies of the same scene over wheel positions: the lowest ``n_modes`` are
        drawn on the spectrum as bands from their lowest to their highest frequency.
    f_max : float, optional
        Upper limit of the spectrum axis [Hz]; default max(1000, 3 x main frequency).

    Returns
    -------
    matplotlib.figure.Figure
        Three axes: lines "y_B" and "y_qs" (``* 1e3``), "d" (``* 1e6``) and the spectrum
        "|D(f)|" (``* 1e6``); the main frequency is a vertical line labelled with its value and
        resolution.
    """
    from .analysis import Analysis, analyse
    from .simulate import Result

    if not isinstance(result, Result):
        raise TypeError(f"result must be a trackwheel.Result (from trackwheel.simulate), "
                        f"got {type(result).__name__}")
    if result.n_wheels > 1:
        if analysis is not None:
            raise ValueError("analysis: leave it None for a run with several wheels (each "
                             "wheel is analysed here)")
        return _dynamic_wheels(result, f_max)
    if analysis is None:
        analysis = analyse(result)
    elif not isinstance(analysis, Analysis):
        raise TypeError(f"analysis must be a trackwheel.Analysis (from trackwheel.analyse), "
                        f"got {type(analysis).__name__}")
    a = analysis
    if a.t.shape != result.t.shape or not np.array_equal(a.t, result.t):
        raise ValueError("analysis does not belong to result (its times differ)")
    if eigen is not None:
        n_modes = _check_eigen(eigen, n_modes)
    fm = a.main_frequency
    if f_max is None:
        f_max = max(1000.0, 3.0 * fm) if np.isfinite(fm) else 1000.0
    f_max = v.positive("f_max", f_max, "Hz")

    fig = Figure(figsize=(8.0, 8.5), layout="constrained")
    ax_y, ax_d, ax_f = fig.subplots(3, 1)
    ax_y.plot(a.x_wheel, a.y_contact * 1e3, color="C0", label="y_B")
    ax_y.plot(a.x_wheel, a.y_qs * 1e3, color="C1", linestyle="--", label="y_qs")
    ax_y.set_ylabel("displacement [mm]")
    ax_y.set_xlabel("wheel position X [m]")
    _legend_outside(ax_y)

    ax_d.plot(a.x_wheel, a.dynamic * 1e6, color="C2", linewidth=0.9, label="d")
    i_max = int(np.argmax(np.abs(a.dynamic)))
    ax_d.plot([a.x_wheel[i_max]], [a.dynamic[i_max] * 1e6], marker="o", linestyle="none",
              color="C3", label=f"amplitude max|d| = {a.amplitude * 1e6:.3g} µm")
    ax_d.axhline(0.0, color="0.7", linewidth=0.8, zorder=0)
    ax_d.set_ylabel("dynamic part d = y_B - y_qs [µm]")
    ax_d.set_xlabel("wheel position X [m]")
    _legend_outside(ax_d)

    freqs, amps = a.spectrum
    keep = freqs <= f_max
    if eigen is not None:
        _eigen_bands(ax_f, eigen, n_modes, horizontal=False)
    ax_f.plot(freqs[keep], amps[keep] * 1e6, color="C2", label="|D(f)|")
    if np.isfinite(fm):
        ax_f.axvline(fm, color="C3", linewidth=1.2, gid="main frequency",
                     label=f"main frequency {fm:.1f} Hz (resolution {a.frequency_resolution:.2g}"
                           " Hz)")
    ax_f.set_xlim(0.0, f_max)
    ax_f.set_xlabel("frequency [Hz]")
    ax_f.set_ylabel("amplitude spectrum of d [µm]")
    _legend_outside(ax_f)
    for ax in (ax_y, ax_d, ax_f):
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"{_speed_kmh(result):g} km/h, k_s = {result.scene.supports.stiffness / 1e6:g}"
                 f" MN/m, {_run_label(result, dt=True, n_elements=True)}")
    return fig


def _dynamic_wheels(result, f_max) -> Figure:
    """:func:`dynamic` for a vehicle: every wheel's contact force N and dynamic part d against
    time, and the spectra of d, one colour per wheel (wheel i: ``analyse(result, wheel=i)``)."""
    from .analysis import analyse

    fig = Figure(figsize=(8.0, 8.5), layout="constrained")
    ax_n, ax_d, ax_f = fig.subplots(3, 1)
    f_max = 1000.0 if f_max is None else v.positive("f_max", f_max, "Hz")
    for i in range(result.n_wheels):
        a = analyse(result, wheel=i)
        ax_n.plot(a.t, a.normal_force * 1e-3, color=f"C{i}", linewidth=0.9, label=f"wheel {i}")
        ax_d.plot(a.t, a.dynamic * 1e6, color=f"C{i}", linewidth=0.9,
                  label=f"wheel {i}: max|d| = {a.amplitude * 1e6:.3g} µm")
        freqs, amps = a.spectrum
        keep = freqs <= f_max
        ax_f.plot(freqs[keep], amps[keep] * 1e6, color=f"C{i}", linewidth=0.9,
                  label=f"wheel {i}: {a.main_frequency:.1f} Hz")
    ax_n.set_ylabel("contact force N [kN]")
    ax_d.set_ylabel("dynamic part d = y_B - y_qs [µm]")
    for ax in (ax_n, ax_d):
        ax.set_xlabel("time t [s]")
    ax_f.set_xlim(0.0, f_max)
    ax_f.set_xlabel("frequency [Hz]")
    ax_f.set_ylabel("amplitude spectrum of d [µm]")
    for ax in (ax_n, ax_d, ax_f):
        ax.grid(True, alpha=0.3)
        _legend_outside(ax)
    fig.suptitle(f"{_speed_kmh(result):g} km/h, {result.n_wheels} wheels, "
                 f"{_run_label(result, dt=True, n_elements=True)}")
    return fig


# --------------------------------------------------------------------------------------------
# sweeps (tables of trackwheel.sweep)
# --------------------------------------------------------------------------------------------
def _check_frame(df, columns) -> None:
    missing = [c for c in columns if not hasattr(df, "columns") or c not in df.columns]
    if missing:
        raise TypeError(f"df must be a sweep table (pandas DataFrame from trackwheel.sweep or "
                        f"trackwheel.load_sweep) with columns {list(columns)}; missing "
                        f"{missing}")
    if len(df) == 0:
        raise ValueError("df is empty: no cases to plot")


def _groups(df, key):
    """(value, rows sorted by the other axis) per distinct value of ``key``."""
    return [(val, grp) for val, grp in df.groupby(key, sort=True)]


#: the frequency panels shift series i of n sideways by (i - (n - 1) / 2) x DODGE x the x span,
#: so that neither series' error bars (the frequency resolution) hide behind the other's marks
DODGE = 0.015


def _dodge(x_all, i: int, n: int) -> float:
    """Sideways shift [x units] of series ``i`` of ``n`` in a frequency panel (see DODGE)."""
    x_all = np.asarray(x_all, dtype=float)
    return (i - (n - 1) / 2) * DODGE * float(np.ptp(x_all)) if x_all.size else 0.0


def _frequency_panel(ax: Axes, x, grp, label, color, shift: float) -> None:
    """Main frequency against x, shifted by ``shift``, open markers with the resolution as
    error bars drawn over them."""
    f = grp["main_frequency"].to_numpy(float)
    ax.plot(x + shift, f, marker="o", markerfacecolor="none", color=color, label=label,
            zorder=2)
    if "frequency_resolution" in grp.columns:
        ax.errorbar(x + shift, f, yerr=grp["frequency_resolution"].to_numpy(float), fmt="none",
                    ecolor=color, elinewidth=1.0, capsize=3, zorder=3)


def support_stiffness(df, *, frequency: bool = False, ax: Axes | None = None) -> Figure:
    """The paper's Fig. 6: the amplitude of the contact-point vibration max |d| [µm] (docs: Model §
    Outputs) against the support stiffness k_s [MN/m], one line per speed (the paper: 100 and
    300 km/h).

    Parameters
    ----------
    df : pandas.DataFrame
        A sweep table (:func:`trackwheel.sweep`), columns ``speed_kmh``, ``support_stiffness``,
        ``amplitude`` (and ``main_frequency``, ``frequency_resolution`` for ``frequency``).
        Failed cases (NaN amplitude) leave gaps.
    frequency : bool
        Add a second panel with the main frequency [Hz] against k_s (bars: the frequency
        resolution of each run; each speed's points shifted sideways by :data:`DODGE` of the
        k_s span per series, so that no error bar hides behind another speed's marker).
    ax : Axes, optional
        Draw the amplitude panel here (not with ``frequency``).

    Returns
    -------
    matplotlib.figure.Figure
        Lines labelled "<v> km/h": x = ``support_stiffness / 1e6``, y = ``amplitude * 1e6``
        (and ``main_frequency`` in the second panel), sorted by stiffness.
    """
    cols = ["speed_kmh", "support_stiffness", "amplitude"]
    frequency = v.boolean("frequency", frequency)
    if frequency:
        cols += ["main_frequency"]
    _check_frame(df, cols)
    if ax is not None and frequency:
        raise ValueError("ax cannot be given with frequency=True (the figure has two panels)")
    if ax is None:
        fig = Figure(figsize=(7.0, 7.5 if frequency else 4.5), layout="constrained")
        axes = fig.subplots(2 if frequency else 1, 1, sharex=True, squeeze=False)[:, 0]
    elif not isinstance(ax, Axes):
        raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    else:
        fig, axes = _root_figure(ax), [ax]
    groups = _groups(df, "speed_kmh")
    x_all = df["support_stiffness"].to_numpy(float) / 1e6
    for i, (speed, grp) in enumerate(groups):
        grp = grp.sort_values("support_stiffness")
        x = grp["support_stiffness"].to_numpy(float) / 1e6
        label = f"{speed:g} km/h"
        axes[0].plot(x, grp["amplitude"].to_numpy(float) * 1e6, marker="o", color=f"C{i}",
                     label=label)
        if frequency:
            _frequency_panel(axes[1], x, grp, label, f"C{i}", _dodge(x_all, i, len(groups)))
    axes[0].set_ylabel("amplitude max |d| [µm]")
    title = "Amplitude against support stiffness (Kato et al. 2005, Fig. 6)"
    if ax is None:
        fig.suptitle(title)
    else:
        ax.set_title(title)
    if frequency:
        axes[1].set_ylabel("main frequency [Hz]")
        _legend_outside(axes[1])
    axes[-1].set_xlabel("support stiffness k_s [MN/m]")
    _legend_outside(axes[0])
    for a in axes:
        a.grid(True, alpha=0.3)
    return fig


def speed(df, eigen: EigenResult | None = None, *, n_modes: int = 4) -> Figure:
    """The paper's Fig. 7: the amplitude of the contact-point vibration max |d| [µm] and its
    main frequency [Hz] against the speed [km/h] (the paper: 50–400 km/h at 140 MN/m), one line
    per support stiffness.

    Parameters
    ----------
    df : pandas.DataFrame
        A sweep table (:func:`trackwheel.sweep`), columns ``speed_kmh``, ``support_stiffness``,
        ``amplitude``, ``main_frequency`` (``frequency_resolution`` draws bars).
    eigen : EigenResult, optional
        Natural frequencies of the coupled system over wheel positions (:func:`trackwheel.eigen`,
        same support stiffness as the table): the lowest ``n_modes`` are drawn on the frequency
        panel as horizontal bands from their lowest to their highest frequency.
    n_modes : int

    Returns
    -------
    matplotlib.figure.Figure
        Two axes, lines labelled "k_s = <k> MN/m": x = ``speed_kmh``, y = ``amplitude * 1e6``
        and ``main_frequency`` (with several stiffnesses, shifted sideways as in
        :func:`support_stiffness`); the eigen bands are lines with gid "eigen mode k min/max".
    """
    _check_frame(df, ["speed_kmh", "support_stiffness", "amplitude", "main_frequency"])
    if eigen is not None:
        n_modes = _check_eigen(eigen, n_modes)
        k_eig = eigen.scene.supports.stiffness
        other = [k for k in df["support_stiffness"].unique()
                 if abs(k - k_eig) > 1e-9 * k_eig]
        if other:
            raise ValueError(f"eigen was computed for k_s = {k_eig:g} N/m but the table has "
                             f"k_s = {other[0]:g} N/m; give eigen for the table's scene")
    fig = Figure(figsize=(7.0, 7.5), layout="constrained")
    ax_a, ax_f = fig.subplots(2, 1, sharex=True)
    groups = _groups(df, "support_stiffness")
    for i, (k, grp) in enumerate(groups):
        grp = grp.sort_values("speed_kmh")
        x = grp["speed_kmh"].to_numpy(float)
        label = f"k_s = {k / 1e6:g} MN/m"
        ax_a.plot(x, grp["amplitude"].to_numpy(float) * 1e6, marker="o", color=f"C{i}",
                  label=label)
        _frequency_panel(ax_f, x, grp, label, f"C{i}",
                         _dodge(df["speed_kmh"].to_numpy(float), i, len(groups)))
    if eigen is not None:
        _eigen_bands(ax_f, eigen, n_modes, horizontal=True)
    ax_a.set_ylabel("amplitude max |d| [µm]")
    fig.suptitle("Amplitude and main frequency against speed (Kato et al. 2005, Fig. 7)")
    ax_f.set_ylabel("main frequency [Hz]")
    ax_f.set_xlabel("speed v [km/h]")
    _legend_outside(ax_a)
    ax_f.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize="small",
                title="data / eigenfrequencies\nover wheel positions", title_fontsize="small")
    for a in (ax_a, ax_f):
        a.grid(True, alpha=0.3)
    return fig


# ---------------------------------------------------------------------------------------------
# Excitation (issue 13): rail profiles, their spectra, contact-force statistics.
# Everything below this line belongs to the excitation block; the functions above are untouched.
# ---------------------------------------------------------------------------------------------
__all__ += ["contact_force", "force_bands", "irregularity_profile"]


def irregularity_profile(irr, x_min: float, x_max: float, dx: float, *, spectrum=None,
                         nperseg: int | None = None) -> Figure:
    """A rail profile r(X) [mm] against X [m] and its Welch PSD [m^2/(rad/m)] against
    Omega [rad/m], beside a target ``spectrum`` (a trackwheel.spectra spectrum; default: the
    spectrum of the profile's first random part, if any) drawn over the generated band.

    The PSD is :meth:`trackwheel.Irregularity.psd` of the samples on [x_min, x_max] at spacing
    <= dx [m]; lines have gid "profile", "welch" and "target".
    """
    from .irregularity import Irregularity, RandomProfile

    if not isinstance(irr, Irregularity):
        raise TypeError(f"irr must be a trackwheel.Irregularity, got {type(irr).__name__}")
    x = irr.grid(x_min, x_max, dx)
    omega, psd = irr.psd(x_min, x_max, dx, nperseg=nperseg)
    randoms = [p for p in irr.parts if isinstance(p, RandomProfile)]
    if spectrum is None and randoms:
        spectrum = randoms[0].spectrum
    fig = Figure(figsize=(7.0, 7.0), layout="constrained")
    ax_r, ax_s = fig.subplots(2, 1)
    ax_r.plot(x, irr(x) * 1e3, linewidth=0.8, gid="profile")
    ax_r.set_xlabel("track coordinate X [m]")
    ax_r.set_ylabel("profile r [mm] (positive = bump)")
    ax_s.loglog(omega, psd, linewidth=0.8, label="Welch estimate", gid="welch")
    if spectrum is not None:
        lo, hi = randoms[0].omega_band if randoms else spectrum.band
        w = np.geomspace(max(lo, omega[0]), min(hi, omega[-1]), 400)
        ax_s.loglog(w, spectrum(w), color="k", linestyle="--", label=f"target: {spectrum.name}",
                    gid="target")
    ax_s.set_xlabel("spatial angular frequency Omega = 2 pi / lambda [rad/m]")
    ax_s.set_ylabel("one-sided PSD S [m^2/(rad/m)]")
    ax_s.legend(loc="best", fontsize="small")
    for a in (ax_r, ax_s):
        a.grid(True, alpha=0.3)
    return fig


def contact_force(x, n, *, defect_at: float | None = None, static_load: float | None = None,
                  ax: Axes | None = None) -> Figure:
    """Contact force N [kN] against the wheel position X [m]; a vertical line (gid "defect")
    at the defect ``defect_at`` [m] and a horizontal one (gid "static load") at P0 [N]."""
    xa = np.asarray(x, dtype=float)
    na = np.asarray(n, dtype=float)
    if xa.ndim != 1 or xa.shape != na.shape:
        raise ValueError(f"x and n must be 1-d arrays of the same length, got shapes "
                         f"{xa.shape} and {na.shape}")
    fig, ax = _figure_and_axes(ax, (7.0, 3.5))
    ax.plot(xa, na / 1e3, linewidth=0.9, label="contact force N", gid="force")
    if static_load is not None:
        p0 = v.positive("static_load", static_load, "N")
        ax.axhline(p0 / 1e3, color="0.4", linestyle="--", label="static load P0",
                   gid="static load")
    if defect_at is not None:
        ax.axvline(v.number("defect_at", defect_at, unit="m"), color="C3", linestyle=":",
                   label="defect", gid="defect")
    ax.set_xlabel("wheel position X [m]")
    ax.set_ylabel("contact force N [kN]")
    ax.legend(loc="best", fontsize="small")
    ax.grid(True, alpha=0.3)
    return fig


def force_bands(stats, *, ax: Axes | None = None) -> Figure:
    """RMS of the contact force in one-third-octave bands [N] against the band centre [Hz]
    (log-log, one marker per band, gid "bands"), from a
    :class:`trackwheel.ForceStatistics`."""
    from .force_statistics import ForceStatistics

    if not isinstance(stats, ForceStatistics):
        raise TypeError(f"stats must be a trackwheel.ForceStatistics, "
                        f"got {type(stats).__name__}")
    fig, ax = _figure_and_axes(ax, (6.0, 3.5))
    keep = stats.band_rms > 0.0  # log axes cannot show an empty band
    ax.loglog(stats.band_centres[keep], stats.band_rms[keep], marker="o", gid="bands")
    ax.set_xlabel("one-third-octave band centre [Hz]")
    ax.set_ylabel("band RMS of N - mean(N) [N]")
    ax.grid(True, which="both", alpha=0.3)
    return fig


def _receptance_points(scene) -> dict[str, float]:
    """Mid-span and above-support excitation points near the rail's middle [m]."""
    pos = np.asarray(scene.support_positions)
    if pos.size == 0:
        return {"mid-span": 0.5 * scene.rail.length}
    j = int(np.argmin(np.abs(pos - 0.5 * scene.rail.length)))
    nxt = pos[j + 1] if j + 1 < pos.size else scene.rail.length
    return {"mid-span": 0.5 * (pos[j] + nxt), "above a support": float(pos[j])}


def receptance(scene, freqs, *, n_elements: int | None = None) -> Figure:
    """Point receptance of the track (:func:`trackwheel.receptance`) at mid-span and above the
    support nearest the rail's middle: magnitude [m/N] (log-log, gid "magnitude: <point>") and
    phase [deg] against frequency [Hz]."""
    from .frequency import receptance as _receptance

    f = np.asarray(freqs, dtype=float)
    fig = Figure(figsize=(6.0, 5.0), layout="constrained")
    ax_m, ax_p = fig.subplots(2, 1, sharex=True, height_ratios=(2, 1))
    for label, x in _receptance_points(scene).items():
        a = _receptance(scene, x, f, n_elements=n_elements)
        ax_m.loglog(f, np.abs(a), label=f"{label} (X = {x:.3g} m)", gid=f"magnitude: {label}")
        ax_p.semilogx(f, np.degrees(np.angle(a)), gid=f"phase: {label}")
    ax_m.set_ylabel("|receptance| [m/N]")
    ax_p.set_ylabel("phase [deg]")
    ax_p.set_xlabel("frequency [Hz]")
    for ax in (ax_m, ax_p):
        ax.grid(True, which="both", alpha=0.3)
    _legend_outside(ax_m)
    return fig


def decay_rate(scene, freqs, *, n_elements: int | None = None, ax: Axes | None = None
               ) -> Figure:
    """Vertical track decay rate [dB/m] (EN 15461, :func:`trackwheel.decay_rate`, gid
    "decay rate") against frequency [Hz], with the ISO 3095:2013 lower limit per
    one-third-octave band (steps, gid "ISO 3095 limit")."""
    from .frequency import ISO3095_VERTICAL_LIMIT, iso3095_band_edges
    from .frequency import decay_rate as _decay_rate

    f = np.asarray(freqs, dtype=float)
    fig, ax = _figure_and_axes(ax, (6.0, 3.5))
    ax.semilogx(f, _decay_rate(scene, f, n_elements=n_elements), marker="o", ms=3,
                label="track (EN 15461)", gid="decay rate")
    ax.stairs(ISO3095_VERTICAL_LIMIT, iso3095_band_edges(), color="k", ls="--",
              label="ISO 3095 lower limit (vertical)", gid="ISO 3095 limit")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("decay rate [dB/m]")
    ax.grid(True, which="both", alpha=0.3)
    _legend_outside(ax)
    return fig
