"""The ``trackwheel`` command: its parser (one sub-command per module of :mod:`.commands`)
and its entry point."""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Sequence

from .._version import __version__
from .commands import COMMANDS
from .options import Parser


def build_parser() -> argparse.ArgumentParser:
    """The command's argument parser: the sub-commands of :data:`.commands.COMMANDS`."""
    parser = Parser(
        prog="trackwheel",
        description="A railway wheel rolling at high speed over a flexible rail on elastic "
                    "supports (Kato et al. 2005). SI units throughout, speeds in km/h on the "
                    "command line.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for command in COMMANDS:
        command.add(sub)
    return parser


def _command(argv: Sequence[str] | None) -> str:
    """" run" etc.: the sub-command named in ``argv`` (the process's arguments if None)."""
    names = {c.__name__.rsplit(".", 1)[-1].replace("_", "-") for c in COMMANDS}
    words = sys.argv[1:] if argv is None else argv
    return next((f" {w}" for w in words if w in names), "")


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``trackwheel`` console script; returns the exit code."""
    started = time.perf_counter()
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        args.started = started
        return args.run(args, args.parser)
    except SystemExit as exc:  # argparse: --help/--version (0) and usage errors (2)
        return exc.code if isinstance(exc.code, int) else 1
    except KeyboardInterrupt:  # Ctrl-C: one line, the shell's code for SIGINT (128 + 2)
        sys.stdout.flush()
        # at a terminal, end the line a progress bar may have left open
        start = "\n" if sys.stderr.isatty() else ""
        print(f"{start}trackwheel{_command(argv)}: interrupted (Ctrl-C)", file=sys.stderr)
        return 130
    except BrokenPipeError:  # the reader left (`trackwheel run ... | head`): stop quietly
        # the interpreter flushes stdout again at exit: point it at devnull so that it can
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 1
