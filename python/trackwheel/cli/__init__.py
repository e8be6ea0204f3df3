"""The ``trackwheel`` command (the paper pipeline is in :mod:`trackwheel.reproduce`).

``trackwheel reproduce --out DIR [--quick] [--only STEP ...]``
    The main job: recompute the paper's Figs. 3-8 for ``Scene.kato2005()`` and write them (PNG +
    CSV) to DIR with a ``summary.txt`` that sets our numbers beside the paper's claims
    (:func:`trackwheel.reproduce.reproduce`). The sweeps keep every finished case in
    ``DIR/sweep-store``, so an interrupted run resumes.
``trackwheel run --speed-kmh V [--support-stiffness K] [--integrator ...] [--plot PNG]``
    One passage: print the amplitude and main frequency of the contact-point vibration, the
    contact-force statistics (range, dynamic factor, contact loss, band levels, P1/P2 after a
    joint) and the wall time; optionally save :func:`plots.dynamic`.
``trackwheel sweep --speeds-kmh V ... [--support-stiffness K ...] [--seeds 0-19] --store DIR``
    A speed x support-stiffness (x seed) sweep into a resumable store; prints the table.

Excitation (``run`` and ``sweep``, docs: Model § Irregularities; lengths in m):
``--irregularity fra:N | german:low | german:high | china | iso3095 | sine:WAVELENGTH,AMPLITUDE``
(repeatable: the profiles add), ``--seed N`` and ``--wavelengths MIN MAX`` for the random
spectra, ``--joint DEPTH,LENGTH,AT`` (a Kabo dipped joint; turns the contact filter on),
``--wheel-flat LENGTH`` (a new flat, half a revolution from the start), ``--patch-filter``;
``run --brake-torque T_B`` brakes the wheel [N m] (beyond adhesion it locks and slides).
``trackwheel eigen [--position X] [--n-modes N]``
    Print the lowest vertical natural frequencies with the wheel at X [m].
``trackwheel receptance [--at midspan|support|X] [--fmin F] [--fmax F] [--n N] [--out CSV]``
    The track's point receptance [m/N] (magnitude and phase) at a mid-span, above a support or
    at X [m], from --fmin to --fmax [Hz] (trackwheel.receptance); ``--plot`` adds both points.
``trackwheel decay-rate [--per-band N] [--out CSV] [--plot PNG]``
    The vertical track decay rate [dB/m] per one-third-octave band (EN 15461, trackwheel.
    decay_rate) beside the ISO 3095 lower limit.

Track (every command but reproduce; docs: Model § Layered supports and the section
"Shear-deformable rail (Timoshenko)"):
``--track kato2005|ballasted`` (``--length L`` [m] for the ballasted preset), ``--beam
euler|timoshenko`` and ``--shear-coefficient K``; every ``--fidelity`` level takes the beam
theory (the full and ancf/... levels the shear-deformable ANCF rail, the linear/... levels the
linear Timoshenko beam). ``run`` and ``sweep`` take a track varying along X (docs: Model §
Supports varying along the track): ``--transition K1,K2,AT[,RAMP]``, ``--scatter CV`` and
``--void AT,GAP``.

Layer 7, the face: :mod:`.main` (the parser and the entry point), :mod:`.commands` (one module
per sub-command), :mod:`.options` (argument types and shared option groups), :mod:`.scenes`
(the scene from the options), :mod:`.checks` (paths and values checked before computing) and
:mod:`.formatting` (notes, warnings, tables and figures written the same way everywhere).
``trackwheel.cli:main`` is the console script; ``python -m trackwheel.cli`` runs it too.

``main(argv)`` returns the exit code: 0 on success, 2 for bad arguments (argparse, or a value
the library rejects), 1 when a computation fails (a diverging run, failed sweep cases). Every
error is one line on stderr; every output path is checked before anything is computed.
"""

from .main import build_parser, main

__all__ = ["build_parser", "main"]
