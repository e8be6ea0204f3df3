"""``trackwheel run``: one passage and its headline outputs (or, with --distance, a long run on
a travelling window and its contact-force statistics per 100 m)."""

from __future__ import annotations

import argparse
import dataclasses
import math
import sys
import warnings
from pathlib import Path

import numpy as np

from ...base.errors import DivergenceError, PlausibilityWarning
from ...base.limits import MAX_SPEED
from ...base.units import kmh
from ...run.eigen import eigen
from ...run.simulate import simulate
from ...scene import Scene, Window
from ...study.analysis import analyse
from ...study.force_statistics import defect_position
from ..checks import option_error, output_options, speeds_kmh
from ..formatting import print_notes, print_warnings, wall_time_text
from ..options import (
    along_x_options,
    damping_options,
    excitation_options,
    finite_float,
    positive_float,
    simulate_kwargs,
    simulate_options,
    track_option,
    window_spec,
)
from ..scenes import (
    VEHICLES,
    OptionError,
    describe,
    describe_track,
    excited_scene,
    scene_name,
    track_scene,
    vehicle_scene,
)


def _k_text(scene: Scene) -> str:
    """The support (pad) stiffness [MN/m]: one value, or its range over the supports."""
    return scene.supports.text("stiffness", 1e-6, scene.support_positions)


def add(sub) -> None:
    p = sub.add_parser(
        "run", help="simulate one passage and print the headline outputs",
        description="Simulate the wheel passing over the rail of the --track scene (default "
                    "Scene.kato2005()) at one speed "
                    "and print the amplitude max|d| of the contact-point vibration "
                    "(d = y_B - y_qs, docs: Model § Outputs), its main frequency and resolution, the "
                    "contact-force range, whether the wheel lost contact (and slid), and the "
                    "wall time of the whole command (the simulation's share beside it); "
                    "measured, as tw.analyse does, on the part of the run clear of the rail's "
                    "ends and the start-up transient (the X range run and measured are "
                    "printed; the paper's 5 m rail is measured whole).")
    p.add_argument("--speed-kmh", type=finite_float, required=True, metavar="V",
                   help=f"forward speed [km/h], 0 < V <= {MAX_SPEED * 3.6:.4g}")
    p.add_argument("--support-stiffness", type=finite_float, metavar="K",
                   help="support stiffness k_s [N/m] (default 140e6; with --track ballasted "
                        "the rail pad's, default 180e6)")
    track_option(p)
    along_x_options(p)
    p.add_argument("--vehicle", choices=VEHICLES, default="single",
                   help="single: the paper's wheel under its constant load; quarter-car: "
                        "Vehicle.quarter_car() (wheel, primary, bogie, secondary, body); "
                        "bogie: Vehicle.bogie() on the --track rail; half-car: "
                        "Vehicle.half_car() on the --track rail lengthened by its 20 m span "
                        "(docs: Model § The vehicle)")
    damping_options(p)
    excitation_options(p)
    p.add_argument("--brake-torque", type=finite_float, metavar="T_B",
                   help="friction brake on the wheel's rotation [N m], >= 0: beyond adhesion "
                        "(mu P rho0, 1414 N m for the paper's wheel) it locks the wheel, which "
                        "then slides (docs: Model § Rolling and slip)")
    simulate_options(p)
    g = p.add_argument_group(
        "long runs on a travelling window (docs: Model § The travelling window)")
    g.add_argument("--distance", type=positive_float, metavar="M",
                   help="run this many metres on a travelling window of the --track (the rail "
                        "becomes --window bays that move with the wheel): any distance at the "
                        "same cost per metre; default --fidelity linear/hertz (the fastest; "
                        "--fidelity full runs the nonlinear model on the window); prints "
                        "contact-force statistics per 100 m")
    g.add_argument("--window", type=window_spec, metavar="BEHIND,AHEAD",
                   help="with --distance: whole sleeper bays behind the rear wheel's bay and "
                        "ahead of the leading wheel's (default 20,20)")
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save y_B, y_qs, d(t) and the spectrum of d to this file (any format "
                        "matplotlib writes: .png, .pdf, .svg, ...)")
    p.set_defaults(run=run, parser=p)


def _print_vehicle_run(scene: Scene, speed_kmh: float, r, x_d) -> None:
    """Headline outputs of a vehicle run, one line per wheel (analyse(r, wheel=i))."""
    st = r.settings
    veh = scene.active_vehicle
    k_name = "k_p" if scene.supports.layered else "k_s"
    print(f"{veh.n_wheels} wheels, {len(veh.bogies)} bogie(s), car body: "
          f"{'yes' if veh.car else 'no'}; {k_name} = {_k_text(scene)} MN/m, "
          f"v = {speed_kmh:g} km/h ({kmh(speed_kmh):.2f} m/s)")
    print(f"  settings : {st.integrator}, dt = {st.dt:.3g} s, {st.n_elements} elements, "
          f"fidelity {st.fidelity}, excitation: {describe(scene)}")
    if (track := describe_track(scene)) is not None:
        print(f"  track    : {track}")
    x = np.asarray(r.x_wheel)
    print(f"  run      : wheel 0 X = {x[0, 0]:.4g} -> {x[-1, 0]:.4g} m, wheel "
          f"{veh.n_wheels - 1} X = {x[0, -1]:.4g} -> {x[-1, -1]:.4g} m"
          if x.ndim == 2 else f"  run      : X = {x[0]:.4g} -> {x[-1]:.4g} m")
    loads = veh.static_loads(scene.gravity)
    for i in range(veh.n_wheels):
        a = analyse(r, wheel=i if veh.n_wheels > 1 else None, defect_at=x_d)
        print(f"  wheel {i} (x = {veh.positions[i]:g} m): measured X = {a.x_range[0]:.4g} -> "
              f"{a.x_range[1]:.4g} m: max|d| = {a.amplitude * 1e6:.3f} µm, "
              f"N = {a.min_contact_force / 1e3:.2f} .. {a.max_contact_force / 1e3:.2f} kN "
              f"(static {loads[i] / 1e3:.2f} kN), dynamic factor {a.dynamic_factor:.4f}, "
              f"lost contact: {'yes' if a.lost_contact else 'no'}")


def _print_forces(scene: Scene, a) -> None:
    f = a.forces
    print(f"  dynamic factor : {a.dynamic_factor:.4f}  (max N / static load)")
    if f.band_rms.size:
        top = np.argsort(f.band_rms)[::-1][:3]
        print("  force bands    : " + ", ".join(
            f"{f.band_centres[k]:.4g} Hz {f.band_rms[k] / 1e3:.3g} kN" for k in top)
            + "  (largest one-third-octave RMS of N)")
    if not math.isnan(f.defect_time):
        print(f"  P1 / P2        : {f.p1 / 1e3:.2f} / {f.p2 / 1e3:.2f} kN at t = "
              f"{f.p1_time * 1e3:.3f} / {f.p2_time * 1e3:.3f} ms (joint reached at "
              f"{f.defect_time * 1e3:.3f} ms)")


def _print_sliding(scene: Scene, r, a) -> None:
    """Whether the wheel slid and locked, beside the brake's torque and the adhesion limit
    mu P rho0 (printed for a braked run, or whenever the wheel slid)."""
    brake = scene.wheel.brake_torque
    if a.slide_duration == 0.0 and brake == 0.0:
        return
    limit = scene.contact.friction * scene.static_load * scene.wheel.radius
    versus = (f"brake torque {brake:g} N m {'>' if brake > limit else '<='} adhesion limit "
              f"mu P rho0 = {limit:.0f} N m" if brake > 0.0 else "no brake")
    if a.slide_duration == 0.0:
        print(f"  sliding        : no ({versus})")
        return
    slid, locked = r.sliding_intervals(), r.locked_intervals()
    lock = (f"; locked (theta' = 0) from t = {locked[0][0] * 1e3:.3f} ms, "
            f"{a.locked_duration * 1e3:.3f} ms in all" if locked else "; never locked")
    print(f"  sliding        : yes, from t = {slid[0][0] * 1e3:.3f} ms, "
          f"{a.slide_duration * 1e3:.3f} ms in all{lock} ({versus})")


def _print_run(scene: Scene, speed_kmh: float, r, a, name: str = "Scene.kato2005()") -> None:
    st = r.settings
    x0, x1 = float(r.x_wheel[0]), float(r.x_wheel[-1])
    i_max = int(np.argmax(np.abs(a.dynamic)))
    k_name = "k_p" if scene.supports.layered else "k_s"
    print(f"{name}, {k_name} = {_k_text(scene)} MN/m, "
          f"v = {speed_kmh:g} km/h ({kmh(speed_kmh):.2f} m/s)")
    print(f"  settings       : {st.integrator}, dt = {st.dt:.3g} s, {st.n_elements} "
          f"elements, fidelity {st.fidelity}")
    print(f"  run            : X = {x0:.4g} -> {x1:.4g} m")
    whole = a.x_range[0] <= x0 and a.x_range[1] >= x1
    print(f"  measured       : X = {a.x_range[0]:.4g} -> {a.x_range[1]:.4g} m  ("
          + ("the whole run: no stretch of it is clear of the rail's ends and the start-up "
             "transient"
             if whole else "clear of the rail's ends and the start-up transient") + ")")
    print(f"  excitation     : {describe(scene)}")
    if (track := describe_track(scene)) is not None:
        print(f"  track along X  : {track}")
    print(f"  amplitude      : {a.amplitude * 1e6:.3f} µm  (max |d|, d = y_B - y_qs; at "
          f"X = {a.x_wheel[i_max]:.3f} m)")
    print(f"  main frequency : {a.main_frequency:.1f} Hz  (resolution "
          f"{a.frequency_resolution:.2g} Hz)")
    print(f"  contact force  : {a.min_contact_force:.1f} .. {a.max_contact_force:.1f} N  "
          f"(static load {scene.static_load:.1f} N)")
    if a.lost_contact:
        free = r.contact_free_intervals()
        print(f"  lost contact   : yes, {len(free)} interval(s), first at "
              f"t = {free[0][0] * 1e3:.3f} ms, {a.loss_duration * 1e3:.3f} ms in all")
    else:
        print("  lost contact   : no")
    _print_sliding(scene, r, a)
    _print_forces(scene, a)


def _wall(args: argparse.Namespace, r) -> str:
    """The whole command's wall time, the simulation's beside it."""
    return wall_time_text(getattr(args, "started", None), r.wall_time, r.steps)


def _finish_vehicle_run(scene: Scene, args: argparse.Namespace, r, x_d) -> int:
    try:
        _print_vehicle_run(scene, args.speed_kmh, r, x_d)
    except (RuntimeError, ValueError) as exc:  # a quasi-static solve, or the joint not reached
        print(f"trackwheel run: the analysis failed: {exc}", file=sys.stderr)
        return 1
    if args.plot is not None:
        from ... import plots  # matplotlib only when a figure is drawn

        try:
            plots.dynamic(r).savefig(args.plot, dpi=150)
        except (OSError, ValueError) as exc:
            print(f"trackwheel run: cannot write --plot {args.plot}: {exc}", file=sys.stderr)
            return 1
        print(f"  plot: {args.plot}")
    print(f"  wall time: {_wall(args, r)}")
    return 0


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    speeds_kmh([args.speed_kmh], "--speed-kmh", parser)
    output_options(args, parser)
    if args.vehicle != "single" and args.wheel_flat is not None:
        parser.error("--wheel-flat is only available with --vehicle single")
    if args.vehicle != "single" and args.brake_torque is not None:
        parser.error("--brake-torque is only available with --vehicle single")
    if args.window is not None and args.distance is None:
        parser.error("--window needs --distance (the window is for long runs)")
    try:
        with warnings.catch_warnings(record=True) as caught:  # e.g. a stiffness in MN/m
            warnings.simplefilter("always")
            track = track_scene(args, args.support_stiffness)
        scene, vehicle_notes = vehicle_scene(track, args.vehicle)
        scene, notes = excited_scene(scene, args)
        notes = vehicle_notes + notes
        if args.brake_torque is not None:
            scene = dataclasses.replace(scene, wheel=dataclasses.replace(
                scene.wheel, brake_torque=args.brake_torque))
        if args.distance is not None:
            scene = scene.windowed(args.window or Window())
    except OptionError as exc:
        parser.error(str(exc))
    except (ValueError, TypeError) as exc:  # e.g. a support stiffness out of range
        parser.error(option_error(exc))
    print_warnings(caught, "run")
    print_notes(notes, "run")
    if args.distance is not None:
        return _window_run(scene, args, parser)
    r = _simulate(scene, args.speed_kmh, simulate_kwargs(args), parser)
    if r is None:
        return 1
    x_d = defect_position(scene)
    if x_d is not None and not r.x_wheel[0] <= x_d <= r.x_wheel[-1]:
        x_d = None  # the run does not reach the joint's middle
    if scene.vehicle is not None:
        return _finish_vehicle_run(scene, args, r, x_d)
    try:
        a = analyse(r, defect_at=x_d)
    except RuntimeError as exc:  # a static solve of the quasi-static line failed
        print(f"trackwheel run: the analysis failed: {exc}", file=sys.stderr)
        return 1
    _print_run(scene, args.speed_kmh, r, a, scene_name(scene, args))
    if args.plot is not None:
        from ... import plots  # matplotlib only when a figure is drawn

        eig = eigen(scene, np.linspace(0.0, scene.rail.length, 41), n_modes=4)
        try:
            plots.dynamic(r, a, eigen=eig).savefig(args.plot, dpi=150)
        except (OSError, ValueError) as exc:
            print(f"trackwheel run: cannot write --plot {args.plot}: {exc}", file=sys.stderr)
            return 1
        print(f"  plot           : {args.plot}")
    print(f"  wall time      : {_wall(args, r)}")
    return 0


def _simulate(scene: Scene, speed_kmh: float, kw: dict, parser):
    """``simulate(scene, speed, **kw)``, its warnings printed (one line each); a bad value is a
    usage error (exit 2), a failed run one line on stderr and None (exit 1)."""
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            # checked in km/h by speeds_kmh (the library's warning speaks of m/s)
            warnings.filterwarnings("ignore", message="speed = ", category=PlausibilityWarning)
            r = simulate(scene, kmh(speed_kmh), **kw)
    except (ValueError, TypeError) as exc:
        parser.error(option_error(exc))
    except DivergenceError as exc:
        print_warnings(caught, "run")
        print(f"trackwheel run: the simulation diverged: {exc}", file=sys.stderr)
        return None
    except RuntimeError as exc:  # the kernel's static solve at the start failed
        print_warnings(caught, "run")
        print(f"trackwheel run: the simulation could not start: {exc}", file=sys.stderr)
        return None
    print_warnings(caught, "run")
    return r


def _window_run(scene: Scene, args: argparse.Namespace, parser) -> int:
    """``run --distance``: the passage on the travelling window and its contact-force
    statistics, over the whole run and per 100 m."""
    if args.plot is not None:
        parser.error("--plot is not available with --distance (plot Result.normal_force "
                     "against Result.x_wheel from the API)")
    kw = simulate_kwargs(args)
    kw.setdefault("fidelity", "linear/hertz")
    if args.x_end is None:
        kw["distance"] = args.distance
        kw.setdefault("x_start", 0.5 * scene.supports.spacing
                      - scene.active_vehicle.span[0])
    elif args.x_start is None:
        parser.error("--distance with --x-end needs --x-start")
    r = _simulate(scene, args.speed_kmh, kw, parser)
    if r is None:
        return 1
    N = np.atleast_2d(np.asarray(r.normal_force).T).T  # (samples, wheels)
    x = np.asarray(r.x_wheel).reshape(len(r.t), -1)[:, 0]
    w, zones = scene.window, scene.rail.absorbing_ends
    ends = f", {zones.length:g} m absorbing ends" if zones is not None else ""
    print(f"scene          : {scene_name(scene, args)} on a travelling window of "
          f"{w.bays_behind} + {w.bays_ahead} bays ({scene.rail.length:g} m{ends}), "
          f"{kw['fidelity']}")
    print(f"run            : {x[-1] - x[0]:.1f} m at {args.speed_kmh:g} km/h, {r.steps} steps "
          f"simulated in {r.wall_time:.1f} s ({1e6 * r.wall_time / max(r.steps, 1):.1f} "
          "us/step)")
    print(f"contact force  : {N.min() / 1e3:.2f} .. {N.max() / 1e3:.2f} kN, mean "
          f"{N.mean() / 1e3:.2f} kN, std {N.std() / 1e3:.2f} kN; lost contact: "
          f"{'yes' if (N <= 0.0).any() else 'no'}")
    print("per 100 m      :   from [m]   min [kN]   max [kN]   std [kN]")
    for x0 in np.arange(x[0], x[-1], 100.0):
        m = (x >= x0) & (x < x0 + 100.0)
        if m.sum() > 1:
            print(f"{'':17s}{x0:>8.1f}  {N[m].min() / 1e3:>9.2f}  {N[m].max() / 1e3:>9.2f}  "
                  f"{N[m].std() / 1e3:>9.2f}")
    print(f"wall time      : {_wall(args, r)}")
    return 0
