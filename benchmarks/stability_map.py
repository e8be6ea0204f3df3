"""Stability map (issue 6): where each integrator fails, measured on real runs.

1. Explicit RK4: the largest stable dt, measured by bisection on short runs (divergence detected
   by the kernel: DivergenceError on a non-finite state or energy runaway) for 10, 20, 40 and 80
   elements at 50, 150, 300 and 400 km/h, against ``trackwheel.stability_limit`` (2 sqrt(2) /
   omega_max of the assembled system at the start).
2. Drift of the rolling constraint for explicit RK4 (acceleration-level constraint, the paper's
   eq. 25) with Baumgarte stabilisation off and on: max |slip velocity| against dt; the
   velocity-level constraint of generalized-alpha for comparison.
3. Generalized-alpha: increase dt until Newton fails (DivergenceError) or a cap, for
   rho_inf in {0, 0.5, 0.8, 1}: on the paper's passage and on harder cases in which the wheel
   is dropped 0.2 mm or 2 mm onto the rail (contact loss, landing, bouncing, stick/slip
   transitions). The cap is 20 steps per run; the Newton iterations per step are recorded.

    python benchmarks/stability_map.py

Writes stability_map_explicit.csv, stability_map_drift.csv, stability_map_newton.csv and
stability_map.png next to this file. Takes about 3-5 minutes on the 2-core machine.
"""

from __future__ import annotations

import math
import os
import time
import warnings

import numpy as np
from _common import write_csv

import trackwheel as tw

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = tw.Scene.kato2005()
MESHES = (10, 20, 40, 80)
SPEEDS_KMH = (50, 150, 300, 400)
MAX_STEPS = 2000
BISECTIONS = 7


def diverges(ne, dt, v, **kw):
    """(diverged, step) of an explicit run of at most MAX_STEPS steps (kept on the rail)."""
    n = int(min(MAX_STEPS, 4.4 / (v * dt)))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tw.StabilityWarning)
        try:
            tw.simulate(SCENE, v, integrator="explicit", dt=dt, n_elements=ne,
                        duration=n * dt, output_every=n, progress=False, **kw)
        except tw.DivergenceError as e:
            return True, e.step
    return False, n


def explicit_map():
    rows = []
    for ne in MESHES:
        pred = tw.stability_limit(SCENE, n_elements=ne)
        for kmh in SPEEDS_KMH:
            v = tw.kmh(kmh)
            t0 = time.perf_counter()
            lo, hi = 0.7 * pred, 1.3 * pred
            while diverges(ne, lo, v)[0]:
                lo *= 0.7
            while not diverges(ne, hi, v)[0]:
                hi *= 1.3
            for _ in range(BISECTIONS):
                mid = math.sqrt(lo * hi)
                if diverges(ne, mid, v)[0]:
                    hi = mid
                else:
                    lo = mid
            steps_at_hi = diverges(ne, hi, v)[1]
            rows.append(dict(n_elements=ne, speed_kmh=kmh, predicted_s=pred, stable_s=lo,
                             unstable_s=hi, measured_s=math.sqrt(lo * hi),
                             ratio=math.sqrt(lo * hi) / pred, steps_to_divergence_at_hi=steps_at_hi,
                             max_steps=MAX_STEPS, wall_s=time.perf_counter() - t0))
            r = rows[-1]
            print(f"explicit {ne:3d} el. {kmh:3d} km/h: predicted {pred:.4e} s, measured "
                  f"[{lo:.4e}, {hi:.4e}] s, ratio {r['ratio']:.3f} ({r['wall_s']:.1f} s)",
                  flush=True)
    return rows


def drift_map():
    rows = []
    v = tw.kmh(300)
    ne = 20
    limit = tw.stability_limit(SCENE, n_elements=ne)
    for alpha in (0.0, 1e3, 1e4):
        for dt in (1e-5, 5e-6, 2.5e-6, 1.25e-6, 6.25e-7, 3.125e-7):
            try:
                r = tw.simulate(SCENE, v, integrator="explicit", dt=dt, n_elements=ne,
                                baumgarte=alpha, x_end=1.25, progress=False)
                slip = float(np.max(np.abs(r.slip)))
                verr = float(np.max(np.abs(r.v_error)))
                err = ""
            except tw.DivergenceError as e:
                slip = verr = math.nan
                err = e.cause
            rows.append(dict(integrator="explicit", baumgarte=alpha, n_elements=ne,
                             speed_kmh=300, dt=dt, dt_over_limit=dt / limit,
                             max_abs_slip=slip, max_abs_v_error_pct=verr, error=err))
            print(f"drift explicit alpha={alpha:g} dt={dt:.3e}: max|slip| {slip:.3e} m/s, "
                  f"max|v_e| {verr:.3e} %", flush=True)
    for dt in (4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6):
        r = tw.simulate(SCENE, v, dt=dt, n_elements=ne, x_end=1.25, progress=False)
        rows.append(dict(integrator="generalized_alpha", baumgarte=math.nan, n_elements=ne,
                         speed_kmh=300, dt=dt, dt_over_limit=dt / limit,
                         max_abs_slip=float(np.max(np.abs(r.slip))),
                         max_abs_v_error_pct=float(np.max(np.abs(r.v_error))), error=""))
        print(f"drift gen.-alpha dt={dt:.3e}: max|slip| {rows[-1]['max_abs_slip']:.3e} m/s",
              flush=True)
    return rows


def newton_map():
    rows = []
    dts = [1e-5 * 2**k for k in range(8)]  # 1e-5 ... 1.28e-3 s
    cases = {"passage": dict(), "drop 0.2 mm": dict(drop_height=2e-4, x_end=1.25),
             "drop 2 mm": dict(drop_height=2e-3)}
    for case, kw in cases.items():
        for kmh in (100, 300):
            v = tw.kmh(kmh)
            for rho in (0.0, 0.5, 0.8, 1.0):
                first_fail = math.nan
                for dt in dts:
                    t_end = ((kw.get("x_end", 4.75) - 0.25) / v)
                    if dt > t_end / 20:  # fewer than 20 steps over the run: the cap
                        break
                    t0 = time.perf_counter()
                    try:
                        r = tw.simulate(SCENE, v, dt=dt, n_elements=20, rho_inf=rho,
                                        progress=False, **kw)
                        ok, cause = True, ""
                        it = r.newton_iterations / max(r.steps, 1)
                        changes = r.state_changes
                        lost = r.lost_contact
                    except tw.DivergenceError as e:
                        ok, cause, it, changes, lost = False, str(e).split(": ", 1)[-1][:160], \
                            math.nan, -1, None
                    rows.append(dict(case=case, speed_kmh=kmh, rho_inf=rho, dt=dt, ok=ok,
                                     newton_per_step=it, state_changes=changes,
                                     lost_contact=lost, cause=cause,
                                     wall_s=time.perf_counter() - t0))
                    if not ok:
                        first_fail = dt
                        break
                print(f"gen.-alpha {case:12s} {kmh} km/h rho_inf={rho}: first failing dt "
                      f"{first_fail:.3g} s (tried up to {dt:.3g} s)", flush=True)
    return rows


def chart(ex, drift, newton, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(17, 5))
    a = ax[0]
    for kmh, m in zip(SPEEDS_KMH, "os^v"):
        pts = [r for r in ex if r["speed_kmh"] == kmh]
        a.loglog([r["n_elements"] for r in pts], [r["measured_s"] for r in pts], m, ms=7,
                 mfc="none", label=f"measured, {kmh} km/h")
    pred = sorted({(r["n_elements"], r["predicted_s"]) for r in ex})
    a.loglog([p[0] for p in pred], [p[1] for p in pred], "k-", label="predicted 2√2/ω_max")
    a.set_xlabel("rail elements [-]")
    a.set_ylabel("largest stable dt, explicit RK4 [s]")
    a.set_title("Explicit stability limit: measured vs predicted")
    a.legend(fontsize=8)
    a.grid(True, which="both", lw=0.3)

    a = ax[1]
    for alpha, st in ((0.0, "o-"), (1e3, "s--"), (1e4, "^:")):
        pts = [r for r in drift if r["integrator"] == "explicit" and r["baumgarte"] == alpha
               and np.isfinite(r["max_abs_slip"])]
        a.loglog([r["dt"] for r in pts], [max(r["max_abs_slip"], 1e-16) for r in pts], st,
                 label=f"explicit RK4, Baumgarte α = {alpha:g} 1/s")
    pts = [r for r in drift if r["integrator"] == "generalized_alpha"]
    a.loglog([r["dt"] for r in pts], [max(r["max_abs_slip"], 1e-16) for r in pts], "k*-",
             label="generalized-alpha (velocity level)")
    lim = tw.stability_limit(SCENE, n_elements=20)
    a.axvline(lim, color="r", lw=0.8, ls=":", label="explicit limit (20 el.)")
    a.set_xlabel("dt [s]")
    a.set_ylabel("max |slip velocity| [m/s]")
    a.set_title("Rolling-constraint drift, 300 km/h, 20 el., first 1 m")
    a.legend(fontsize=8)
    a.grid(True, which="both", lw=0.3)

    a = ax[2]
    styles = {"passage": "-", "drop 0.2 mm": "--", "drop 2 mm": ":"}
    colors = {0.0: "tab:blue", 0.5: "tab:orange", 0.8: "tab:green", 1.0: "tab:red"}
    for case in styles:
        for rho in colors:
            pts = [r for r in newton if r["case"] == case and r["speed_kmh"] == 300
                   and r["rho_inf"] == rho]
            good = [r for r in pts if r["ok"]]
            a.semilogx([r["dt"] for r in good], [r["newton_per_step"] for r in good],
                       styles[case], marker="o", ms=3, color=colors[rho],
                       label=f"{case}, ρ∞ = {rho:g}")
            bad = [r for r in pts if not r["ok"]]
            if bad:
                a.semilogx([r["dt"] for r in bad], [1.0] * len(bad), "kx", ms=10)
    a.set_xlabel("dt [s] (x: Newton failed; lines end at the cap of 20 steps per run)")
    a.set_ylabel("Newton iterations per step [-]")
    a.set_title("Generalized-alpha, 20 el., 300 km/h: Newton effort vs dt")
    a.legend(fontsize=6, ncol=2)
    a.grid(True, which="both", lw=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main():
    t0 = time.perf_counter()
    ex = explicit_map()
    write_csv("stability_map_explicit.csv", ex)
    drift = drift_map()
    write_csv("stability_map_drift.csv", drift)
    newton = newton_map()
    write_csv("stability_map_newton.csv", newton)
    chart(ex, drift, newton, os.path.join(HERE, "stability_map.png"))
    ratios = [r["ratio"] for r in ex]
    print(f"explicit: measured/predicted in [{min(ratios):.3f}, {max(ratios):.3f}] over "
          f"{len(ex)} cases; total {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
