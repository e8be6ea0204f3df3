"""Sweep tables (:func:`trackwheel.sweep`) drawn: amplitude and main frequency against support
stiffness (the paper's Fig. 6) and against speed (Fig. 7)."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..base import validate as v
from ..run.eigen import EigenResult
from ..study.columns import SPEED_KMH as _KMH
from ..study.columns import label
from .common import check_n_modes, eigen_bands, legend_outside, root_figure

#: the sweep table's columns drawn here
SPEED_KMH = _KMH.label
STIFFNESS, AMPLITUDE, MAIN_F, RESOLUTION = (
    label(n) for n in ("support_stiffness", "amplitude", "main_frequency", "frequency_resolution"))


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
    f = grp[MAIN_F].to_numpy(float)
    ax.plot(x + shift, f, marker="o", markerfacecolor="none", color=color, label=label,
            zorder=2)
    if RESOLUTION in grp.columns:
        ax.errorbar(x + shift, f, yerr=grp[RESOLUTION].to_numpy(float), fmt="none",
                    ecolor=color, elinewidth=1.0, capsize=3, zorder=3)


def support_stiffness(df, *, frequency: bool = False, ax: Axes | None = None) -> Figure:
    """The paper's Fig. 6: the amplitude of the contact-point vibration max |d| [µm] (docs: Model §
    Outputs) against the support stiffness k_s [MN/m], one line per speed (the paper: 100 and
    300 km/h).

    Parameters
    ----------
    df : pandas.DataFrame
        A sweep table (:func:`trackwheel.sweep`), columns ``speed_kmh``, ``support_stiffness_N_m``,
        ``amplitude_m`` (and ``main_frequency_hz``, ``frequency_resolution_hz`` for ``frequency``).
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
        Lines labelled "<v> km/h": x = ``support_stiffness_N_m / 1e6``, y = ``amplitude_m * 1e6``
        (and ``main_frequency_hz`` in the second panel), sorted by stiffness.
    """
    cols = [SPEED_KMH, STIFFNESS, AMPLITUDE]
    frequency = v.boolean("frequency", frequency)
    if frequency:
        cols += [MAIN_F]
    _check_frame(df, cols)
    if ax is not None and frequency:
        raise ValueError("ax cannot be given with frequency=True (the figure has two panels)")
    if ax is None:
        fig = Figure(figsize=(7.0, 7.5 if frequency else 4.5), layout="constrained")
        axes = fig.subplots(2 if frequency else 1, 1, sharex=True, squeeze=False)[:, 0]
    elif not isinstance(ax, Axes):
        raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    else:
        fig, axes = root_figure(ax), [ax]
    groups = _groups(df, SPEED_KMH)
    x_all = df[STIFFNESS].to_numpy(float) / 1e6
    for i, (speed, grp) in enumerate(groups):
        grp = grp.sort_values(STIFFNESS)
        x = grp[STIFFNESS].to_numpy(float) / 1e6
        label = f"{speed:g} km/h"
        axes[0].plot(x, grp[AMPLITUDE].to_numpy(float) * 1e6, marker="o", color=f"C{i}",
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
        legend_outside(axes[1])
    axes[-1].set_xlabel("support stiffness k_s [MN/m]")
    legend_outside(axes[0])
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
        A sweep table (:func:`trackwheel.sweep`), columns ``speed_kmh``, ``support_stiffness_N_m``,
        ``amplitude_m``, ``main_frequency_hz`` (``frequency_resolution_hz`` draws bars).
    eigen : EigenResult, optional
        Natural frequencies of the coupled system over wheel positions (:func:`trackwheel.eigen`,
        same support stiffness as the table): the lowest ``n_modes`` are drawn on the frequency
        panel as horizontal bands from their lowest to their highest frequency.
    n_modes : int

    Returns
    -------
    matplotlib.figure.Figure
        Two axes, lines labelled "k_s = <k> MN/m": x = ``speed_kmh``, y = ``amplitude_m * 1e6``
        and ``main_frequency_hz`` (with several stiffnesses, shifted sideways as in
        :func:`support_stiffness`); the eigen bands are lines with gid "eigen mode k min/max".
    """
    _check_frame(df, [SPEED_KMH, STIFFNESS, AMPLITUDE, MAIN_F])
    if eigen is not None:
        n_modes = check_n_modes(eigen, n_modes)
        k_eig = eigen.scene.supports.stiffness
        other = [] if callable(k_eig) or isinstance(k_eig, tuple) else [
            k for k in df[STIFFNESS].unique() if abs(k - k_eig) > 1e-9 * k_eig]
        if other:
            raise ValueError(f"eigen was computed for k_s = {k_eig:g} N/m but the table has "
                             f"k_s = {other[0]:g} N/m; give eigen for the table's scene")
    fig = Figure(figsize=(7.0, 7.5), layout="constrained")
    ax_a, ax_f = fig.subplots(2, 1, sharex=True)
    groups = _groups(df, STIFFNESS)
    for i, (k, grp) in enumerate(groups):
        grp = grp.sort_values(SPEED_KMH)
        x = grp[SPEED_KMH].to_numpy(float)
        label = f"k_s = {k / 1e6:g} MN/m"
        ax_a.plot(x, grp[AMPLITUDE].to_numpy(float) * 1e6, marker="o", color=f"C{i}",
                  label=label)
        _frequency_panel(ax_f, x, grp, label, f"C{i}",
                         _dodge(df[SPEED_KMH].to_numpy(float), i, len(groups)))
    if eigen is not None:
        eigen_bands(ax_f, eigen, n_modes, horizontal=True)
    ax_a.set_ylabel("amplitude max |d| [µm]")
    fig.suptitle("Amplitude and main frequency against speed (Kato et al. 2005, Fig. 7)")
    ax_f.set_ylabel("main frequency [Hz]")
    ax_f.set_xlabel("speed v [km/h]")
    legend_outside(ax_a)
    ax_f.legend(loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize="small",
                title="data / eigenfrequencies\nover wheel positions", title_fontsize="small")
    for a in (ax_a, ax_f):
        a.grid(True, alpha=0.3)
    return fig

