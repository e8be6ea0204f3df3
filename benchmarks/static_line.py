"""The quasi-static line ``analyse`` measures a passage from, against the rail's length.

``analyse`` solves y_qs at QS_DEGREE = 8 Chebyshev points per element the wheel crosses. On the
ballasted preset (4 elements per 0.6 m bay) of length L = 25 .. 400 m, a passage over the whole
rail (every element: 8 n_el + 1 positions):

(a) the linear track's line (the ``linear/*`` levels): before, one band solve per position
    (``_core.linear_static_line``, O(n) each: O(L^2) per passage); now the selected inverse
    (``trackwheel.run.statics.linear_line_of``: the entries of K^-1 within its band in one O(n)
    pass, then O(1) per position: O(L)). Both on the same points in the same process, the
    cases alternated, the median of --repeats; the largest difference of the two lines against
    the static deflection. "line" also times the whole of ``qs_series`` (the fit included).
(b) the ANCF line (the full level, ``trackwheel.quasi_static``, warm-started Newton per
    position over the whole rail): the cost per position against L (O(n) each), on 32
    positions mid-rail, and the passage's cost as 8 n_el + 1 times that.
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
    walls, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        walls.append(time.perf_counter() - t0)
    return statistics.median(walls), out


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


def ancf_rows(lengths, repeats: int) -> list[dict]:
    rows = []
    for L in lengths:
        scene = tw.Scene.ballasted_track(length=L)
        x = 0.5 * L + np.linspace(0.0, 1.2, 32)
        tw.quasi_static(scene, x[:2])  # the model built and cached
        wall, _ = timed(lambda: tw.quasi_static(scene, x), max(1, repeats // 2))
        per = wall / x.size
        n_pos = 8 * scene.rail.n_elements + 1
        rows.append(dict(part="b", length_m=L, n_elements=scene.rail.n_elements,
                         positions=n_pos, before_s=per * n_pos, after_s=np.nan, line_s=np.nan,
                         ratio=np.nan, max_diff_rel=np.nan, bays=np.nan,
                         ancf_per_position_ms=per * 1e3))
        print(f"ANCF line, L = {L:6.1f} m: {per * 1e3:.3f} ms per position; a passage over the "
              f"rail ({n_pos} positions) {per * n_pos:.1f} s")
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
        t0 = time.perf_counter()
        y = np.asarray(_core.quasi_static(model, kernel.wheel_params(piece),
                                          kernel.contact_params(piece),
                                          (x - origin).tolist())["y_contact"])
        wall = time.perf_counter() - t0
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
    ap.add_argument("--ancf-lengths", type=float, nargs="*", default=(25.2, 50.4, 100.2, 199.8))
    ap.add_argument("--bays", type=int, nargs="*", default=(5, 10, 20, 30, 40))
    args = ap.parse_args(argv)
    print(f"trackwheel {tw.__version__}, {platform.processor() or platform.machine()}, "
          f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}")
    rows = (linear_rows(args.lengths, args.repeats) + ancf_rows(args.ancf_lengths, args.repeats)
            + window_rows(args.bays))
    print(f"load average at the end {os.getloadavg()[0]:.1f}")
    write_csv("static_line.csv", rows)


if __name__ == "__main__":
    main()
