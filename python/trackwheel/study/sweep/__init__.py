"""Parameter sweeps over speed, support stiffness and random realisations, in parallel,
resumable.

``sweep(scene, speed=[...], support_stiffness=[...], seeds=[...], **simulate_kwargs)`` runs
``simulate(case_scene, v, **simulate_kwargs)`` and :func:`trackwheel.analyse` for every
(speed, support stiffness, seed) case and returns one table row per case and wheel (long
format: a vehicle's case has one row per wheel, ``wheel`` its index, ``worst`` True on the wheel
with the largest amplitude, so ``df[df.worst]`` is one row per case; a single wheel is wheel 0);
:func:`summarise_seeds` turns the rows of a Monte Carlo sweep into percentiles per speed. The
table's columns are :data:`trackwheel.study.columns.SWEEP_COLUMNS`, each named with its unit
(``speed_m_s``, ``amplitude_m``, ...): the same names in the DataFrame, the store and a CSV.

The rooms: :mod:`.runner` (the sweep: arguments, cases, the run), :mod:`.cases` (one case:
its scene, run and row; the rows as the table), :mod:`.store` (the records), :mod:`.pool`
(parallel runs) and :mod:`.summaries` (percentiles over the seeds).

Seeds (the realisation axis): with ``seeds=[s, ...]`` the case scene's irregularity is
``scene.irregularity.reseeded(s)`` (:meth:`trackwheel.Irregularity.reseeded`): its first random
part is drawn with seed s, random part k >= 1 with ``derived_seed(s, k)``, deterministic parts
(sines, joints, measured samples) are kept. The reseeded profile is part of the case scene, so
it is in the inputs hash: each realisation is its own record and a re-run resumes. Scattered
supports (:meth:`trackwheel.Supports.scattered`) are reseeded by the same rule
(:meth:`trackwheel.Supports.reseeded`).

Supports that vary along X enter the hash by value: a sequence as its values, a recipe
(:class:`trackwheel.Transition`, :class:`~trackwheel.Scatter`, :class:`~trackwheel.Voids`) as
its fields and ``kind``; any other function of X is tabulated at the case's supports first
(:meth:`trackwheel.Supports.tabulated`: what the kernel sees on a fixed rail), so the case
pickles for the workers and its record names the values it ran with.

Store format (``store=DIR``)
----------------------------
One JSON file per finished case, ``DIR/case-<h>.json`` where ``<h>`` is the first 24 hex digits
of the case's *inputs hash*: the SHA-256 of the canonical JSON (sorted keys, no spaces, floats
written with ``repr`` so they round-trip exactly) of ::

    {"scene": dataclasses.asdict(case scene),   # support stiffness and seed already applied
     "speed": v [m/s], "support_stiffness": k [N/m], "seed": s or None,
     "simulate": {the simulate keyword arguments given to sweep},
     "version": trackwheel.__version__}

The file holds ``{"format": "trackwheel.sweep.case", "format_version": 5, "inputs_hash": <full
hash>, "inputs": {...}, "row": {column: value}, "checksum": <SHA-256 of the canonical JSON of
everything but the checksum>}``; NaN and inf are written as ``null``. Records of format 4
(written before the support-force columns ``max_ballast_force_N``, ``max_ballast_force_x_m``,
``max_rail_seat_force_N``) are read with NaN in those, and records of format 3 (also with the
columns named without their units) are read with their columns renamed. Each
record is written to a temporary file in the same directory, flushed to disk and renamed over
the final name (``os.replace``, atomic on POSIX and Windows), by the process that runs the
sweep, as soon as its case completes; so an interrupted sweep (Ctrl-C, a crashed worker, a
killed machine) leaves only complete records. On a re-run a record is used only if it parses,
its checksum matches and its inputs equal the case's; anything else is reported
(``RuntimeWarning``) and recomputed. Leftover temporary files (``.tmp-*``) are ignored.
:func:`load_sweep` reads a store back into a DataFrame (checking every record); plain pandas
reads it too: ``pd.DataFrame([json.load(open(p))["row"] for p in
Path(DIR).glob("case-*.json")])``.

Parallel runs: by default a ``ProcessPoolExecutor`` over the available cores, started with the
``forkserver`` method (``spawn`` where there is none) -- never ``fork``, which is unsafe in a
parent running threads (Jupyter, progress bars, Dask). Its workers import the main module, so a
*script* must call ``sweep`` under ``if __name__ == "__main__":`` (notebooks, the ``trackwheel``
command and ``max_workers=1`` need nothing). Records are written by the calling process as the
cases come back, so any executor works, local or remote.

The periodic level (``fidelity="periodic/linear"``): each case is the steady state from
:func:`trackwheel.periodic_response`, in milliseconds, run in the calling process
(:mod:`.periodic`); the output columns it fills and those it leaves NaN are listed by
:data:`trackwheel.study.columns.PERIODIC_OUTPUTS`, its settings columns are empty but
``fidelity``, and a case it refuses (contact loss, an undamped or non-periodic track, several
wheels, a profile that is not a sum of sines) is a failed case with the reason.

Failed cases: a case whose run diverges (:class:`trackwheel.DivergenceError`), is rejected
(``ValueError``, e.g. a speed above simulate's range) or cannot start (``RuntimeError``: the
static solve at the start failed) becomes a row with its message in ``error`` and NaN outputs,
and the sweep carries on. Such rows are stored too: they are deterministic (same inputs, same
version, same failure), so re-running a sweep does not retry them unless ``retry_errors=True``.
Any other exception is a bug or an interruption: the sweep stops, keeps (and stores) every
case that finished, and re-raises.
"""

from ..columns import COLUMNS, SEED_COLUMNS
from .runner import sweep
from .store import FORMAT, FORMAT_VERSION, load_sweep
from .summaries import summarise_seeds

__all__ = ["COLUMNS", "FORMAT", "FORMAT_VERSION", "SEED_COLUMNS", "load_sweep",
           "summarise_seeds", "sweep"]
