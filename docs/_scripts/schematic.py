"""The model at a glance: wheel, rail, pad, sleeper, ballast and vehicle, drawn with matplotlib.

    python docs/_scripts/schematic.py            # writes docs/_static/schematic.png

A drawing, not a plot of results: the proportions are chosen to be readable (the rail's
deflection is exaggerated, the springs are not to scale). The symbols are those of
docs/model.md. Needs only matplotlib; the output is committed, so the docs build does not run
this script (docs/development.md says when to rerun it).
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.patches import Circle, FancyArrowPatch, Polygon, Rectangle  # noqa: E402

OUT = Path(__file__).resolve().parent.parent / "_static" / "schematic.png"

INK = "#222222"
STEEL = "#5b6f86"
RAIL = "#3b4a5c"
CONCRETE = "#b9b2a5"
BALLAST = "#d9cfb8"
BODY = "#e8eef5"
ACCENT = "#c0392b"
LABEL = dict(fontsize=9, color=INK)
SYMBOL = dict(fontsize=9, color="#444444")


def spring(ax, x, y0, y1, width=0.09, turns=4, **kw):
    """A zigzag spring from (x, y0) down or up to (x, y1), straight leads at both ends."""
    lead = 0.18 * (y1 - y0)
    ys = np.linspace(y0 + lead, y1 - lead, 2 * turns + 1)
    xs = x + width * np.array([0.0] + [(-1) ** i for i in range(1, 2 * turns)] + [0.0])
    ax.plot([x, *xs, x], [y0, *ys, y1], color=INK, lw=1.0, solid_joinstyle="miter", **kw)


def damper(ax, x, y0, y1, width=0.07):
    """A dashpot between y0 (top) and y1 (bottom): a cup on the lower rod, a piston above."""
    top, bottom = max(y0, y1), min(y0, y1)
    mid = 0.5 * (top + bottom)
    h = 0.28 * (top - bottom)
    ax.plot([x, x], [top, mid + 0.2 * h], color=INK, lw=1.0)  # piston rod
    ax.plot([x - 0.75 * width, x + 0.75 * width], [mid + 0.2 * h] * 2, color=INK, lw=1.4)
    ax.plot([x - width, x - width, x + width, x + width],
            [mid + 0.9 * h, mid - 0.5 * h, mid - 0.5 * h, mid + 0.9 * h], color=INK, lw=1.0)
    ax.plot([x, x], [mid - 0.5 * h, bottom], color=INK, lw=1.0)


def spring_damper(ax, x, y_top, y_bottom, gap=0.11):
    """A spring and a dashpot side by side between two horizontal levels, with end plates."""
    spring(ax, x - gap, y_top, y_bottom)
    damper(ax, x + gap, y_top, y_bottom)
    for y in (y_top, y_bottom):
        ax.plot([x - gap, x + gap], [y, y], color=INK, lw=1.0)


def ground(ax, x0, x1, y, depth=0.12):
    ax.plot([x0, x1], [y, y], color=INK, lw=1.2)
    for x in np.arange(x0 + 0.05, x1, 0.12):
        ax.plot([x, x - 0.08], [y, y - depth], color=INK, lw=0.6)


def label(ax, text, xy, xytext, symbol=None, ha="left"):
    """An annotation with a thin leader line; ``symbol`` is set under the name."""
    ax.annotate(text, xy=xy, xytext=xytext, ha=ha, va="center",
                arrowprops=dict(arrowstyle="-", color="#777777", lw=0.7,
                                shrinkA=2, shrinkB=2), **LABEL)
    if symbol:
        ax.annotate(symbol, xy=xytext, xytext=(0, -11), textcoords="offset points",
                    ha=ha, va="center", **SYMBOL)


def rail_y(x, load_positions, sag=0.06, width=0.9):
    """The rail's centre line: straight, pressed down under each wheel (exaggerated)."""
    y = np.zeros_like(x)
    for xw in load_positions:
        y -= sag * np.exp(-((x - xw) / width) ** 2) * np.cos(1.2 * (x - xw))
    return y


def draw(ax):
    """The schematic on ``ax`` (data units: about 12 wide, 7.4 high)."""
    x0, x1 = 0.0, 11.0
    y_rail = 0.0
    rail_h = 0.16
    sleepers = np.arange(0.6, x1, 1.0)
    wheels = (3.6, 6.6)
    radius = 0.62

    # ballast bed and ground
    ground(ax, x0 - 0.1, x1 + 0.1, -2.15)
    ax.add_patch(Rectangle((x0 - 0.1, -2.15), x1 + 0.2, 0.06, color=BALLAST, lw=0, zorder=0))

    # sleepers on the ballast (spring + damper to the ground), pads between rail and sleeper
    for xs in sleepers:
        ax.add_patch(Rectangle((xs - 0.22, -1.02), 0.44, 0.22, facecolor=CONCRETE,
                               edgecolor=INK, lw=0.8, zorder=2))
        spring_damper(ax, xs, -1.02, -2.15)
        y_here = y_rail + rail_y(np.array([xs]), wheels)[0] - rail_h / 2
        spring_damper(ax, xs, y_here, -0.80)

    # the rail: a beam, pressed down under the wheels
    x = np.linspace(x0, x1, 400)
    yc = y_rail + rail_y(x, wheels)
    ax.fill_between(x, yc - rail_h / 2, yc + rail_h / 2, color=RAIL, lw=0, zorder=3)
    for xe in np.linspace(x0, x1, 23)[1:-1]:  # element boundaries (nodes)
        ye = y_rail + rail_y(np.array([xe]), wheels)[0]
        ax.plot([xe, xe], [ye - rail_h / 2, ye + rail_h / 2], color="white", lw=0.5, zorder=4)
    # cut ends: the rail continues (or ends in absorbing zones)
    for xe in (x0, x1):
        ax.plot([xe, xe], [-0.12, 0.12], color=INK, lw=0.8, ls=(0, (2, 2)), zorder=4)

    # wheels on the rail, each with its primary suspension to the bogie frame
    y_frame = 1.95
    for xw in wheels:
        y_top = y_rail + rail_y(np.array([xw]), wheels)[0] + rail_h / 2
        cy = y_top + radius
        ax.add_patch(Circle((xw, cy), radius, facecolor="#dfe5ec", edgecolor=STEEL, lw=2.0,
                            zorder=5))
        ax.add_patch(Circle((xw, cy), 0.08, facecolor=STEEL, edgecolor=INK, lw=0.8, zorder=6))
        ax.plot([xw, xw + 0.45 * radius], [cy, cy + 0.55 * radius], color=STEEL, lw=0.8,
                zorder=6)
        spring_damper(ax, xw, y_frame, cy + 0.08, gap=0.13)
    # the bogie frame and the secondary suspension to the car body
    xb = 0.5 * (wheels[0] + wheels[1])
    ax.add_patch(Rectangle((wheels[0] - 0.45, y_frame), wheels[1] - wheels[0] + 0.9, 0.32,
                           facecolor="#c9d3de", edgecolor=INK, lw=0.9, zorder=5))
    y_car = 3.35
    spring_damper(ax, xb, y_car, y_frame + 0.32, gap=0.16)
    # the car body, cut: a half car has a second bogie to the right
    car = Polygon([(1.2, y_car), (10.6, y_car), (10.9, y_car + 0.55), (10.6, y_car + 1.1),
                   (1.2, y_car + 1.1)], closed=True, facecolor=BODY, edgecolor=INK, lw=0.9,
                  zorder=5)
    ax.add_patch(car)
    ax.plot([10.6, 10.9, 10.6], [y_car, y_car + 0.55, y_car + 1.1], color=BODY, lw=1.6,
            zorder=6)  # the cut edge drawn open
    ax.plot([10.6, 10.9, 10.6], [y_car, y_car + 0.55, y_car + 1.1], color=INK, lw=0.8,
            ls=(0, (3, 2)), zorder=7)

    # motion: speed and rotation
    ax.add_patch(FancyArrowPatch((0.7, 2.4), (2.3, 2.4), arrowstyle="-|>", mutation_scale=12,
                                 color=ACCENT, lw=1.4, zorder=8))
    ax.text(1.5, 2.52, r"$v$", ha="center", va="bottom", color=ACCENT, fontsize=12)
    # coordinate axes
    ax.add_patch(FancyArrowPatch((-1.2, 0.9), (-0.35, 0.9), arrowstyle="-|>", mutation_scale=9,
                                 color=INK, lw=0.9))
    ax.add_patch(FancyArrowPatch((-1.2, 0.9), (-1.2, 1.75), arrowstyle="-|>",
                                 mutation_scale=9, color=INK, lw=0.9))
    ax.text(-0.3, 0.9, r"$X$", va="center", **LABEL)
    ax.text(-1.2, 1.82, r"$Y$", ha="center", va="bottom", **LABEL)

    # labels, right of the drawing
    lx = 11.55
    xw = wheels[1]
    y_top = y_rail + rail_y(np.array([xw]), wheels)[0] + rail_h / 2
    label(ax, "car body", (10.2, y_car + 0.8), (lx, 4.25), r"$M_c$, $J_c$ (half car)")
    label(ax, "secondary suspension", (xb + 0.2, y_car - 0.4), (lx, 3.3), r"$k_2$, $c_2$")
    label(ax, "bogie frame", (wheels[1] + 0.4, y_frame + 0.2), (lx, 2.55), r"$M_b$, $J_b$")
    label(ax, "primary suspension", (xw + 0.2, y_frame - 0.3), (lx, 1.85), r"$k_1$, $c_1$")
    label(ax, "wheel", (xw + 0.45, y_top + radius + 0.35), (lx, 1.15),
          r"$M$, $J$, $\rho_0$; flats, polygons")
    label(ax, "contact", (xw + 0.03, y_top + 0.02), (lx, 0.45), r"Hertz; stick/slip, $\mu$")
    label(ax, "rail", (9.6, 0.05), (lx, -0.2), r"ANCF beam $EI$, $EA$, $\varrho A$")
    label(ax, "rail pad", (sleepers[-1] + 0.1, -0.45), (lx, -0.85), r"$k_p$, $c_p$")
    label(ax, "sleeper", (sleepers[-1] + 0.2, -0.92), (lx, -1.45), r"$m_s$")
    label(ax, "ballast", (sleepers[-1] + 0.1, -1.6), (lx, -2.05), r"$k_b$, $c_b$")
    ax.set_xlim(-1.5, 14.9)
    ax.set_ylim(-2.45, 4.7)
    ax.set_aspect("equal")
    ax.axis("off")


def main(out: Path = OUT) -> Path:
    fig, ax = plt.subplots(figsize=(10.0, 4.6))
    fig.subplots_adjust(0.0, 0.0, 1.0, 1.0)
    draw(ax)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=110, facecolor="white")
    plt.close(fig)
    return out


if __name__ == "__main__":
    path = main(Path(sys.argv[1]) if len(sys.argv) > 1 else OUT)
    print(f"wrote {path} ({path.stat().st_size // 1024} KiB)")
