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
(d) a vehicle's ANCF line (the full level; a half car and a bogie): before, the vehicle's static
    solve on the whole rail at each point (O(n) each: O(L^2) per passage); now, per bay of the
    rear wheel on a piece of the rail holding the vehicle and B bays either side
    (``static_line.vehicle_group_series``; the groups whose piece would reach the far end on the
    whole rail): O(L). The cost per point (the whole rail, 8 points mid-rail) and per group (one
    piece) as medians of --repeats; a passage over the rail (the reference point over its whole
    range) from them, and timed whole up to --whole-passage-up-to; the cost per metre of rail.
    Written to static_line_vehicle.csv.

    python benchmarks/static_line.py [--repeats 5] [--lengths 25 50 100 200 400] [--parts abcd]
"""

from __future__ import annotations

import argparse
import dataclasses as dc
import math
import os
import platform
import statistics
import time

import numpy as np
from _common import write_csv

import trackwheel as tw
from trackwheel import _core
from trackwheel.run import kernel
from trackwheel.run.statics import linear_line_of, static_rail, vehicle_static
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
            before = timed(lambda: static_line.qs_series(scene, ne, 0, ne, False), 1)[0]
            static_line.qs_series.cache_clear()
            static_line.piece_bay_series.cache_clear()
            after = timed(lambda: static_line.quasi_static_line(scene, ne, xs), 1)[0]
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


VEHICLES = {"half car": tw.Vehicle.half_car, "bogie": tw.Vehicle.bogie}


def vehicle_rows(lengths, repeats: int, whole_passage_up_to: float) -> list[dict]:
    """The full level's vehicle line: before, ``vehicle_static`` on the whole rail at each of
    the 8 n_seg + 1 points of a passage (n_seg the segments between the points where a wheel
    crosses a node); now ``vehicle_group_series`` per bay of the rear wheel (a piece, or the
    whole rail near the far end). Costs from the medians per point and per group; whole
    passages timed up to ``whole_passage_up_to`` m (once each, both routes)."""
    rows = []
    for name, make in VEHICLES.items():
        for L in lengths:
            scene = dc.replace(tw.Scene.ballasted_track(length=L), vehicle=make())
            ne = scene.rail.n_elements
            d = scene.supports.spacing
            n_bays = round(L / d)
            bays = static_line.vehicle_piece_bays(scene, ne)
            ahead = static_line._ahead(scene)
            rear, front = scene.vehicle.span
            n_seg = static_line.vehicle_breakpoints(scene, ne).size - 1
            n_pos = 8 * n_seg + 1
            groups = math.ceil((L - (front - rear)) / d - 1e-9)
            whole_groups = sum(g + ahead + bays >= n_bays for g in range(groups)) if bays \
                else groups
            x = 0.5 * (L - front - rear) + np.linspace(0.0, 0.3, 8)
            vehicle_static(scene, x[0])  # the model built and cached
            per_pos = timed(lambda: [vehicle_static(scene, xi) for xi in x], repeats)[0] / x.size
            mid = groups // 2

            def one_group(g=mid):
                static_line.vehicle_group_series.cache_clear()
                return static_line.vehicle_group_series(scene, ne, g, bays, False)

            per_group = timed(one_group, repeats)[0] if bays else np.nan
            pos_per_group = n_pos / groups
            before = per_pos * n_pos
            after = (per_group * (groups - whole_groups) + per_pos * pos_per_group * whole_groups
                     if bays else before)
            measured = L <= whole_passage_up_to
            if measured:
                b = static_line.vehicle_breakpoints(scene, ne)
                xs = b[:-1] + 0.5 * np.diff(b)
                static_line.vehicle_qs_series.cache_clear()
                before = timed(lambda: static_line.vehicle_qs_series(scene, ne, 0, n_seg, False),
                               1)[0]
                static_line.vehicle_qs_series.cache_clear()
                static_line.vehicle_group_series.cache_clear()
                after = timed(lambda: static_line.vehicle_quasi_static_line(scene, ne, xs, 0), 1)[0]
            rows.append(dict(vehicle=name, length_m=L, n_elements=ne, segments=n_seg,
                             positions=n_pos, groups=groups, whole_rail_groups=whole_groups,
                             bays=bays, per_position_ms=per_pos * 1e3,
                             per_group_ms=per_group * 1e3, before_s=before, after_s=after,
                             before_per_m_s=before / L, after_per_m_s=after / L,
                             measured=measured))
            print(f"{name}, L = {L:6.1f} m, B = {bays}: {per_pos * 1e3:.2f} ms per point on "
                  f"the whole rail, {per_group * 1e3:.0f} ms per group of "
                  f"{pos_per_group:.0f} points on a piece; a passage ({n_pos} points, {groups} "
                  f"groups, {whole_groups} on the whole rail) {before:.1f} s -> {after:.1f} s, "
                  f"{before / L * 1e3:.0f} -> {after / L * 1e3:.0f} ms per metre "
                  f"({'measured' if measured else 'from the costs per point and per group'})")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--lengths", type=float, nargs="*", default=LENGTHS)
    ap.add_argument("--ancf-lengths", type=float, nargs="*", default=LENGTHS)
    ap.add_argument("--bays", type=int, nargs="*", default=(5, 10, 20, 30, 40))
    ap.add_argument("--whole-passage-up-to", type=float, default=60.0,
                    help="time the full level's whole passage on rails up to this long [m]")
    ap.add_argument("--vehicle-lengths", type=float, nargs="*", default=LENGTHS[1:])
    ap.add_argument("--parts", default="abcd", help="the parts to run, e.g. 'd'")
    args = ap.parse_args(argv)
    print(f"trackwheel {tw.__version__}, {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    rows = ((linear_rows(args.lengths, args.repeats) if "a" in args.parts else [])
            + (ancf_rows(args.ancf_lengths, args.repeats, args.whole_passage_up_to)
               if "b" in args.parts else [])
            + (window_rows(args.bays) if "c" in args.parts else []))
    vehicle = (vehicle_rows(args.vehicle_lengths, args.repeats, args.whole_passage_up_to)
               if "d" in args.parts else [])
    print(f"load average at the end {os.getloadavg()[0]:.1f}")
    if rows:
        write_csv("static_line.csv", rows)
    if vehicle:
        write_csv("static_line_vehicle.csv", vehicle)


if __name__ == "__main__":
    main()
