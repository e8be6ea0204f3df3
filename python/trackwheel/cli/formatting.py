"""What every command prints and writes the same way: notes and warnings (one line each on
stderr), CSV tables and figures."""

from __future__ import annotations

import sys
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
