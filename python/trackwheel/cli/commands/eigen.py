"""``trackwheel eigen``: the natural frequencies with the wheel at one position."""

from __future__ import annotations

import argparse
import math

import numpy as np

from ...reproduce import X_REPORT
from ...run.eigen import eigen
from ...run.frequency import receptance_points
from ...scene import Scene
from ..options import finite_float, positive_int, track_option
from ..scenes import OptionError, scene_name, track_scene

#: modes within this relative spread of each other form a cluster worth a note [-]
CLUSTER_SPREAD = 0.01


def add(sub) -> None:
    p = sub.add_parser(
        "eigen", help="print the natural frequencies with the wheel at one position",
        description="Lowest vertical natural frequencies [Hz] of the wheel/rail/support system "
                    "of the --track scene (default Scene.kato2005()) with the wheel at "
                    "--position, and the rail's lowest axial frequencies. A cluster of "
                    "near-equal modes (the track bouncing on its supports) is explained in a "
                    "note.")
    p.add_argument("--position", type=finite_float, metavar="X",
                   help=f"wheel position X [m], 0 <= X <= L (default: {X_REPORT} m on the "
                        "paper's track, the paper's; elsewhere the middle of the support bay "
                        "nearest the rail's middle, away from its rigid ends)")
    p.add_argument("--n-modes", type=positive_int, default=6, metavar="N",
                   help="number of vertical modes (default 6)")
    track_option(p, fidelity=False)
    p.set_defaults(run=run, parser=p)


def default_position(scene: Scene, track: str) -> float:
    """--position's default [m]: the paper's X_REPORT on its track, else the mid-span nearest
    the rail's middle (where the rigid ends stiffen the track least)."""
    return X_REPORT if track == "kato2005" else receptance_points(scene)["mid-span"]


def cut_on_frequency(scene: Scene) -> tuple[float, str]:
    """The track's lowest resonance at zero wavenumber [Hz], and what moves: one bay of rail
    (mass m_r = m d) on its support bouncing in phase with its neighbours, so the rail does not
    bend. Single springs: sqrt(k_s / m_r) / 2 pi; layered supports: the lower root of the rail
    bay on the pad k_p on the sleeper m_s on the ballast k_b,
    m_r m_s w^4 - (k_p m_s + (k_p + k_b) m_r) w^2 + k_p k_b = 0. The modes of a finite rail
    (one per half wavelength between its ends, bending a little) lie close to it."""
    s = scene.supports
    m_r = scene.rail.mass_per_length * s.spacing
    if not s.layered:
        return (math.sqrt(s.stiffness / m_r) / (2.0 * math.pi),
                f"one bay of rail ({m_r:.3g} kg) on its support")
    kp, kb, ms = s.stiffness, s.ballast_stiffness, s.sleeper_mass
    b = kp * ms + (kp + kb) * m_r
    w2 = (b - math.sqrt(b * b - 4.0 * m_r * ms * kp * kb)) / (2.0 * m_r * ms)
    return (math.sqrt(w2) / (2.0 * math.pi),
            f"one bay of rail ({m_r:.3g} kg) and its sleeper ({ms:.3g} kg) on the pad and the "
            "ballast")


def cluster_note(scene: Scene, freqs: np.ndarray) -> str | None:
    """A note on the largest run of at least three consecutive modes within CLUSTER_SPREAD of
    each other, if any: what they are and the frequency they gather at."""
    best = None
    i = 0
    while i < freqs.size:
        j = i
        while j + 1 < freqs.size and freqs[j + 1] <= freqs[i] * (1.0 + CLUSTER_SPREAD):
            j += 1
        if j - i >= 2 and (best is None or j - i > best[1] - best[0]):
            best = (i, j)
        i = j + 1
    if best is None or not scene.supports.uniform:  # the closed form is the uniform track's
        return None
    i, j = best
    f0, what = cut_on_frequency(scene)
    return (f"modes {i + 1}-{j + 1} ({freqs[i]:.2f}-{freqs[j]:.2f} Hz) lie within "
            f"{(freqs[j] / freqs[i] - 1.0) * 100:.2g} % of each other, near {f0:.2f} Hz, the "
            f"track's lowest resonance: {what}, every bay bouncing in phase; a "
            f"{scene.rail.length:g} m rail has one such mode per half wavelength between its "
            "rigid ends, all close to that frequency (docs: guide, Track)")


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    try:
        scene = track_scene(args)
    except OptionError as exc:
        parser.error(str(exc))
    length = scene.rail.length
    position = default_position(scene, args.track) if args.position is None else args.position
    if not 0.0 <= position <= length:
        parser.error(f"--position {position:g} m is outside the rail; "
                     f"allowed range [0, {length:g}] m")
    try:
        res = eigen(scene, [position], n_modes=args.n_modes)
    except ValueError as exc:  # e.g. more modes than the mesh has
        parser.error(str(exc).replace("n_modes", "--n-modes"))
    name = scene_name(scene, args)
    print(f"{name}, wheel at X = {position:g} m ({res.n_elements} elements)")
    print("vertical modes:")
    for k, f in enumerate(res.frequencies[0], 1):
        print(f"  {k:>3}  {f:10.2f} Hz")
    if res.axial_frequencies.size:
        print("axial (x) modes of the rail: "
              + ", ".join(f"{f:.1f}" for f in res.axial_frequencies) + " Hz")
    note = cluster_note(scene, res.frequencies[0])
    if note:
        print(f"note: {note}")
    return 0
