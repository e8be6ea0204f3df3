"""The paper's Figs. 4 and 5: the convergence of a passage in the time step and in the mesh,
on a short stretch, against the finest run; the tables and the sentences of the summary."""

from __future__ import annotations

import numpy as np

from ..base.units import kmh
from ..run.stretch import default_start
from ..run.simulate import simulate
from ..study.analysis import analyse
from ..base.fields import Quantity, by_name
from ..run.results import SETTINGS_FIELDS
from .plan import CONVERGENCE_SAMPLE, Context

_SET = by_name(SETTINGS_FIELDS)
#: The columns of a convergence table (Figs. 4, 5; :func:`convergence_table`), one row per run:
#: its settings, its cost and its largest differences from its reference run.
CONVERGENCE_COLUMNS: tuple[Quantity, ...] = (
    Quantity("run", "", "the run, as its figure's legend names it", "str"),
    Quantity("reference", "", "the run it is compared with", "str"),
    _SET["integrator"], _SET["dt"], _SET["n_elements"],
    Quantity("speed", "km/h", "forward speed v"),
    Quantity("x_start", "m", "the first wheel position"),
    Quantity("x_end", "m", "the last wheel position"),
    Quantity("steps", "", "time steps taken", "int"),
    Quantity("wall_time", "s", "simulate's wall time"),
    Quantity("max_abs_acc_contact", "m/s^2", "max |d^2 y_B/dt^2| of the run"),
    Quantity("ref_max_abs_acc_contact", "m/s^2", "max |d^2 y_B/dt^2| of the reference"),
    Quantity("ref_amplitude", "m", "max |d| of the reference"),
    Quantity("diff_y_contact", "m", "largest difference of y_B from the reference's"),
    Quantity("diff_dynamic", "m", "largest difference of d = y_B - y_qs (each run's own "
             "quasi-static line)"),
    Quantity("diff_acc_contact", "m/s^2", "largest difference of d^2 y_B/dt^2"),
    Quantity("diff_v_error", "%", "largest difference of the calculation error v_e"),
)
#: the column of each convergence-table quantity (``dt`` -> ``dt_s``)
C = {q.name: q.label for q in CONVERGENCE_COLUMNS}


def _convergence_run(ctx: Context, speed_kmh: float, stretch: float, integrator: str,
                     dt: float, n_elements: int):
    x0 = default_start(ctx.scene)
    r = simulate(ctx.scene, kmh(speed_kmh), integrator=integrator, dt=dt,
                 n_elements=n_elements, x_start=x0, x_end=x0 + stretch,
                 output_every=max(1, round(CONVERGENCE_SAMPLE / dt)), progress=False)
    ctx.log(f"{integrator}, dt = {dt:g} s, {n_elements} elements: {r.steps} steps, "
            f"{r.wall_time:.1f} s")
    return r


def convergence_table(runs, references):
    """One row per run of a convergence figure (a pandas DataFrame): its settings, cost and the
    largest differences from its reference run (``references[i]`` for ``runs[i]``) over the
    run's samples, of the contact-point displacement y_B [m], of the dynamic part
    d = y_B - y_qs [m] (each run with the quasi-static line of its own mesh), of the
    contact-point acceleration [m/s²] and of the calculation error v_e [%], with the reference's
    max |d| (``ref_amplitude`` [m]) and max |acceleration| as scales. The reference is
    interpolated in time at the run's samples; all sample grids here are nested, so the
    interpolation only picks samples."""
    import pandas as pd

    from ..plots import run_label

    def diff(r, ref, x, x_ref):
        return float(np.max(np.abs(x - np.interp(r.t, ref.t, x_ref))))

    rows = []
    for r, ref in zip(runs, references):
        a, a_ref = analyse(r), analyse(ref)
        s = r.settings
        values = {
            "run": run_label(r, dt=True, n_elements=True),
            "reference": run_label(ref, dt=True, n_elements=True),
            "integrator": s.integrator, "dt": s.dt, "n_elements": s.n_elements,
            "speed": s.speed * 3.6, "x_start": float(r.x_wheel[0]),
            "x_end": float(r.x_wheel[-1]), "steps": r.steps, "wall_time": r.wall_time,
            "max_abs_acc_contact": float(np.max(np.abs(r.acc_contact))),
            "ref_max_abs_acc_contact": float(np.max(np.abs(ref.acc_contact))),
            "ref_amplitude": a_ref.amplitude,
            "diff_y_contact": diff(r, ref, r.y_contact, ref.y_contact),
            "diff_dynamic": diff(r, ref, a.dynamic, a_ref.dynamic),
            "diff_acc_contact": diff(r, ref, r.acc_contact, ref.acc_contact),
            "diff_v_error": diff(r, ref, r.v_error, ref.v_error)}
        rows.append({C[name]: value for name, value in values.items()})
    return pd.DataFrame(rows, columns=list(C.values()))


def _convergence_summary(ctx: Context, table, ref_name: str) -> None:
    s = ctx.summary
    s.append(f"  largest differences from {ref_name}:")
    s.append(f"  {'run':<46} {'steps':>8} {'wall':>7}  {'y_B [m]':>9}  {'d [m]':>9}  "
             f"{'acceleration':>22}")
    for _, row in table.iterrows():
        rel = 100.0 * row[C["diff_acc_contact"]] / row[C["ref_max_abs_acc_contact"]]
        s.append(f"  {row[C['run']]:<46} {row[C['steps']]:>8} {row[C['wall_time']]:>6.1f}s  "
                 f"{row[C['diff_y_contact']]:>9.2e}  {row[C['diff_dynamic']]:>9.2e}  "
                 f"{row[C['diff_acc_contact']]:>7.3g} m/s² ({rel:5.1f} %)")
    s.append("  (acceleration: % of the reference's max |acceleration|)")


def passage_cost_sentence(wall_time: float, steps: int, dt: float, passage: float,
                          speed: float) -> str:
    """What a run's measured cost per step means for the whole passage: wall time [s] and
    steps of the run, its step dt [s], the passage length [m] and the speed [m/s]."""
    per_step = wall_time / max(steps, 1)
    total = per_step * passage / speed / dt
    return (f"  (a shorter stretch than the paper's passage: the dt = {dt:g} s run cost "
            f"{per_step * 1e6:.4g} µs per step here, so the {passage:g} m passage at that step "
            f"would take about {_duration(total)})")


def _duration(seconds: float) -> str:
    if seconds < 120.0:
        return f"{seconds:.3g} s"
    if seconds < 7200.0:
        return f"{seconds / 60.0:.3g} min"
    return f"{seconds / 3600.0:.3g} h"


def fig4_time_step(ctx: Context) -> None:
    """Paper Fig. 4: explicit at 1e-6, 1e-7, 1e-8 s, 50 km/h, 20 elements, plus generalized-alpha
    at much larger steps; compared with the explicit run at the smallest step."""
    from .. import plots

    p = ctx.plan
    runs = [_convergence_run(ctx, p.fig4_speed_kmh, p.fig4_stretch, "explicit", dt,
                             p.fig4_n_elements) for dt in p.fig4_explicit_dt]
    runs += [_convergence_run(ctx, p.fig4_speed_kmh, p.fig4_stretch, "generalized_alpha", dt,
                              p.fig4_n_elements) for dt in p.fig4_alpha_dt]
    ref = runs[int(np.argmin(p.fig4_explicit_dt))]
    table = convergence_table(runs, [ref] * len(runs))
    ctx.table(table, "fig4_time_step.csv")
    where = _stretch(runs[0], p.fig4_stretch, p.fig4_speed_kmh)
    fig = plots.time_step_convergence(
        runs, title=f"Effect of the time step (Kato et al. 2005, Fig. 4): "
                    f"{p.fig4_speed_kmh:g} km/h, {p.fig4_n_elements} elements,\n"
                    f"{where}: a short stretch, the paper's steps are expensive")
    ctx.save(fig, "fig4_time_step.png")
    s = ctx.summary
    s.append(f"Fig. 4 -- effect of the time step: {p.fig4_speed_kmh:g} km/h, "
             f"{p.fig4_n_elements} elements, {where}")
    L = ctx.scene.rail.length
    s.append(passage_cost_sentence(ref.wall_time, ref.steps, ref.settings.dt,
                                   L - 2 * default_start(ctx.scene), kmh(p.fig4_speed_kmh)))
    _convergence_summary(ctx, table, plots.run_label(ref, dt=True, n_elements=False))
    s.append("  paper: 1e-6 s is enough for the displacement, 1e-7 s is needed for the "
             "acceleration.")
    s.extend(convergence_conclusions(table, "dt"))


def _stretch(run, stretch: float, speed_kmh: float) -> str:
    """Where a convergence figure looks: X range [m], track length [mm] and duration [ms]."""
    x0 = float(run.x_wheel[0])
    return (f"X = {x0:g}–{x0 + stretch:g} m ({stretch * 1e3:g} mm of track, "
            f"{stretch / kmh(speed_kmh) * 1e3:.2g} ms)")


def fig5_elements(ctx: Context) -> None:
    """Paper Fig. 5: 20, 40, 80 elements at 200 km/h, explicit at 1e-7 s and generalized-alpha
    at 1e-5 s; each compared with the same integrator on the finest mesh."""
    from .. import plots

    p = ctx.plan
    explicit = [_convergence_run(ctx, p.fig5_speed_kmh, p.fig5_stretch, "explicit",
                                 p.fig5_explicit_dt, ne) for ne in p.fig5_n_elements]
    alpha = [_convergence_run(ctx, p.fig5_speed_kmh, p.fig5_stretch, "generalized_alpha",
                              p.fig5_alpha_dt, ne) for ne in p.fig5_n_elements]
    i_ref = int(np.argmax(p.fig5_n_elements))
    runs = explicit + alpha
    table = convergence_table(runs, [explicit[i_ref]] * len(explicit)
                              + [alpha[i_ref]] * len(alpha))
    ctx.table(table, "fig5_elements.csv")
    where = _stretch(runs[0], p.fig5_stretch, p.fig5_speed_kmh)
    fig = plots.element_convergence(
        runs, title=f"Effect of the number of elements (Kato et al. 2005, Fig. 5): "
                    f"{p.fig5_speed_kmh:g} km/h,\n{where}: a short stretch")
    ctx.save(fig, "fig5_elements.png")
    s = ctx.summary
    s.append(f"Fig. 5 -- effect of the number of elements: {p.fig5_speed_kmh:g} km/h, {where}")
    _convergence_summary(ctx, table, f"the same integrator with {max(p.fig5_n_elements)} "
                                     "elements")
    s.append("  paper: 20 elements are enough for the displacement, 40 are needed for the "
             "acceleration.")
    s.extend(convergence_conclusions(table, "n_elements"))


#: a run agrees with its reference when its largest difference is below this fraction of the
#: reference's largest value (max |d| for the displacement, max |acceleration| for the
#: acceleration)
AGREE = 0.01


def _setting(key: str, value) -> str:
    return f"dt = {value:g} s" if key == "dt" else f"{int(value)} elements"


def convergence_conclusions(table, key: str) -> list[str]:
    """One sentence per integrator of a convergence table (:func:`convergence_table`): the
    coarsest run (largest ``dt``, or fewest ``n_elements``: ``key``) whose displacement d and
    whose acceleration agree with its reference within :data:`AGREE`."""
    lines = []
    for integrator, rows in table.groupby(C["integrator"], sort=False):
        rows = rows[rows[C["run"]] != rows[C["reference"]]]
        if rows.empty:
            continue
        found = []
        for what, diff, scale in (("d", "diff_dynamic", "ref_amplitude"),
                                  ("acceleration", "diff_acc_contact",
                                   "ref_max_abs_acc_contact")):
            ok = rows[rows[C[diff]] <= AGREE * rows[C[scale]]]
            if ok.empty:
                found.append(f"{what} at none of the runs")
                continue
            column = ok[C[key]]
            coarsest = column.max() if key == "dt" else column.min()
            found.append(f"{what} from {_setting(key, coarsest)}")
        lines.append(f"  here ({integrator}): coarsest run within {AGREE:.0%} of its reference "
                     f"-- {'; '.join(found)}.")
    return lines

