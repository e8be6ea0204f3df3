"""The paper's Figs. 6 and 7: the sweeps over the support stiffness and the speed, and one run
at 300 km/h shown in full; the tables and the sentences of the summary."""

from __future__ import annotations

import time

import numpy as np

from ..base.units import kmh
from ..run.eigen import eigen
from ..run.simulate import simulate
from ..study.analysis import analyse
from ..study.columns import SPEED_KMH, label
from ..study.sweep import sweep
from .plan import Context

#: the sweep table's columns read here
KMH = SPEED_KMH.label
STIFFNESS, AMPLITUDE, MAIN_F, RESOLUTION, ERROR = (label(n) for n in (
    "support_stiffness", "amplitude", "main_frequency", "frequency_resolution", "error"))

# --------------------------------------------------------------------------------------------
# Figs. 6 and 7: sweeps
def _sweep(ctx: Context, speeds_kmh, stiffness):
    t0 = time.perf_counter()
    df = sweep(ctx.scene, speed=[kmh(v) for v in speeds_kmh], support_stiffness=list(stiffness),
               store=ctx.store, progress=False, max_workers=ctx.workers, **ctx.plan.simulate)
    ctx.log(f"{len(df)} cases ({df.attrs.get('computed', '?')} computed, "
            f"{df.attrs.get('from_store', '?')} from {ctx.store}) in "
            f"{time.perf_counter() - t0:.1f} s")
    for _, row in df[df[ERROR] != ""].iterrows():
        ctx.summary.append(f"  FAILED: {row[KMH]:g} km/h, {row[STIFFNESS] / 1e6:g} "
                           f"MN/m: {row[ERROR]}")
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


def fig6_support_stiffness(ctx: Context) -> None:
    """Paper Fig. 6: amplitude against support stiffness at 100 and 300 km/h."""
    from .. import plots

    p = ctx.plan
    s = ctx.summary
    s.append(f"Fig. 6 -- amplitude max|d| against support stiffness, "
             f"{' and '.join(f'{v:g}' for v in p.fig6_speeds_kmh)} km/h; "
             f"{p.describe_settings(ctx.scene)}")
    df = _sweep(ctx, p.fig6_speeds_kmh, p.stiffness)
    ctx.table(df, "fig6_support_stiffness.csv")
    ctx.save(plots.support_stiffness(df, frequency=True), "fig6_support_stiffness.png")
    piv = df.pivot_table(index=STIFFNESS, columns=KMH, values=AMPLITUDE,
                         dropna=False)
    fr = df.pivot_table(index=STIFFNESS, columns=KMH, values=MAIN_F,
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


def fig7_speed(ctx: Context) -> None:
    """Paper Fig. 7: amplitude and main frequency against speed at the scene's stiffness, with
    the coupled system's eigenfrequencies (Fig. 3) as reference bands; and one run at 300 km/h
    shown in full (y_B, y_qs, d(t), spectrum)."""
    from .. import plots

    p = ctx.plan
    scene = ctx.scene
    k_s = scene.supports.stiffness
    s = ctx.summary
    s.append(f"Fig. 7 -- amplitude and main frequency against speed, k_s = {k_s / 1e6:g} MN/m; "
             f"{p.describe_settings(scene)}")
    df = _sweep(ctx, p.speeds_kmh, [k_s])
    ctx.table(df, "fig7_speed.csv")
    eig = eigen(scene, np.linspace(0.0, scene.rail.length, p.n_eigen_positions), n_modes=4,
                n_elements=scene.rail.n_elements)  # the paper's mesh, as Fig. 3
    ctx.save(plots.speed(df, eig), "fig7_speed.png")
    lo, hi = eig.frequencies.min(axis=0), eig.frequencies.max(axis=0)
    s.append(f"  {'v [km/h]':>8}  {'amplitude':>11}  {'main frequency':>24}  nearest mode")
    for _, row in df.iterrows():
        if not np.isfinite(row[MAIN_F]):
            s.append(f"  {row[KMH]:>8g}  (failed)")
            continue
        k = nearest_mode(row[MAIN_F], lo, hi)
        s.append(f"  {row[KMH]:>8g}  {row[AMPLITUDE] * 1e6:>8.3f} µm  "
                 f"{row[MAIN_F]:>7.1f} Hz (± {row[RESOLUTION]:4.1f} Hz)  "
                 f"mode {k + 1} ({lo[k]:.0f}-{hi[k]:.0f} Hz)")
    s.append("  paper: the main frequency is about 400 Hz whatever the speed, the third mode; "
             "the amplitude increases with the speed.")
    s.extend(fig7_conclusions(df[AMPLITUDE], df[MAIN_F], lo, hi))

    v_show = 300.0 if 300.0 in p.speeds_kmh else p.speeds_kmh[-1]
    r = simulate(scene, kmh(v_show), progress=False, **p.simulate)
    ctx.save(plots.dynamic(r, analyse(r), eigen=eig), f"fig7_dynamic_{v_show:g}kmh.png")

