"""Checks made before anything is computed: output paths, speeds, and the library's messages
worded with the command's option names."""

from __future__ import annotations

import argparse
import os
import re
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

from ..base.limits import MAX_SPEED, RECORD_SPEED

def writable_folder(path: Path, option: str, parser: argparse.ArgumentParser,
                     create: bool) -> None:
    """Error unless ``path`` is (or, with ``create``, can be made) a folder we can write in."""
    if path.exists() and not path.is_dir():
        parser.error(f"{option} {path}: exists and is not a folder")
    if not path.exists():
        if not create:
            parser.error(f"{option}: the folder {path} does not exist")
        try:
            path.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            parser.error(f"{option} {path}: cannot create the folder ({exc.strerror or exc})")
    try:  # as root, os.access says yes to read-only file systems such as /proc: try it
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        parser.error(f"{option} {path}: cannot write in this folder ({exc.strerror or exc})")


def output_file(path: Path, option: str, parser: argparse.ArgumentParser,
                 formats: Sequence[str] | None = None) -> None:
    """Error unless ``path`` can be written: an existing, writable folder, not a folder itself,
    and (if ``formats`` is given) one of those extensions."""
    if path.is_dir():
        parser.error(f"{option} {path}: is a folder, expected a file name")
    if formats is not None:
        ext = path.suffix.lstrip(".").lower()
        if ext not in formats:
            parser.error(f"{option} {path}: unknown file format {ext or '(none)'!r}; "
                         f"use one of {', '.join(sorted(formats))}")
    writable_folder(path.parent if str(path.parent) else Path("."), option, parser,
                     create=False)
    if path.exists() and not os.access(path, os.W_OK):
        parser.error(f"{option} {path}: the file is not writable")


def figure_formats() -> list[str]:
    """File extensions matplotlib can save figures to."""
    from matplotlib.backend_bases import FigureCanvasBase

    return list(FigureCanvasBase.get_supported_filetypes())


def speeds_kmh(values: Sequence[float], option: str, parser: argparse.ArgumentParser) -> None:
    """Error, in km/h, for a speed outside (0, MAX_SPEED]; a warning line for one above the
    wheel-on-rail record (the library's warning speaks of m/s)."""
    top = MAX_SPEED * 3.6
    for v in values:
        if not 0.0 < v <= top:
            parser.error(f"{option} {v:g}: the speed must be above 0 and at most {top:.4g} "
                         "km/h")
        if v > RECORD_SPEED * 3.6:
            print(f"{parser.prog}: warning: {option} {v:g} is faster than any train has run on "
                  f"rails ({RECORD_SPEED * 3.6:g} km/h)", file=sys.stderr)


def option_error(exc: Exception) -> str:
    """A library message with its parameter names spelled as the command's options."""
    text = str(exc)
    text = text.replace("Supports.stiffness", "--support-stiffness")
    text = text.replace("Supports.damping", "--support-damping")
    text = text.replace("Contact.damping", "--contact-damping")
    text = text.replace("Rail.shear_coefficient", "--shear-coefficient")
    text = text.replace("Wheel.brake_torque", "--brake-torque")
    # the fields of --joint DEPTH,LENGTH,AT and --irregularity sine:WAVELENGTH,AMPLITUDE
    text = re.sub(r"Irregularity\.(dipped_joint|sine)\.(\w+)", lambda m: m.group(2).upper(), text)
    text = re.sub(r"Irregularity\.(dipped_joint|sine): ", "", text)
    text = text.replace("WheelFlat.length", "--wheel-flat")
    if text.startswith("length = "):  # Scene.ballasted_track's length
        text = "--length " + text[len("length = "):]
    for name in ("n_elements", "x_start", "x_end", "speed_kmh", "support_stiffness"):
        text = text.replace(name, "--" + name.replace("_", "-"))
    # short names only where they stand as the parameter ("dt = -1e-05 ...")
    return re.sub(r"(?<![\w-])(dt|integrator|fidelity)(?= = )", r"--\1", text)


def output_options(args: argparse.Namespace, parser: argparse.ArgumentParser) -> None:
    """Error unless the command's --out table and --plot figure (where it has them and they
    are given) can be written."""
    if getattr(args, "out", None) is not None:
        output_file(args.out, "--out", parser)
    if getattr(args, "plot", None) is not None:
        output_file(args.plot, "--plot", parser, formats=figure_formats())
