"""One passage: the paper's measurement of a run (y_B, y_qs, d(t) and its spectrum, Fig. 7)
and the acceleration terms of the contact point (Fig. 8)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from ..base import validate as v
from ..run.eigen import EigenResult
from ..run.results import Result
from ..study.analysis import Analysis, analyse
from .common import (
    check_n_modes,
    check_results,
    eigen_bands,
    legend_above,
    run_label,
    speed_kmh,
)

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


def _k_text(scene) -> str:
    """The supports' stiffness [MN/m] for a title: one value, or its range over the supports."""
    return scene.supports.text("stiffness", 1e-6, scene.support_positions)


def acceleration_terms(results, *, against: str = "position", title: str | None = None
                       ) -> Figure:
    """The paper's Fig. 8: the terms A–E of the contact-point vertical acceleration (docs:
    Model § Outputs, paper's eq. 21) for each run (the paper: 100 and 300 km/h), one row per run.

    Left column: A = ρ cosφ θ' v φ_s and B = ρ cosφ θ' φ_t (first order in the rail's slope);
    right column: C = ρ cosφ v² φ_s², D = ρ cosφ φ_t², E = 2 ρ cosφ φ_t v φ_s (second order,
    about 10⁻⁴ of A and B for the paper's scene, hence their own axes). Each column shares its
    y axis between the runs, so the growth with speed is seen directly. C and D are nearly equal
    (the deflection bowl travels with the wheel, so φ_t ≈ -v φ_s): C is drawn wide and pale
    under a thin D. The legends stand above the top row, one per column, outside the data.

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
    results = check_results("results", results)
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
        head = (f"{speed_kmh(r):g} km/h, k_s = {_k_text(r.scene)} MN/m")
        ax_l.set_title(f"{head}: terms A, B", loc="left", fontsize="medium")
        ax_r.set_title(f"{head}: terms C, D, E", loc="left", fontsize="medium")
        for ax in (ax_l, ax_r):
            ax.set_ylabel("acceleration [m/s²]")
            ax.grid(True, alpha=0.3)
            ax.axhline(0.0, color="0.7", linewidth=0.8, zorder=0)
    xlabel = "wheel position X [m]" if against == "position" else "time t [ms]"
    for ax in axes[-1]:
        ax.set_xlabel(xlabel)
    # above the top row, one per column: the columns keep the figure's width
    legend_above(axes[0, 0], ncols=1, over_title=True)
    legend_above(axes[0, 1], ncols=1, over_title=True)
    fig.suptitle("Terms of the contact-point acceleration (Kato et al. 2005, Fig. 8)"
                 if title is None else title)
    return fig



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
    i0 = int(np.searchsorted(result.t, a.t[0]))
    if not np.array_equal(a.t, result.t[i0:i0 + a.t.size]):
        # the analysis measures a stretch of the run (Analysis.x_range), its samples the run's
        raise ValueError("analysis does not belong to result (its times differ)")
    if eigen is not None:
        n_modes = check_n_modes(eigen, n_modes)
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
    legend_above(ax_y)

    ax_d.plot(a.x_wheel, a.dynamic * 1e6, color="C2", linewidth=0.9, label="d")
    i_max = int(np.argmax(np.abs(a.dynamic)))
    ax_d.plot([a.x_wheel[i_max]], [a.dynamic[i_max] * 1e6], marker="o", linestyle="none",
              color="C3", label=f"amplitude max|d| = {a.amplitude * 1e6:.3g} µm")
    ax_d.axhline(0.0, color="0.7", linewidth=0.8, zorder=0)
    ax_d.set_ylabel("dynamic part d = y_B - y_qs [µm]")
    ax_d.set_xlabel("wheel position X [m]")
    legend_above(ax_d)

    freqs, amps = a.spectrum
    keep = freqs <= f_max
    if eigen is not None:
        eigen_bands(ax_f, eigen, n_modes, horizontal=False)
    ax_f.plot(freqs[keep], amps[keep] * 1e6, color="C2", label="|D(f)|", zorder=2)
    if np.isfinite(fm):
        ax_f.axvline(fm, color="C3", linewidth=1.5, gid="main frequency", zorder=3,
                     label=f"main frequency {fm:.1f} Hz (resolution {a.frequency_resolution:.2g}"
                           " Hz)")
    ax_f.set_xlim(0.0, f_max)
    if eigen is not None and keep.any():  # headroom: the spectrum stays below the mode strip
        ax_f.set_ylim(0.0, float(np.max(amps[keep])) * 1e6 * 1.25)
    ax_f.set_xlabel("frequency [Hz]")
    ax_f.set_ylabel("amplitude spectrum of d [µm]")
    legend_above(ax_f, ncols=2)
    for ax in (ax_y, ax_d, ax_f):
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"{speed_kmh(result):g} km/h, k_s = {_k_text(result.scene)}"
                 f" MN/m, {run_label(result, dt=True, n_elements=True)}")
    return fig


def _dynamic_wheels(result, f_max) -> Figure:
    """:func:`dynamic` for a vehicle: every wheel's contact force N and dynamic part d against
    its position X on the track (as for one wheel: a defect of the track shows at the same X
    under every wheel), and the spectra of d, one colour per wheel (wheel i:
    ``analyse(result, wheel=i)``)."""
    fig = Figure(figsize=(8.0, 8.5), layout="constrained")
    ax_n, ax_d, ax_f = fig.subplots(3, 1)
    f_max = 1000.0 if f_max is None else v.positive("f_max", f_max, "Hz")
    for i in range(result.n_wheels):
        a = analyse(result, wheel=i)
        ax_n.plot(a.x_wheel, a.normal_force * 1e-3, color=f"C{i}", linewidth=0.9,
                  label=f"wheel {i}")
        ax_d.plot(a.x_wheel, a.dynamic * 1e6, color=f"C{i}", linewidth=0.9,
                  label=f"wheel {i}: max|d| = {a.amplitude * 1e6:.3g} µm")
        freqs, amps = a.spectrum
        keep = freqs <= f_max
        ax_f.plot(freqs[keep], amps[keep] * 1e6, color=f"C{i}", linewidth=0.9,
                  label=f"wheel {i}: {a.main_frequency:.1f} Hz")
    ax_n.set_ylabel("contact force N [kN]")
    ax_d.set_ylabel("dynamic part d = y_B - y_qs [µm]")
    for ax in (ax_n, ax_d):
        ax.set_xlabel("wheel position X [m] (each wheel its own)")
    ax_f.set_xlim(0.0, f_max)
    ax_f.set_xlabel("frequency [Hz]")
    ax_f.set_ylabel("amplitude spectrum of d [µm]")
    for ax in (ax_n, ax_d, ax_f):
        ax.grid(True, alpha=0.3)
        legend_above(ax, ncols=min(result.n_wheels, 4))
    fig.suptitle(f"{speed_kmh(result):g} km/h, {result.n_wheels} wheels, "
                 f"{run_label(result, dt=True, n_elements=True)}")
    return fig

