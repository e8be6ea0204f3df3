"""The paper pipeline behind ``trackwheel reproduce``: Figs. 3-8 of Kato et al. (2005).

:func:`reproduce` runs the steps of :data:`REPRODUCE_STEPS` (one per figure) for a
:class:`Plan` (:data:`FULL` or :data:`QUICK`) and writes, into the output folder, each figure's
PNG and CSV (column names carry their units) and ``summary.txt``. Each step's part of the summary
is kept in ``summary-sections/<step>.txt`` and summary.txt is assembled from every section
present, so ``only=["fig6"]`` refreshes the Fig. 6 section and keeps the others.

Every sentence of the summary that states a result is computed from the data (the
``*_conclusions`` functions): a changed result changes the sentence. The lines starting with
"paper:" quote the paper's claims, which do not change.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._version import __version__
from .analysis import analyse
from .defaults import default_settings, default_start
from .eigen import eigen
from .scene import Scene, kmh
from .simulate import simulate
from .sweep import sweep

__all__ = ["FULL", "QUICK", "REPRODUCE_STEPS", "Plan", "Step", "reproduce"]

#: wheel position of the mode-shape figure and of the reported frequencies [m] (mid-rail)
X_REPORT = 2.5
#: sample spacing of the convergence runs [s]: every run keeps its samples on this grid (or on
#: its own step, if coarser), so that runs at different time steps are compared at equal times
CONVERGENCE_SAMPLE = 1e-6
#: name of the sweep store inside the output folder
STORE_NAME = "sweep-store"
#: folder (inside the output folder) of the summary sections, one file per step
SECTIONS_NAME = "summary-sections"

#: units of the sweep table's columns, appended to their names in the CSV files
SWEEP_UNITS = {
    "speed": "m_s", "support_stiffness": "N_m", "amplitude": "m", "main_frequency": "hz",
    "frequency_resolution": "hz", "min_contact_force": "N", "max_contact_force": "N",
    "wall_time": "s", "dt": "s", "x_start": "m", "x_end": "m", "t_end": "s",
    "baumgarte": "1_s", "drop_height": "m", "loss_duration": "s", "force_rms": "N",
    "p1": "N", "p1_time": "s", "p2": "N", "p2_time": "s"}
#: units of the convergence tables (Figs. 4, 5)
CONVERGENCE_UNITS = {
    "dt": "s", "x_start": "m", "x_end": "m", "wall_time": "s",
    "max_abs_acc_contact": "m_s2", "ref_max_abs_acc_contact": "m_s2", "ref_amplitude": "m",
    "diff_y_contact": "m",
    "diff_dynamic": "m", "diff_acc_contact": "m_s2", "diff_v_error": "percent"}
#: units of the acceleration-term table (Fig. 8)
TERM_UNITS = {"max_abs": "m_s2", "rms": "m_s2", "mean": "m_s2"}


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


# --------------------------------------------------------------------------------------------
# what it computes
@dataclass(frozen=True)
class Plan:
    """What :func:`reproduce` computes. Speeds in km/h, stiffnesses in N/m, lengths in m.

    The convergence runs (Figs. 4, 5) start where every run starts (the middle of the first
    support bay) and cover only ``fig4_stretch`` / ``fig5_stretch`` of track: the paper's
    smallest explicit step over the whole passage is expensive (the summary states the cost per
    step measured in the run and what the whole passage would take).
    """

    name: str
    n_eigen_positions: int  #: Fig. 3: wheel positions over the rail
    fig4_stretch: float  #: Fig. 4: length of track covered [m]
    fig5_stretch: float  #: Fig. 5: length of track covered [m]
    stiffness: tuple[float, ...]  #: Fig. 6: support stiffnesses [N/m]
    speeds_kmh: tuple[float, ...]  #: Fig. 7: speeds [km/h]
    #: settings of the sweeps (Figs. 6, 7) and of the Fig. 8 runs, passed to simulate; empty:
    #: simulate's derived defaults (trackwheel.default_settings)
    simulate: dict = field(default_factory=dict)
    fig4_speed_kmh: float = 50.0
    fig4_n_elements: int = 20
    fig4_explicit_dt: tuple[float, ...] = (1e-6, 1e-7, 1e-8)  #: the paper's steps [s]
    fig4_alpha_dt: tuple[float, ...] = (1e-5, 5e-6)  #: generalized-alpha at larger steps [s]
    fig5_speed_kmh: float = 200.0
    fig5_n_elements: tuple[int, ...] = (20, 40, 80)
    fig5_explicit_dt: float = 1e-7  #: the paper's step [s]
    fig5_alpha_dt: float = 1e-5  #: [s]
    fig6_speeds_kmh: tuple[float, ...] = (100.0, 300.0)
    fig8_speeds_kmh: tuple[float, ...] = (100.0, 300.0)

    def describe_settings(self, scene: Scene) -> str:
        """The simulate settings of the sweeps, in words."""
        if not self.simulate:
            d = default_settings(scene)
            return (f"simulate's derived defaults (generalized-alpha, {d['n_elements']} "
                    f"elements, dt = {d['dt']:.3g} s)")
        return ", ".join(f"{k} = {val}" for k, val in self.simulate.items())


#: The full run: the paper's ranges (Fig. 6: 20-300 MN/m, 10 values; Fig. 7: 50-400 km/h in
#: steps of 50) at simulate's derived (converged) settings.
FULL = Plan(
    name="full", n_eigen_positions=201, fig4_stretch=0.10, fig5_stretch=0.25,
    stiffness=tuple(k * 1e6 for k in (20, 30, 45, 70, 100, 140, 180, 220, 260, 300)),
    speeds_kmh=tuple(float(s) for s in range(50, 401, 50)))
#: --quick: coarse grids, the paper's 20-element mesh at 1e-5 s for the sweeps (amplitudes
#: within about 5 % of the full run's), short convergence stretches.
QUICK = Plan(
    name="quick", n_eigen_positions=41, fig4_stretch=0.005, fig5_stretch=0.01,
    stiffness=(20e6, 45e6, 70e6, 140e6, 300e6), speeds_kmh=(50.0, 100.0, 200.0, 300.0, 400.0),
    simulate={"n_elements": 20, "dt": 1e-5})


@dataclass
class Context:
    """What every step gets: the scene, the output folder and the plan; steps append the files
    they wrote and the lines of their summary section, and report progress through :meth:`log`."""

    scene: Scene
    out: Path
    plan: Plan = FULL
    workers: int | None = None  #: sweep processes (None: one per core)
    stream: object = None  #: where progress is printed (None: stdout)
    written: list[Path] = field(default_factory=list)
    summary: list[str] = field(default_factory=list)  #: the current step's section

    def log(self, message: str) -> None:
        print(f"      {message}", file=self.stream or sys.stdout, flush=True)

    @property
    def store(self) -> Path:
        return self.out / STORE_NAME

    def save(self, fig, name: str) -> None:
        path = self.out / name
        fig.savefig(path, dpi=150)
        self.written.append(path)

    def table(self, df, name: str, units: dict[str, str]) -> None:
        """Write ``df`` as CSV, each column named ``<name>_<unit>`` where ``units`` has one."""
        path = self.out / name
        df.rename(columns={c: f"{c}_{u}" for c, u in units.items()}).to_csv(path, index=False)
        self.written.append(path)


@dataclass(frozen=True)
class Step:
    """One figure of the paper: ``run(ctx)`` computes it and writes its files into ``ctx.out``."""

    name: str  #: short id, e.g. "fig3"
    title: str  #: what it reproduces
    run: Callable[[Context], None]


# --------------------------------------------------------------------------------------------
# Fig. 3
def _fig3_eigen(ctx: Context) -> None:
    """Paper Fig. 3: the lowest four vertical natural frequencies against wheel position."""
    from . import plots  # matplotlib is imported only when a figure is drawn

    scene = ctx.scene
    n_pos = ctx.plan.n_eigen_positions
    res = eigen(scene, np.linspace(0.0, scene.rail.length, n_pos), n_modes=4)
    csv = ctx.out / "fig3_eigen.csv"
    header = "position_m," + ",".join(f"f{k + 1}_hz" for k in range(4))
    np.savetxt(csv, np.column_stack([res.positions, res.frequencies]), delimiter=",",
               fmt="%.12g", header=header, comments="")
    ctx.written.append(csv)
    ctx.save(plots.eigen(res), "fig3_eigen.png")
    at = eigen(scene, [X_REPORT], n_modes=4)
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


# --------------------------------------------------------------------------------------------
# Figs. 4 and 5: convergence
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

    from .plots import _run_label

    def diff(r, ref, x, x_ref):
        return float(np.max(np.abs(x - np.interp(r.t, ref.t, x_ref))))

    rows = []
    for r, ref in zip(runs, references):
        a, a_ref = analyse(r), analyse(ref)
        s = r.settings
        rows.append({
            "run": _run_label(r, dt=True, n_elements=True),
            "reference": _run_label(ref, dt=True, n_elements=True),
            "integrator": s.integrator, "dt": s.dt, "n_elements": s.n_elements,
            "speed_kmh": s.speed * 3.6, "x_start": float(r.x_wheel[0]),
            "x_end": float(r.x_wheel[-1]), "steps": r.steps, "wall_time": r.wall_time,
            "max_abs_acc_contact": float(np.max(np.abs(r.acc_contact))),
            "ref_max_abs_acc_contact": float(np.max(np.abs(ref.acc_contact))),
            "ref_amplitude": a_ref.amplitude,
            "diff_y_contact": diff(r, ref, r.y_contact, ref.y_contact),
            "diff_dynamic": diff(r, ref, a.dynamic, a_ref.dynamic),
            "diff_acc_contact": diff(r, ref, r.acc_contact, ref.acc_contact),
            "diff_v_error": diff(r, ref, r.v_error, ref.v_error)})
    return pd.DataFrame(rows)


def _convergence_summary(ctx: Context, table, ref_name: str) -> None:
    s = ctx.summary
    s.append(f"  largest differences from {ref_name}:")
    s.append(f"  {'run':<46} {'steps':>8} {'wall':>7}  {'y_B [m]':>9}  {'d [m]':>9}  "
             f"{'acceleration':>22}")
    for row in table.itertuples():
        rel = 100.0 * row.diff_acc_contact / row.ref_max_abs_acc_contact
        s.append(f"  {row.run:<46} {row.steps:>8} {row.wall_time:>6.1f}s  "
                 f"{row.diff_y_contact:>9.2e}  {row.diff_dynamic:>9.2e}  "
                 f"{row.diff_acc_contact:>7.3g} m/s² ({rel:5.1f} %)")
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


def _fig4_time_step(ctx: Context) -> None:
    """Paper Fig. 4: explicit at 1e-6, 1e-7, 1e-8 s, 50 km/h, 20 elements, plus generalized-alpha
    at much larger steps; compared with the explicit run at the smallest step."""
    from . import plots

    p = ctx.plan
    runs = [_convergence_run(ctx, p.fig4_speed_kmh, p.fig4_stretch, "explicit", dt,
                             p.fig4_n_elements) for dt in p.fig4_explicit_dt]
    runs += [_convergence_run(ctx, p.fig4_speed_kmh, p.fig4_stretch, "generalized_alpha", dt,
                              p.fig4_n_elements) for dt in p.fig4_alpha_dt]
    ref = runs[int(np.argmin(p.fig4_explicit_dt))]
    table = convergence_table(runs, [ref] * len(runs))
    ctx.table(table, "fig4_time_step.csv", CONVERGENCE_UNITS)
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
    _convergence_summary(ctx, table, plots._run_label(ref, dt=True, n_elements=False))
    s.append("  paper: 1e-6 s is enough for the displacement, 1e-7 s is needed for the "
             "acceleration.")
    s.extend(convergence_conclusions(table, "dt"))


def _stretch(run, stretch: float, speed_kmh: float) -> str:
    """Where a convergence figure looks: X range [m], track length [mm] and duration [ms]."""
    x0 = float(run.x_wheel[0])
    return (f"X = {x0:g}–{x0 + stretch:g} m ({stretch * 1e3:g} mm of track, "
            f"{stretch / kmh(speed_kmh) * 1e3:.2g} ms)")


def _fig5_elements(ctx: Context) -> None:
    """Paper Fig. 5: 20, 40, 80 elements at 200 km/h, explicit at 1e-7 s and generalized-alpha
    at 1e-5 s; each compared with the same integrator on the finest mesh."""
    from . import plots

    p = ctx.plan
    explicit = [_convergence_run(ctx, p.fig5_speed_kmh, p.fig5_stretch, "explicit",
                                 p.fig5_explicit_dt, ne) for ne in p.fig5_n_elements]
    alpha = [_convergence_run(ctx, p.fig5_speed_kmh, p.fig5_stretch, "generalized_alpha",
                              p.fig5_alpha_dt, ne) for ne in p.fig5_n_elements]
    i_ref = int(np.argmax(p.fig5_n_elements))
    runs = explicit + alpha
    table = convergence_table(runs, [explicit[i_ref]] * len(explicit)
                              + [alpha[i_ref]] * len(alpha))
    ctx.table(table, "fig5_elements.csv", CONVERGENCE_UNITS)
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
    coarsest run (largest ``dt``, or fewest ``n_elements``) whose displacement d and whose
    acceleration agree with its reference within :data:`AGREE`."""
    lines = []
    for integrator, rows in table.groupby("integrator", sort=False):
        rows = rows[rows.run != rows.reference]
        if rows.empty:
            continue
        found = []
        for what, diff, scale in (("d", "diff_dynamic", "ref_amplitude"),
                                  ("acceleration", "diff_acc_contact",
                                   "ref_max_abs_acc_contact")):
            ok = rows[rows[diff] <= AGREE * rows[scale]]
            if ok.empty:
                found.append(f"{what} at none of the runs")
                continue
            coarsest = ok[key].max() if key == "dt" else ok[key].min()
            found.append(f"{what} from {_setting(key, coarsest)}")
        lines.append(f"  here ({integrator}): coarsest run within {AGREE:.0%} of its reference "
                     f"-- {'; '.join(found)}.")
    return lines


# --------------------------------------------------------------------------------------------
# Figs. 6 and 7: sweeps
def _sweep(ctx: Context, speeds_kmh, stiffness):
    t0 = time.perf_counter()
    df = sweep(ctx.scene, speed=[kmh(v) for v in speeds_kmh], support_stiffness=list(stiffness),
               store=ctx.store, progress=False, max_workers=ctx.workers, **ctx.plan.simulate)
    ctx.log(f"{len(df)} cases ({df.attrs.get('computed', '?')} computed, "
            f"{df.attrs.get('from_store', '?')} from {ctx.store}) in "
            f"{time.perf_counter() - t0:.1f} s")
    for row in df[df["error"] != ""].itertuples():
        ctx.summary.append(f"  FAILED: {row.speed_kmh:g} km/h, {row.support_stiffness / 1e6:g} "
                           f"MN/m: {row.error}")
    return df


def _monotone(x: np.ndarray, sign: int) -> bool:
    return bool(np.all(np.isfinite(x)) and np.all(sign * np.diff(x) > 0))


def _yes(flag: bool) -> str:
    return "yes" if flag else "NO"


def fig6_conclusions(amplitude, frequency) -> list[str]:
    """The sentences of Fig. 6 from the pivot tables ``amplitude`` [m] and main ``frequency``
    [Hz] (index: support stiffness [N/m] ascending, columns: speed [km/h])."""
    speeds = list(amplitude.columns)
    dec = ", ".join(f"{v:g} km/h: {_yes(_monotone(amplitude[v].to_numpy(), -1))}"
                    for v in speeds)
    rises = ", ".join(f"{v:g} km/h: {_yes(_monotone(frequency[v].to_numpy(), +1))}"
                      for v in speeds)
    out = [f"  here: amplitude decreasing with k_s -- {dec}.",
           f"  here: main frequency rising with k_s -- {rises}."]
    if len(speeds) == 2:
        ratio = (amplitude[speeds[1]] / amplitude[speeds[0]]).to_numpy()
        if np.any(np.isfinite(ratio)):
            k_max = amplitude.index[int(np.nanargmax(ratio))]
            out.append(f"  here: amplitude ratio {speeds[1]:g}/{speeds[0]:g} km/h "
                       f"{np.nanmin(ratio):.2f}..{np.nanmax(ratio):.2f}, largest at "
                       f"k_s = {k_max / 1e6:g} MN/m.")
    return out


def _fig6_support_stiffness(ctx: Context) -> None:
    """Paper Fig. 6: amplitude against support stiffness at 100 and 300 km/h."""
    from . import plots

    p = ctx.plan
    s = ctx.summary
    s.append(f"Fig. 6 -- amplitude max|d| against support stiffness, "
             f"{' and '.join(f'{v:g}' for v in p.fig6_speeds_kmh)} km/h; "
             f"{p.describe_settings(ctx.scene)}")
    df = _sweep(ctx, p.fig6_speeds_kmh, p.stiffness)
    ctx.table(df, "fig6_support_stiffness.csv", SWEEP_UNITS)
    ctx.save(plots.support_stiffness(df, frequency=True), "fig6_support_stiffness.png")
    piv = df.pivot_table(index="support_stiffness", columns="speed_kmh", values="amplitude",
                         dropna=False)
    fr = df.pivot_table(index="support_stiffness", columns="speed_kmh", values="main_frequency",
                        dropna=False)
    speeds = list(piv.columns)
    s.append("  k_s [MN/m]  " + "  ".join(f"{v:>6g} km/h [µm]" for v in speeds)
             + ("  ratio" if len(speeds) == 2 else "")
             + "  " + " / ".join(f"f({v:g})" for v in speeds) + " [Hz]")
    for k in piv.index:
        amps = [piv.loc[k, v] for v in speeds]
        line = f"  {k / 1e6:>10g}  " + "  ".join(f"{a * 1e6:>16.3f}" for a in amps)
        if len(speeds) == 2:
            line += f"  {amps[1] / amps[0]:>5.2f}"
        line += "  " + " / ".join(f"{fr.loc[k, v]:.0f}" for v in speeds)
        s.append(line)
    s.append("  paper: the amplitude decreases with the support stiffness at both speeds, and "
             "the speed effect is strongest around 70-140 MN/m.")
    s.extend(fig6_conclusions(piv, fr))


def nearest_mode(f: float, lo: np.ndarray, hi: np.ndarray) -> int:
    """0-based index of the mode whose band [lo, hi] [Hz] is closest to f [Hz]."""
    dist = np.maximum(0.0, np.maximum(lo - f, f - hi))
    return int(np.argmin(dist))


def _ordinal(k: int) -> str:
    return {1: "first", 2: "second", 3: "third", 4: "fourth"}.get(k, f"{k}th")


def fig7_conclusions(amplitude, frequency, lo, hi) -> list[str]:
    """The sentences of Fig. 7 from the amplitudes [m] and main frequencies [Hz] at ascending
    speeds and the bands [lo, hi] [Hz] of the coupled system's modes over the wheel positions."""
    amplitude, frequency = np.asarray(amplitude, float), np.asarray(frequency, float)
    ok = np.isfinite(frequency)
    modes = sorted({nearest_mode(f, lo, hi) + 1 for f in frequency[ok]})
    if not modes:
        follows = "no main frequency was found"
    elif len(modes) == 1:
        m = modes[0]
        follows = (f"the main frequency follows mode {m} at every speed, the {_ordinal(m)} "
                   f"mode ({lo[m - 1]:.0f}-{hi[m - 1]:.0f} Hz)")
    else:
        follows = ("the main frequency moves between modes "
                   + ", ".join(str(m) for m in modes) + " with the speed")
    third = "" if not modes else (
        "; as in the paper, the third mode" if modes == [3] else
        f"; not the paper's third mode ({lo[2]:.0f}-{hi[2]:.0f} Hz)" if len(lo) > 2 else "")
    return [(f"  here: amplitude increasing with speed -- {_yes(_monotone(amplitude, +1))} "
            f"({np.nanmin(amplitude) * 1e6:.2f} to {np.nanmax(amplitude) * 1e6:.2f} µm)."),
            (f"  here: main frequency {np.nanmin(frequency):.0f}-{np.nanmax(frequency):.0f} Hz; "
            f"{follows}{third}.")]


def _fig7_speed(ctx: Context) -> None:
    """Paper Fig. 7: amplitude and main frequency against speed at the scene's stiffness, with
    the coupled system's eigenfrequencies (Fig. 3) as reference bands; and one run at 300 km/h
    shown in full (y_B, y_qs, d(t), spectrum)."""
    from . import plots

    p = ctx.plan
    scene = ctx.scene
    k_s = scene.supports.stiffness
    s = ctx.summary
    s.append(f"Fig. 7 -- amplitude and main frequency against speed, k_s = {k_s / 1e6:g} MN/m; "
             f"{p.describe_settings(scene)}")
    df = _sweep(ctx, p.speeds_kmh, [k_s])
    ctx.table(df, "fig7_speed.csv", SWEEP_UNITS)
    eig = eigen(scene, np.linspace(0.0, scene.rail.length, p.n_eigen_positions), n_modes=4)
    ctx.save(plots.speed(df, eig), "fig7_speed.png")
    lo, hi = eig.frequencies.min(axis=0), eig.frequencies.max(axis=0)
    s.append(f"  {'v [km/h]':>8}  {'amplitude':>11}  {'main frequency':>24}  nearest mode")
    for row in df.itertuples():
        if not np.isfinite(row.main_frequency):
            s.append(f"  {row.speed_kmh:>8g}  (failed)")
            continue
        k = nearest_mode(row.main_frequency, lo, hi)
        s.append(f"  {row.speed_kmh:>8g}  {row.amplitude * 1e6:>8.3f} µm  "
                 f"{row.main_frequency:>7.1f} Hz (± {row.frequency_resolution:4.1f} Hz)  "
                 f"mode {k + 1} ({lo[k]:.0f}-{hi[k]:.0f} Hz)")
    s.append("  paper: the main frequency is about 400 Hz whatever the speed, the third mode; "
             "the amplitude increases with the speed.")
    s.extend(fig7_conclusions(df["amplitude"], df["main_frequency"], lo, hi))

    v_show = 300.0 if 300.0 in p.speeds_kmh else p.speeds_kmh[-1]
    r = simulate(scene, kmh(v_show), progress=False, **p.simulate)
    ctx.save(plots.dynamic(r, analyse(r), eigen=eig), f"fig7_dynamic_{v_show:g}kmh.png")


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


def _fig8_acceleration_terms(ctx: Context) -> None:
    """Paper Fig. 8: the acceleration terms A-E at 100 and 300 km/h."""
    import pandas as pd

    from . import plots

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
            rows.append({"speed_kmh": v, "term": term, "max_abs": float(np.max(np.abs(x))),
                         "rms": float(np.sqrt(np.mean(x**2))), "mean": float(np.mean(x))})
    table = pd.DataFrame(rows)
    ctx.table(table, "fig8_acceleration_terms.csv", TERM_UNITS)
    ctx.save(plots.acceleration_terms(runs), "fig8_acceleration_terms.png")

    s = ctx.summary
    s.append(f"Fig. 8 -- terms of the contact-point acceleration (docs: Model § Outputs), "
             f"{p.describe_settings(ctx.scene)}")
    s.append("  term  " + "  ".join(f"rms at {v:g} km/h" for v in p.fig8_speeds_kmh)
             + "  [m/s²]")
    rms = table.pivot(index="term", columns="speed_kmh", values="rms")
    for term in "ABCDE":
        s.append(f"  {term:>4}  " + "  ".join(f"{rms.loc[term, v]:>16.3g}"
                                               for v in p.fig8_speeds_kmh))
    if len(p.fig8_speeds_kmh) == 2:
        s.append("  paper: the terms grow as the square of the speed and are remarkable at "
                 "high speed.")
        s.extend(fig8_conclusions(rms[list(p.fig8_speeds_kmh)]))


#: The figures :func:`reproduce` makes, in order.
REPRODUCE_STEPS: list[Step] = [
    Step("fig3", "Fig. 3: natural frequencies against wheel position", _fig3_eigen),
    Step("fig4", "Fig. 4: effect of the time step", _fig4_time_step),
    Step("fig5", "Fig. 5: effect of the number of elements", _fig5_elements),
    Step("fig6", "Fig. 6: amplitude against support stiffness", _fig6_support_stiffness),
    Step("fig7", "Fig. 7: amplitude and main frequency against speed", _fig7_speed),
    Step("fig8", "Fig. 8: terms of the contact-point acceleration", _fig8_acceleration_terms),
]


# --------------------------------------------------------------------------------------------
# the run
def select_steps(only: Sequence[str] | None) -> list[Step]:
    """The steps named in ``only`` (all if None), in figure order; ValueError for unknown
    names."""
    if only is None:
        return list(REPRODUCE_STEPS)
    names = [st.name for st in REPRODUCE_STEPS]
    unknown = [n for n in only if n not in names]
    if unknown:
        raise ValueError(f"only = {unknown}: no such step; allowed: {names}")
    return [st for st in REPRODUCE_STEPS if st.name in only]


def assemble_summary(out: Path) -> str:
    """summary.txt: a header, then every section present in ``out/summary-sections``, in
    figure order (sections of steps not run this time are kept from earlier runs)."""
    head = f"trackwheel {__version__} reproduce: Kato et al. (2005), scene Scene.kato2005()"
    parts = [head, ""]
    for step in REPRODUCE_STEPS:
        path = out / SECTIONS_NAME / f"{step.name}.txt"
        if path.is_file():
            parts.append(path.read_text(encoding="utf-8").rstrip("\n"))
            parts.append("")
    return "\n".join(parts).rstrip("\n") + "\n"


def _run_step(ctx: Context, step: Step, i: int, n: int, stream) -> None:
    """Run one step and write its summary section, ending with its plan and wall time."""
    print(f"[{i}/{n}] {step.title} ...", file=stream, flush=True)
    ctx.summary = []
    t0 = time.perf_counter()
    step.run(ctx)
    wall = time.perf_counter() - t0
    print(f"      done ({wall:.1f} s)", file=stream, flush=True)
    ctx.summary.append(f"  ({ctx.plan.name} plan; computed in {wall:.1f} s by trackwheel "
                       f"{__version__})")
    path = ctx.out / SECTIONS_NAME / f"{step.name}.txt"
    path.write_text("\n".join(ctx.summary) + "\n", encoding="utf-8")
    ctx.written.append(path)


def reproduce(out: Path, quick: bool = False, scene: Scene | None = None,
              stream=None, only: Sequence[str] | None = None,
              workers: int | None = None) -> Context:
    """Run every step of :data:`REPRODUCE_STEPS` (or those named in ``only``) into ``out`` and
    write ``out/summary.txt`` (keeping the sections of steps not run). ``quick`` selects
    :data:`QUICK` instead of :data:`FULL`; ``workers`` is the number of sweep processes
    (default one per core)."""
    stream = sys.stdout if stream is None else stream
    steps = select_steps(only)
    ctx = Context(scene=Scene.kato2005() if scene is None else scene, out=Path(out),
                  plan=QUICK if quick else FULL, workers=workers, stream=stream)
    (ctx.out / SECTIONS_NAME).mkdir(parents=True, exist_ok=True)
    t_all = time.perf_counter()
    for i, step in enumerate(steps, 1):
        _run_step(ctx, step, i, len(steps), stream)
    text = assemble_summary(ctx.out)
    summary = ctx.out / "summary.txt"
    summary.write_text(text, encoding="utf-8")
    ctx.written.append(summary)
    print(file=stream)
    print(text, file=stream, end="")
    print(f"\nwrote {len(ctx.written)} files to {ctx.out} in "
          f"{time.perf_counter() - t_all:.1f} s:", file=stream)
    for p in ctx.written:
        print(f"  {p.relative_to(ctx.out)}", file=stream)
    return ctx
