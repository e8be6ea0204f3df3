"""The quasi-static line ``analyse`` measures a passage from, against the rail's length.

``analyse`` solves y_qs at QS_DEGREE = 8 Chebyshev points per element the wheel crosses. On the
ballasted preset (4 elements per 0.6 m bay) of length L = 25 .. 400 m, a passage over the whole
rail (every element: 8 n_el + 1 positions):

(a) the linear track's line (the ``linear/*`` levels): before, one band solve per position
    (``_core.linear_static_line``, O(n) each: O(L^2) per passage); now the selected inverse
    (``trackwheel.run.statics.linear_line_of``: the entries of K^-1 within its band in one O(n)
    pass, then O(1) per position: O(L)). Both on the same points in the same process, the
    cases alternated, the median CPU time of --repeats; the largest difference of the two lines
    against the static deflection. "line" also times the whole of ``qs_series`` (the fit included).
(b) the ANCF line (the full level): before, a warm-started Newton per position on the whole
    rail (O(n) each: O(L^2) per passage); now, bay by bay on a piece of the rail B bays either
    side (``static_line.piece_bays``; the last B bays on the whole rail): O(L). Whole passages
    timed up to --whole-passage-up-to; longer ones from the measured cost per position (32
    positions mid-rail) and per bay (one piece).
(c) what a windowed ANCF solve would cost in accuracy: the ANCF line at 17 points of the middle
    bay of a 60 m rail solved on a piece of the rail B bays either side of that bay (its ends
    rigid, as the rail's), against the whole rail, for B = 5 .. 40.

    python benchmarks/static_line.py [--repeats 5] [--lengths 25 50 100 200 400]
"""

from __future__ import annotations

import argparse
import dataclasses as dc
import os
import platform
import statistics
import time

import numpy as np
from _common import write_csv

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel
from trackwheel.run.statics import linear_line_of, static_rail
from trackwheel.study import static_line

LENGTHS = (25.2, 50.4, 100.2, 199.8, 399.6)  # whole 0.6 m bays near 25 .. 400 m


def passage_points(scene: tw.Scene) -> np.ndarray:
    """The Chebyshev-Lobatto points of every element (what analyse solves for a passage over
    the whole rail)."""
    ne = scene.rail.n_elements
    le = scene.rail.length / ne
    return np.minimum(static_line._lobatto_points(np.arange(ne) * le, np.full(ne, le)),
                      scene.rail.length)


def timed(fn, repeats: int) -> tuple[float, object]:
    """(median CPU time of ``repeats`` calls [s], the last result): CPU time, not wall, as the
    machine is shared (every call here is single-threaded)."""
    cpu, out = [], None
    for _ in range(repeats):
        t0 = time.process_time()
        out = fn()
        cpu.append(time.process_time() - t0)
    return statistics.median(cpu), out


def linear_rows(lengths, repeats: int) -> list[dict]:
    rows = []
    for L in lengths:
        scene = tw.Scene.ballasted_track(length=L)
        ne = scene.rail.n_elements
        x = passage_points(scene)
        P = scene.static_load
        old_model = kernel.rail_model(scene, ne)
        beam = kernel.beam_params(scene)

        def before():
            return np.asarray(_core.linear_static_line(old_model, beam, P, x.tolist(), 0,
                                                       kernel.element_compliance(scene)))

        def after():
            return linear_line_of(scene, static_rail(scene, ne), P, x)

        def series():
            static_line.qs_series.cache_clear()
            return static_line.qs_series(scene, ne, 0, ne, True)

        reps = max(1, repeats if L < 150 else repeats // 2)
        w_old, w_new, w_series = [], [], []
        for _ in range(reps):  # alternated: the machine's drift hits both alike
            w_old.append(timed(before, 1)[0])
            w_new.append(timed(after, 1)[0])
            w_series.append(timed(series, 1)[0])
        y_old, y_new = before(), after()
        deflection = float(np.max(np.abs(y_old)))
        err = float(np.max(np.abs(y_new - y_old)))
        old, new, ser = (statistics.median(w) for w in (w_old, w_new, w_series))
        rows.append(dict(part="a", length_m=L, n_elements=ne, positions=x.size,
                         before_s=old, after_s=new, line_s=ser, ratio=old / new,
                         max_diff_rel=err / deflection, bays=np.nan, ancf_per_position_ms=np.nan))
        print(f"L = {L:6.1f} m, {ne:5d} elements, {x.size:6d} positions: solve per position "
              f"{old * 1e3:9.2f} ms, selected inverse {new * 1e3:7.2f} ms (ratio "
              f"{old / new:7.1f}), qs_series {ser * 1e3:7.2f} ms; |diff| / deflection "
              f"{err / deflection:.1e}")
    return rows


def ancf_rows(lengths, repeats: int, whole_passage_up_to: float) -> list[dict]:
    """The full level's line: before, the whole rail per position; now, pieces per bay (and
    the last B bays on the whole rail). Whole passages timed up to ``whole_passage_up_to`` m;
    beyond, the passage's cost from the measured cost per position (whole rail) and per bay
    (piece): before = c_pos (8 n_el + 1), now = c_bay (n_bays - B) + c_pos 8 epb B."""
    rows = []
    for L in lengths:
        scene = tw.Scene.ballasted_track(length=L)
        ne = scene.rail.n_elements
        n_bays = round(L / scene.supports.spacing)
        epb = ne // n_bays
        bays = static_line.piece_bays(scene, ne)
        x = 0.5 * L + np.linspace(0.0, 1.2, 32)
        tw.quasi_static(scene, x[:2])  # the model built and cached
        per_pos, _ = timed(lambda: tw.quasi_static(scene, x), max(1, repeats // 2))
        per_pos /= x.size
        mid = n_bays // 2

        def one_bay(b=mid):
            static_line.piece_bay_series.cache_clear()
            return static_line.piece_bay_series(scene, ne, b, bays)

        per_bay = timed(one_bay, max(1, repeats // 2))[0] if bays else np.nan
        n_pos = 8 * ne + 1
        before = per_pos * n_pos
        after = (per_bay * (n_bays - bays) + per_pos * 8 * epb * bays) if bays else before
        measured = L <= whole_passage_up_to
        if measured:  # the whole passage, both routes
            xs = passage_points(scene)
            static_line.qs_series.cache_clear()
            t0 = time.process_time()
            static_line.qs_series(scene, ne, 0, ne, False)
            before = time.process_time() - t0
            static_line.qs_series.cache_clear()
            static_line.piece_bay_series.cache_clear()
            t0 = time.process_time()
            static_line.quasi_static_line(scene, ne, xs)
            after = time.process_time() - t0
        rows.append(dict(part="b", length_m=L, n_elements=ne, positions=n_pos, before_s=before,
                         after_s=after, line_s=np.nan, ratio=before / after,
                         max_diff_rel=np.nan, bays=bays, ancf_per_position_ms=per_pos * 1e3))
        print(f"ANCF line, L = {L:6.1f} m, B = {bays}: {per_pos * 1e3:.3f} ms per position on "
              f"the whole rail, {per_bay * 1e3:.1f} ms per bay on a piece; a passage over the "
              f"rail ({n_pos} positions) {before:.1f} s -> {after:.1f} s "
              f"({'measured' if measured else 'from the costs per position and per bay'})")
    return rows


def window_rows(bays_list) -> list[dict]:
    """The ANCF line on a piece of the rail of B bays either side of the middle bay against
    the whole 60 m rail's."""
    scene = tw.Scene.ballasted_track(length=60.0)
    d, epb = scene.supports.spacing, scene.rail.n_elements // round(60.0 / 0.6)
    mid = 50  # the middle bay
    x = mid * d + np.linspace(0.0, d, 17)
    full = tw.quasi_static(scene, x).y_contact
    deflection = float(np.max(np.abs(full)))
    rows = []
    for B in bays_list:
        piece = dc.replace(scene, rail=dc.replace(scene.rail, length=(2 * B + 1) * d,
                                                  n_elements=(2 * B + 1) * epb))
        origin = (mid - B) * d
        model = _core.RailModel(kernel.rail_params(piece), kernel.support_params(piece, origin),
                                _core.Profile())
        t0 = time.process_time()
        y = np.asarray(_core.quasi_static(model, kernel.wheel_params(piece),
                                          kernel.contact_params(piece),
                                          (x - origin).tolist())["y_contact"])
        wall = time.process_time() - t0
        err = float(np.max(np.abs(y - full)))
        rows.append(dict(part="c", length_m=(2 * B + 1) * d, n_elements=(2 * B + 1) * epb,
                         positions=x.size, before_s=np.nan, after_s=wall, line_s=np.nan,
                         ratio=np.nan, max_diff_rel=err / deflection, bays=B,
                         ancf_per_position_ms=wall / x.size * 1e3))
        print(f"ANCF line on {2 * B + 1} bays ({B} either side): |y - y_60m| / deflection "
              f"{err / deflection:.2e} ({err:.2e} m), {wall / x.size * 1e3:.3f} ms per position")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--lengths", type=float, nargs="*", default=LENGTHS)
    ap.add_argument("--ancf-lengths", type=float, nargs="*", default=LENGTHS)
    ap.add_argument("--bays", type=int, nargs="*", default=(5, 10, 20, 30, 40))
    ap.add_argument("--whole-passage-up-to", type=float, default=60.0,
                    help="time the full level's whole passage on rails up to this long [m]")
    args = ap.parse_args(argv)
    print(f"trackwheel {tw.__version__}, {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    rows = (linear_rows(args.lengths, args.repeats) + ancf_rows(args.ancf_lengths, args.repeats,
                                                                  args.whole_passage_up_to)
            + window_rows(args.bays))
    print(f"load average at the end {os.getloadavg()[0]:.1f}")
    write_csv("static_line.csv", rows)


if __name__ == "__main__":
    main()
