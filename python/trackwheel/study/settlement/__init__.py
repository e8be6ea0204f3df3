"""Ballast settlement under traffic: the laws that settle each sleeper from its peak ballast
forces, cycle by cycle or many cycles at a time (docs: Model § Ballast settlement).

``trackwheel.settlement`` is this package. A law is a frozen dataclass of its parameters; it
starts a state for n sleepers and advances it by load cycles::

    law = trackwheel.settlement.Varandas()          # ROSE's defaults after Varandas (2014)
    state = law.initial_state(n_sleepers)
    state, increment = law.advance(state, peak_force, cycles)   # [N] per sleeper, [-]
    state.settlement                                 # [m] per sleeper, down positive

The rooms: :mod:`.state` (the state, the interface, the checks of the inputs),
:mod:`.varandas` (the load-history law), :mod:`.empirical` (the curve laws of Sato and
Shenton), :mod:`.power_sums` (partial sums of n^-beta for any number of cycles at once);
the loop that runs traffic over the track and feeds the settled bed back
(:func:`trackwheel.settle`): :mod:`.traffic` (what runs), :mod:`.passage` (one passage and
the peak ballast forces it gives), :mod:`.stages` (the stages' parts: the settling sleepers,
the bed, the stage length), :mod:`.loop` (``settle`` itself), :mod:`.history` (the results
and their store).
"""

from __future__ import annotations

from collections.abc import Mapping

from .empirical import HARDENING, CurveLaw, Sato, Shenton
from .history import SettlementHistory
from .loop import settle
from .passage import PASSAGE_LEVELS, PassageForces, PassageTask, peak_ballast_forces, run_passage
from .power_sums import power_sum
from .state import MAX_CYCLES, SettlementLaw, SettlementState
from .traffic import Traffic, TrafficItem
from .varandas import Varandas

#: The laws by their names (the ``law`` of a state and of ``SettlementLaw.to_dict``).
LAWS = {law.name: law for law in (Varandas, Sato, Shenton)}


def law_from_dict(data: Mapping) -> SettlementLaw:
    """The law that ``SettlementLaw.to_dict`` wrote: ``{"law": name, **parameters}``."""
    params = dict(data)
    name = params.pop("law", None)
    if name not in LAWS:
        raise ValueError(f"law = {name!r} is not one of {sorted(LAWS)}")
    return LAWS[name](**params)


__all__ = ["HARDENING", "LAWS", "MAX_CYCLES", "PASSAGE_LEVELS", "CurveLaw", "PassageForces",
           "PassageTask", "Sato", "SettlementHistory", "SettlementLaw", "SettlementState",
           "Shenton", "Traffic", "TrafficItem", "Varandas", "law_from_dict",
           "peak_ballast_forces", "power_sum", "run_passage", "settle"]
