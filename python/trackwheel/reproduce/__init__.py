"""The paper pipeline behind ``trackwheel reproduce``: Figs. 3-8 of Kato et al. (2005).

:func:`reproduce` runs the steps of :data:`REPRODUCE_STEPS` (one per figure) for a
:class:`Plan` (:data:`FULL` or :data:`QUICK`) and writes, into the output folder, each figure's
PNG and CSV (every column named with its unit) and ``summary.txt``, whose sentences are
computed from the data (the ``*_conclusions`` functions).

Layer 6, one module per figure group: :mod:`.plan` (what is computed, the context every step
gets), :mod:`.modes` (Fig. 3), :mod:`.convergence` (Figs. 4, 5), :mod:`.sweeps` (Figs. 6, 7),
:mod:`.terms` (Fig. 8) and :mod:`.pipeline` (the run: steps, sections, summary).
"""

from .convergence import (
    AGREE,
    CONVERGENCE_COLUMNS,
    convergence_conclusions,
    convergence_table,
    passage_cost_sentence,
)
from .modes import analytic_references
from .pipeline import REPRODUCE_STEPS, assemble_summary, reproduce, select_steps
from .plan import (
    CONVERGENCE_SAMPLE,
    FULL,
    QUICK,
    SECTIONS_NAME,
    STORE_NAME,
    X_REPORT,
    Context,
    Plan,
    Step,
)
from .sweeps import fig6_conclusions, fig7_conclusions, nearest_mode
from .terms import TERM_COLUMNS, fig8_conclusions

__all__ = [
    "AGREE",
    "CONVERGENCE_COLUMNS",
    "CONVERGENCE_SAMPLE",
    "FULL",
    "QUICK",
    "REPRODUCE_STEPS",
    "SECTIONS_NAME",
    "STORE_NAME",
    "TERM_COLUMNS",
    "X_REPORT",
    "Context",
    "Plan",
    "Step",
    "analytic_references",
    "assemble_summary",
    "convergence_conclusions",
    "convergence_table",
    "fig6_conclusions",
    "fig7_conclusions",
    "fig8_conclusions",
    "nearest_mode",
    "passage_cost_sentence",
    "reproduce",
    "select_steps",
]
