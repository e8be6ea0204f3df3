"""The quasi-static line a run is measured from (docs: Model § Outputs): y_qs(X), the static
contact-point displacement with the wheel resting at X -- one wheel's, or a vehicle wheel's with
the whole vehicle resting on the track -- solved at Chebyshev points where it is smooth and
interpolated, cached per scene, mesh, model and range.

The linear track's line costs O(1) per position after one O(n) pass over the rail (the entries
of K^-1 within its band, :func:`trackwheel.run.statics.linear_line_of`), so a passage over a
rail of length L costs O(L). On a travelling window over supports that vary along X the line at
X is solved on the window's rail as the run has it with the wheel at X: its origin where the
run's window stands then, its supports those of the track there (:func:`window_bay_series`).

A vehicle's line is solved in groups, one per bay of its rear wheel (:func:`vehicle_group_series`):
on a long fixed rail the full level's on a piece of the rail that holds the whole vehicle and
:func:`piece_bays` bays either side of it, O(1) per bay; on a travelling window over supports
that vary along X on the window's rail where the run's window stands while its rear wheel is
in that bay.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.polynomial import chebyshev

from ..run.stretch import END_DECAY, end_clearance
from ..run import kernel
from ..run.statics import (linear_line_of, linear_quasi_static, linear_vehicle_line,
                           linear_vehicle_line_on, piece_line, piece_scene, quasi_static,
                           static_rail, vehicle_line_on, vehicle_piece_line, vehicle_static,
                           vehicle_window_line, window_line)
from ..scene import Scene
from ..scene.support_fields import PER_SUPPORT

__all__ = ["QS_DEGREE", "in_window", "qs_series", "quasi_static_line", "vehicle_breakpoints",
           "vehicle_qs_series", "vehicle_quasi_static_line", "window_bay_series",
           "window_reference", "PIECE_DECAY", "piece_bays", "piece_bay_series",
           "vehicle_piece_bays", "vehicle_group_series"]

#: Degree of the polynomial that represents the quasi-static line inside each rail element.
#: With the wheel at X, the static contact-point displacement is, to within the geometric
#: nonlinearity, N(X)^T K^-1 N(X) P with cubic Hermite shape functions N: a polynomial of degree
#: 6 in X inside an element, with kinks in its derivatives only at the nodes (the support springs
#: enter K, not N). So y_qs is solved at the QS_DEGREE + 1 Chebyshev-Lobatto points of each
#: element the run crosses (the end points shared with the neighbours: QS_DEGREE static solves
#: per element) and interpolated by the element's Chebyshev series. Measured against direct
#: static solves: < 2e-13 m for the paper's scene with 20 elements and < 1e-15 m with 80, i.e.
#: below 1e-8 of the static deflection (7e-5 m) and 1e-7 of the smallest dynamic amplitude of
#: Fig. 7 (1.2e-6 m at 50 km/h); a cubic on a 5 mm grid costs 7 (20 elements) or 1.5 (80) times
#: as many solves for an error of 2e-11 m. Each analysis reports an estimate of its own error,
#: |c_7| + |c_8| of the Chebyshev coefficients (``Analysis.y_qs_error``, ~1e-12 m here).
QS_DEGREE = 8

#: The ANCF line (the full level) on a long fixed rail is solved bay by bay on a piece of the
#: rail around the wheel's bay (:func:`piece_bay_series`), far enough either side that the
#: piece's rigid ends change the static deflection under the wheel by about this fraction of it
#: [-]: a load's bowl on the track decays as exp(-beta x), beta = (k_f / 4 EI)^(1/4), so the
#: piece reaches ln(1 / PIECE_DECAY) / beta beyond the bay. Measured against the whole rail
#: (benchmarks/static_line.py): 1.7e-9 of the deflection at beta x = 17 on the ballasted preset,
#: 4e-10 at 35 (the static solver's tolerance); the line's budget is 1e-8. The rail between the
#: rail's axially held near end and the piece's is accounted for by :func:`_axial_correction`.
PIECE_DECAY = 1e-9

def _lobatto_points(a: np.ndarray, w: np.ndarray) -> np.ndarray:
    """The QS_DEGREE + 1 Chebyshev-Lobatto points of each interval [a_i, a_i + w_i] [m], the
    end points shared with the neighbours: (QS_DEGREE n + 1,) for n intervals."""
    t = -np.cos(np.pi * np.arange(QS_DEGREE + 1) / QS_DEGREE)
    x = (a[:, None] + 0.5 * (t[None, :-1] + 1.0) * w[:, None]).ravel()
    return np.append(x, a[-1] + w[-1])


def _series(y: np.ndarray, n_el: int):
    """Each interval's Chebyshev coefficients (QS_DEGREE + 1, n_el) [m] from the values ``y`` at
    :func:`_lobatto_points`, and the error estimate |c_7| + |c_8| [m]."""
    n = QS_DEGREE
    t = -np.cos(np.pi * np.arange(n + 1) / n)
    values = y[np.arange(n_el)[:, None] * n + np.arange(n + 1)[None, :]]  # (n_el, n + 1)
    coef = np.linalg.solve(chebyshev.chebvander(t, n), values.T)  # (n + 1, n_el)
    coef.setflags(write=False)
    return coef, float(np.max(np.abs(coef[-2]) + np.abs(coef[-1])))


@lru_cache(maxsize=128)
def qs_series(scene: Scene, n_elements: int, e0: int, e1: int, linear: bool):
    """Chebyshev series of y_qs on each element e0 .. e1-1 of the mesh: of the ANCF model or
    (``linear``) of the linear track in all its coordinates.

    Returns (coefficients (QS_DEGREE + 1, e1 - e0) [m], error estimate [m]). Cached per (scene,
    mesh, element range): the same range is always solved the same way (the ANCF line in one
    warm-started sweep; the linear line's values do not depend on the range), so the line is
    bit-identical whichever process or earlier analysis computed it.
    """
    le = scene.rail.length / n_elements
    n_el = e1 - e0
    x = np.minimum(_lobatto_points(np.arange(e0, e1) * le, np.full(n_el, le)),
                   scene.rail.length)
    if linear:
        y = linear_quasi_static(scene, x, n_elements=n_elements)
    else:
        y = quasi_static(scene, x, n_elements=n_elements).y_contact
    return _series(y, n_el)


def piece_bays(scene: Scene, n_elements: int) -> int:
    """B: the ANCF line of a fixed rail is solved for each bay on the piece of the rail B bays
    either side of it (:data:`PIECE_DECAY`), or 0 to solve it on the whole rail: a rail no
    longer than such a piece (the paper's 5 m), a travelling window, supports at given
    positions or given one value per support (they number the rail's supports, not places on
    the track), a pinned far end (the piece's far end would hold the rail axially where the
    rail does not), or a mesh that is not whole elements per bay."""
    if (scene.window is not None or scene.supports.positions is not None
            or scene.rail.far_end != "roller"
            or any(isinstance(getattr(scene.supports, name), tuple) for name in PER_SUPPORT)):
        return 0
    d, L = scene.supports.spacing, scene.rail.length
    n_bays = round(L / d)
    if abs(n_bays * d - L) > 1e-9 * L or n_elements % n_bays:
        return 0
    beta = math.log(1.0 / END_DECAY) / end_clearance(scene)
    if not math.isfinite(beta) or beta <= 0.0:
        return 0
    bays = math.ceil(math.log(1.0 / PIECE_DECAY) / beta / d)
    return bays if 2 * bays + 1 < n_bays else 0


@lru_cache(maxsize=1024)
def piece_bay_series(scene: Scene, n_elements: int, bay: int, bays: int):
    """Chebyshev series of the ANCF line over bay ``bay`` [-] of a long fixed rail, solved on
    the piece of the rail ``bays`` bays either side of it (at the rail's near end the piece's
    end is the rail's): its supports, profile and mesh those of the rail there, its ends rigid
    as the rail's. O(1) per bay in the rail's length; the last ``bays`` bays on the whole rail.
    The piece's line is corrected for the rail's axial stretch between the rail's held near
    end and the piece's (:func:`_axial_correction`). Cached per (scene, mesh, bay) and
    computed the same way whatever asked for it. Returns (coefficients (QS_DEGREE + 1,
    elements per bay) [m], error estimate [m])."""
    d = scene.supports.spacing
    n_bays = round(scene.rail.length / d)
    epb = n_elements // n_bays
    le = scene.rail.length / n_elements
    width = 2 * bays + 1
    if bay + bays >= n_bays:
        # a piece that reaches the rail's far end (a roller: the rail slides there, held
        # axially only at its near end) would hold it stiffer: where the rigid end's bowl is
        # steep, the contact force's horizontal part then moves the contact point differently
        # (measured 9e-7 of the deflection in the last metre). These ``bays`` bays are
        # solved on the whole rail in one warm-started sweep: O(L) together.
        e0 = (n_bays - bays) * epb
        coef, err = qs_series(scene, n_elements, e0, n_elements, False)
        j = (bay - (n_bays - bays)) * epb
        return coef[:, j:j + epb], err
    first = max(bay - bays, 0)
    x = _lobatto_points(((bay - first) * epb + np.arange(epb)) * le, np.full(epb, le))
    y, H = piece_line(scene, n_elements, first, width, x)
    piece = piece_scene(scene, n_elements, width)
    y_lin = linear_line_of(piece, static_rail(piece, None, first * d), piece.static_load, x)
    y = _axial_correction(y[:, None], H * (first * d) / scene.rail.axial_stiffness,
                          np.arange(epb + 1) * le, y_lin[:, None])[:, 0]
    return _series(y, epb)


def _streams(scene: Scene) -> bool:
    """A travelling window over supports that vary along X: the window's rail changes with
    its place."""
    return scene.window is not None and not scene.supports.uniform


def _bay(scene: Scene, x: np.ndarray) -> np.ndarray:
    """The track's bay [-] that holds X [m] as the run's window counts it (its origin a whole
    number of bays, the rear wheel's bay ``bays_behind`` bays in)."""
    return np.floor(np.asarray(x) / scene.supports.spacing + 1e-9).astype(np.int64)


@lru_cache(maxsize=1024)
def window_bay_series(scene: Scene, n_elements: int, bay: int, linear: bool):
    """Chebyshev series of y_qs over track bay ``bay`` [-] of a travelling window over supports
    that vary along X: the window's rail with its origin X_w = (bay - bays_behind) d (where
    the run's window stands while its wheel is in that bay), its supports the track's at
    X_w + x, the wheel at the rail coordinates x = X - X_w of the bay (the window's bay
    ``bays_behind``). One rail per bay, so O(1) per bay in the distance run.

    Returns (coefficients (QS_DEGREE + 1, elements per bay) [m], error estimate [m]); cached
    per (scene, mesh, bay) and computed the same way whatever asked for it.
    """
    d = scene.supports.spacing
    nb = scene.window.bays_behind
    epb = n_elements // round(scene.rail.length / d)
    le = scene.rail.length / n_elements
    origin = (bay - nb) * d
    x = _lobatto_points((nb * epb + np.arange(epb)) * le, np.full(epb, le))
    y = window_line(scene, n_elements, origin, x, linear)
    return _series(y, epb)


def in_window(scene: Scene, x: np.ndarray) -> np.ndarray:
    """X [m] as the rail coordinate of a fixed rail, or on a travelling window over a periodic
    track the same place in its bay in the window's bay ``bays_behind`` (where the run holds
    its wheel: the quasi-static line of the periodic track)."""
    if scene.window is None:
        return x
    d = scene.supports.spacing
    return scene.window.bays_behind * d + np.mod(x, d)


def _bay_line(scene: Scene, n_elements: int, x: np.ndarray, series):
    """y_qs [m] at X = ``x`` [m] bay by bay, ``series(bay)`` the (coefficients, error) of the
    bay's elements, and the largest error estimate [m]."""
    n_bays = round(scene.rail.length / scene.supports.spacing)
    epb = n_elements // n_bays
    le = scene.rail.length / n_elements
    bay = _bay(scene, x)
    if scene.window is None:  # X = L is the last bay's end
        bay = np.clip(bay, 0, n_bays - 1)
    y = np.empty_like(x)
    err = 0.0
    for b in np.unique(bay):
        at = bay == b
        coef, e = series(int(b))
        s = x[at] / le - b * epb  # elements into the bay
        k = np.clip(np.floor(s).astype(np.int64), 0, epb - 1)
        t = np.clip(2.0 * (s - k) - 1.0, -1.0, 1.0)
        y[at] = chebyshev.chebval(t, coef[:, k], tensor=False)
        err = max(err, e)
    return y, err


def quasi_static_line(scene: Scene, n_elements: int, x: np.ndarray, linear: bool = False):
    """y_qs at the wheel positions x [m] and the estimate of its error [m]."""
    x = np.asarray(x, dtype=float)
    if _streams(scene):
        return _bay_line(scene, n_elements, x,
                         lambda b: window_bay_series(scene, n_elements, b, linear))
    bays = 0 if linear else piece_bays(scene, n_elements)
    if bays:
        return _bay_line(scene, n_elements, x,
                         lambda b: piece_bay_series(scene, n_elements, b, bays))
    x = in_window(scene, x)
    le = scene.rail.length / n_elements
    e0 = max(0, min(n_elements - 1, math.floor(float(x.min()) / le)))
    e1 = max(e0 + 1, min(n_elements, math.ceil(float(x.max()) / le)))
    coef, err = qs_series(scene, n_elements, e0, e1, linear)
    k = np.clip(np.floor(x / le).astype(np.int64) - e0, 0, e1 - e0 - 1)
    t = np.clip(2.0 * (x / le - (k + e0)) - 1.0, -1.0, 1.0)
    return chebyshev.chebval(t, coef[:, k], tensor=False), err


def window_reference(scene: Scene, x_ref: np.ndarray) -> np.ndarray:
    """The vehicle's reference positions [m] on a fixed rail, or on a travelling window over a
    periodic track the same place in the bay with the rear wheel in the window's bay
    ``bays_behind`` (where the run holds it: the periodic track's line)."""
    if scene.window is None:
        return x_ref
    d = scene.supports.spacing
    rear, _ = scene.active_vehicle.span
    return scene.window.bays_behind * d + np.mod(x_ref + rear, d) - rear


@lru_cache(maxsize=16)
def vehicle_breakpoints(scene: Scene, n_elements: int) -> np.ndarray:
    """The reference positions [m] where some wheel of the vehicle crosses a node of the mesh
    (and the ends of the range the vehicle can take): between two of them every wheel stays
    inside one element, so each wheel's static displacement is smooth there."""
    veh = scene.active_vehicle
    rear, front = veh.span
    lo, hi = -rear, scene.rail.length - front
    le = scene.rail.length / n_elements
    nodes = np.arange(n_elements + 1) * le
    b = np.sort(np.concatenate([nodes - p for p in veh.positions] + [[lo, hi]]))
    b = b[(b >= lo) & (b <= hi)]
    keep = np.concatenate(([True], np.diff(b) > 1e-9 * le))
    return b[keep]


@lru_cache(maxsize=128)
def vehicle_qs_series(scene: Scene, n_elements: int, s0: int, s1: int, linear: bool):
    """Chebyshev series of every wheel's quasi-static line on the segments s0 .. s1-1 between
    :func:`vehicle_breakpoints`: the static contact-point displacement of each wheel with the
    whole vehicle resting on the track under the lever-rule loads (the ANCF statics of
    :func:`trackwheel.statics.vehicle_static`, or for ``linear`` the linear track's, the
    superposition of each wheel's own line and the static flexibility, the receptance at 0 Hz,
    to its neighbours' loads). Returns (coefficients (QS_DEGREE + 1, s1 - s0, n_wheels) [m],
    error estimate [m]); cached like :func:`qs_series`."""
    n = QS_DEGREE
    b = vehicle_breakpoints(scene, n_elements)
    t = -np.cos(np.pi * np.arange(n + 1) / n)
    a, w = b[s0:s1], b[s0 + 1:s1 + 1] - b[s0:s1]
    x = (a[:, None] + 0.5 * (t[None, :-1] + 1.0) * w[:, None]).ravel()
    x = np.append(x, b[s1])
    veh = scene.active_vehicle
    if linear:
        y = linear_vehicle_line(scene, x, n_elements=n_elements)
    else:
        y = np.array([vehicle_static(scene, xi, n_elements=n_elements).y_contact for xi in x])
    return _vehicle_series(y, s1 - s0, veh.n_wheels)


def _vehicle_series(y: np.ndarray, n_seg: int, n_wheels: int):
    """Each segment's and wheel's Chebyshev coefficients (QS_DEGREE + 1, n_seg, n_wheels) [m]
    from the values ``y`` (QS_DEGREE n_seg + 1, n_wheels) at :func:`_lobatto_points`, and the
    error estimate |c_7| + |c_8| [m]."""
    n = QS_DEGREE
    t = -np.cos(np.pi * np.arange(n + 1) / n)
    idx = np.arange(n_seg)[:, None] * n + np.arange(n + 1)[None, :]  # (n_seg, n + 1)
    values = y[idx]  # (n_seg, n + 1, n_wheels)
    inv = np.linalg.inv(chebyshev.chebvander(t, n))
    coef = np.einsum("kj,sjw->ksw", inv, values)
    coef.setflags(write=False)
    err = float(np.max(np.abs(coef[-2]) + np.abs(coef[-1]))) if n_wheels else 0.0
    return coef, err


def _ahead(scene: Scene) -> int:
    """Bays from the rear wheel's bay to the last one the leading wheel can reach while the
    rear wheel stays in its bay [-] (as the travelling window counts them)."""
    rear, front = scene.active_vehicle.span
    return math.ceil((front - rear) / scene.supports.spacing - 1e-9)


def vehicle_piece_bays(scene: Scene, n_elements: int) -> int:
    """B: the vehicle's ANCF line of a fixed rail is solved for each bay of its rear wheel on
    the piece of the rail from B bays behind that bay to B bays beyond the last bay its leading
    wheel reaches (:func:`piece_bays`' B), or 0 to solve it on the whole rail: where
    :func:`piece_bays` says so, or where such a piece is not shorter than the rail."""
    bays = piece_bays(scene, n_elements)
    n_bays = round(scene.rail.length / scene.supports.spacing)
    return bays if bays and 2 * bays + 1 + _ahead(scene) < n_bays else 0


def _group_breakpoints(scene: Scene, n_elements: int, group: int) -> np.ndarray:
    """The reference positions [m] with the rear wheel in track bay ``group`` [-] (on a fixed
    rail within the range the vehicle can take) where some wheel crosses a node of the mesh,
    the group's ends included: between two of them each wheel's static displacement is
    smooth (:func:`vehicle_breakpoints`, one bay of the rear wheel)."""
    veh = scene.active_vehicle
    rear, front = veh.span
    d, le = scene.supports.spacing, scene.rail.length / n_elements
    lo, hi = group * d - rear, (group + 1) * d - rear
    if scene.window is None:
        lo, hi = max(lo, -rear), min(hi, scene.rail.length - front)
    tol = 1e-9 * le
    inner = [k * le - p for p in veh.positions
             for k in range(math.floor((lo + p) / le), math.ceil((hi + p) / le) + 1)]
    inner = np.sort(np.asarray(inner, dtype=float))
    inner = inner[(inner > lo + tol) & (inner < hi - tol)]
    if inner.size:
        inner = inner[np.concatenate(([True], np.diff(inner) > tol))]
    return np.concatenate(([lo], inner, [hi]))


@lru_cache(maxsize=1024)
def vehicle_group_series(scene: Scene, n_elements: int, group: int, bays: int, linear: bool):
    """Chebyshev series of every wheel's quasi-static line (as :func:`vehicle_qs_series`) with
    the rear wheel in track bay ``group`` [-], on the segments between its
    :func:`_group_breakpoints`:

    - on a travelling window over supports that vary along X (linear or ANCF): the window's
      rail with its origin X_w = (group - bays_behind) d, where the run's window stands while
      its rear wheel is in that bay, its supports the track's at X_w + x, each wheel at its
      rail coordinate X - X_w;
    - on a long fixed rail (the ANCF line, ``bays`` = :func:`vehicle_piece_bays`): the piece
      of the rail from ``bays`` bays behind the group's bay over 2 ``bays`` + 1 + the vehicle's
      bays (at the near end from the rail's end; its supports, profile and mesh those of the
      rail there, its ends rigid as the rail's), corrected for the rail's axial stretch
      between the rail's held near end and the piece's (:func:`_axial_correction`); where
      that piece would reach the rail's far end (a roller; see :func:`piece_bay_series`) on
      the whole rail, O(L) for those groups together.

    O(1) per group in the rail's length or the distance run. Returns (breakpoints [m],
    coefficients (QS_DEGREE + 1, segments, n_wheels) [m], error estimate [m]); cached per
    (scene, mesh, group) and computed the same way whatever asked for it.
    """
    veh = scene.active_vehicle
    d = scene.supports.spacing
    b = _group_breakpoints(scene, n_elements, group)
    x = _lobatto_points(b[:-1], np.diff(b))
    X = x[:, None] + np.asarray(veh.positions)[None, :]  # each wheel's track coordinate
    if _streams(scene):
        origin = (group - scene.window.bays_behind) * d
        y = vehicle_window_line(scene, n_elements, origin, X - origin, linear)
    elif group + _ahead(scene) + bays >= round(scene.rail.length / d):
        y = vehicle_line_on(scene, kernel.rail_model(scene, n_elements), X)
    else:
        first = max(group - bays, 0)
        width = 2 * bays + 1 + _ahead(scene)
        y, H = vehicle_piece_line(scene, n_elements, first, width, X - first * d)
        piece = piece_scene(scene, n_elements, width)
        y_lin = linear_vehicle_line_on(piece, static_rail(piece, None, first * d),
                                       X - first * d)
        y = _axial_correction(y, H * (first * d) / scene.rail.axial_stiffness, b, y_lin)
    coef, err = _vehicle_series(y, b.size - 1, veh.n_wheels)
    b.setflags(write=False)
    return b, coef, err


def _axial_correction(y: np.ndarray, du: np.ndarray, b: np.ndarray,
                      y_lin: np.ndarray) -> np.ndarray:
    """The line ``y`` (points, n_wheels) [m] of a piece of the rail at the Lobatto points of
    the segments between ``b`` [m], corrected for the rail between the rail's axially held
    near end and the piece's, X_0 long: its supports act vertically, so it carries the
    horizontal force H holding the wheels and stretches by ``du`` = H X_0 / EA [m] (points,)
    more than the piece, whose near end is held. The rail beyond, with its supports, stands
    that much further along against the wheels (and against the rail profile, which the
    contact reads at the place X, not on the material), so to first order the whole rail's
    line is y - y_s du, y_s the line's slope with the load moving over the supports alone:
    that of ``y_lin``, the linear track's line on the piece (no profile; the ANCF line's own
    slope would carry the profile's), from each segment's series (the line is C^1 across the
    breakpoints: cubic Hermite shape functions). The neglected parts are of order
    y'' du^2 (du ~ 1e-7 m) and rho0 theta^2 du y_s (the linear line's own error)."""
    n = QS_DEGREE
    n_seg = b.size - 1
    coef, _ = _vehicle_series(y_lin, n_seg, y_lin.shape[1])
    t = -np.cos(np.pi * np.arange(n + 1) / n)
    slope = np.einsum("jk,ksw->sjw", chebyshev.chebvander(t, n - 1),
                      chebyshev.chebder(coef, axis=0))  # d/dt, (n_seg, n + 1, n_wheels)
    slope *= (2.0 / np.diff(b))[:, None, None]
    dy = np.concatenate([slope[:, :-1].reshape(-1, y.shape[1]), slope[-1:, -1]])
    return y - dy * du[:, None]


def _vehicle_group_line(scene: Scene, n_elements: int, x: np.ndarray, wheel: int, bays: int,
                        linear: bool):
    """Wheel ``wheel``'s line [m] at the reference positions ``x`` [m] group by group
    (:func:`vehicle_group_series`), and the largest error estimate [m]."""
    rear, front = scene.active_vehicle.span
    d = scene.supports.spacing
    group = _bay(scene, x + rear)
    if scene.window is None:  # the last group with room for the vehicle holds X = L - front
        last = math.ceil((scene.rail.length - (front - rear)) / d - 1e-9) - 1
        group = np.clip(group, 0, max(last, 0))
    y = np.empty_like(x)
    err = 0.0
    for g in np.unique(group):
        at = group == g
        b, coef, e = vehicle_group_series(scene, n_elements, int(g), bays, linear)
        k = np.clip(np.searchsorted(b, x[at], side="right") - 1, 0, b.size - 2)
        t = np.clip(2.0 * (x[at] - b[k]) / (b[k + 1] - b[k]) - 1.0, -1.0, 1.0)
        y[at] = chebyshev.chebval(t, coef[:, k, wheel], tensor=False)
        err = max(err, e)
    return y, err


def vehicle_quasi_static_line(scene: Scene, n_elements: int, x_ref: np.ndarray, wheel: int,
                               linear: bool = False):
    """Wheel ``wheel``'s quasi-static line with the whole vehicle resting at the reference
    positions ``x_ref`` [m], and the estimate of its error [m]."""
    x_ref = np.asarray(x_ref, dtype=float)
    if _streams(scene):
        return _vehicle_group_line(scene, n_elements, x_ref, wheel, 0, linear)
    bays = 0 if linear else vehicle_piece_bays(scene, n_elements)
    if bays:
        return _vehicle_group_line(scene, n_elements, x_ref, wheel, bays, linear)
    x = window_reference(scene, x_ref)
    b = vehicle_breakpoints(scene, n_elements)
    last = b.size - 2
    k = np.clip(np.searchsorted(b, x, side="right") - 1, 0, last)
    s0, s1 = int(k.min()), int(k.max()) + 1
    coef, err = vehicle_qs_series(scene, n_elements, s0, s1, linear)
    a, w = b[k], b[k + 1] - b[k]
    t = np.clip(2.0 * (x - a) / w - 1.0, -1.0, 1.0)
    return chebyshev.chebval(t, coef[:, k - s0, wheel], tensor=False), err
