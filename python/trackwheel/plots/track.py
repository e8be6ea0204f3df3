"""The track in the frequency domain: point receptance and decay rate."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from matplotlib.ticker import NullFormatter

from ..run import frequency
from .common import figure_and_axes, legend_above


def receptance(scene, freqs, *, n_elements: int | None = None) -> Figure:
    """Point receptance of the track (:func:`trackwheel.receptance`) at mid-span and above the
    support nearest the rail's middle: magnitude [m/N] (log-log, gid "magnitude: <point>") and
    phase [deg] against frequency [Hz], titled with the track."""
    f = np.asarray(freqs, dtype=float)
    fig = Figure(figsize=(6.0, 5.0), layout="constrained")
    ax_m, ax_p = fig.subplots(2, 1, sharex=True, height_ratios=(2, 1))
    for label, x in frequency.receptance_points(scene).items():
        a = frequency.receptance(scene, x, f, n_elements=n_elements)
        ax_m.loglog(f, np.abs(a), label=f"{label} (X = {x:.3g} m)", gid=f"magnitude: {label}")
        ax_p.semilogx(f, np.degrees(np.angle(a)), gid=f"phase: {label}")
    ax_m.set_ylabel("|receptance| [m/N]")
    ax_p.set_ylabel("phase [deg]")
    ax_p.set_xlabel("frequency [Hz]")
    for ax in (ax_m, ax_p):
        ax.grid(True, which="both", alpha=0.3)
    legend_above(ax_m)
    fig.suptitle(_track_title("Point receptance of the track alone", scene),
                 fontsize="medium")
    return fig


def _track_title(what: str, scene) -> str:
    """The title of a track figure: what, and the track (rail length, supports)."""
    s = scene.supports
    supports = (f"pad, sleeper and ballast every {s.spacing:g} m" if s.layered else
                f"supports every {s.spacing:g} m" if s.positions is None else
                f"{len(scene.support_positions)} supports")
    return f"{what}: {scene.rail.length:g} m rail, {supports}"


def _octave_ticks(ax, f) -> None:
    """Plain-number ticks at the octaves 1000 x 2^k Hz inside the frequencies ``f`` [Hz] of a
    log axis, the minor ticks unlabelled (matplotlib labels the minor ticks of an axis that
    spans less than two decades, and their labels ran into each other)."""
    lo, hi = float(np.min(f)), float(np.max(f))
    k = np.arange(np.ceil(np.log2(lo / 1000.0)), np.floor(np.log2(hi / 1000.0)) + 1)
    ticks = 1000.0 * 2.0**k
    ax.set_xticks(ticks, [f"{t:g}" for t in ticks])
    ax.xaxis.set_minor_formatter(NullFormatter())


def decay_rate(scene, freqs, *, n_elements: int | None = None, ax: Axes | None = None
               ) -> Figure:
    """Vertical track decay rate [dB/m] (EN 15461, :func:`trackwheel.decay_rate`, gid
    "decay rate") against frequency [Hz] (ticks at the octaves 250 Hz, 500 Hz, ...), with the
    ISO 3095:2013 lower limit per one-third-octave band (steps, gid "ISO 3095 limit"); titled
    with the track when the figure is new (``ax=None``)."""
    f = np.asarray(freqs, dtype=float)
    own = ax is None
    fig, ax = figure_and_axes(ax, (6.0, 3.5))
    ax.semilogx(f, frequency.decay_rate(scene, f, n_elements=n_elements), marker="o", ms=3,
                label="track (EN 15461)", gid="decay rate")
    ax.stairs(frequency.ISO3095_VERTICAL_LIMIT, frequency.iso3095_band_edges(), color="k", ls="--",
              label="ISO 3095 lower limit (vertical)", gid="ISO 3095 limit")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("decay rate [dB/m]")
    ax.grid(True, which="both", alpha=0.3)
    _octave_ticks(ax, np.concatenate([f[f > 0], frequency.iso3095_band_edges()]))
    legend_above(ax)
    if own:  # a title above the legend: the figure's (in an axes of yours, yours)
        fig.suptitle(_track_title("Vertical track decay rate (EN 15461)", scene),
                     fontsize="medium")
    return fig

