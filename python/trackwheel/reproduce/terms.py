"""The paper's Fig. 8: the terms of the contact-point acceleration at two speeds."""

from __future__ import annotations

import math

import numpy as np

from ..base.units import kmh
from ..run.simulate import simulate
from ..base.fields import Quantity
from .plan import Context

#: the columns of the acceleration-term table (Fig. 8), one row per speed and term
TERM_COLUMNS: tuple[Quantity, ...] = (
    Quantity("speed", "km/h", "forward speed v"),
    Quantity("term", "", "the term, A .. E (docs: Model § Outputs, eq. 21)", "str"),
    Quantity("max_abs", "m/s^2", "the term's largest magnitude"),
    Quantity("rms", "m/s^2", "the term's root mean square"),
    Quantity("mean", "m/s^2", "the term's mean"),
)
T = {q.name: q.label for q in TERM_COLUMNS}

# --------------------------------------------------------------------------------------------
# Fig. 8: acceleration terms
def fig8_conclusions(rms) -> list[str]:
    """The sentences of Fig. 8 from the rms [m/s²] of each term (index "A".."E", columns: two
    speeds [km/h] ascending)."""
    v0, v1 = rms.columns[:2]
    growth = rms[v1] / rms[v0]
    small = rms.loc[["C", "D", "E"]].max(axis=0) / rms.loc[["A", "B"]].min(axis=0)
    worst = float(small.max())
    order = f"1e{math.floor(math.log10(worst))}" if worst > 0 else "0"
    size = (f"C, D, E are at most {worst:.2g} of the smaller of A, B (order {order})"
            if worst < 1 else f"C, D, E reach {worst:.2g} times the smaller of A, B")
    return [(f"  here: rms ratio {v1:g}/{v0:g} km/h = {growth.min():.1f}..{growth.max():.1f}"
            f" (v² ratio {(v1 / v0) ** 2:.1f}); {size}.")]


def fig8_acceleration_terms(ctx: Context) -> None:
    """Paper Fig. 8: the acceleration terms A-E at 100 and 300 km/h."""
    import pandas as pd

    from .. import plots

    p = ctx.plan
    runs = []
    for v in p.fig8_speeds_kmh:
        r = simulate(ctx.scene, kmh(v), progress=False, **p.simulate)
        ctx.log(f"{v:g} km/h: {r.steps} steps, {r.wall_time:.1f} s")
        runs.append(r)
    rows = []
    for v, r in zip(p.fig8_speeds_kmh, runs):
        for term in "ABCDE":
            x = getattr(r, f"acc_{term}")
            rows.append({T["speed"]: v, T["term"]: term, T["max_abs"]: float(np.max(np.abs(x))),
                         T["rms"]: float(np.sqrt(np.mean(x**2))), T["mean"]: float(np.mean(x))})
    table = pd.DataFrame(rows)
    ctx.table(table, "fig8_acceleration_terms.csv")
    ctx.save(plots.acceleration_terms(runs), "fig8_acceleration_terms.png")

    s = ctx.summary
    s.append(f"Fig. 8 -- terms of the contact-point acceleration (docs: Model § Outputs), "
             f"{p.describe_settings(ctx.scene)}")
    s.append("  term  " + "  ".join(f"rms at {v:g} km/h" for v in p.fig8_speeds_kmh)
             + "  [m/s²]")
    rms = table.pivot(index=T["term"], columns=T["speed"], values=T["rms"])
    for term in "ABCDE":
        s.append(f"  {term:>4}  " + "  ".join(f"{rms.loc[term, v]:>16.3g}"
                                               for v in p.fig8_speeds_kmh))
    if len(p.fig8_speeds_kmh) == 2:
        s.append("  paper: the terms grow as the square of the speed and are remarkable at "
                 "high speed.")
        s.extend(fig8_conclusions(rms[list(p.fig8_speeds_kmh)]))


