"""The track along X: each sleeper's force envelope beside the supports' properties there."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .common import legend_above

#: the support properties drawn under the envelope, with their axis labels and scales
_PROPERTIES = (("ballast_stiffness", "k_b [MN/m]", 1e-6), ("stiffness", "k_p, k_s [MN/m]", 1e-6))


def sleeper_envelope(result) -> Figure:
    """Each support's envelope along the track (:meth:`trackwheel.Result.sleeper_envelope`,
    also on a travelling window) over X [m]: the largest and smallest ballast force [kN]
    (gids "ballast max", "ballast min") and rail-seat force (gids "rail seat max", "rail seat
    min") on top, the sleepers' lowest displacement [mm] (gid "sleeper z min") in the middle,
    and below the supports' properties at the same X (``Supports.values``: the ballast and pad
    stiffness [MN/m], gids "k_b", "k_p"), so a force peak reads against the bed under it."""
    df = result.sleeper_envelope()
    x = df.x.to_numpy()
    fig = Figure(figsize=(7.0, 6.0), layout="constrained")
    ax_f, ax_z, ax_k = fig.subplots(3, 1, sharex=True, height_ratios=(2, 1, 1))
    for name, label, style in (("ballast_force_max", "ballast max", "-"),
                               ("ballast_force_min", "ballast min", "--"),
                               ("rail_seat_force_max", "rail seat max", "-"),
                               ("rail_seat_force_min", "rail seat min", "--")):
        color = "C0" if label.startswith("ballast") else "C1"
        ax_f.plot(x, 1e-3 * df[name].to_numpy(), style, color=color, marker=".", label=label,
                  gid=label)
    ax_f.set_ylabel("force [kN]\n(compression > 0)")
    legend_above(ax_f, ncols=4)
    ax_z.plot(x, 1e3 * df.sleeper_z_min.to_numpy(), color="C2", marker=".",
              gid="sleeper z min")
    ax_z.set_ylabel("lowest z [mm]")
    values = result.scene.supports.values(x)
    for (name, label, scale), color in zip(_PROPERTIES, ("C3", "C4")):
        v = getattr(values, name)
        if v is None:
            continue
        gid = "k_b" if name == "ballast_stiffness" else "k_p"
        ax_k.step(x, scale * np.asarray(v), where="mid", color=color, label=label, gid=gid)
    ax_k.set_ylabel("stiffness [MN/m]")
    ax_k.set_xlabel("X [m]")
    ax_k.legend(fontsize="small")
    for ax in (ax_f, ax_z, ax_k):
        ax.grid(True, alpha=0.3)
    s = result.settings
    fig.suptitle(f"Sleeper envelope along the track at {s.speed * 3.6:.0f} km/h "
                 f"({s.fidelity})", fontsize="medium")
    return fig
