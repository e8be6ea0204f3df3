"""The track in the frequency domain: point receptance and decay rate."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..run import frequency
from .common import figure_and_axes, legend_outside


def receptance(scene, freqs, *, n_elements: int | None = None) -> Figure:
    """Point receptance of the track (:func:`trackwheel.receptance`) at mid-span and above the
    support nearest the rail's middle: magnitude [m/N] (log-log, gid "magnitude: <point>") and
    phase [deg] against frequency [Hz]."""
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
    legend_outside(ax_m)
    return fig


def decay_rate(scene, freqs, *, n_elements: int | None = None, ax: Axes | None = None
               ) -> Figure:
    """Vertical track decay rate [dB/m] (EN 15461, :func:`trackwheel.decay_rate`, gid
    "decay rate") against frequency [Hz], with the ISO 3095:2013 lower limit per
    one-third-octave band (steps, gid "ISO 3095 limit")."""
    f = np.asarray(freqs, dtype=float)
    fig, ax = figure_and_axes(ax, (6.0, 3.5))
    ax.semilogx(f, frequency.decay_rate(scene, f, n_elements=n_elements), marker="o", ms=3,
                label="track (EN 15461)", gid="decay rate")
    ax.stairs(frequency.ISO3095_VERTICAL_LIMIT, frequency.iso3095_band_edges(), color="k", ls="--",
              label="ISO 3095 lower limit (vertical)", gid="ISO 3095 limit")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("decay rate [dB/m]")
    ax.grid(True, which="both", alpha=0.3)
    legend_outside(ax)
    return fig

