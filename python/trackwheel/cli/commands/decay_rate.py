"""``trackwheel decay-rate``: the track decay rate per one-third-octave band (EN 15461)
beside the ISO 3095 limit."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from ...run import frequency
from ..checks import output_options
from ..formatting import frequency_elements, save_figure, write_csv
from ..options import damping_options, mesh_option, positive_int, track_option
from ..scenes import OptionError, scene_name, track_scene

#: rail length [m] of ``decay-rate --track ballasted``: the EN 15461 line (66 bays, 39.6 m)
#: with about ten metres of damped rail beyond it at each end
DECAY_LENGTH = 60.0


def add(sub) -> None:
    p = sub.add_parser(
        "decay-rate", help="print the track decay rate per one-third-octave band",
        description="Vertical track decay rate [dB/m] of the linear track by the EN 15461 method "
                    "(trackwheel.decay_rate) in the one-third-octave bands 250 Hz - 5 kHz, each "
                    "from the band average of the squared magnitude of the transfer receptances over --per-band "
                    "frequencies, beside the ISO 3095:2013 lower limit for a test track. "
                    "The rail must be longer than 66 support spacings: --track ballasted, "
                    f"whose length here defaults to {DECAY_LENGTH:g} m.")
    p.add_argument("--per-band", type=positive_int, default=8, metavar="N",
                   help="frequencies per band, log-spaced inside it (default 8)")
    mesh_option(p)
    damping_options(p, contact=False)
    track_option(p, length_default=f"{DECAY_LENGTH:g} here", fidelity=False)
    p.add_argument("--out", type=Path, metavar="CSV",
                   help="write band_hz, decay_rate_db_per_m, iso3095_limit_db_per_m to this file")
    p.add_argument("--plot", type=Path, metavar="PNG",
                   help="save the decay rate over the bands against the ISO 3095 limit "
                        "(plots.decay_rate) to this file")
    p.set_defaults(run=run, parser=p)


def run(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    output_options(args, parser)
    try:
        scene = track_scene(args, length=DECAY_LENGTH)
    except OptionError as exc:
        parser.error(str(exc))
    span = (frequency.EN15461_SPANS[-1] + 1.0) * scene.supports.spacing
    if scene.rail.length <= span:
        advice = (f"give a --length of at least {span:g} m (a multiple of "
                  f"{scene.supports.spacing:g} m; default {DECAY_LENGTH:g} m)"
                  if args.track == "ballasted" else
                  f"use --track ballasted (default length {DECAY_LENGTH:g} m)")
        parser.error(f"the EN 15461 positions need a rail longer than {span:g} m (67 support "
                     f"spacings); {scene_name(scene, args)} is {scene.rail.length:g} m: "
                     f"{advice}")
    edges = frequency.iso3095_band_edges()
    n_el = frequency_elements(scene, edges[-1], args.n_elements, "decay-rate")
    dr = frequency.band_decay_rates(scene, args.per_band, n_el)
    limit = np.asarray(frequency.ISO3095_VERTICAL_LIMIT)
    print(f"{scene_name(scene, args)}, {scene.rail.length:g} m, {n_el} elements")
    print(f"vertical track decay rate (EN 15461, {args.per_band} frequencies per band) and the "
          "ISO 3095:2013 lower limit")
    print(f"  {'band [Hz]':>9}  {'DR [dB/m]':>9}  {'limit':>6}")
    for fc, d, lim in zip(frequency.ISO3095_BANDS, dr, limit):
        print(f"  {fc:>9g}  {d:>9.3g}  {lim:>6g}  {'' if d >= lim else 'below the limit'}")
    print(f"  {int(np.sum(dr >= limit))} of {dr.size} bands at or above the limit")
    if args.out is not None:
        table = np.column_stack([frequency.ISO3095_BANDS, dr, limit])
        if not write_csv(args.out, table, "band_hz,decay_rate_db_per_m,iso3095_limit_db_per_m",
                         "decay-rate"):
            return 1
    if args.plot is not None:
        from ... import plots  # matplotlib only when a figure is drawn

        f = np.geomspace(edges[0], edges[-1], 8 * edges.size)
        if not save_figure(plots.decay_rate(scene, f, n_elements=n_el), args.plot,
                           "decay-rate"):
            return 1
    return 0
