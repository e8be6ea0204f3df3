"""The settlement loop's targets: 10^6 axle passes over a 60 m transition zone in 20 stages on a
linear level (< 2 min) and on the full model (< 15 min), with the stage convergence (the same
run with half the increment, or twice the stages: the change of the final settlement).

The track: Scene.ballasted_track on a 72 m rail, the ballast stiffness changing from 50 to
200 MN/m at X = 36 m over a 6 m linear ramp (soft -> stiff), one wheel at 200 km/h; the
settling sleepers are the ~60 m the wheel passes (simulate's default stretch). Varandas' law
with ROSE's parameters.

    python benchmarks/settle.py                         # adaptive, increment 0.2 and 0.1
    python benchmarks/settle.py --increment 0.1 0.05    # the default and its halving
    python benchmarks/settle.py --increment --stages 20 40     # the fixed schedule
    python benchmarks/settle.py --fidelity full --increment 0.4
    python benchmarks/settle.py --step --increment 0.4 0.2 0.1 0.05   # the 24 m step

Each run prints its wall time and its passages (the machine-independent cost: one passage per
traffic item and state of the bed).
"""

from __future__ import annotations

import argparse
import dataclasses
import time

import numpy as np

import trackwheel as tw


def scene(step: bool = False) -> tw.Scene:
    """The benchmark's 72 m transition, or (``step``) the tests' 24 m step at X = 12 m."""
    if step:
        base = tw.Scene.ballasted_track(24.0)
        supports = base.supports.transition(12.0, ballast_stiffness=(50e6, 200e6))
    else:
        base = tw.Scene.ballasted_track(72.0)
        supports = base.supports.transition(36.0, ramp=6.0, shape="linear",
                                            ballast_stiffness=(50e6, 200e6))
    return dataclasses.replace(base, supports=supports)


def run(fidelity: str, stages: int | None, cycles: float, feedback: bool,
        increment: float = 0.1,
        step: bool = False, stage_rule: str = "explicit") -> tuple[tw.settlement.SettlementHistory, float, float]:
    """The history, its wall time and this process's CPU time [s] (the passages run here, one
    thread: on a shared machine the CPU time is the cost, the wall time includes waiting)."""
    t0, c0 = time.perf_counter(), time.process_time()
    h = tw.settle(scene(step), tw.kmh(200), cycles, fidelity=fidelity, stages=stages,
                  increment=increment, feedback=feedback, progress=False,
                  stage_rule=stage_rule)
    return h, time.perf_counter() - t0, time.process_time() - c0


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--fidelity", default="linear/hertz")
    p.add_argument("--stages", type=int, nargs="*", default=[],
                   help="runs on the fixed schedule N_k = N^(k/m)")
    p.add_argument("--increment", type=float, nargs="*", default=[0.2, 0.1],
                   help="adaptive runs, each stage's largest change of a void this fraction of w0")
    p.add_argument("--cycles", type=float, default=1e6)
    p.add_argument("--open-loop", action="store_true", help="feedback=False")
    p.add_argument("--step", action="store_true",
                   help="the tests' 24 m step (ballast 50 -> 200 MN/m at X = 12 m) instead")
    p.add_argument("--stage-rule", default="explicit", choices=("explicit", "quasi-static"))
    p.add_argument("--save", default=None,
                   help="write each run's final settlement to this .npz (keyed by stages)")
    args = p.parse_args()
    results = []
    cases = [(m, 0.1) for m in args.stages] + [(None, inc) for inc in args.increment]
    for m, inc in cases:
        h, wall, cpu = run(args.fidelity, m, args.cycles, not args.open_loop, inc, args.step,
                            args.stage_rule)
        results.append(h)
        s = h.settlement[-1]
        how = f"{m:>3} stages" if m is not None else f"increment {inc:g}, {h.n_stages} stages"
        passages = len(h.stage_list) * len(h.item_labels)
        print(f"{args.fidelity:>13} {how}: {wall:7.1f} s wall, {cpu:7.1f} s CPU, {passages} "
              f"passages ({cpu / passages:.1f} s CPU each); {h.sleepers.size} sleepers; "
              f"settlement {1e3 * s.min():.3f}..{1e3 * s.max():.3f} mm, differential "
              f"{1e3 * h.differential[-1]:.3f} mm; dynamic factor {h.dynamic_factor[0]:.4f} -> "
              f"{h.dynamic_factor[-1]:.4f}")
        print(f"  most settled sleeper at X = {h.sleepers[np.argmax(s)]:.1f} m, least at "
              f"{h.sleepers[np.argmin(s)]:.1f} m")
        print("  per stage: cycles " + " ".join(f"{c:.3g}" for c in h.cycles))
        print("  dynamic factor " + " ".join(f"{d:.3f}" for d in h.dynamic_factor))
        print("  largest void [mm] " + " ".join(f"{1e3 * g:.3f}" for g in h.voids.max(axis=1)))
    if args.save:
        np.savez(args.save, sleepers=results[0].sleepers, **{
            f"{args.stage_rule}_{h.n_stages}": h.settlement[-1] for h in results})
    for a, b in zip(results, results[1:]):
        change = np.max(np.abs(a.settlement[-1] - b.settlement[-1]))
        print(f"{a.n_stages} -> {b.n_stages} stages: final settlement changes by at most "
              f"{1e6 * change:.2f} um ({100 * change / b.differential[-1]:.2f} % of the "
              "differential settlement)")


if __name__ == "__main__":
    main()
