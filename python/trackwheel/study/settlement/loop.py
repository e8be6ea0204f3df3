"""``trackwheel.settle``: the settlement loop (docs: Model § The settlement loop)."""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import Executor

import numpy as np

from ...scene import Scene
from . import history as hist
from . import stages as sg
from .history import SettlementHistory, Stage
from .passage import run_passage
from .quasi_static import StaticBed, advance_stage
from .state import SettlementLaw


def settle(scene: Scene, traffic, cycles, law: SettlementLaw | None = None, *,
           stages: int | None = None, increment: float = sg.DEFAULT_INCREMENT,
           feedback: bool = True, datum: str = "min", fidelity: str = "linear/hertz",
           x_start: float | None = None, x_end: float | None = None,
           executor: Executor | None = None, max_workers: int | None = None, store=None,
           progress: bool = True, passage: Callable | None = None,
           stage_rule: str = "explicit", **simulate_kwargs) -> SettlementHistory:
    """Settle the ballast of ``scene`` under ``traffic`` for ``cycles`` axle passes, the settled
    bed fed back into the track stage by stage.

    Each stage runs one passage per traffic item on the current bed, takes every settling
    sleeper's peak ballast force per axle, advances the settlement ``law`` by the stage's
    passages (each axle of each passage one load cycle) and adds the settlement to the
    sleepers' voids (``Supports.void``): the next stage runs on the settled bed.

    Parameters
    ----------
    scene : a Scene with layered supports (pad, sleeper, ballast); its supports may vary along
        X and carry voids of their own, to which the settlement adds.
    traffic : a :class:`~trackwheel.settlement.Traffic`, a
        :class:`~trackwheel.settlement.TrafficItem` or a sequence of them (speed, passages a
        day, vehicle or wheel load each), or a speed [m/s] (the scene's own wheel or vehicle).
    cycles : axle passes N over each sleeper, a whole number in [1, 2^53]; shared among the
        items in proportion to their axle passes a day, in whole passages.
    law : the settlement law (default ``Varandas()``, ROSE's parameters).
    stages : the number of stages, on the schedule N_k = N^(k/m) (rounded); None (default):
        adaptive, each stage as long as keeps the largest change of a settling sleeper's void
        (its settlement less the datum's: a settlement the whole track shares leaves the forces
        as they were) at most ``increment`` x w0, w0 = P beta / (2 k_f) the static deflection
        of the beam on a Winkler foundation of the settling sleepers' mean support stiffness
        under the heaviest wheel (``history.static_deflection``). The fixed schedule runs away
        on a transition once a stage opens voids near w0 (docs: Model § The settlement loop).
    increment : that fraction (0, 10] [-], default 0.1.
    feedback : True (default): each stage's passages run on the settled bed, the settlement
        in the track as voids (on a fixed rail or a travelling window). False: every stage
        uses the intact bed's forces (the open-loop estimate of tools without feedback, for
        comparison); the bed is not settled into the track.
    datum : "min" (default): the track sinks as a whole by the least settlement of the settling
        sleepers, only the settlement beyond it opens voids (the rail, continuous over
        kilometres, follows a uniform settlement; a rail of finite length on rigid end supports
        cannot); "none": every sleeper's whole settlement opens a void.
    fidelity : the passages' model: a level of :data:`trackwheel.TIME_DOMAIN_LEVELS` (default
        "linear/hertz": the linear track under the Hertzian wheel, the level that keeps the
        contact law and loss of contact and costs a fraction of the full model's run), or
        "static": each wheel standing still above each sleeper (no inertia, no speed).
    x_start, x_end : the reference point's start and end of each passage [m] (simulate's
        defaults on a fixed rail). The settling sleepers are those every axle passes with a bay
        to spare on each side; the supports beyond take the nearest one's settlement.
    executor : a ``concurrent.futures.Executor`` to run a stage's passages on (Dask's
        ``client.get_executor()`` included); default: in this process, or a process pool of
        ``max_workers``.
    store : a directory to keep each stage in; re-running with the same inputs and store goes
        on from the last stage stored, bit for bit as if the run had not stopped.
    progress : a progress bar over the cycles (tqdm), one step per stage.
    passage : a documented internal hook: the function that runs one passage,
        ``passage(task: PassageTask) -> PassageForces`` (default
        :func:`~trackwheel.study.settlement.passage.run_passage`); picklable (module level) for
        an executor. Tests inject a model of their own here.
    stage_rule : how a stage advances the law. "explicit" (default): at the peaks of the
        passage at the stage's start. "quasi-static": each sleeper's and axle's dynamic ratio
        r = F_dyn / F_st(g_start) is kept from that passage, and the law advances in sub-steps
        at F = r F_st(g), F_st(g) the peak static ballast force over the passage's wheel
        positions on the current bed (an Euler-Bernoulli rail on the unilateral ballast,
        solved by an active set; each sub-step changes a void by at most 0.01 w0), so the fast
        redistribution of the load through the rail is resolved inside the stage and only the
        dynamic ratio is frozen; the stage ends where its voids have changed by ``increment``
        x w0 (adaptive) or at the schedule's next total. It takes far fewer stages for the
        same accuracy on a transition (a larger ``increment``, e.g. 0.8-1.6); a fixed rail
        only (docs: Model § The settlement loop, "The quasi-static stage").
    **simulate_kwargs : passed to every :func:`trackwheel.simulate` call (dt, n_elements, ...).

    Returns
    -------
    SettlementHistory : the bed stage by stage (``.frame()``, ``.stages()``).

    Raises
    ------
    ValueError, TypeError : bad arguments, naming the parameter and the allowed range.
    """
    passage = run_passage if passage is None else passage
    if not callable(passage):
        raise TypeError(f"passage must be callable, got {type(passage).__name__}")
    if not isinstance(progress, bool):
        raise TypeError("progress must be True or False")
    su = sg.setup(scene, traffic, cycles, law, stages, increment, feedback, datum, fidelity,
                    x_start, x_end, simulate_kwargs, stage_rule)
    inputs = sg.inputs(su, passage)
    digest = hist.inputs_digest(inputs)
    store_dir, done = hist.open_store(store, inputs)
    computed = 0
    with sg.executor_for(executor, max_workers, len(su.traffic)) as ex:
        stage_list = list(done)
        if not stage_list:
            stage_list.append(_first_stage(su, passage, ex))
            hist.write_stage(store_dir, stage_list[0], digest)
            computed += 1
        computed += _run_stages(su, passage, ex, stage_list, store_dir, digest, progress)
    labels = [item.label(i) for i, item in enumerate(su.traffic.items)]
    days_per_cycle = 1.0 / su.traffic.axle_rate(su.scene)
    return SettlementHistory.build(stage_list, su.sleepers, su.stiffness, days_per_cycle,
                                   su.law, su.feedback, labels, su.static_deflection, computed)


def _first_stage(su: sg.Setup, passage, ex) -> Stage:
    state = su.law.initial_state(su.sleepers.size)
    voids_zone, voids_all = sg.bed(su, state.settlement)
    forces = sg.run_tasks(passage, sg.tasks(su, voids_all), ex)
    return Stage(0, 0, tuple([0] * len(su.traffic)), state, voids_zone, forces)


def _run_stages(su: sg.Setup, passage, ex, stage_list: list, store_dir, digest,
                progress: bool) -> int:
    """Run stages from the last in ``stage_list`` to the end, appending and storing each;
    returns how many were computed."""
    from tqdm.auto import tqdm

    last = stage_list[-1]
    static_bed = None
    if su.stage_rule == "quasi-static" and su.feedback:
        static_bed = StaticBed(su.scene, su.item_scenes, su.x_range, su.supports, su.sleepers)
    bar = tqdm(total=su.cycles, initial=last.cycles, unit="cycle", unit_scale=True,
               desc=f"settle [{su.fidelity}]", disable=not progress)
    computed = 0
    try:
        while last.cycles < su.cycles:
            if last.index >= sg.MAX_STAGES:
                raise ValueError(f"the run needs more than {sg.MAX_STAGES} stages: a larger "
                                 "increment, or stages=...")
            done = np.asarray(last.passages, dtype=np.int64)
            if static_bed is None:
                total = sg.next_cycles(su, last.state, last.forces, last.cycles, done,
                                       last.index)
                dp = su.traffic.passages(su.scene, total) - done
                rows, counts = sg.cycle_rows(su, last.forces, dp)
                state, _ = su.law.advance(last.state, rows, counts)
            else:
                total, state, _ = advance_stage(su, last, static_bed)
                dp = su.traffic.passages(su.scene, total) - done
            if su.feedback:
                voids_zone, voids_all = sg.bed(su, state.settlement)
                forces = sg.run_tasks(passage, sg.tasks(su, voids_all), ex)
            else:
                voids_zone, forces = stage_list[0].voids, stage_list[0].forces
            last = Stage(last.index + 1, total, tuple((done + dp).tolist()), state,
                         voids_zone, forces)
            hist.write_stage(store_dir, last, digest)
            stage_list.append(last)
            computed += 1
            bar.update(total - bar.n)
            bar.set_postfix(stage=last.index, refresh=False)
    finally:
        bar.close()
    return computed
