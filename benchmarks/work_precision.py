"""Work-precision of the two integrators on the paper's scene (issue 6): wall time against error.

For the paper's scene at 100 and 300 km/h (full passage 0.25 m -> 4.75 m), each integrator runs over
a range of dt with 20, 40 and 80 elements. Wall time is the median of REPEATS runs of
``trackwheel.simulate`` (fewer for slow explicit points, see ``repeats_for``: one run above 20 s,
three above 3 s; the CSV says how many). Errors are against a converged reference computed once and
cached in benchmarks/.cache/: generalized-alpha, 80 elements, dt = 6.25e-7 s. Its convergence is
checked against a second reference with 160 elements at dt = 1.25e-6 s (the difference is printed
and recorded in work_precision_reference.csv). Three errors:

- relative error of the amplitude max |d| (d = y_B - y_qs(X_A), docs: Model § Outputs),
- relative error of the main frequency of d(t),
- RMS of d(t) - d_ref(t) over the passage, divided by max |d_ref|.

The paper's own setting (explicit RK4, dt = 1e-7 s, 20 elements) is run once per speed over the
full passage (one run each: about a minute at 300 km/h, three at 100 km/h) and marked on the
chart.

Also measured: the per-step cost of generalized-alpha against one banded factorisation + solve
of the rail's iteration matrix M + gamma' h C_s + beta' h^2 K_t (kernel helper
``_core.testing.time_band_factor_solve``, plain band and bordered with the wheel's three rows).

    python benchmarks/work_precision.py [--quick]

Writes work_precision.csv, work_precision_reference.csv, work_precision_cost.csv and
work_precision.png next to this file.
"""

from __future__ import annotations

import argparse
import csv
import os
import platform
import statistics
import time

import numpy as np
from _common import write_csv

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel  # documented internal: the kernel's parameter structs

HERE = os.path.dirname(os.path.abspath(__file__))
CACHE = os.path.join(HERE, ".cache")
SCENE = tw.Scene.kato2005()
SPEEDS_KMH = (100, 300)
MESHES = (20, 40, 80)
REPEATS = 5
REF = dict(n_elements=80, dt=6.25e-7, output_every=2)  # samples every 1.25e-6 s
REF_CHECK = dict(n_elements=160, dt=1.25e-6, output_every=1)
PAPER = dict(integrator="explicit", n_elements=20, dt=1e-7)
GA_DTS = (4e-5, 2e-5, 1e-5, 5e-6, 2.5e-6)
# explicit: steps at and below each mesh's stability limit (1.03e-5, 2.58e-6, 6.44e-7 s)
EX_DTS = {20: (1e-5, 5e-6, 2.5e-6, 1.25e-6), 40: (2.5e-6, 1.25e-6),
          80: (6.25e-7,)}


def repeats_for(seconds: float, integrator: str) -> int:
    """Generalized-alpha: always REPEATS; explicit: 1 above 20 s, 3 above 3 s."""
    if integrator == "generalized_alpha":
        return REPEATS
    return 1 if seconds > 20 else 3 if seconds > 3 else REPEATS


def measure(result):
    a = tw.analyse(result)
    return a.t, a.dynamic, a.amplitude, a.main_frequency


def reference(kmh: float, cfg: dict, tag: str):
    """(t, d, amplitude, frequency) of a reference run, cached on disk."""
    os.makedirs(CACHE, exist_ok=True)
    path = os.path.join(CACHE, f"ref_{tag}_{kmh:g}kmh_{cfg['n_elements']}el_{cfg['dt']:.3e}.npz")
    if os.path.exists(path):
        z = np.load(path)
        return z["t"], z["d"], float(z["amplitude"]), float(z["frequency"])
    t0 = time.perf_counter()
    r = tw.simulate(SCENE, tw.kmh(kmh), progress=False, **cfg)
    t, d, amp, f = measure(r)
    np.savez(path, t=t, d=d, amplitude=amp, frequency=f)
    print(f"  reference {tag} {kmh:g} km/h: {cfg} in {time.perf_counter() - t0:.1f} s",
          flush=True)
    return t, d, amp, f


def errors(t, d, amp, f, ref):
    tr, dr, ampr, fr = ref
    dref = np.interp(t, tr, dr)
    return (abs(amp - ampr) / ampr, abs(f - fr) / fr,
            float(np.sqrt(np.mean((d - dref) ** 2)) / np.max(np.abs(dr))))


def timed_case(kmh, integrator, ne, dt, ref, repeats=None):
    v = tw.kmh(kmh)
    walls, kernels = [], []
    t0 = time.perf_counter()
    r = tw.simulate(SCENE, v, integrator=integrator, n_elements=ne, dt=dt, progress=False)
    walls.append(time.perf_counter() - t0)
    kernels.append(r.wall_time)
    n = repeats if repeats is not None else repeats_for(walls[0], integrator)
    for _ in range(n - 1):
        t0 = time.perf_counter()
        r = tw.simulate(SCENE, v, integrator=integrator, n_elements=ne, dt=dt, progress=False)
        walls.append(time.perf_counter() - t0)
        kernels.append(r.wall_time)
    t, d, amp, f = measure(r)
    ea, ef, er = errors(t, d, amp, f, ref)
    return dict(speed_kmh=kmh, integrator=integrator, n_elements=ne, dt=dt, repeats=n,
                wall_median_s=statistics.median(walls), wall_min_s=min(walls),
                kernel_median_s=statistics.median(kernels), steps=r.steps,
                us_per_step=1e6 * statistics.median(kernels) / r.steps,
                newton_per_step=r.newton_iterations / r.steps, amplitude=amp,
                main_frequency=f, amp_err=ea, freq_err=ef, rms_err=er)


def step_cost():
    """Per-step cost of generalized-alpha vs one band factorisation + solve, per mesh.

    Both timed back to back (best of 5: the machine is shared): the kernel time of a full
    passage at 300 km/h, dt = 1e-5 s, divided by its steps, and the kernel helper's mean time
    of a factorisation + solve of M + gamma' h C_s + beta' h^2 K_t (20000 repeats), for the plain
    band and for the bordered matrix with the wheel's three rows (what a Newton iteration
    factorises)."""
    out = []
    rho = 0.8
    am, af = (2 * rho - 1) / (rho + 1), rho / (rho + 1)
    gam, bet = 0.5 - am + af, 0.25 * (1 - am + af) ** 2
    h = 1e-5
    cq, cv = bet * (1 - af) / (1 - am) * h * h, gam * (1 - af) / (1 - am) * h
    for ne in MESHES:
        model = kernel.rail_model(SCENE, ne)
        runs = [tw.simulate(SCENE, tw.kmh(300), dt=h, n_elements=ne, progress=False)
                for _ in range(5)]
        step = min(r.wall_time for r in runs) / runs[0].steps
        band = min(_core.testing.time_band_factor_solve(model, cq, cv, 20000) for _ in range(5))
        bord = min(_core.testing.time_band_factor_solve(model, cq, cv, 20000, True) for _ in range(5))
        out.append(dict(n_elements=ne, ga_step_us=1e6 * step,
                        newton_per_step=runs[0].newton_iterations / runs[0].steps,
                        band_factor_solve_us=1e6 * band, bordered_factor_solve_us=1e6 * bord,
                        ratio_band=step / band, ratio_bordered=step / bord))
    return out


def summary(rows):
    """The issue's speed-up target, in two readings (see benchmarks/README.md)."""
    paper_rows = [r for r in rows if r["integrator"] == "explicit" and r["dt"] == 1e-7]
    for p in paper_rows:
        ga = [r for r in rows if r["speed_kmh"] == p["speed_kmh"] and
              r["integrator"] == "generalized_alpha"]
        for label, ok in (("amplitude error <= 1 %", lambda r: r["amp_err"] <= 0.01),
                          ("amplitude error and RMS(d) error <= 1 %",
                           lambda r: r["amp_err"] <= 0.01 and r["rms_err"] <= 0.01)):
            good = [r for r in ga if ok(r)]
            if not good:
                print(f"{p['speed_kmh']:g} km/h: no gen.-alpha run with {label}")
                continue
            b = min(good, key=lambda r: r["wall_median_s"])
            print(f"{p['speed_kmh']:g} km/h: paper's scheme {p['wall_median_s']:.1f} s (amplitude "
                  f"error {p['amp_err']:.2%}, RMS {p['rms_err']:.2%}); cheapest gen.-alpha run "
                  f"with {label}: {b['n_elements']} el., dt = {b['dt']:g} s, "
                  f"{b['wall_median_s']:.3f} s (amplitude {b['amp_err']:.2%}, RMS "
                  f"{b['rms_err']:.2%}) -> {p['wall_median_s'] / b['wall_median_s']:.0f}x faster "
                  f"(target >= 100x)")


def read_csv(name):
    with open(os.path.join(HERE, name)) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, val in r.items():
            if k != "integrator":
                r[k] = float(val) if any(c in val for c in ".en") else int(val)
    return rows


def chart(rows, paper_rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    metrics = [("amp_err", "relative amplitude error [-]"),
               ("freq_err", "relative main-frequency error [-]"),
               ("rms_err", "RMS error of d(t) / max|d_ref| [-]")]
    fig, axes = plt.subplots(len(SPEEDS_KMH), 3, figsize=(15, 4.6 * len(SPEEDS_KMH)),
                             squeeze=False)
    styles = {"generalized_alpha": "-", "explicit": "--"}
    colors = {20: "tab:blue", 40: "tab:orange", 80: "tab:green"}
    for i, kmh in enumerate(SPEEDS_KMH):
        for j, (key, label) in enumerate(metrics):
            ax = axes[i, j]
            for integ in ("generalized_alpha", "explicit"):
                for ne in MESHES:
                    pts = sorted((r for r in rows if r["speed_kmh"] == kmh and
                                  r["integrator"] == integ and r["n_elements"] == ne),
                                 key=lambda r: -r["dt"])
                    if not pts:
                        continue
                    ax.loglog([max(p[key], 1e-7) for p in pts],
                              [p["wall_median_s"] for p in pts], styles[integ], marker="o",
                              ms=3, color=colors[ne],
                              label=f"{'gen.-alpha' if integ[0] == 'g' else 'explicit RK4'}, "
                                    f"{ne} el.")
            for p in paper_rows:
                if p["speed_kmh"] == kmh:
                    ax.loglog([max(p[key], 1e-7)], [p["wall_median_s"]], "r*", ms=14,
                              label="paper: explicit, dt = 1e-7 s, 20 el.")
            if key == "amp_err":
                ax.axvline(0.01, color="0.6", lw=0.8, ls=":")
            ax.set_xlabel(label)
            ax.set_ylabel("wall time [s]")
            ax.set_title(f"{kmh} km/h")
            ax.grid(True, which="both", lw=0.3)
    axes[0, 0].legend(fontsize=7)
    fig.suptitle("Work-precision, paper's scene, full passage (dt labels in the CSV)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


def main(argv=None):
    global SPEEDS_KMH, GA_DTS, EX_DTS
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true",
                    help="300 km/h only, two dts per line, no paper run (a smoke test)")
    ap.add_argument("--from-csv", action="store_true",
                    help="redo the cost measurement, chart and summary from work_precision.csv")
    args = ap.parse_args(argv)
    if args.from_csv:
        finish(read_csv("work_precision.csv"))
        return
    if args.quick:
        SPEEDS_KMH, GA_DTS = (300,), (2e-5, 1e-5)
        EX_DTS = {20: (5e-6,), 40: (2.5e-6,), 80: (6.25e-7,)}
    print(f"machine: {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}", flush=True)
    tw.simulate(SCENE, tw.kmh(300), x_end=0.5)  # warm-up
    rows, paper_rows, ref_rows = [], [], []
    for kmh in SPEEDS_KMH:
        ref = reference(kmh, REF, "main")
        chk = reference(kmh, REF_CHECK, "check")
        ea, ef, er = errors(chk[0], chk[1], chk[2], chk[3], ref)
        ref_rows.append(dict(speed_kmh=kmh, ref=str(REF), check=str(REF_CHECK),
                             amplitude_ref=ref[2], amplitude_check=chk[2],
                             frequency_ref=ref[3], frequency_check=chk[3], amp_diff=ea,
                             freq_diff=ef, rms_diff=er))
        print(f"{kmh} km/h reference: amplitude {ref[2]:.6e} m, main frequency {ref[3]:.4f} Hz;"
              f" vs 160 el.: amplitude {ea:.2e}, frequency {ef:.2e}, RMS(d) {er:.2e}",
              flush=True)
        for ne in MESHES:
            for dt in GA_DTS:
                rows.append(timed_case(kmh, "generalized_alpha", ne, dt, ref))
                print(_fmt(rows[-1]), flush=True)
            for dt in EX_DTS[ne]:
                rows.append(timed_case(kmh, "explicit", ne, dt, ref))
                print(_fmt(rows[-1]), flush=True)
        if not args.quick:
            paper_rows.append(timed_case(kmh, "explicit", 20, 1e-7, ref, repeats=1))
            print("paper:", _fmt(paper_rows[-1]), flush=True)
    write_csv("work_precision.csv", rows + paper_rows)
    write_csv("work_precision_reference.csv", ref_rows)
    finish(rows + paper_rows)


def finish(all_rows):
    cost = step_cost()
    write_csv("work_precision_cost.csv", cost)
    for c in cost:
        print(f"{c['n_elements']} el.: gen.-alpha {c['ga_step_us']:.1f} us/step "
              f"({c['newton_per_step']:.2f} Newton it.), band factor+solve "
              f"{c['band_factor_solve_us']:.2f} us (ratio {c['ratio_band']:.1f}), bordered "
              f"{c['bordered_factor_solve_us']:.2f} us (ratio {c['ratio_bordered']:.1f})")
    rows = [r for r in all_rows if r["dt"] != 1e-7]
    paper_rows = [r for r in all_rows if r["dt"] == 1e-7]
    chart(rows, paper_rows, os.path.join(HERE, "work_precision.png"))
    summary(all_rows)


def _fmt(r):
    return (f"{r['speed_kmh']:>4g} km/h {r['integrator']:<17s} {r['n_elements']:>3d} el. "
            f"dt={r['dt']:.3e}  {r['wall_median_s']:8.3f} s (x{r['repeats']})  "
            f"amp err {r['amp_err']:.2e}  freq err {r['freq_err']:.2e}  rms {r['rms_err']:.2e}")


if __name__ == "__main__":
    main()
