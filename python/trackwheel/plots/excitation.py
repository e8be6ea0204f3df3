"""The excitation: a rail profile and its spectrum, the contact force along the track and its
one-third-octave band levels."""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..base import validate as v
from ..excitation import Irregularity, RandomProfile
from ..study.force_statistics import ForceStatistics
from .common import figure_and_axes

def irregularity_profile(irr, x_min: float, x_max: float, dx: float, *, spectrum=None,
                         nperseg: int | None = None) -> Figure:
    """A rail profile r(X) [mm] against X [m] and its Welch PSD [m^2/(rad/m)] against
    Omega [rad/m], beside a target ``spectrum`` (a trackwheel.spectra spectrum; default: the
    spectrum of the profile's first random part, if any) drawn over the generated band.

    The PSD is :meth:`trackwheel.Irregularity.psd` of the samples on [x_min, x_max] at spacing
    <= dx [m]; lines have gid "profile", "welch" and "target".
    """
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
    fig, ax = figure_and_axes(ax, (7.0, 3.5))
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
    if not isinstance(stats, ForceStatistics):
        raise TypeError(f"stats must be a trackwheel.ForceStatistics, "
                        f"got {type(stats).__name__}")
    fig, ax = figure_and_axes(ax, (6.0, 3.5))
    keep = stats.band_rms > 0.0  # log axes cannot show an empty band
    ax.loglog(stats.band_centres[keep], stats.band_rms[keep], marker="o", gid="bands")
    ax.set_xlabel("one-third-octave band centre [Hz]")
    ax.set_ylabel("band RMS of N - mean(N) [N]")
    ax.grid(True, which="both", alpha=0.3)
    return fig

