"""The README's figure: the model (docs/_scripts/schematic.py) and two of its results on the
ballasted track preset (``Scene.ballasted_track()``).

    PYTHONPATH=python python docs/_scripts/readme_figure.py   # writes docs/_static/readme.png

Left: the wheel/rail contact force of the preset's wheel over a 1 mm dipped joint (0.6 m long,
starting at X = 15 m) at 80, 120 and 160 km/h (jointed track is a conventional line's), full model with the contact-patch filter the joint's cusp
needs. Right: the rail's point receptance at mid-span, Euler-Bernoulli against Timoshenko: the
pinned-pinned peak of the 0.6 m bays moves from 1.4 kHz to about 1 kHz with shear. About 15 s.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import schematic  # noqa: E402

import trackwheel as tw  # noqa: E402

OUT = Path(__file__).resolve().parent.parent / "_static" / "readme.png"


def joint_forces(ax):
    track = tw.Scene.ballasted_track()
    joint = tw.Irregularity.dipped_joint(depth=1e-3, length=0.6, at=15.0)
    rough = dataclasses.replace(track, irregularity=joint,
                                contact=dataclasses.replace(track.contact, patch_filter=True))
    # jointed track is a conventional line's: speeds up to 160 km/h
    for kmh, color in ((80, "#7fb3d5"), (120, "#2e86c1"), (160, "#1b4f72")):
        r = tw.simulate(rough, tw.kmh(kmh), x_start=13.5, x_end=17.0, progress=False)
        ax.plot(r.x_wheel, r.normal_force / 1e3, color=color, lw=1.1, label=f"{kmh} km/h")
    ax.axhline(track.static_load / 1e3, color="#888888", lw=0.8, ls=":")
    ax.axvspan(15.0, 15.6, color="#e6e6e6", zorder=0, label="joint: 1 mm deep, 0.6 m")
    ax.set_xlim(14.5, 17.0)
    ax.set_ylim(-5.0, 265.0)
    ax.set_xlabel("wheel position X [m]")
    ax.set_ylabel("contact force N [kN]")
    ax.set_title("Wheel/rail force over a dipped joint", fontsize=10)
    ax.legend(fontsize=8, frameon=False, loc="upper left", ncol=2)


def receptance(ax):
    track = tw.Scene.ballasted_track()
    f = np.geomspace(20.0, 3000.0, 600)
    for beam, color in (("euler", "#b03a2e"), ("timoshenko", "#1e8449")):
        s = dataclasses.replace(track, rail=dataclasses.replace(track.rail, beam=beam))
        a = tw.receptance(s, 15.3, f)
        name = "Euler-Bernoulli" if beam == "euler" else "Timoshenko"
        ax.loglog(f, np.abs(a), color=color, lw=1.1, label=f"{name} rail")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("|receptance| at mid-span [m/N]")
    ax.set_title("Track receptance: the pinned-pinned peak", fontsize=10)
    ax.legend(fontsize=8, frameon=False, loc="lower left")
    ax.grid(True, which="both", lw=0.3, color="#dddddd")


def main(out: Path = OUT) -> Path:
    fig = plt.figure(figsize=(10.0, 7.6))
    top = fig.add_axes([0.0, 0.44, 1.0, 0.56])
    schematic.draw(top)
    left = fig.add_axes([0.08, 0.07, 0.38, 0.31])
    right = fig.add_axes([0.59, 0.07, 0.38, 0.31])
    joint_forces(left)
    receptance(right)
    for ax in (left, right):
        ax.tick_params(labelsize=8)
        ax.xaxis.label.set_size(9)
        ax.yaxis.label.set_size(9)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=90, facecolor="white")
    plt.close(fig)
    return out


if __name__ == "__main__":
    path = main(Path(sys.argv[1]) if len(sys.argv) > 1 else OUT)
    print(f"wrote {path} ({path.stat().st_size // 1024} KiB)")
