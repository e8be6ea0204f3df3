"""``trackwheel sweep``: a speed x support-stiffness (x seed) sweep into a resumable store."""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

from ...base.errors import FailedCasesWarning, PlausibilityWarning, SweepFailedError
from ...base.limits import MAX_SPEED
from ...base.units import kmh
from ...study.columns import OUTPUTS, SPEED_KMH, SUPPORT_STIFFNESS, label
from ...study.sweep import summarise_seeds, sweep
from ..checks import option_error, output_file, speeds_kmh, writable_folder
from ..formatting import print_notes, print_warnings
from ..options import (
    along_x_options,
    damping_options,
    excitation_options,
    finite_float,
    positive_int,
    simulate_kwargs,
    simulate_options,
    track_option,
)
from ..scenes import OptionError, describe, describe_track, excited_scene, track_scene


def add(sub) -> None:
    p = sub.add_parser(
        "sweep", help="run a speed x support-stiffness sweep into a store",
        description="Run every (speed, support stiffness) case of the --track scene (default "
                    "Scene.kato2005()) in parallel "
                    "(trackwheel.sweep), with --seeds one case per realisation of the random "
                    "--irregularity, keep each finished case in --store (a re-run skips them) "
                    "and print the table (with --seeds also the 5/50/95 % percentiles over "
                    "the seeds per speed). Exit code 1 if a case failed (it is recorded with "
                    "its error).")
    p.add_argument("--speeds-kmh", type=finite_float, nargs="+", required=True, metavar="V",
                   help=f"forward speeds [km/h], 0 < V <= {MAX_SPEED * 3.6:.4g}")
    p.add_argument("--support-stiffness", type=finite_float, nargs="+", metavar="K",
                   help="support stiffnesses k_s [N/m] (default 140e6; with --track ballasted "
                        "the rail pad's, default 180e6)")
    track_option(p)
    along_x_options(p)
    p.add_argument("--store", type=Path, required=True, metavar="DIR",
                   help="folder keeping one record per finished case (created if missing)")
    p.add_argument("--out", type=Path, metavar="CSV", help="also write the table to this file")
    p.add_argument("--workers", type=positive_int, metavar="N",
                   help="processes (default: one per core)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    damping_options(p)
    excitation_options(p, seeds=True)
    simulate_options(p, auto=True)
    p.set_defaults(run=run, parser=p)


#: the table printed, one column per quantity (the min and max force share one): the header
#: and the displayed unit and scale come from the quantity (trackwheel.study.columns)
_OUT = {q.name: q for q in OUTPUTS}
_TABLE = ((SPEED_KMH, ">8g"), (SUPPORT_STIFFNESS, ">10g"))
_ROW = ((_OUT["amplitude"], ">14.3f"), (_OUT["main_frequency"], ">11.1f"),
        (_OUT["frequency_resolution"], ">6.1f"))
_N_MIN, _N_MAX, _FACTOR, _LOST = (_OUT[n] for n in ("min_contact_force", "max_contact_force",
                                                     "dynamic_factor", "lost_contact"))
_FB, _FB_X = _OUT["max_ballast_force"], _OUT["max_ballast_force_x"]
_SEED, _ERROR, _SPEED = (label(n) for n in ("seed", "error", "speed"))


def _print_sweep(df, store: Path, excitation: str, track: str | None = None) -> None:
    print(f"excitation: {excitation}")
    if track is not None:
        print(f"track along X: {track}")
    auto = df.attrs.get("fidelity_auto")
    if auto:
        k = auto["sample_support_stiffness"]
        print(f"--fidelity auto: {auto['chosen']} (adequate within {auto['tol']:g} on "
              f"{auto['sample_speed'] * 3.6:g} km/h, "
              + ("the scene's supports)" if k is None else f"{k / 1e6:g} MN/m)"))
    seeded = bool(df[_SEED].notna().any())
    ballast = bool(df[_FB.label].notna().any())
    n_range = f"{_N_MAX.symbol} min..max [{_N_MAX.display[0]}]"
    print("  ".join(f"{q.header:>{_width(fmt)}}" for q, fmt in _TABLE) + "  "
          + ("seed  " if seeded else "")
          + "  ".join(f"{q.header:>{_width(fmt)}}" for q, fmt in _ROW)
          + f"  {n_range:>15}  {_FACTOR.header:>6}  {_LOST.header}"
          + (f"  {_FB.header:>13}  {_FB_X.header:>9}" if ballast else "") + "  error")
    for _, row in df.iterrows():
        head = ("  ".join(_cell(q, row[q.label], fmt) for q, fmt in _TABLE) + "  "
                + (f"{row[_SEED]:>4}  " if seeded else ""))
        if row[_ERROR]:
            print(f"{head}{row[_ERROR]}")
            continue
        print(head + "  ".join(f"{q.shown(row[q.label]):{fmt}}" for q, fmt in _ROW)
              + f"  {_N_MIN.shown(row[_N_MIN.label]):>6.2f}.."
              f"{_N_MAX.shown(row[_N_MAX.label]):<7.2f}  "
              f"{row[_FACTOR.label]:>6.3f}  {'yes' if row[_LOST.label] else 'no':>4}"
              + (f"  {_FB.shown(row[_FB.label]):>13.2f}  {row[_FB_X.label]:>9.2f}"
                 if ballast else ""))
    if seeded and (df[_ERROR] == "").any():
        _print_seed_summary(df)
    print(f"{len(df)} cases: {df.attrs.get('computed', 0)} computed, "
          f"{df.attrs.get('from_store', 0)} from the store {store}")


def _cell(q, value, fmt: str) -> str:
    """A case axis' cell: the value in the displayed unit, or "along X" for a support stiffness
    the scene varies along the track (the table's NaN there)."""
    if q is SUPPORT_STIFFNESS and value != value:
        return f"{'along X':>{_width(fmt)}}"
    return f"{q.shown(value):{fmt}}"


def _width(fmt: str) -> int:
    """The field width of a format such as ">14.3f"."""
    return int(fmt.lstrip("<>^").split(".")[0].rstrip("gfd"))


def _print_seed_summary(df) -> None:
    """The 5th / 50th / 95th percentiles over the seeds of the largest force and the dynamic
    factor, per speed (and support stiffness, if the sweep has several)."""
    stiffness = SUPPORT_STIFFNESS.label
    by = _SPEED if df[stiffness].nunique(dropna=False) == 1 else [_SPEED, stiffness]
    summary = summarise_seeds(df, [_N_MAX.label, _FACTOR.label], by=by)
    print("over the seeds (5th / 50th / 95th percentile):")
    for key, row in summary.iterrows():
        v, k = (key, None) if isinstance(by, str) else key
        where = f"{v * 3.6:>8g} km/h" + (f", {k / 1e6:g} MN/m" if k is not None else "")
        print(f"{where}: max N {_pcts(row, _N_MAX)} {_N_MAX.display[0]}, N/P0 "
              f"{_pcts(row, _FACTOR)} ({int(row[('n_seeds', '')])} seeds)")


def _pcts(row, q) -> str:
    return " / ".join(f"{q.shown(row[(q.label, p)]):.4g}" for p in ("p5", "p50", "p95"))


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    speeds_kmh(args.speeds_kmh, "--speeds-kmh", parser)
    for option, values, unit in (("--speeds-kmh", args.speeds_kmh, "km/h"),
                                 ("--support-stiffness", args.support_stiffness or [], "N/m")):
        twice = sorted({x for x in values if values.count(x) > 1})
        if twice:
            parser.error(f"{option}: {twice[0]:g} {unit} is given twice")
    if args.out is not None:
        output_file(args.out, "--out", parser)
    writable_folder(args.store, "--store", parser, create=True)
    extra = {}
    if args.fidelity_tol is not None:
        if args.fidelity != "auto":
            parser.error("--fidelity-tol is only used with --fidelity auto")
        extra["fidelity_tol"] = args.fidelity_tol
    seeds = None
    if args.seeds is not None:
        seeds = [s for group in args.seeds for s in group]
        if len(set(seeds)) != len(seeds):
            parser.error(f"--seeds: a seed is given twice ({', '.join(map(str, seeds))})")
        if args.seed is not None:
            parser.error("give --seed (one realisation) or --seeds (several), not both")
    try:
        scene, notes = excited_scene(track_scene(args), args)
    except OptionError as exc:
        parser.error(str(exc))
    print_notes(notes, "sweep")
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            # the failed cases are counted below; the speeds were checked in km/h above
            warnings.filterwarnings("ignore", category=FailedCasesWarning)
            warnings.filterwarnings("ignore", message="speed = ", category=PlausibilityWarning)
            df = sweep(scene, speed=[kmh(v) for v in args.speeds_kmh], seeds=seeds,
                       support_stiffness=args.support_stiffness, store=args.store,
                       progress=not args.no_progress, max_workers=args.workers,
                       **simulate_kwargs(args), **extra)
    except SweepFailedError as exc:
        print_warnings(caught, "sweep")
        _print_sweep(exc.table, args.store, describe(scene, seeds), describe_track(scene, seeds))
        print(f"trackwheel sweep: {exc}", file=sys.stderr)
        return 1
    except (ValueError, TypeError) as exc:
        parser.error(option_error(exc))
    print_warnings(caught, "sweep")
    _print_sweep(df, args.store, describe(scene, seeds), describe_track(scene, seeds))
    if args.out is not None:
        try:
            df.to_csv(args.out, index=False)
        except OSError as exc:
            print(f"trackwheel sweep: cannot write --out {args.out}: {exc}", file=sys.stderr)
            return 1
        print(f"table written to {args.out}")
    n_failed = int((df["error"] != "").sum())
    if n_failed:
        first = df["error"][df["error"] != ""].iloc[0]
        print(f"trackwheel sweep: {n_failed} of {len(df)} case(s) failed (recorded with their "
              f"error); the first: {first}", file=sys.stderr)
        return 1
    return 0
