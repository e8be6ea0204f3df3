"""The periodic level: the steady contact force over the sleeper bay and its harmonics, and the
force's one-third-octave bands under a random profile (docs: Model § The periodic level)."""

from __future__ import annotations

import math

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..run.periodic import PeriodicResponse, RandomResponse
from .common import figure_and_axes, legend_outside

#: points drawn per sleeper bay [-]
POINTS_PER_BAY = 200


def periodic_force(responses, *, bays: float = 2.0) -> Figure:
    """The steady contact force of one or several :class:`trackwheel.PeriodicResponse`
    (:func:`trackwheel.periodic_response`): N [kN] against the wheel position X [m] over
    ``bays`` sleeper bays from a support (top, gid "force: <label>") and the amplitudes of its
    harmonics [N] against frequency [Hz] (bottom, gid "harmonics: <label>"; the sleeper
    passing filled, the running surfaces' lines open), one colour per response, labelled by
    speed."""
    rs = [responses] if isinstance(responses, PeriodicResponse) else list(responses)
    if not rs or not all(isinstance(r, PeriodicResponse) for r in rs):
        raise TypeError("responses must be a trackwheel PeriodicResponse or a sequence of them")
    if not (isinstance(bays, (int, float)) and 0.0 < bays <= 100.0):
        raise ValueError(f"bays = {bays!r}: allowed range (0, 100]")
    fig = Figure(figsize=(7.0, 5.5), layout="constrained")
    ax_n, ax_h = fig.subplots(2, 1)
    for i, r in enumerate(rs):
        label = f"{r.speed * 3.6:.4g} km/h"
        d = r.scene.supports.spacing
        x = np.linspace(0.0, bays * d, max(2, math.ceil(bays * POINTS_PER_BAY)))
        line, = ax_n.plot(x, r.force(x / r.speed) / 1e3, label=label, gid=f"force: {label}")
        h = r.force_harmonics
        sp = (h.source == "sleeper_passing").to_numpy()
        colour = line.get_color()
        for mask, face in ((sp, colour), (~sp, "none")):
            if mask.any():
                ax_h.semilogy(h.frequency_hz[mask], h.amplitude_n[mask], "o", color=colour,
                              mfc=face, gid=f"harmonics: {label}")
    for j in range(math.floor(bays) + 1):
        ax_n.axvline(j * rs[0].scene.supports.spacing, color="0.6", lw=0.8, ls=":", zorder=0)
    ax_n.set_xlabel("wheel position X from a support [m]")
    ax_n.set_ylabel("contact force N [kN]")
    ax_h.set_xlabel("frequency [Hz] (filled: sleeper passing; open: running surfaces)")
    ax_h.set_ylabel("harmonic amplitude [N]")
    for ax in (ax_n, ax_h):
        ax.grid(True, which="both", alpha=0.3)
    legend_outside(ax_n)
    return fig


def random_force_bands(response, *, ax: Axes | None = None) -> Figure:
    """The one-third-octave band RMS of the contact force [N] of a
    :class:`trackwheel.RandomResponse` (:func:`trackwheel.random_response`) against the band
    centre [Hz]: the random part (gid "random"), the sleeper passing's lines (gid "sleeper")
    and both together (gid "total"), in the bands whose total is at least 1e-3 of the
    largest's."""
    if not isinstance(response, RandomResponse):
        raise TypeError(f"response must be a trackwheel RandomResponse, "
                        f"got {type(response).__name__}")
    fig, ax = figure_and_axes(ax, (6.0, 3.5))
    b = response.band_rms
    b = b[b.rms_n >= 1e-3 * b.rms_n.max()]  # the bands that carry the force
    for column, style, gid, label in (("rms_n", "o-", "total", "total"),
                                      ("rms_random_n", "s--", "random", "random profile"),
                                      ("rms_sleeper_n", "^:", "sleeper", "sleeper passing")):
        keep = (b[column] > 0.0).to_numpy()  # log axes cannot show an empty band
        ax.loglog(b.centre_hz[keep], b[column][keep], style, ms=4, label=label, gid=gid)
    ax.set_xlabel("one-third-octave band centre [Hz]")
    ax.set_ylabel("band RMS of N - P [N]")
    ax.set_title(f"{response.speed * 3.6:.4g} km/h", fontsize="medium")
    ax.grid(True, which="both", alpha=0.3)
    legend_outside(ax)
    return fig
