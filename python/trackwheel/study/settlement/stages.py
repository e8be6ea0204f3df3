"""The stages of the settlement loop: traffic runs over the track, the ballast settles, the
settled bed goes back into the track, stage by stage (docs: Model § The settlement loop).

:func:`~trackwheel.settle` (:mod:`.loop`) is the entry point; this module holds its parts: the setup (the settling
sleepers, each item's run, the static deflection that sets the stage length), the bed of a
settlement (the voids), the passages of a stage on an executor, and the stage length.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
from collections.abc import Callable
from concurrent.futures import Executor

import numpy as np

from ..._version import __version__
from ...base import validate as v
from ...run.stretch import default_end, default_start
from ...scene import Scene
from ..sweep import pool
from ..sweep.store import jsonable
from .passage import PASSAGE_LEVELS, PassageForces, PassageTask, bed_voids, track_supports
from .state import MAX_CYCLES, SettlementLaw, whole
from .traffic import Traffic
from .varandas import Varandas

#: how the settlement becomes voids: "min" (the track sinks as a whole by the least
#: settlement of the settling sleepers, the rest opens voids) or "none" (all of it)
DATUMS = ("min", "none")
#: most stages a run may take [-]
MAX_STAGES = 10_000
#: default largest change of a void in an adaptive stage, a fraction of the static
#: deflection [-]: halving it changes the final settlement by a few per cent of the
#: differential settlement on a stiffness step (docs: Model § The settlement loop)
DEFAULT_INCREMENT = 0.1
#: how a stage advances the law: "explicit" (at the forces of the passage at its start) or
#: "quasi-static" (sub-steps at those forces' dynamic ratios times the statics of the
#: settling bed, :mod:`.quasi_static`)
STAGE_RULES = ("explicit", "quasi-static")
#: the quasi-static stage's largest change of a void per sub-step, a fraction of the static
#: deflection [-] (the stiff redistribution sheds a 1 % excess at a void of a few micrometres,
#: about 0.01 w0)
SUBSTEP_INCREMENT = 0.01


@dataclasses.dataclass(frozen=True)
class Setup:
    """What every stage of a run shares (built once by :func:`setup`)."""

    scene: Scene
    traffic: Traffic
    law: SettlementLaw
    cycles: int
    item_scenes: tuple[Scene, ...]
    axles: np.ndarray  # (k,) axles per passage of each item
    x_range: tuple[tuple[float, float], ...]  # each item's reference start and end [m]
    sleepers: np.ndarray  # (n,) X of the settling sleepers [m]
    supports: np.ndarray  # (N,) X of every support of the rail [m]
    base_void: np.ndarray  # (N,) the scene's own voids [m]
    stiffness: np.ndarray  # (n,) static support stiffness of the settling sleepers [N/m]
    static_deflection: float  # w0 [m]
    stages: int | None
    increment: float
    feedback: bool
    datum: str
    fidelity: str
    simulate_kwargs: dict
    stage_rule: str = "explicit"


def setup(scene, traffic, cycles, law, stages, increment, feedback, datum, fidelity, x_start,
          x_end, simulate_kwargs, stage_rule="explicit") -> Setup:
    """The run's inputs checked (ValueError/TypeError naming the parameter and its range) and
    everything the stages share."""
    if not isinstance(scene, Scene):
        raise TypeError(f"scene must be a trackwheel.Scene, got {type(scene).__name__}")
    if not scene.supports.layered:
        raise ValueError("scene.supports must be layered (sleeper_mass and ballast_stiffness "
                         "given): the ballast settles under the sleepers")
    traffic = Traffic.of(traffic)
    if law is None:
        law = Varandas()
    if not isinstance(law, SettlementLaw):
        raise TypeError(f"law must be a settlement law (trackwheel.settlement.Varandas(), "
                        f"Sato(...), Shenton(...)), got {type(law).__name__}")
    cycles = whole("cycles", cycles, low=1, high=MAX_CYCLES)
    if stages is not None:
        stages = whole("stages", stages, low=1, high=MAX_STAGES)
    increment = v.number("increment", increment, low=0.0, low_open=True, high=10.0)
    v.boolean("feedback", feedback)
    v.choice("datum", datum, DATUMS)
    v.choice("fidelity", fidelity, PASSAGE_LEVELS)
    v.choice("stage_rule", stage_rule, STAGE_RULES)
    if stage_rule == "quasi-static" and scene.window is not None:
        raise ValueError('stage_rule="quasi-static" needs a fixed rail: the statics of the '
                         'bed are the fixed rail\'s (use stage_rule="explicit" on a window)')
    item_scenes = tuple(item.scene(scene) for item in traffic.items)
    x_range = tuple(_x_range(s, x_start, x_end) for s in item_scenes)
    supports = track_supports(scene, x_range)
    sleepers = _zone(supports, item_scenes, x_range, scene.supports.spacing)
    stiffness = _support_values(scene, "static_stiffness", supports)
    zone = np.isin(supports, sleepers)
    return Setup(scene, traffic, law, cycles, item_scenes, traffic.axles(scene), x_range,
                 sleepers, supports, _support_values(scene, "void", supports),
                 stiffness[zone], _static_deflection(scene, item_scenes, stiffness[zone]),
                 stages, increment, bool(feedback), datum, fidelity, dict(simulate_kwargs),
                 stage_rule)


def _x_range(scene: Scene, x_start, x_end) -> tuple[float, float]:
    """The reference point's start and end [m]: given, or simulate's defaults (the rear wheel
    from the middle of the first bay clear of the rail's end, the leading wheel to the middle
    of the last)."""
    rear, front = scene.active_vehicle.span
    if scene.window is not None and (x_start is None or x_end is None):
        raise ValueError("on a travelling window give x_start and x_end [m]: the stretch of "
                         "track the traffic settles")
    x0 = default_start(scene) - rear if x_start is None else v.number("x_start", x_start,
                                                                        unit="m")
    x1 = default_end(scene, x0 + front) - front if x_end is None else v.number("x_end", x_end,
                                                                                unit="m")
    if x1 <= x0:
        raise ValueError(f"x_end = {x1:g} m must be beyond x_start = {x0:g} m")
    return float(x0), float(x1)


def _zone(supports, item_scenes, x_range, spacing) -> np.ndarray:
    """The settling sleepers: those every axle of every item passes with a bay to spare on
    each side (their peak is the passage's, not its start's or end's)."""
    lo, hi = -math.inf, math.inf
    for scene, (x0, x1) in zip(item_scenes, x_range):
        offsets = np.asarray(scene.active_vehicle.positions, dtype=float)
        lo = max(lo, x0 + offsets.max() + spacing)
        hi = min(hi, x1 + offsets.min() - spacing)
    zone = supports[(supports >= lo - 1e-9) & (supports <= hi + 1e-9)]
    if zone.size == 0:
        raise ValueError(f"no sleeper lies between X = {lo:g} and {hi:g} m, where every axle "
                         "passes with a bay to spare: a longer run (x_start, x_end)")
    return zone


def _support_values(scene: Scene, name: str, positions: np.ndarray) -> np.ndarray:
    """The supports' property ``name`` at ``positions`` (N,) (one value broadcast where the
    supports are the same everywhere)."""
    s = scene.supports
    if hasattr(s, "values"):
        return np.asarray(getattr(s.values(positions), name), dtype=float)
    if name == "void":
        return np.zeros(positions.size)
    return np.full(positions.size, float(getattr(s, name)))


def _static_deflection(scene, item_scenes, stiffness) -> float:
    """w0 [m]: the rail's static deflection under the heaviest static wheel load P of the
    traffic on the beam on a Winkler foundation of the settling sleepers' mean static support
    stiffness, w0 = P beta / (2 k_f), k_f = mean k / d, beta = (k_f / (4 EI))^(1/4)."""
    load = max(max(s.active_vehicle.static_loads(s.gravity)) for s in item_scenes)
    kf = float(np.mean(stiffness)) / scene.supports.spacing
    beta = (kf / (4.0 * scene.rail.bending_stiffness)) ** 0.25
    return load * beta / (2.0 * kf)


def inputs(su: Setup, passage) -> dict:
    """The run's inputs as stored and hashed (the stage rule only where it is not the
    default, so that the stores of explicit runs stay valid)."""
    extra = {} if su.stage_rule == "explicit" else {"stage_rule": su.stage_rule}
    return jsonable({**extra,
        "scene": dataclasses.asdict(su.scene), "traffic": su.traffic.to_dict(),
        "law": su.law.to_dict(), "cycles": su.cycles, "stages": su.stages,
        "increment": su.increment, "stage_limit": "voids", "feedback": su.feedback,
        "datum": su.datum, "fidelity": su.fidelity, "x_range": [list(r) for r in su.x_range],
        "simulate": su.simulate_kwargs, "version": __version__,
        "passage": f"{getattr(passage, '__module__', '?')}."
                   f"{getattr(passage, '__qualname__', type(passage).__qualname__)}"})


# ----------------------------------------------------------------------------------------------
# the bed and the passages
def bed(su: Setup, settlement: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The voids of a bed settled by ``settlement`` (n,) [m]: (the settling sleepers' (n,),
    every support's (N,)) [m]. Each support's settlement is its own in the settling stretch and
    its nearest settling sleeper's beyond it (the bed stays continuous where the traffic was
    not modelled); the datum (``datum="min"``: the least settlement) is subtracted, the rest
    adds to the scene's own void."""
    datum = float(settlement.min()) if su.datum == "min" else 0.0
    along = np.interp(su.supports, su.sleepers, settlement) - datum
    voids = su.base_void + np.maximum(along, 0.0)
    zone = np.isin(su.supports, su.sleepers)
    return voids[zone], voids


def tasks(su: Setup, voids_all: np.ndarray) -> list[PassageTask]:
    """One passage per traffic item on the bed with these voids (N,) [m]: the scene as given
    where they are the scene's own."""
    same = np.array_equal(voids_all, su.base_void)
    out = []
    for item, scene, (x0, x1) in zip(su.traffic.items, su.item_scenes, su.x_range):
        voids = None if same else bed_voids(su.scene, su.supports, voids_all)
        out.append(PassageTask(scene, voids, item.speed, su.fidelity, x0, x1,
                               tuple(su.sleepers.tolist()), su.simulate_kwargs))
    return out


@contextlib.contextmanager
def executor_for(executor: Executor | None, max_workers: int | None, n_tasks: int):
    """(executor or None for in-process) for the run: the one given, our own process pool of
    ``max_workers`` (shut down at the end), or none (the default: passages one after the
    other in this process)."""
    if executor is not None and not isinstance(executor, Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor, "
                        f"got {type(executor).__name__}")
    if executor is not None and max_workers is not None:
        raise ValueError("give executor or max_workers, not both")
    workers = 1 if max_workers is None else v.integer("max_workers", max_workers, low=1,
                                                      high=4096)
    if executor is not None:
        yield executor
    elif workers > 1 and n_tasks > 1:
        with pool.make_pool(min(workers, n_tasks)) as ex:
            yield ex
    else:
        yield None


def run_tasks(passage: Callable, task_list, ex) -> tuple[PassageForces, ...]:
    """Each task's forces, in order (on ``ex``, or here)."""
    results = [passage(t) for t in task_list] if ex is None else list(ex.map(passage, task_list))
    for r in results:
        if not isinstance(r, PassageForces):
            raise TypeError(f"passage must return a PassageForces, got {type(r).__name__}")
    return tuple(results)


# ----------------------------------------------------------------------------------------------
# the stage length
def cycle_rows(su: Setup, forces, dp: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The law's input for ``dp`` (k,) passages of each item: every axle's peaks (rows) and
    their counts."""
    rows = np.concatenate([f.peaks for f in forces], axis=0)
    counts = np.concatenate([np.full(f.peaks.shape[0], d, dtype=np.int64)
                             for f, d in zip(forces, dp)])
    return rows, counts


def next_cycles(su: Setup, state, forces, done: int, passages_done, index: int) -> int:
    """The cycles at the end of the stage that starts at ``done``: with ``stages`` the
    schedule N_k = N^(k/m) (rounded, strictly increasing: equal settlement steps of a law
    that grows like a power of N); adaptive, the largest total whose largest change of a
    settling sleeper's void at this stage's forces is at most ``increment`` x w0 (bisection on
    the whole number; at least one passage).

    The void, not the settlement: a settlement the whole track shares sinks the track with
    the datum and leaves the forces as they were, so only the change of the bed's voids
    (settlement less the datum's) limits the stage; with ``datum="none"`` the two are the
    same."""
    if su.stages is not None:
        k = index + 1
        target = su.cycles if k >= su.stages else int(round(su.cycles ** (k / su.stages)))
        return min(su.cycles, max(target, done + 1))
    limit = su.increment * su.static_deflection
    before = bed(su, state.settlement)[0]

    def step(total: int) -> float:
        dp = su.traffic.passages(su.scene, total) - passages_done
        rows, counts = cycle_rows(su, forces, dp)
        after = bed(su, su.law.advance(state, rows, counts)[0].settlement)[0]
        return float(np.max(np.abs(after - before)))

    if step(su.cycles) <= limit:
        return su.cycles
    lo, hi = done, su.cycles  # step(lo) <= limit < step(hi)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if step(mid) <= limit:
            lo = mid
        else:
            hi = mid
    if np.all(su.traffic.passages(su.scene, lo) == passages_done):
        return hi  # even the first passage changes the voids by more than the limit
    return lo
