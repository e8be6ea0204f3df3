"""The ``trackwheel`` command.

``trackwheel reproduce --out DIR [--quick]``
    Recompute the paper's figures for ``Scene.kato2005()`` and write them (PNG + CSV) to DIR with
    a ``summary.txt``. The figures are a list of :class:`Step` in :data:`REPRODUCE_STEPS`; a new
    figure is one more step.
``trackwheel eigen [--position X] [--n-modes N]``
    Print the lowest vertical natural frequencies with the wheel at X [m].

``main(argv)`` returns the exit code: 0 on success, 2 for bad arguments (argparse), 1 when a
computation fails.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import __version__
from .eigen import eigen as _eigen
from .scene import Scene

#: wheel position of the mode-shape figure and of the reported frequencies [m] (mid-rail)
X_REPORT = 2.5


# --------------------------------------------------------------------------------------------
# analytic references (MODEL.md §9)
# --------------------------------------------------------------------------------------------
def analytic_references(scene: Scene) -> dict[str, float]:
    """Frequencies [Hz] of MODEL.md §9 for the bare rail of ``scene``:

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
# `reproduce`: a list of steps, each writing its files and adding lines to the summary
# --------------------------------------------------------------------------------------------
@dataclass
class Context:
    """What every reproduce step gets: the scene, the output folder, the --quick flag; steps
    append the files they wrote and the lines of the summary."""

    scene: Scene
    out: Path
    quick: bool
    written: list[Path] = field(default_factory=list)
    summary: list[str] = field(default_factory=list)


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
    n_pos = 41 if ctx.quick else 201
    positions = np.linspace(0.0, scene.rail.length, n_pos)
    res = _eigen(scene, positions, n_modes=4)

    csv = ctx.out / "fig3_eigen.csv"
    header = "position_m," + ",".join(f"f{k + 1}_hz" for k in range(4))
    np.savetxt(csv, np.column_stack([res.positions, res.frequencies]), delimiter=",",
               fmt="%.12g", header=header, comments="")
    ctx.written.append(csv)

    png = ctx.out / "fig3_eigen.png"
    plots.eigen(res).savefig(png, dpi=150)
    ctx.written.append(png)

    at = _eigen(scene, [X_REPORT], n_modes=4)
    png = ctx.out / "fig3_mode_shapes_x2.5m.png"
    plots.mode_shapes(at, 0).savefig(png, dpi=150)
    ctx.written.append(png)

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
    s.append("  analytic references (bare rail, MODEL.md §9):")
    s.append(f"    Winkler cut-on sqrt(k_f/m)/(2 pi), k_f = k_s/d_s : "
             f"{ref['winkler_cut_on']:8.1f} Hz")
    s.append(f"    pinned-pinned span f_pp                        : "
             f"{ref['pinned_pinned']:8.1f} Hz")
    s.append(f"    simply supported rail without supports, f_1    : "
             f"{ref['simply_supported_1']:8.1f} Hz")


#: The figures ``trackwheel reproduce`` makes, in order. Later figures are appended here.
REPRODUCE_STEPS: list[Step] = [
    Step("fig3", "Fig. 3: natural frequencies against wheel position", _fig3_eigen),
]


def reproduce(out: Path, quick: bool = False, scene: Scene | None = None,
              stream=None) -> Context:
    """Run every step of :data:`REPRODUCE_STEPS` into ``out`` and write ``out/summary.txt``."""
    stream = sys.stdout if stream is None else stream
    ctx = Context(scene=Scene.kato2005() if scene is None else scene, out=Path(out), quick=quick)
    ctx.out.mkdir(parents=True, exist_ok=True)
    t_all = time.perf_counter()
    for i, step in enumerate(REPRODUCE_STEPS, 1):
        print(f"[{i}/{len(REPRODUCE_STEPS)}] {step.title} ...", end=" ", file=stream, flush=True)
        t0 = time.perf_counter()
        step.run(ctx)
        print(f"done ({time.perf_counter() - t0:.1f} s)", file=stream, flush=True)
    head = [f"trackwheel {__version__} reproduce: Kato et al. (2005), scene Scene.kato2005()"
            + (" [--quick]" if quick else ""), ""]
    text = "\n".join(head + ctx.summary) + "\n"
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


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="trackwheel",
        description="A railway wheel rolling at high speed over a flexible rail on elastic "
                    "supports (Kato et al. 2005). SI units throughout.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser(
        "reproduce", help="recompute the paper's figures into a folder",
        description="Recompute the paper's figures for Scene.kato2005() and write PNG + CSV "
                    "files and summary.txt into --out. Steps: "
                    + "; ".join(s.title for s in REPRODUCE_STEPS) + ".")
    p.add_argument("--out", required=True, type=Path, metavar="DIR",
                   help="output folder (created if missing)")
    p.add_argument("--quick", action="store_true",
                   help="coarser sweeps, for a fast check")
    p.set_defaults(run=_cmd_reproduce, parser=p)

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


def _cmd_reproduce(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    if args.out.exists() and not args.out.is_dir():
        parser.error(f"--out {args.out}: exists and is not a folder")
    try:
        args.out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        parser.error(f"--out {args.out}: cannot create the folder ({exc.strerror or exc})")
    reproduce(args.out, quick=args.quick)
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
