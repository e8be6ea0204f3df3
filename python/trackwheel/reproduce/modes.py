"""The paper's Fig. 3: the natural frequencies against the wheel position, with the analytic
references of the bare rail."""

from __future__ import annotations

import math

import numpy as np

from ..run.eigen import eigen
from ..scene import Scene
from .plan import X_REPORT, Context

# --------------------------------------------------------------------------------------------
# analytic references (docs: Model § Validation)
def analytic_references(scene: Scene) -> dict[str, float]:
    """Frequencies [Hz] of docs: Model § Validation for the bare rail of ``scene``:

    - ``winkler_cut_on``: sqrt(k_f / m) / (2 pi), k_f = k_s / d_s (equivalent Winkler foundation);
    - ``pinned_pinned``: f_pp = pi / (2 d_s^2) sqrt(EI / m) (one span between rigid supports);
    - ``simply_supported_1``: f_1 = pi / (2 L^2) sqrt(EI / m) (the rail without supports).
    """
    r = scene.rail
    m, ei = r.mass_per_length, r.bending_stiffness
    d = scene.supports.spacing
    return {
        "winkler_cut_on": math.sqrt(scene.winkler_modulus / m) / (2.0 * math.pi),
        "pinned_pinned": math.pi / (2.0 * d**2) * math.sqrt(ei / m),
        "simply_supported_1": math.pi / (2.0 * r.length**2) * math.sqrt(ei / m),
    }



def fig3_eigen(ctx: Context) -> None:
    """Paper Fig. 3: the lowest four vertical natural frequencies against wheel position."""
    from .. import plots  # matplotlib is imported only when a figure is drawn

    scene = ctx.scene
    n_pos = ctx.plan.n_eigen_positions
    # the paper's mesh (its 20 elements), as the paper's Fig. 3, not a run's derived one
    ne = scene.rail.n_elements
    res = eigen(scene, np.linspace(0.0, scene.rail.length, n_pos), n_modes=4, n_elements=ne)
    csv = ctx.out / "fig3_eigen.csv"
    header = "position_m," + ",".join(f"f{k + 1}_hz" for k in range(4))
    np.savetxt(csv, np.column_stack([res.positions, res.frequencies]), delimiter=",",
               fmt="%.12g", header=header, comments="")
    ctx.written.append(csv)
    ctx.save(plots.eigen(res), "fig3_eigen.png")
    at = eigen(scene, [X_REPORT], n_modes=4, n_elements=ne)
    ctx.save(plots.mode_shapes(at, 0), "fig3_mode_shapes_x2.5m.png")

    ref = analytic_references(scene)
    lo, hi = res.frequencies.min(axis=0), res.frequencies.max(axis=0)
    s = ctx.summary
    s.append(f"Fig. 3 -- vertical natural frequencies, {n_pos} wheel positions over "
             f"0..{scene.rail.length:g} m")
    at_x = f"at X = {X_REPORT:g} m"
    s.append(f"  {'mode':>4}  {at_x:>13}  {'min':>9}  {'max':>9}")
    for k in range(4):
        s.append(f"  {k + 1:>4}  {at.frequencies[0, k]:>10.1f} Hz  {lo[k]:>6.1f} Hz"
                 f"  {hi[k]:>6.1f} Hz")
    s.append("  analytic references (bare rail, docs: Model § Validation):")
    s.append(f"    Winkler cut-on sqrt(k_f/m)/(2 pi), k_f = k_s/d_s : "
             f"{ref['winkler_cut_on']:8.1f} Hz")
    s.append(f"    pinned-pinned span f_pp                        : "
             f"{ref['pinned_pinned']:8.1f} Hz")
    s.append(f"    simply supported rail without supports, f_1    : "
             f"{ref['simply_supported_1']:8.1f} Hz")

