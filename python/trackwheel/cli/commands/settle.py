"""``trackwheel settle``: the ballast settling under traffic, the settled bed fed back into the
track stage by stage (trackwheel.settle)."""

from __future__ import annotations

import argparse
from pathlib import Path

from ...base.limits import MAX_SPEED
from ...base.units import kmh
from ...study.settlement import LAWS, Traffic, TrafficItem, law_from_dict, settle
from ...study.settlement.passage import PASSAGE_LEVELS
from ...study.settlement.stages import DATUMS, DEFAULT_INCREMENT
from ..checks import figure_formats, option_error, output_file, speeds_kmh
from ..formatting import print_notes, save_figure
from ..options import (
    along_x_options,
    finite_float,
    positive_float,
    positive_int,
    track_option,
)
from ..scenes import OptionError, along_x_scene, describe_track, scene_name, track_scene


def add(sub) -> None:
    p = sub.add_parser(
        "settle", help="ballast settlement under traffic, fed back into the track",
        description="Run the traffic (one item per --speed-kmh, --per-day passages a day each) "
                    "over the --track for --cycles axle passes (trackwheel.settle; docs: Model "
                    "§ Ballast settlement): each stage runs one passage per item on the "
                    "current bed, advances the settlement --law by the stage's axle passes at "
                    "each sleeper's peak ballast force and adds the settlement to the "
                    "sleepers' voids. Prints the stages and the final settlement; --out "
                    "writes the settlement per sleeper and stage, --plot the profile.")
    p.add_argument("--speed-kmh", type=finite_float, nargs="+", required=True, metavar="V",
                   help=f"the speed of each traffic item [km/h], 0 < V <= {MAX_SPEED * 3.6:.4g}")
    p.add_argument("--per-day", type=positive_float, nargs="+", metavar="N",
                   help="passages a day of each item (default 1 each)")
    p.add_argument("--wheel-load", type=positive_float, nargs="+", metavar="F",
                   help="the static load F on the wheel of each item [N] (default the "
                        "track's)")
    p.add_argument("--cycles", type=positive_float, required=True, metavar="N",
                   help="axle passes over each sleeper (e.g. 1e6)")
    p.add_argument("--stages", type=positive_int, metavar="M",
                   help="the number of stages (default: adaptive, see --increment)")
    p.add_argument("--increment", type=positive_float, default=DEFAULT_INCREMENT, metavar="R",
                   help="adaptive stages: the largest change of a sleeper's void in a stage "
                        "as a fraction of the static deflection (default "
                        f"{DEFAULT_INCREMENT:g})")
    p.add_argument("--stage-rule", choices=("explicit", "quasi-static"), default="explicit",
                   help="explicit stages (default) or quasi-static: sub-steps at the "
                        "passage's dynamic ratio times the settling bed's statics")
    p.add_argument("--law", choices=tuple(LAWS), default="varandas",
                   help="the settlement law (default varandas with ROSE's parameters)")
    p.add_argument("--law-param", nargs="+", default=[], metavar="NAME=VALUE",
                   help="the law's parameters (e.g. gamma=0.005; sato and shenton need theirs)")
    p.add_argument("--open-loop", action="store_true",
                   help="keep the intact bed's forces (feedback=False), for comparison")
    p.add_argument("--datum", choices=DATUMS, default="min",
                   help="min (default): the track sinks by the least settlement, the rest "
                        "opens voids; none: all of it opens voids")
    p.add_argument("--fidelity", choices=PASSAGE_LEVELS, default="linear/hertz",
                   help="the passages' model level (default linear/hertz; static: the wheel "
                        "standing above each sleeper)")
    p.add_argument("--x-start", type=finite_float, metavar="X", help="passage start [m]")
    p.add_argument("--x-end", type=finite_float, metavar="X", help="passage end [m]")
    track_option(p)
    along_x_options(p)
    p.set_defaults(track="ballasted", seed=None)
    p.add_argument("--store", type=Path, metavar="DIR",
                   help="folder keeping each stage (a re-run goes on from the last)")
    p.add_argument("--out", type=Path, metavar="CSV",
                   help="write the settlement, void and peak force per sleeper and stage")
    p.add_argument("--plot", type=Path, metavar="FILE", help="save the settlement profile")
    p.add_argument("--workers", type=positive_int, metavar="N",
                   help="processes for the passages of a stage (default: this one)")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(run=run, parser=p)


def _traffic(args, parser) -> Traffic:
    n = len(args.speed_kmh)
    for name in ("per_day", "wheel_load"):
        given = getattr(args, name)
        if given is not None and len(given) != n:
            parser.error(f"--{name.replace('_', '-')}: give one value per --speed-kmh ({n})")
    per_day = args.per_day or [1.0] * n
    loads = args.wheel_load or [None] * n
    try:
        return Traffic(tuple(TrafficItem(kmh(v), per_day=d, wheel_load=f,
                                         name=f"{v:g} km/h")
                             for v, d, f in zip(args.speed_kmh, per_day, loads)))
    except ValueError as exc:
        parser.error(option_error(exc))


def _law(args, parser):
    params = {}
    for text in args.law_param:
        name, sep, value = text.partition("=")
        if not sep:
            parser.error(f"--law-param {text!r}: expected NAME=VALUE")
        try:
            params[name] = float(value)
        except ValueError:
            parser.error(f"--law-param {text!r}: {value!r} is not a number")
    try:
        return law_from_dict({"law": args.law, **params})
    except (TypeError, ValueError) as exc:
        parser.error(f"--law {args.law}: {option_error(exc)}")


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    speeds_kmh(args.speed_kmh, "--speed-kmh", parser)
    if args.out is not None:
        output_file(args.out, "--out", parser, ["csv"])
    if args.plot is not None:
        output_file(args.plot, "--plot", parser, figure_formats())
    traffic, law = _traffic(args, parser), _law(args, parser)
    try:
        scene = along_x_scene(track_scene(args), args)
    except OptionError as exc:
        parser.error(str(exc))
    try:
        history = settle(scene, traffic, args.cycles, law, stages=args.stages,
                         increment=args.increment, feedback=not args.open_loop,
                         datum=args.datum, fidelity=args.fidelity, x_start=args.x_start,
                         x_end=args.x_end, max_workers=args.workers, store=args.store,
                         progress=not args.no_progress, stage_rule=args.stage_rule)
    except (TypeError, ValueError) as exc:
        parser.error(option_error(exc))
    along = describe_track(scene)
    _print(history, scene_name(scene, args) + (f"; {along}" if along else ""), args)
    notes = []
    if args.out is not None:
        history.frame().to_csv(args.out, index=False)
        notes.append(f"wrote {args.out}")
    if args.plot is not None:
        from ... import plots

        save_figure(plots.settlement_profile(history), args.plot, "settle")
    print_notes(notes, "settle")
    return 0


def _print(history, name: str, args) -> None:
    print(f"track: {name}; {history.sleepers.size} settling sleepers at X = "
          f"{history.sleepers[0]:g}..{history.sleepers[-1]:g} m; law {history.law.name}; "
          f"{'open loop' if args.open_loop else 'feedback'}; {args.fidelity}")
    print(f"{'stage':>5} {'cycles':>10} {'days':>10} {'S min [mm]':>10} {'S max [mm]':>10} "
          f"{'void max [mm]':>13} {'Fb max [kN]':>11} {'factor':>7}")
    df = history.stages()
    step = max(1, len(df) // 20)  # at most about 20 rows, the last always
    for i in sorted(set(range(0, len(df), step)) | {len(df) - 1}):
        r = df.iloc[i]
        print(f"{int(r['stage']):>5} {int(r['cycles']):>10} {r['days']:>10.4g} "
              f"{1e3 * r['settlement_min_m']:>10.4f} {1e3 * r['settlement_max_m']:>10.4f} "
              f"{1e3 * r['void_max_m']:>13.4f} {1e-3 * r['peak_ballast_force_max_N']:>11.2f} "
              f"{r['dynamic_factor']:>7.4f}")
