"""The excitation as the kernel reads it: the rail profile and the wheel's out-of-roundness as
piecewise cubic spline tables (docs: Model § Irregularities, § The travelling window).

The kernel interpolates the rail profile by a cubic spline through samples X_i = x0 + i h
(:func:`spline_grid`), fitted :data:`SPLINE_CHUNK` intervals at a time (:func:`spline_chunks`)
and, over a long run, streamed: it draws the chunks as the vehicle advances and drops those
far behind (:func:`rail_profile`). The wheel's defects reach it as a periodic spline over one
revolution (:func:`defects_profile`).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from .. import _core
from ..base import validate as v
from ..excitation.contact_filter import contact_half_width
from ..excitation.irregularity import Irregularity, grid_size
from ..scene import Scene

#: The kernel interpolates the rail profile by a cubic spline through samples X_i = i dx over
#: the whole rail, dx at most PROFILE_DX [m] and at most 1/PROFILE_POINTS_PER_WAVELENGTH of the
#: profile's shortest wavelength: the spline's error is ~(2 pi dx / lambda)^4 / 384 < 2e-6 of
#: the amplitude, and a joint's cusp is rounded over about 1 mm only.
PROFILE_DX = 1e-3
PROFILE_POINTS_PER_WAVELENGTH = 40
#: The wheel's out-of-roundness reaches the kernel the same way, as a periodic cubic spline
#: through samples every WHEEL_ARC_STEP [m] of its circumference (rounding a new flat's corners
#: over about that arc).
WHEEL_ARC_STEP = 5e-4
#: :func:`spline_chunks` fits the spline this many intervals at a time [-], each chunk extended
#: by SPLINE_OVERLAP knots at both sides [-]
SPLINE_CHUNK = 1 << 16
SPLINE_OVERLAP = 40
#: A rail profile of more than STREAM_MIN_CHUNKS spline chunks is streamed into the kernel,
#: which keeps its chunks STREAM_RETENTION [m] (or four vehicle spans) behind the furthest X
#: read (:func:`rail_profile`).
STREAM_MIN_CHUNKS = 3
STREAM_RETENTION = 200.0


# --------------------------------------------------------------------------------------------
# the rail profile's spline table
def spline_grid(irr: Irregularity, x_min: float, x_max: float, dx: float
                ) -> tuple[float, float, int]:
    """(x0 [m], h [m], n) of the spline's knots X_i = x0 + i h, i < n: the grid of
    ``irr.table(x_min, x_max, dx)`` (``irr`` only names the profile the grid is for)."""
    n = grid_size(x_min, x_max, dx)
    x_min, x_max = float(x_min), float(x_max)
    return x_min, (x_min + (x_max - x_min) / (n - 1)) - x_min, n


def spline_chunks(irr: Irregularity, x_min: float, x_max: float, dx: float, *,
                  chunk: int = SPLINE_CHUNK):
    """:func:`spline_table` ``chunk`` intervals at a time, for building the table without
    holding more than one chunk: yields (i0, c, worst [1/m], its X [m]) per chunk, c of
    shape (4, m) the coefficients of intervals i0..i0 + m - 1, worst the largest r'' at the
    chunk's knots (and at the last knot, in the last chunk).

    Each chunk's spline is fitted on the chunk extended by SPLINE_OVERLAP knots at both
    sides (not-a-knot at the profile's true ends). A cubic spline's dependence on a far
    sample decays by a factor 2 - sqrt(3) = 0.27 per knot (the tridiagonal system's
    decay), 0.27^40 < 1e-22 over the overlap, so the chunks join to round-off of the one
    spline through all samples; with a single chunk it is that spline, bit for bit. The
    samples are those of ``irr.table``, bit for bit (the same grid X_i = x_min + i
    (x_max - x_min)/(n - 1))."""
    from scipy.interpolate import CubicSpline

    x_min, h, n = spline_grid(irr, x_min, x_max, dx)
    step = (float(x_max) - x_min) / (n - 1)
    chunk = v.integer("chunk", chunk, low=1)
    for i0 in range(0, n - 1, chunk):
        i1 = min(i0 + chunk, n - 1)  # intervals [i0, i1), knots i0..i1
        j0, j1 = max(0, i0 - SPLINE_OVERLAP), min(n, i1 + 1 + SPLINE_OVERLAP)
        idx = np.arange(j0, j1)
        xs = idx * step + x_min  # np.linspace's arithmetic, its last value exact
        if j1 == n:
            xs[-1] = x_max
        knots = x_min + h * idx
        spline = CubicSpline(knots, irr(xs))
        c = spline.c[:, i0 - j0:i1 - j0]
        # r'' at a knot is 2 c_2 of its interval, at the last knot the last interval's end
        k = int(np.argmax(c[1]))
        worst, at = float(2.0 * c[1, k]), float(knots[i0 - j0 + k])
        if i1 == n - 1:
            end = float(spline(knots[-1], 2))
            if end > worst:
                worst, at = end, float(knots[-1])
        yield i0, c, worst, at
        del spline, c  # one chunk's spline alive at a time


def spline_table(irr: Irregularity, x_min: float, x_max: float, dx: float, *,
                 chunk: int = SPLINE_CHUNK) -> tuple[float, float, np.ndarray, float, float]:
    """The kernel's rail profile: the not-a-knot cubic spline through the samples of
    ``irr.table`` (unfiltered) at the knots X_i = x0 + i h, as (x0 [m], h [m], c, worst
    curvature [1/m], its X [m]) with c of shape (4, n - 1) holding scipy's PPoly
    coefficients (highest power first) of each interval, and the largest r'' of the spline
    at its knots (where a cubic's r'' is extreme on a grid this fine) and where it is.
    Assembled from :func:`spline_chunks`."""
    x0, h, n = spline_grid(irr, x_min, x_max, dx)
    c = np.empty((4, n - 1))
    worst, at = -math.inf, x0
    for i0, cc, w, x in spline_chunks(irr, x_min, x_max, dx, chunk=chunk):
        c[:, i0:i0 + cc.shape[1]] = cc
        if w > worst:
            worst, at = w, x
    return x0, h, c, worst, at


# --------------------------------------------------------------------------------------------
# the kernel's profiles
def rail_profile(scene: Scene, end: float | None = None, shift: float = 0.0) -> _core.Profile:
    """The scene's rail profile as the kernel's piecewise cubic over [0, L] (or [0, ``end``]
    [m]; none: empty), patch-filtered if ``scene.contact.patch_filter``, as a function of
    X - ``shift`` [m].

    A table of more than STREAM_MIN_CHUNKS chunks of SPLINE_CHUNK intervals (a travelling
    window's run over hundreds of metres) is streamed: the kernel draws its chunks as the
    vehicle advances and keeps those within :func:`stream_retention` behind the leading
    wheel, so its memory does not grow with the distance.

    Raises ValueError where the profile curves upwards more sharply than the wheel (r'' >=
    1/rho0, e.g. a dipped joint's cusp): the wheel would bridge the dip on two points, which
    the single contact point of the model cannot represent. A streamed profile raises it
    where the run reaches the chunk that holds the point.
    """
    irr = scene.irregularity
    if irr is None or not irr.parts:
        return _core.Profile()
    dx = min(PROFILE_DX, irr.shortest_wavelength() / PROFILE_POINTS_PER_WAVELENGTH)
    end = scene.rail.length if end is None else end
    if scene.contact.patch_filter:
        x0, h, c, worst, at = _filtered_table(irr, end, dx, contact_half_width(scene))
        _check_curvature(scene, worst, at)
        return _core.Profile(x0 - shift, h, c)
    x0, h, n = spline_grid(irr, 0.0, end, dx)
    chunk = SPLINE_CHUNK  # read at each call: tests shrink it

    def chunks():
        for _, c, worst, at in spline_chunks(irr, 0.0, end, dx, chunk=chunk):
            _check_curvature(scene, worst, at)
            yield c
            del c  # the kernel has copied it

    if n - 1 > STREAM_MIN_CHUNKS * chunk:
        return _core.Profile(x0 - shift, h, n - 1, chunks, stream_retention(scene))
    # chunk by chunk into the kernel: no whole-table array in Python
    return _core.Profile(x0 - shift, h, n - 1, chunks())


@lru_cache(maxsize=4)
def rail_table(scene: Scene):
    """The rail profile's spline table over the whole rail [0, L] as :func:`rail_profile`
    gives it to the kernel (patch-filtered if ``scene.contact.patch_filter``), held whole:
    (x0 [m], h [m], c (4, n)), or None without a profile. For the statics of pieces of a long
    rail (:func:`profile_part`)."""
    irr = scene.irregularity
    if irr is None or not irr.parts:
        return None
    dx = min(PROFILE_DX, irr.shortest_wavelength() / PROFILE_POINTS_PER_WAVELENGTH)
    L = scene.rail.length
    if scene.contact.patch_filter:
        x0, h, c, _, _ = _filtered_table(irr, L, dx, contact_half_width(scene))
    else:
        x0, h, c, _, _ = spline_table(irr, 0.0, L, dx)
    return x0, h, c


def profile_part(scene: Scene, origin: float, length: float) -> _core.Profile:
    """The rail profile of the track over [origin, origin + length] [m] in the rail coordinate
    x = X - ``origin`` of a piece of the rail: the whole rail's spline (:func:`rail_table`),
    its intervals there (an empty profile without one)."""
    table = rail_table(scene)
    if table is None:
        return _core.Profile()
    x0, h, c = table
    i0 = max(0, math.floor((origin - x0) / h) - 2)
    i1 = min(c.shape[1], math.ceil((origin + length - x0) / h) + 2)
    return _core.Profile(x0 + i0 * h - origin, h, np.ascontiguousarray(c[:, i0:i1]))


def stream_retention(scene: Scene) -> float:
    """How far behind the furthest X read a streamed profile keeps its chunks [m]: the
    vehicle's span (its rear wheels read that far behind the leading one) four times over,
    at least STREAM_RETENTION; the contact point never moves back by more than a rail
    deflection's slope times the span."""
    behind, ahead = scene.active_vehicle.span
    return max(STREAM_RETENTION, 4.0 * (ahead - behind))


def _check_curvature(scene: Scene, worst: float, at: float) -> None:
    if worst >= 1.0 / scene.wheel.radius:
        raise ValueError(
            f"Scene.irregularity curves upwards by {worst:.3g} 1/m at X = {at:.4g} m, more "
            f"than the wheel's 1/rho0 = {1 / scene.wheel.radius:.3g} 1/m: the wheel would "
            "bridge it on two points, which one contact point cannot represent; allowed: "
            "r'' < 1/rho0 (round the profile, or set Contact(patch_filter=True) to average it "
            "over the contact patch)")


def _filtered_table(irr, end: float, dx: float, half_width: float):
    """:func:`spline_table`'s tuple for the patch-filtered profile, the spline
    through all samples at once (the filter's running integral spans the whole table)."""
    from scipy.interpolate import CubicSpline

    x0, h, r = irr.table(0.0, end, dx, half_width=half_width)
    x = x0 + h * np.arange(r.size)
    spline = CubicSpline(x, r)
    curvature = spline(x, 2)
    worst = int(np.argmax(curvature))
    return x0, h, spline.c, float(curvature[worst]), float(x[worst])


@lru_cache(maxsize=64)
def defects_profile(defects: tuple, rho0: float) -> _core.Profile:
    """The wheel ``defects`` summed as the kernel's periodic piecewise cubic Delta rho(psi) on a
    wheel of radius ``rho0`` [m] (none: empty)."""
    # cached: wheel_params is built several times per run (start, step, kernel call) and for
    # every static solve, and the spline is the same each time
    if not defects:
        return _core.Profile()
    from scipy.interpolate import CubicSpline

    n = max(64, math.ceil(2.0 * math.pi * rho0 / WHEEL_ARC_STEP))
    drho = sum(d.table(rho0, n)[2] for d in defects)
    psi = 2.0 * math.pi * np.arange(n + 1) / n
    spline = CubicSpline(psi, np.append(drho, drho[0]), bc_type="periodic")
    return _core.Profile(0.0, 2.0 * math.pi / n, spline.c)


def radius_change_at_start(scene: Scene) -> float:
    """Delta rho [m] at psi = 0, where the wheel stands at the start (theta = 0)."""
    return float(sum(d.delta_rho(0.0, scene.wheel.radius) for d in scene.wheel.defects))
