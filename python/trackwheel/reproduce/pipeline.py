"""The run of the paper pipeline: the steps in order, each step's summary section, summary.txt.

:func:`reproduce` runs the steps of :data:`REPRODUCE_STEPS` (one per figure) for a
:class:`Plan` (:data:`FULL` or :data:`QUICK`) and writes, into the output folder, each figure's
PNG and CSV (column names carry their units) and ``summary.txt``. Each step's part of the summary
is kept in ``summary-sections/<step>.txt`` and summary.txt is assembled from every section
present, so ``only=["fig6"]`` refreshes the Fig. 6 section and keeps the others.

Every sentence of the summary that states a result is computed from the data (the
``*_conclusions`` functions): a changed result changes the sentence. The lines starting with
"paper:" quote the paper's claims, which do not change.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from pathlib import Path

from .._version import __version__
from ..scene import Scene
from .convergence import fig4_time_step, fig5_elements
from .modes import fig3_eigen
from .plan import FULL, QUICK, SECTIONS_NAME, Context, Step
from .sweeps import fig6_support_stiffness, fig7_speed
from .terms import fig8_acceleration_terms

#: The figures :func:`reproduce` makes, in order.
REPRODUCE_STEPS: list[Step] = [
    Step("fig3", "Fig. 3: natural frequencies against wheel position", fig3_eigen),
    Step("fig4", "Fig. 4: effect of the time step", fig4_time_step),
    Step("fig5", "Fig. 5: effect of the number of elements", fig5_elements),
    Step("fig6", "Fig. 6: amplitude against support stiffness", fig6_support_stiffness),
    Step("fig7", "Fig. 7: amplitude and main frequency against speed", fig7_speed),
    Step("fig8", "Fig. 8: terms of the contact-point acceleration", fig8_acceleration_terms),
]


# --------------------------------------------------------------------------------------------
# the run
def select_steps(only: Sequence[str] | None) -> list[Step]:
    """The steps named in ``only`` (all if None), in figure order; ValueError for unknown
    names."""
    if only is None:
        return list(REPRODUCE_STEPS)
    names = [st.name for st in REPRODUCE_STEPS]
    unknown = [n for n in only if n not in names]
    if unknown:
        raise ValueError(f"only = {unknown}: no such step; allowed: {names}")
    return [st for st in REPRODUCE_STEPS if st.name in only]


def assemble_summary(out: Path) -> str:
    """summary.txt: a header, then every section present in ``out/summary-sections``, in
    figure order (sections of steps not run this time are kept from earlier runs)."""
    head = f"trackwheel {__version__} reproduce: Kato et al. (2005), scene Scene.kato2005()"
    parts = [head, ""]
    for step in REPRODUCE_STEPS:
        path = out / SECTIONS_NAME / f"{step.name}.txt"
        if path.is_file():
            parts.append(path.read_text(encoding="utf-8").rstrip("\n"))
            parts.append("")
    return "\n".join(parts).rstrip("\n") + "\n"


def _run_step(ctx: Context, step: Step, i: int, n: int, stream) -> None:
    """Run one step and write its summary section, ending with its plan and wall time."""
    print(f"[{i}/{n}] {step.title} ...", file=stream, flush=True)
    ctx.summary = []
    t0 = time.perf_counter()
    step.run(ctx)
    wall = time.perf_counter() - t0
    print(f"      done ({wall:.1f} s)", file=stream, flush=True)
    ctx.summary.append(f"  ({ctx.plan.name} plan; computed in {wall:.1f} s by trackwheel "
                       f"{__version__})")
    path = ctx.out / SECTIONS_NAME / f"{step.name}.txt"
    path.write_text("\n".join(ctx.summary) + "\n", encoding="utf-8")
    ctx.written.append(path)


def reproduce(out: Path, quick: bool = False, scene: Scene | None = None,
              stream=None, only: Sequence[str] | None = None,
              workers: int | None = None) -> Context:
    """Run every step of :data:`REPRODUCE_STEPS` (or those named in ``only``) into ``out`` and
    write ``out/summary.txt`` (keeping the sections of steps not run). ``quick`` selects
    :data:`QUICK` instead of :data:`FULL`; ``workers`` is the number of sweep processes
    (default one per core)."""
    stream = sys.stdout if stream is None else stream
    steps = select_steps(only)
    ctx = Context(scene=Scene.kato2005() if scene is None else scene, out=Path(out),
                  plan=QUICK if quick else FULL, workers=workers, stream=stream)
    (ctx.out / SECTIONS_NAME).mkdir(parents=True, exist_ok=True)
    t_all = time.perf_counter()
    for i, step in enumerate(steps, 1):
        _run_step(ctx, step, i, len(steps), stream)
    text = assemble_summary(ctx.out)
    summary = ctx.out / "summary.txt"
    summary.write_text(text, encoding="utf-8")
    ctx.written.append(summary)
    print(file=stream)
    print(text, file=stream, end="")
    print(f"\nwrote {len(ctx.written)} files to {ctx.out} in "
          f"{time.perf_counter() - t_all:.1f} s:", file=stream)
    for p in ctx.written:
        print(f"  {p.relative_to(ctx.out)}", file=stream)
    return ctx

