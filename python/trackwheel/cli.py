"""The ``trackwheel`` command.

``trackwheel reproduce --out DIR [--quick] [--only STEP ...]``
    The main job: recompute the paper's Figs. 3-8 for ``Scene.kato2005()`` and write them (PNG +
    CSV) to DIR with a ``summary.txt`` that sets our numbers beside the paper's claims. The
    figures are a list of :class:`Step` in :data:`REPRODUCE_STEPS`; what each computes is a
    :class:`Plan` (:data:`FULL` or :data:`QUICK`). The sweeps keep every finished case in
    ``DIR/sweep-store`` (:func:`trackwheel.sweep`), so an interrupted run resumes.
``trackwheel run --speed-kmh V [--support-stiffness K] [--integrator ...] [--plot PNG]``
    One passage: print the amplitude and main frequency of the contact-point vibration, the
    contact-force range, lost contact and the wall time; optionally save :func:`plots.dynamic`.
``trackwheel sweep --speeds-kmh V ... [--support-stiffness K ...] --store DIR [--out CSV]``
    A speed x support-stiffness sweep into a resumable store; prints the table.
``trackwheel eigen [--position X] [--n-modes N]``
    Print the lowest vertical natural frequencies with the wheel at X [m].

``main(argv)`` returns the exit code: 0 on success, 2 for bad arguments (argparse, or a value
the library rejects), 1 when a computation fails (a diverging run, failed sweep cases).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import __version__
from ._errors import DivergenceError
from .eigen import eigen as _eigen
from .scene import Scene, kmh
from .simulate import FIDELITY_LEVELS

#: wheel position of the mode-shape figure and of the reported frequencies [m] (mid-rail)
X_REPORT = 2.5
#: sample spacing of the convergence runs [s]: every run keeps its samples on this grid (or on
#: its own step, if coarser), so that runs at different time steps are compared at equal times
CONVERGENCE_SAMPLE = 1e-6
#: name of the sweep store inside the output folder of ``reproduce``
STORE_NAME = "sweep-store"


# --------------------------------------------------------------------------------------------
# analytic references (docs: Model § Validation)
# --------------------------------------------------------------------------------------------
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
# `reproduce`: what it computes (Plan), a list of steps, each writing its files and adding lines
# to the summary
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Plan:
    """What ``trackwheel reproduce`` computes. Speeds in km/h, stiffnesses in N/m, lengths in m.

    The convergence runs (Figs. 4, 5) start at the middle of the first support bay, as every
    run does, and cover ``fig4_stretch`` / ``fig5_stretch`` of track: the paper's explicit steps
    cost about 70 µs each on one core (20 elements; 80 elements about 5x more), so 1e-8 s over
    the whole 4.5 m passage at 50 km/h (32 million steps) would take most of an hour.
    """

    name: str
    n_eigen_positions: int  #: Fig. 3: wheel positions over the rail
    fig4_stretch: float  #: Fig. 4: length of track covered [m]
    fig5_stretch: float  #: Fig. 5: length of track covered [m]
    stiffness: tuple[float, ...]  #: Fig. 6: support stiffnesses [N/m]
    speeds_kmh: tuple[float, ...]  #: Fig. 7: speeds [km/h]
    #: settings of the sweeps (Figs. 6, 7) and of the Fig. 8 runs, passed to simulate; empty:
    #: simulate's derived defaults (generalized-alpha, 8 elements per bay, 150 steps per period
    #: of the wheel on its contact spring: 80 elements and 4.96e-6 s for the paper's scene)
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

    def describe_settings(self) -> str:
        """The simulate settings of the sweeps, in words."""
        if not self.simulate:
            return "simulate's derived defaults (generalized-alpha, 80 elements, dt = 4.96e-6 s)"
        return ", ".join(f"{k} = {val}" for k, val in self.simulate.items())


#: The full run: the paper's ranges (Fig. 6: 20-300 MN/m, 10 values; Fig. 7: 50-400 km/h in
#: steps of 50) at simulate's default (converged) settings; several minutes on two cores.
FULL = Plan(
    name="full", n_eigen_positions=201, fig4_stretch=0.10, fig5_stretch=0.25,
    stiffness=tuple(k * 1e6 for k in (20, 30, 45, 70, 100, 140, 180, 220, 260, 300)),
    speeds_kmh=tuple(float(s) for s in range(50, 401, 50)))
#: --quick: under a minute on two cores. Coarse grids, the paper's 20-element mesh at 1e-5 s for
#: the sweeps (amplitudes within about 5 % of the full run's), short convergence stretches.
QUICK = Plan(
    name="quick", n_eigen_positions=41, fig4_stretch=0.005, fig5_stretch=0.01,
    stiffness=(20e6, 45e6, 70e6, 140e6, 300e6), speeds_kmh=(50.0, 100.0, 200.0, 300.0, 400.0),
    simulate=dict(n_elements=20, dt=1e-5))


@dataclass
class Context:
    """What every reproduce step gets: the scene, the output folder, the --quick flag and the
    plan; steps append the files they wrote and the lines of the summary, and report progress
    through :meth:`log`."""

    scene: Scene
    out: Path
    quick: bool
    plan: Plan = FULL
    workers: int | None = None  #: sweep processes (None: one per core)
    stream: object = None  #: where progress is printed (None: stdout)
    written: list[Path] = field(default_factory=list)
    summary: list[str] = field(default_factory=list)

    def log(self, message: str) -> None:
        print(f"      {message}", file=self.stream or sys.stdout, flush=True)

    @property
    def store(self) -> Path:
        return self.out / STORE_NAME

    def save(self, fig, name: str) -> None:
        path = self.out / name
        fig.savefig(path, dpi=150)
        self.written.append(path)

    def table(self, df, name: str) -> None:
        path = self.out / name
        df.to_csv(path, index=False)
        self.written.append(path)


@dataclass(frozen=True)
class Step:
    """One figure of the paper: ``run(ctx)`` computes it and writes its files into ``ctx.out``."""

    name: str  #: short id, e.g. "fig3"
    title: str  #: what it reproduces
    run: Callable[[Context], None]


def _fig3_eigen(ctx: Context) -> None:
    """Paper Fig. 3: the lowest four vertical natural frequencies against wheel position."""
    from . import plots  # matplotlib is imported only when a figure is drawn

    scene = ctx.scene
    n_pos = ctx.plan.n_eigen_positions
    positions = np.linspace(0.0, scene.rail.length, n_pos)
    res = _eigen(scene, positions, n_modes=4)

    csv = ctx.out / "fig3_eigen.csv"
    header = "position_m," + ",".join(f"f{k + 1}_hz" for k in range(4))
    np.savetxt(csv, np.column_stack([res.positions, res.frequencies]), delimiter=",",
               fmt="%.12g", header=header, comments="")
    ctx.written.append(csv)

    ctx.save(plots.eigen(res), "fig3_eigen.png")
    at = _eigen(scene, [X_REPORT], n_modes=4)
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
    s.append("")


# ---- Figs. 4 and 5: convergence --------------------------------------------------------------
def _convergence_run(ctx: Context, speed_kmh: float, stretch: float, integrator: str,
                     dt: float, n_elements: int):
    from .simulate import simulate

    x0 = 0.5 * ctx.scene.supports.spacing  # simulate's default start
    r = simulate(ctx.scene, kmh(speed_kmh), integrator=integrator, dt=dt,
                 n_elements=n_elements, x_start=x0, x_end=x0 + stretch,
                 output_every=max(1, round(CONVERGENCE_SAMPLE / dt)), progress=False)
    ctx.log(f"{integrator}, dt = {dt:g} s, {n_elements} elements: {r.steps} steps, "
            f"{r.wall_time:.1f} s")
    return r


def convergence_table(runs, references) -> pandas.DataFrame:  # noqa: F821
    """One row per run of a convergence figure: its settings, cost and the largest differences
    from its reference run (``references[i]`` for ``runs[i]``) over the run's samples, of the
    contact-point displacement y_B [m], of the dynamic part d = y_B - y_qs [m] (each run with
    the quasi-static line of its own mesh), of the contact-point acceleration [m/s²] and of the
    calculation error v_e [%]. The reference is interpolated in time at the run's samples; all
    sample grids here are nested, so the interpolation only picks samples."""
    import pandas as pd

    from .analysis import analyse
    from .plots import _run_label

    def diff(r, ref, x, x_ref):
        return float(np.max(np.abs(x - np.interp(r.t, ref.t, x_ref))))

    rows = []
    for r, ref in zip(runs, references):
        a, a_ref = analyse(r), analyse(ref)
        s = r.settings
        rows.append(dict(
            run=_run_label(r, dt=True, n_elements=True),
            reference=_run_label(ref, dt=True, n_elements=True),
            integrator=s["integrator"], dt=s["dt"], n_elements=s["n_elements"],
            speed_kmh=s["speed"] * 3.6, x_start=float(r.x_wheel[0]), x_end=float(r.x_wheel[-1]),
            steps=r.steps, wall_time=r.wall_time,
            max_abs_acc_contact=float(np.max(np.abs(r.acc_contact))),
            ref_max_abs_acc_contact=float(np.max(np.abs(ref.acc_contact))),
            diff_y_contact=diff(r, ref, r.y_contact, ref.y_contact),
            diff_dynamic=diff(r, ref, a.dynamic, a_ref.dynamic),
            diff_acc_contact=diff(r, ref, r.acc_contact, ref.acc_contact),
            diff_v_error=diff(r, ref, r.v_error, ref.v_error)))
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
    ctx.table(table, "fig4_time_step.csv")
    x0 = float(runs[0].x_wheel[0])
    where = (f"X = {x0:g}–{x0 + p.fig4_stretch:g} m ({p.fig4_stretch * 1e3:g} mm of track, "
             f"{p.fig4_stretch / kmh(p.fig4_speed_kmh) * 1e3:.2g} ms)")
    fig = plots.time_step_convergence(
        runs, title=f"Effect of the time step (Kato et al. 2005, Fig. 4): "
                    f"{p.fig4_speed_kmh:g} km/h, {p.fig4_n_elements} elements,\n"
                    f"{where}: a short stretch, the paper's steps are expensive")
    ctx.save(fig, "fig4_time_step.png")
    s = ctx.summary
    s.append(f"Fig. 4 -- effect of the time step: {p.fig4_speed_kmh:g} km/h, "
             f"{p.fig4_n_elements} elements, {where}")
    s.append("  (a shorter stretch than the paper's full passage: explicit RK4 costs ~70 µs per "
             "step, 1e-8 s over the passage would take hours)")
    _convergence_summary(ctx, table, plots._run_label(ref, dt=True, n_elements=False))
    s.append("  paper: 1e-6 s is enough for the displacement, 1e-7 s is needed for the "
             "acceleration.")
    s.append("")


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
    ctx.table(table, "fig5_elements.csv")
    x0 = float(runs[0].x_wheel[0])
    where = (f"X = {x0:g}–{x0 + p.fig5_stretch:g} m ({p.fig5_stretch * 1e3:g} mm of track, "
             f"{p.fig5_stretch / kmh(p.fig5_speed_kmh) * 1e3:.2g} ms)")
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
    s.append("")


# ---- Figs. 6 and 7: sweeps -------------------------------------------------------------------
def _sweep(ctx: Context, speeds_kmh, stiffness):
    from .sweep import sweep

    t0 = time.perf_counter()
    df = sweep(ctx.scene, speed=[kmh(v) for v in speeds_kmh], support_stiffness=list(stiffness),
               store=ctx.store, progress=False, max_workers=ctx.workers, **ctx.plan.simulate)
    ctx.log(f"{len(df)} cases ({df.attrs.get('computed', '?')} computed, "
            f"{df.attrs.get('from_store', '?')} from {ctx.store}) in "
            f"{time.perf_counter() - t0:.1f} s")
    failed = df[df["error"] != ""]
    for row in failed.itertuples():
        ctx.summary.append(f"  FAILED: {row.speed_kmh:g} km/h, {row.support_stiffness / 1e6:g} "
                           f"MN/m: {row.error}")
    return df


def _monotone(x: np.ndarray, sign: int) -> bool:
    return bool(np.all(np.isfinite(x)) and np.all(sign * np.diff(x) > 0))


def _fig6_support_stiffness(ctx: Context) -> None:
    """Paper Fig. 6: amplitude against support stiffness at 100 and 300 km/h."""
    from . import plots

    p = ctx.plan
    s = ctx.summary
    s.append(f"Fig. 6 -- amplitude max|d| against support stiffness, "
             f"{' and '.join(f'{v:g}' for v in p.fig6_speeds_kmh)} km/h; "
             f"{p.describe_settings()}")
    df = _sweep(ctx, p.fig6_speeds_kmh, p.stiffness)
    ctx.table(df, "fig6_support_stiffness.csv")
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
    dec = ", ".join(f"{v:g} km/h: {'yes' if _monotone(piv[v].to_numpy(), -1) else 'NO'}"
                    for v in speeds)
    s.append("  paper: the amplitude decreases with the support stiffness at both speeds, and "
             "the speed effect is strongest around 70-140 MN/m.")
    s.append(f"  here: amplitude decreasing with k_s -- {dec}.")
    if len(speeds) == 2:
        ratio = (piv[speeds[1]] / piv[speeds[0]]).to_numpy()
        k_max = piv.index[int(np.nanargmax(ratio))]
        s.append(f"  here: amplitude ratio {speeds[1]:g}/{speeds[0]:g} km/h "
                 f"{np.nanmin(ratio):.2f}..{np.nanmax(ratio):.2f}, largest at "
                 f"k_s = {k_max / 1e6:g} MN/m; the main frequency rises with k_s (the track's "
                 "lowest mode).")
    s.append("")


def _nearest_mode(f: float, lo: np.ndarray, hi: np.ndarray) -> int:
    """0-based index of the mode whose band [lo, hi] is closest to f."""
    dist = np.maximum(0.0, np.maximum(lo - f, f - hi))
    return int(np.argmin(dist))


def _fig7_speed(ctx: Context) -> None:
    """Paper Fig. 7: amplitude and main frequency against speed at the scene's stiffness, with
    the coupled system's eigenfrequencies (Fig. 3) as reference bands; and one run at 300 km/h
    shown in full (y_B, y_qs, d(t), spectrum)."""
    from . import plots
    from .analysis import analyse
    from .simulate import simulate

    p = ctx.plan
    scene = ctx.scene
    k_s = scene.supports.stiffness
    s = ctx.summary
    s.append(f"Fig. 7 -- amplitude and main frequency against speed, k_s = {k_s / 1e6:g} MN/m; "
             f"{p.describe_settings()}")
    df = _sweep(ctx, p.speeds_kmh, [k_s])
    ctx.table(df, "fig7_speed.csv")
    eig = _eigen(scene, np.linspace(0.0, scene.rail.length, p.n_eigen_positions), n_modes=4)
    ctx.save(plots.speed(df, eig), "fig7_speed.png")
    lo, hi = eig.frequencies.min(axis=0), eig.frequencies.max(axis=0)

    s.append(f"  {'v [km/h]':>8}  {'amplitude':>11}  {'main frequency':>24}  nearest mode")
    for row in df.itertuples():
        if not np.isfinite(row.main_frequency):
            s.append(f"  {row.speed_kmh:>8g}  (failed)")
            continue
        k = _nearest_mode(row.main_frequency, lo, hi)
        s.append(f"  {row.speed_kmh:>8g}  {row.amplitude * 1e6:>8.3f} µm  "
                 f"{row.main_frequency:>7.1f} Hz (± {row.frequency_resolution:4.1f} Hz)  "
                 f"mode {k + 1} ({lo[k]:.0f}-{hi[k]:.0f} Hz)")
    amp = df["amplitude"].to_numpy()
    fm = df["main_frequency"].to_numpy()
    s.append("  paper: the main frequency is about 400 Hz whatever the speed, the third mode; "
             "the amplitude increases with the speed.")
    s.append(f"  here: amplitude increasing with speed -- {'yes' if _monotone(amp, +1) else 'NO'}"
             f" ({np.nanmin(amp) * 1e6:.2f} to {np.nanmax(amp) * 1e6:.2f} µm); main frequency "
             f"{np.nanmin(fm):.0f}-{np.nanmax(fm):.0f} Hz, the lowest mode of the track "
             f"({lo[0]:.0f}-{hi[0]:.0f} Hz), not the third ({lo[2]:.0f}-{hi[2]:.0f} Hz).")
    s.append("")

    v_show = 300.0 if 300.0 in p.speeds_kmh else p.speeds_kmh[-1]
    r = simulate(scene, kmh(v_show), progress=False, **p.simulate)
    ctx.save(plots.dynamic(r, analyse(r), eigen=eig), f"fig7_dynamic_{v_show:g}kmh.png")


# ---- Fig. 8: acceleration terms --------------------------------------------------------------
def _fig8_acceleration_terms(ctx: Context) -> None:
    """Paper Fig. 8: the acceleration terms A-E at 100 and 300 km/h."""
    import pandas as pd

    from . import plots
    from .simulate import simulate

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
            rows.append(dict(speed_kmh=v, term=term, max_abs=float(np.max(np.abs(x))),
                             rms=float(np.sqrt(np.mean(x**2))), mean=float(np.mean(x))))
    table = pd.DataFrame(rows)
    ctx.table(table, "fig8_acceleration_terms.csv")
    ctx.save(plots.acceleration_terms(runs), "fig8_acceleration_terms.png")

    s = ctx.summary
    s.append(f"Fig. 8 -- terms of the contact-point acceleration (docs: Model § Outputs), "
             f"{p.describe_settings()}")
    s.append("  term  " + "  ".join(f"rms at {v:g} km/h" for v in p.fig8_speeds_kmh)
             + "  [m/s²]")
    rms = table.pivot(index="term", columns="speed_kmh", values="rms")
    for term in "ABCDE":
        s.append(f"  {term:>4}  " + "  ".join(f"{rms.loc[term, v]:>16.3g}"
                                               for v in p.fig8_speeds_kmh))
    if len(p.fig8_speeds_kmh) == 2:
        v0, v1 = p.fig8_speeds_kmh
        growth = rms[v1] / rms[v0]
        s.append("  paper: the terms grow as the square of the speed and are remarkable at "
                 "high speed.")
        s.append(f"  here: rms ratio {v1:g}/{v0:g} km/h = {growth.min():.1f}..{growth.max():.1f}"
                 f" (v² ratio {(v1 / v0) ** 2:.1f}); C, D, E are ~1e-4 of A, B.")
    s.append("")


#: The figures ``trackwheel reproduce`` makes, in order. Later figures are appended here.
REPRODUCE_STEPS: list[Step] = [
    Step("fig3", "Fig. 3: natural frequencies against wheel position", _fig3_eigen),
    Step("fig4", "Fig. 4: effect of the time step", _fig4_time_step),
    Step("fig5", "Fig. 5: effect of the number of elements", _fig5_elements),
    Step("fig6", "Fig. 6: amplitude against support stiffness", _fig6_support_stiffness),
    Step("fig7", "Fig. 7: amplitude and main frequency against speed", _fig7_speed),
    Step("fig8", "Fig. 8: terms of the contact-point acceleration", _fig8_acceleration_terms),
]


def reproduce(out: Path, quick: bool = False, scene: Scene | None = None,
              stream=None, only: Sequence[str] | None = None,
              workers: int | None = None) -> Context:
    """Run every step of :data:`REPRODUCE_STEPS` (or those named in ``only``) into ``out`` and
    write ``out/summary.txt``. ``quick`` selects :data:`QUICK` instead of :data:`FULL`;
    ``workers`` is the number of sweep processes (default one per core)."""
    stream = sys.stdout if stream is None else stream
    steps = REPRODUCE_STEPS
    if only is not None:
        names = [st.name for st in REPRODUCE_STEPS]
        unknown = [n for n in only if n not in names]
        if unknown:
            raise ValueError(f"only = {unknown}: no such step; allowed: {names}")
        steps = [st for st in REPRODUCE_STEPS if st.name in only]
    ctx = Context(scene=Scene.kato2005() if scene is None else scene, out=Path(out), quick=quick,
                  plan=QUICK if quick else FULL, workers=workers, stream=stream)
    ctx.out.mkdir(parents=True, exist_ok=True)
    t_all = time.perf_counter()
    for i, step in enumerate(steps, 1):
        print(f"[{i}/{len(steps)}] {step.title} ...", file=stream, flush=True)
        t0 = time.perf_counter()
        step.run(ctx)
        print(f"      done ({time.perf_counter() - t0:.1f} s)", file=stream, flush=True)
    head = [f"trackwheel {__version__} reproduce: Kato et al. (2005), scene Scene.kato2005()"
            + (" [--quick: coarse grids, 20 elements at 1e-5 s in the sweeps, short "
               "convergence stretches]" if quick else ""), ""]
    text = "\n".join(head + ctx.summary).rstrip("\n") + "\n"
    summary = ctx.out / "summary.txt"
    summary.write_text(text, encoding="utf-8")
    ctx.written.append(summary)
    print(file=stream)
    print(text, file=stream, end="")
    print(f"\nwrote {len(ctx.written)} files to {ctx.out} in "
          f"{time.perf_counter() - t_all:.1f} s:", file=stream)
    for p in ctx.written:
        print(f"  {p.name}", file=stream)
    return ctx


# --------------------------------------------------------------------------------------------
# argument parsing
# --------------------------------------------------------------------------------------------
def _positive_int(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected a positive integer, got {n}")
    return n


def _finite_float(text: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return x


def _positive_float(text: str) -> float:
    x = _finite_float(text)
    if x <= 0.0:
        raise argparse.ArgumentTypeError(f"expected a positive number, got {text!r}")
    return x


def _simulate_options(p: argparse.ArgumentParser, auto: bool = False) -> None:
    """Options passed to trackwheel.simulate (left out: simulate's defaults); ``auto`` offers
    ``--fidelity auto`` (sweep only: the cheapest level adequate on the sweep's hardest case)."""
    g = p.add_argument_group("simulation settings (default: simulate's derived defaults)")
    g.add_argument("--integrator", choices=("generalized_alpha", "explicit"),
                   help="time integrator (default generalized_alpha)")
    g.add_argument("--dt", type=_positive_float, metavar="S",
                   help="time step [s] (default: derived from the scene, 4.96e-6 s for the "
                        "paper's)")
    g.add_argument("--n-elements", type=_positive_int, metavar="N",
                   help="rail elements (default: 8 per support bay when --dt is not given, "
                        "else the scene's 20)")
    g.add_argument("--x-start", type=_finite_float, metavar="X",
                   help="wheel start [m] (default: middle of the first support bay)")
    g.add_argument("--x-end", type=_finite_float, metavar="X",
                   help="wheel end [m] (default: middle of the last support bay)")
    g.add_argument("--fidelity", choices=FIDELITY_LEVELS + (("auto",) if auto else ()),
                   help="model level (default full: the paper's model)"
                        + ("; auto: the cheapest level within --fidelity-tol of the full model "
                           "on the highest speed and softest supports of the sweep"
                           if auto else ""))
    if auto:
        g.add_argument("--fidelity-tol", type=_positive_float, metavar="TOL",
                       help="with --fidelity auto: relative tolerance on amplitude, main "
                            "frequency and peak contact force (default 0.005)")


def _simulate_kwargs(args: argparse.Namespace) -> dict:
    names = ("integrator", "dt", "n_elements", "x_start", "x_end", "fidelity")
    return {n: getattr(args, n) for n in names if getattr(args, n) is not None}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="trackwheel",
        description="A railway wheel rolling at high speed over a flexible rail on elastic "
                    "supports (Kato et al. 2005). SI units throughout, speeds in km/h on the "
                    "command line.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser(
        "reproduce", help="recompute the paper's figures (Figs. 3-8) into a folder",
        description="Recompute the paper's figures for Scene.kato2005() and write PNG + CSV "
                    "files and summary.txt (our numbers beside the paper's claims) into --out. "
                    "Steps: " + "; ".join(f"{s.name} = {s.title}" for s in REPRODUCE_STEPS)
                    + f". The sweeps keep finished cases in OUT/{STORE_NAME}: a re-run "
                    "resumes. The full run takes several minutes on two cores; --quick well "
                    "under one.")
    p.add_argument("--out", required=True, type=Path, metavar="DIR",
                   help="output folder (created if missing)")
    p.add_argument("--quick", action="store_true",
                   help="coarse grids, 20 elements at 1e-5 s in the sweeps and short "
                        "convergence stretches, for a fast check")
    p.add_argument("--only", nargs="+", choices=[s.name for s in REPRODUCE_STEPS],
                   metavar="STEP", help="run only these steps (" + ", ".join(
                       s.name for s in REPRODUCE_STEPS) + ")")
    p.add_argument("--workers", type=_positive_int, metavar="N",
                   help="processes for the sweeps (default: one per core)")
    p.set_defaults(run=_cmd_reproduce, parser=p)

    p = sub.add_parser(
        "run", help="simulate one passage and print the headline outputs",
        description="Simulate the wheel passing over the rail of Scene.kato2005() at one speed "
                    "and print the amplitude max|d| of the contact-point vibration "
                    "(d = y_B - y_qs, docs: Model § Outputs), its main frequency and resolution, the "
                    "contact-force range, whether the wheel lost contact, and the wall time.")
    p.add_argument("--speed-kmh", type=_positive_float, required=True, metavar="V",
                   help="forward speed [km/h]")
    p.add_argument("--support-stiffness", type=_positive_float, metavar="K",
                   help="support stiffness k_s [N/m] (default 140e6)")
    _simulate_options(p)
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save y_B, y_qs, d(t) and the spectrum of d to this file")
    p.set_defaults(run=_cmd_run, parser=p)

    p = sub.add_parser(
        "sweep", help="run a speed x support-stiffness sweep into a store",
        description="Run every (speed, support stiffness) case of Scene.kato2005() in parallel "
                    "(trackwheel.sweep), keep each finished case in --store (a re-run skips "
                    "them) and print the table. Exit code 1 if a case failed (it is recorded "
                    "with its error).")
    p.add_argument("--speeds-kmh", type=_positive_float, nargs="+", required=True, metavar="V",
                   help="forward speeds [km/h]")
    p.add_argument("--support-stiffness", type=_positive_float, nargs="+", metavar="K",
                   help="support stiffnesses k_s [N/m] (default 140e6)")
    p.add_argument("--store", type=Path, required=True, metavar="DIR",
                   help="folder keeping one record per finished case (created if missing)")
    p.add_argument("--out", type=Path, metavar="CSV", help="also write the table to this file")
    p.add_argument("--workers", type=_positive_int, metavar="N",
                   help="processes (default: one per core)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    _simulate_options(p, auto=True)
    p.set_defaults(run=_cmd_sweep, parser=p)

    p = sub.add_parser(
        "eigen", help="print the natural frequencies with the wheel at one position",
        description="Lowest vertical natural frequencies [Hz] of the wheel/rail/support system "
                    "of Scene.kato2005() with the wheel at --position, and the rail's lowest "
                    "axial frequencies.")
    p.add_argument("--position", type=_finite_float, default=X_REPORT, metavar="X",
                   help=f"wheel position X [m], 0 <= X <= L (default {X_REPORT})")
    p.add_argument("--n-modes", type=_positive_int, default=6, metavar="N",
                   help="number of vertical modes (default 6)")
    p.set_defaults(run=_cmd_eigen, parser=p)
    return parser


def _out_folder(path: Path, option: str, parser: argparse.ArgumentParser) -> None:
    if path.exists() and not path.is_dir():
        parser.error(f"{option} {path}: exists and is not a folder")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        parser.error(f"{option} {path}: cannot create the folder ({exc.strerror or exc})")


def _cmd_reproduce(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    _out_folder(args.out, "--out", parser)
    reproduce(args.out, quick=args.quick, only=args.only, workers=args.workers)
    return 0


def _scene(stiffness: float | None = None) -> Scene:
    """Scene.kato2005(), with the support stiffness replaced if given [N/m]."""
    scene = Scene.kato2005()
    if stiffness is not None:
        scene = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports,
                                                                        stiffness=stiffness))
    return scene


def _option_error(exc: Exception) -> str:
    """A library message with its parameter names spelled as the command's options."""
    text = str(exc)
    for name in ("n_elements", "x_start", "x_end", "speed_kmh", "support_stiffness"):
        text = text.replace(name, "--" + name.replace("_", "-"))
    return text


def _cmd_run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    from .analysis import analyse
    from .simulate import simulate

    scene = _scene(args.support_stiffness)
    speed = kmh(args.speed_kmh)
    kwargs = _simulate_kwargs(args)
    try:
        r = simulate(scene, speed, **kwargs)
    except ValueError as exc:
        parser.error(_option_error(exc))
    except DivergenceError as exc:
        print(f"trackwheel run: the simulation diverged: {exc}", file=sys.stderr)
        return 1
    a = analyse(r)
    st = r.settings
    x0, x1 = float(r.x_wheel[0]), float(r.x_wheel[-1])
    i_max = int(np.argmax(np.abs(a.dynamic)))
    print(f"Scene.kato2005(), k_s = {scene.supports.stiffness / 1e6:g} MN/m, "
          f"v = {args.speed_kmh:g} km/h ({speed:.2f} m/s)")
    print(f"  settings       : {st['integrator']}, dt = {st['dt']:.3g} s, {st['n_elements']} "
          f"elements, X = {x0:.4g} -> {x1:.4g} m, fidelity {st.get('fidelity', 'full')}")
    print(f"  amplitude      : {a.amplitude * 1e6:.3f} µm  (max |d|, d = y_B - y_qs; at "
          f"X = {a.x_wheel[i_max]:.3f} m)")
    print(f"  main frequency : {a.main_frequency:.1f} Hz  (resolution "
          f"{a.frequency_resolution:.2g} Hz)")
    print(f"  contact force  : {a.min_contact_force:.1f} .. {a.max_contact_force:.1f} N  "
          f"(static load {scene.static_load:.1f} N)")
    if a.lost_contact:
        free = r.contact_free_intervals()
        print(f"  lost contact   : yes, {len(free)} interval(s), first at "
              f"t = {free[0][0] * 1e3:.3f} ms")
    else:
        print("  lost contact   : no")
    print(f"  wall time      : {r.wall_time:.3f} s ({r.steps} steps)")
    if args.plot is not None:
        from . import plots

        eig = _eigen(scene, np.linspace(0.0, scene.rail.length, 41), n_modes=4)
        try:
            plots.dynamic(r, a, eigen=eig).savefig(args.plot, dpi=150)
        except OSError as exc:
            print(f"trackwheel run: cannot write --plot {args.plot}: {exc}", file=sys.stderr)
            return 1
        print(f"  plot           : {args.plot}")
    return 0


def _cmd_sweep(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    from .sweep import sweep

    top = 300.0 * 3.6  # simulate's speed range [0, 300] m/s
    too_fast = [v for v in args.speeds_kmh if v > top]
    if too_fast:
        parser.error(f"--speeds-kmh {too_fast[0]:g}: above the allowed {top:g} km/h")
    _out_folder(args.store, "--store", parser)
    scene = Scene.kato2005()
    extra = {}
    if args.fidelity_tol is not None:
        if args.fidelity != "auto":
            parser.error("--fidelity-tol is only used with --fidelity auto")
        extra["fidelity_tol"] = args.fidelity_tol
    try:
        df = sweep(scene, speed=[kmh(v) for v in args.speeds_kmh],
                   support_stiffness=args.support_stiffness, store=args.store,
                   progress=not args.no_progress, max_workers=args.workers,
                   **_simulate_kwargs(args), **extra)
    except (ValueError, TypeError) as exc:
        parser.error(_option_error(exc))
    auto = df.attrs.get("fidelity_auto")
    if auto:
        print(f"--fidelity auto: {auto['chosen']} (adequate within {auto['tol']:g} on "
              f"{auto['sample_speed'] * 3.6:g} km/h, "
              f"{auto['sample_support_stiffness'] / 1e6:g} MN/m)")
    print(f"{'v [km/h]':>8}  {'k_s [MN/m]':>10}  {'amplitude [µm]':>14}  "
          f"{'main f [Hz]':>11}  {'± [Hz]':>6}  {'N min..max [kN]':>15}  lost  error")
    for row in df.itertuples():
        if row.error:
            print(f"{row.speed_kmh:>8g}  {row.support_stiffness / 1e6:>10g}  {row.error}")
            continue
        print(f"{row.speed_kmh:>8g}  {row.support_stiffness / 1e6:>10g}  "
              f"{row.amplitude * 1e6:>14.3f}  {row.main_frequency:>11.1f}  "
              f"{row.frequency_resolution:>6.1f}  "
              f"{row.min_contact_force / 1e3:>6.2f}..{row.max_contact_force / 1e3:<7.2f}  "
              f"{'yes' if row.lost_contact else 'no':>4}")
    print(f"{len(df)} cases: {df.attrs.get('computed', 0)} computed, "
          f"{df.attrs.get('from_store', 0)} from the store {args.store}")
    if args.out is not None:
        try:
            df.to_csv(args.out, index=False)
        except OSError as exc:
            print(f"trackwheel sweep: cannot write --out {args.out}: {exc}", file=sys.stderr)
            return 1
        print(f"table written to {args.out}")
    n_failed = int((df["error"] != "").sum())
    if n_failed:
        print(f"{n_failed} case(s) failed (recorded with their error)", file=sys.stderr)
        return 1
    return 0


def _cmd_eigen(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    scene = Scene.kato2005()
    length = scene.rail.length
    if not 0.0 <= args.position <= length:
        parser.error(f"--position {args.position:g} m is outside the rail; "
                     f"allowed range [0, {length:g}] m")
    try:
        res = _eigen(scene, [args.position], n_modes=args.n_modes)
    except ValueError as exc:  # e.g. more modes than the mesh has
        parser.error(str(exc).replace("n_modes", "--n-modes"))
    print(f"Scene.kato2005(), wheel at X = {args.position:g} m ({res.n_elements} elements)")
    print("vertical modes:")
    for k, f in enumerate(res.frequencies[0], 1):
        print(f"  {k:>3}  {f:10.2f} Hz")
    if res.axial_frequencies.size:
        print("axial (x) modes of the rail: "
              + ", ".join(f"{f:.1f}" for f in res.axial_frequencies) + " Hz")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``trackwheel`` console script; returns the exit code."""
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        return args.run(args, args.parser)
    except SystemExit as exc:  # argparse: --help/--version (0) and usage errors (2)
        return exc.code if isinstance(exc.code, int) else 1


if __name__ == "__main__":
    sys.exit(main())
