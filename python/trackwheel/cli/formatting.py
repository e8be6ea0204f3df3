"""What every command prints and writes the same way: notes and warnings (one line each on
stderr), CSV tables and figures."""

from __future__ import annotations

import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from ..run.defaults import frequency_mesh
from ..scene import Scene
from .checks import option_error

def print_warnings(caught, command: str) -> None:
    """The library's warnings (mesh, stability), one line each on stderr."""
    for w in caught:
        print(f"trackwheel {command}: warning: {option_error(w.message)}", file=sys.stderr)



def print_notes(notes: list[str], command: str) -> None:
    for note in notes:
        if note.startswith("warning:"):
            print(f"trackwheel {command}: {note}", file=sys.stderr)
        else:
            print(f"note: {note}")



def write_csv(path: Path, table: np.ndarray, header: str, command: str) -> bool:
    """Write ``table`` as CSV (17 digits: the values read back bit-identical); False on error."""
    try:
        np.savetxt(path, table, delimiter=",", header=header, comments="", fmt="%.17g")
    except OSError as exc:
        print(f"trackwheel {command}: cannot write --out {path}: {exc}", file=sys.stderr)
        return False
    print(f"  table          : {path}")
    return True


def save_figure(fig, path: Path, command: str) -> bool:
    """Save ``fig`` to ``path`` (150 dpi); False, with a one-line error, if it cannot."""
    try:
        fig.savefig(path, dpi=150)
    except (OSError, ValueError) as exc:
        print(f"trackwheel {command}: cannot write --plot {path}: {exc}", file=sys.stderr)
        return False
    print(f"  plot           : {path}")
    return True


def frequency_elements(scene: Scene, f_max: float, n_elements: int | None, command: str) -> int:
    """--n-elements, or the frequency-domain mesh of ``scene`` up to ``f_max`` [Hz]
    (:func:`trackwheel.run.defaults.frequency_mesh`), its warning printed if it is capped."""
    if n_elements is not None:
        return n_elements
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        n = frequency_mesh(scene, f_max)
    print_warnings(caught, command)
    return n


def process_age() -> float | None:
    """Seconds since this process started (Linux: /proc/self/stat's start time against
    /proc/uptime, both in clock ticks since boot, 10 ms resolution), or None elsewhere."""
    try:
        with open("/proc/self/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        with open("/proc/uptime") as f:
            uptime = float(f.read().split()[0])
        return uptime - int(fields[19]) / os.sysconf("SC_CLK_TCK")
    except (OSError, ValueError, IndexError, AttributeError):
        return None


def wall_time_text(started: float | None, simulation: float, steps: int) -> str:
    """The command's wall time: since the process started (Python's start-up and imports
    included) where the system tells, else since the command's arguments were read
    (``started``, a ``time.perf_counter()``), said which; and the simulation's share."""
    age = process_age()
    part = f"the simulation {simulation:.2f} s, {steps} steps"
    if age is not None:
        return f"{age:.2f} s for the whole command ({part})"
    if started is not None:
        return f"{time.perf_counter() - started:.2f} s since the arguments were read ({part})"
    return part
