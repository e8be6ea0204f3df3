"""The scene a command runs, from its options: the --track preset (with --length, --beam,
--shear-coefficient, --shear-modulus, a support stiffness and the track along X: --transition,
--scatter, --void), the --vehicle and the excitation (--irregularity, --seed, --wavelengths,
--joint, --wheel-flat, --patch-filter)."""

from __future__ import annotations

import argparse
import dataclasses
import math

import numpy as np

from ..base.limits import MAX_ELEMENTS
from ..excitation import Irregularity, WheelFlat, spectra
from ..scene import Scatter, Scene, Transition, Vehicle, Voids
from .checks import option_error
from .options import TRACKS, floats

#: sleeper spacing of Scene.ballasted_track [m]
BALLASTED_SPACING = Scene.ballasted_track().supports.spacing


def track_scene(args: argparse.Namespace, stiffness: float | None = None,
                length: float | None = None) -> Scene:
    """The --track preset with --length (or ``length`` [m] if not given), the support (pad)
    stiffness ``stiffness`` [N/m] and the beam options applied. Raises OptionError."""
    if args.shear_coefficient is not None and args.beam != "timoshenko":
        raise OptionError("--shear-coefficient is only used with --beam timoshenko")
    if args.length is not None and args.track != "ballasted":
        raise OptionError(f"--length is only for --track ballasted (--track {args.track} "
                           "has its fixed length)")
    if getattr(args, "shear_modulus", None) is not None and args.beam != "timoshenko":
        raise OptionError("--shear-modulus is only used with --beam timoshenko")
    try:
        scene = preset(args.track, stiffness, args.length or length)
        rail = dataclasses.replace(scene.rail, beam=args.beam)
        if args.shear_coefficient is not None:
            rail = dataclasses.replace(rail, shear_coefficient=args.shear_coefficient)
        if getattr(args, "shear_modulus", None) is not None:
            rail = dataclasses.replace(rail, shear_modulus=args.shear_modulus)
        scene = dataclasses.replace(scene, rail=rail)
        if getattr(args, "support_damping", None) is not None:
            scene = dataclasses.replace(scene, supports=dataclasses.replace(
                scene.supports, damping=args.support_damping))
        if getattr(args, "contact_damping", None) is not None:
            scene = dataclasses.replace(scene, contact=dataclasses.replace(
                scene.contact, damping=args.contact_damping))
    except ValueError as exc:
        raise OptionError(option_error(exc)) from None
    return along_x_scene(scene, args, stiffness)


def along_x_scene(scene: Scene, args: argparse.Namespace, stiffness=None) -> Scene:
    """``scene`` with the supports of --transition, --scatter and --void (where the command
    has them): the ballast stiffness of layered supports, the support stiffness of single
    springs. Raises OptionError."""
    transition = getattr(args, "transition", None)
    scatter, voids = getattr(args, "scatter", None), getattr(args, "void", None)
    if getattr(args, "transition_shape", None) and not (transition and transition[3] > 0.0):
        raise OptionError("--transition-shape needs --transition K1,K2,AT,RAMP with RAMP > 0")
    if transition is None and scatter is None and not voids:
        return scene
    sup = scene.supports
    name = "ballast_stiffness" if sup.layered else "stiffness"
    if name == "stiffness" and stiffness is not None and (transition or scatter):
        raise OptionError("--transition and --scatter set the support stiffness along X of "
                          "--track kato2005: give them or --support-stiffness, not both")
    option = "--transition"
    try:
        if transition is not None:
            k1, k2, at, ramp = transition
            shape = "step" if ramp == 0.0 else (args.transition_shape or "linear")
            sup = sup.transition(at, ramp=ramp, shape=shape, **{name: (k1, k2)})
        if scatter is not None:
            option = "--scatter"
            sup = sup.scattered(scatter, seed=args.seed or 0, property=name)
        for at, gap in voids or ():
            option = "--void"
            if not sup.layered:
                raise ValueError("a void lies between a sleeper and its ballast: use --track "
                                 "ballasted")
            sup = sup.hanging(at, gap=gap)
        return dataclasses.replace(scene, supports=sup)
    except ValueError as exc:  # named by the library's field: the option sets that field
        raise OptionError(f"{option}: {exc}") from None


def describe_track(scene: Scene, seeds=None) -> str | None:
    """One line naming how the supports vary along X (None if they do not); with ``seeds``
    (a sweep's --seeds) the scatter is named by those realisations."""
    sup = scene.supports
    if sup.uniform:
        return None
    words = []
    for name, symbol in (("stiffness", "k_p" if sup.layered else "k_s"),
                         ("ballast_stiffness", "k_b")):
        value = getattr(sup, name)
        scatter = value if isinstance(value, Scatter) else None
        mean = scatter.mean if scatter else value
        if isinstance(mean, Transition):
            ramp = (f" over {mean.ramp:g} m ({mean.shape})" if mean.ramp > 0.0 else "")
            words.append(f"{symbol} {mean.before / 1e6:g} -> {mean.after / 1e6:g} MN/m at "
                         f"X = {mean.at:g} m{ramp}")
        if scatter:
            drawn = seed_text(seeds) if seeds else f"seed {scatter.seed}"
            words.append(f"{symbol} scattered, cv {scatter.cv:g} ({drawn})")
    if isinstance(sup.void, Voids):
        words += [f"void {g * 1e3:g} mm under the sleeper at X = {x:g} m"
                  for x, g in zip(sup.void.positions, sup.void.gaps)]
    return ", ".join(words) or "supports vary along X"


def scene_name(scene: Scene, args: argparse.Namespace) -> str:
    """The preset's name, with the length and beam theory if not the defaults."""
    name = "Scene.kato2005()" if args.track == "kato2005" else (
        "Scene.ballasted_track()" if args.length is None
        else f"Scene.ballasted_track(length={args.length:g})")
    if scene.rail.beam == "timoshenko":
        name += f" with a Timoshenko rail (kappa = {scene.rail.shear_coefficient:g})"
    return name



#: --vehicle choices of ``trackwheel run``
VEHICLES = ("single", "quarter-car", "bogie", "half-car")


def vehicle_scene(scene: Scene, vehicle: str) -> tuple[Scene, list[str]]:
    """``scene`` carrying the --vehicle choice, and notes to print. For a half car the rail is
    lengthened by the vehicle's span (20 m: 25 m for the paper's track, 50.4 m for the
    ballasted one), in whole support bays with the preset's elements per bay, so that the car
    runs on the stretch the one wheel has (clear of the rail's ends where the preset's rail
    leaves one), and a note says so."""
    if vehicle == "single":
        return scene, []
    if vehicle == "quarter-car":
        return dataclasses.replace(scene, vehicle=Vehicle.quarter_car()), []
    if vehicle == "bogie":
        return dataclasses.replace(scene, vehicle=Vehicle.bogie()), []
    veh = Vehicle.half_car()
    d, old = scene.supports.spacing, scene.rail.length
    bays = max(round(old / d), 1)
    more = math.ceil((veh.span[1] - veh.span[0]) / d - 1e-9)
    per_bay = max(1, round(scene.rail.n_elements / bays))
    length = (bays + more) * d
    rail = dataclasses.replace(scene.rail, length=length, n_elements=(bays + more) * per_bay)
    note = (f"--vehicle half-car: the rail is lengthened from {old:g} m to {length:g} m for the "
            f"half car's {veh.span[1] - veh.span[0]:g} m of wheels")
    return dataclasses.replace(scene, rail=rail, vehicle=veh), [note]



def preset(track: str, stiffness: float | None = None, length: float | None = None) -> Scene:
    """The --track preset, with the support (pad) stiffness [N/m] and the ballasted track's
    length [m] replaced if given."""
    if track == "kato2005":
        return paper_scene(stiffness)
    if length is None:
        scene = TRACKS[track]()
    else:  # the preset's 4 elements per bay, fewer on a long rail (the CLI re-meshes anyway)
        n_bays = max(round(length / BALLASTED_SPACING), 1)
        if n_bays > MAX_ELEMENTS:
            raise ValueError(f"length = {length:g} m is too long; allowed: at most "
                             f"{MAX_ELEMENTS * BALLASTED_SPACING:g} m ({MAX_ELEMENTS} "
                             f"elements, one per {BALLASTED_SPACING:g} m sleeper bay)")
        scene = TRACKS[track](length, elements_per_bay=min(4, MAX_ELEMENTS // n_bays))
    if stiffness is not None:
        scene = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports,
                                                                        stiffness=stiffness))
    return scene


def paper_scene(stiffness: float | None = None) -> Scene:
    """Scene.kato2005(), with the support stiffness replaced if given [N/m]."""
    scene = Scene.kato2005()
    if stiffness is not None:
        scene = dataclasses.replace(scene, supports=dataclasses.replace(scene.supports,
                                                                        stiffness=stiffness))
    return scene


def seed_text(seeds) -> str:
    """``seeds`` [0, 1, 2, 5] as "seeds 0-2, 5" (one realisation each)."""
    seeds = sorted(seeds)
    runs, start = [], seeds[0]
    for a, b in zip(seeds, seeds[1:] + [None]):
        if b != a + 1:
            runs.append(f"{start}" if start == a else f"{start}-{a}")
            start = b
    return ("seed " if len(seeds) == 1 else "seeds ") + ", ".join(runs)


class OptionError(ValueError):
    """A bad excitation value, worded for the command line."""


def spectrum(kind: str, arg: str):
    if kind == "fra":
        try:
            track_class = int(arg)
        except ValueError:
            raise OptionError(f"--irregularity fra:{arg}: the FRA class must be an integer "
                               "1..6") from None
        return spectra.fra(track_class)
    if kind == "german":
        return spectra.german(arg)
    return spectra.china_hsr() if kind == "china" else spectra.iso3095()


def profile(args: argparse.Namespace) -> Irregularity | None:
    """The rail profile of --irregularity/--joint (None: smooth). The random parts are drawn
    with --seed (first part) and seeds derived from it (Irregularity.reseeded)."""
    parts = []
    for kind, arg in args.irregularity or ():
        text = f"--irregularity {kind}{':' + arg if arg else ''}"
        try:
            if kind == "sine":
                lam, amp = floats(arg, 2, "sine:WAVELENGTH,AMPLITUDE in m, e.g. sine:0.5,1e-5")
                parts.append(Irregularity.sine(lam, amp))
            else:
                parts.append(Irregularity.random(spectrum(kind, arg), seed=0,
                                                 wavelengths=args.wavelengths))
        except OptionError:
            raise
        except (ValueError, argparse.ArgumentTypeError) as exc:
            msg = option_error(exc).replace("wavelengths = ", "--wavelengths ")
            raise OptionError(f"{text}: {msg}") from None
    irr = sum(parts) if parts else None
    n_random = 0 if irr is None else irr.n_random
    scatter = getattr(args, "scatter", None) is not None
    if n_random == 0 and args.wavelengths is not None:
        raise OptionError("--wavelengths needs a random --irregularity (fra:N, german:low|high, "
                          "china or iso3095)")
    if n_random == 0 and not scatter and (args.seed is not None
                                          or getattr(args, "seeds", None)):
        used = [o for o, val in (("--seed", args.seed),
                                 ("--seeds", getattr(args, "seeds", None))) if val is not None]
        raise OptionError(f"{' and '.join(used)} need(s) a random --irregularity "
                           "(fra:N, german:low|high, china or iso3095) or --scatter")
    if args.seed is not None and args.seed < 0:
        raise OptionError(f"--seed {args.seed}: allowed range 0 .. 2^63 - 1")
    if n_random:
        irr = irr.reseeded(args.seed or 0)
    if args.joint is not None:
        depth, length, at = args.joint
        try:
            joint = Irregularity.dipped_joint(depth, length, at)
        except ValueError as exc:
            raise OptionError(f"--joint: {option_error(exc)}") from None
        irr = joint if irr is None else irr + joint
    return irr


def excited_scene(scene: Scene, args: argparse.Namespace) -> tuple[Scene, list[str]]:
    """``scene`` with the excitation options applied, and notes to print (stdout) or warn
    (lines starting "warning:"). Raises OptionError for bad values."""
    notes = []
    irr = profile(args)
    if irr is not None:
        length = scene.rail.length
        if args.joint is not None and args.joint[1] > length:
            raise OptionError(f"--joint: the joint's LENGTH {args.joint[1]:g} m is longer than "
                              f"the rail ({length:g} m)")
        if args.joint is not None and not 0.0 <= args.joint[2] <= length - args.joint[1]:
            raise OptionError(f"--joint: the joint from X = {args.joint[2]:g} m over "
                               f"{args.joint[1]:g} m leaves the rail; allowed AT range "
                               f"[0, {length - args.joint[1]:g}] m")
        scene = dataclasses.replace(scene, irregularity=irr)
    if args.wheel_flat is not None:
        if not args.wheel_flat > 0.0:
            raise OptionError(f"--wheel-flat {args.wheel_flat:g}: the flat's length must be "
                               "> 0 m")
        try:
            flat = WheelFlat(args.wheel_flat, at_angle=math.pi)
            scene = dataclasses.replace(scene, wheel=dataclasses.replace(
                scene.wheel, defects=(*scene.wheel.defects, flat)))
        except ValueError as exc:
            raise OptionError(option_error(exc)) from None
    if args.patch_filter or args.joint is not None:
        scene = dataclasses.replace(scene, contact=dataclasses.replace(scene.contact,
                                                                       patch_filter=True))
        if not args.patch_filter:
            notes.append("--joint turns the contact filter on (Contact.patch_filter = True: "
                         "the dip's cusp curves more sharply than the wheel)")
    impact = [o for o, given in (("--wheel-flat", args.wheel_flat is not None),
                                 ("--joint", args.joint is not None)) if given]
    sv = scene.support_values
    if impact and not np.any(sv.damping) and scene.contact.damping == 0.0 and (
            not np.any(sv.ballast_damping)):
        notes.append(f"{' and '.join(impact)} on an undamped track (the paper's: supports and "
                     "contact without damping): nothing dissipates the energy of each impact, "
                     "so the wheel bounces off the rail and later impacts build up on the "
                     "ringing track, to forces well above the first impact's; give "
                     "--support-damping (rail pads: about 1e4-5e4 N s/m) for a damped track "
                     "(docs: guide, Excitation)")
    return scene, notes


def describe(scene: Scene, seeds=None) -> str:
    """One line naming the excitation of ``scene``; with ``seeds`` (a sweep's --seeds) the
    random parts are named by those realisations, not by the scene's own seed."""
    words = []
    drawn = None if not seeds else seed_text(seeds)
    for p in () if scene.irregularity is None else scene.irregularity.parts:
        if p.kind == "random":
            words.append(f"{p.spectrum.name} ({drawn or f'seed {p.seed}'}, "
                         f"{p.wavelengths[0]:g}-{p.wavelengths[1]:g} m)")
        elif p.kind == "sine":
            words.append(f"sine {p.wavelength:g} m x {p.amplitude:g} m")
        elif p.kind == "dipped_joint":
            words.append(f"dipped joint {p.depth * 1e3:g} mm over {p.length:g} m at "
                         f"X = {p.at:g} m")
    for d in scene.wheel.defects:
        words.append(f"wheel flat {d.length * 1e3:g} mm" if d.kind == "wheel_flat"
                     else f"polygon order {d.order}")
    if scene.contact.patch_filter:
        words.append("contact filter on")
    return ", ".join(words) if words else "none (smooth rail, round wheel)"

