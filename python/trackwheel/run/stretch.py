"""The stretch of a run: where it starts and ends by default and which part of it
``trackwheel.analyse`` measures, clear of the rail's rigid ends and of the start-up transient
(docs: Model § Outputs, "What is measured").

A finite rail rests on rigid supports at its ends, where the track is stiffer, and a run starts
from the static state, not the moving one: both put into a record what a wheel on a long track at
constant speed does not see. :func:`end_clearance` is how far a wheel keeps from a rail end,
:func:`startup_length` how long the start-up rings, :func:`measured_stretch` the part of a run
measured; on a rail too short to leave a stretch clear of its ends (the paper's 5 m), runs cover
and are measured over the whole rail, as the paper does.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from .. import _core
from ..base import validate as v
from ..scene import Scene
from . import kernel
from .defaults import MeshWarning, check_speed, frequency_mesh, highest_frequency

__all__ = ["END_DECAY", "STARTUP_DECAY", "clear_stretch", "default_end", "default_start",
           "end_clearance", "measured_stretch", "start_position", "startup_length"]

#: The rail's rigid end changes the static deflection under the wheel by less than this
#: fraction of it beyond :func:`end_clearance` [-].
END_DECAY = 1e-3
#: The start-up transient of a run has decayed to this fraction where the measured stretch
#: begins, one decay time of the wheel's bounce on the track (see :func:`startup_length`) [-].
STARTUP_DECAY = math.exp(-1.0)


def end_clearance(scene: Scene) -> float:
    """Distance from a rigid rail end [m] beyond which a wheel's static deflection bowl no
    longer reaches the end: the bowl of a load on the track (a beam on the supports' static
    stiffness per length k_f) decays as exp(-beta x) (cos beta x + sin beta x),
    beta = (k_f / 4 EI)^(1/4), so at ln(1 / END_DECAY) / beta it is below END_DECAY of its
    peak (and the end's reaction changes the deflection under the wheel by about END_DECAY^2).
    4.8 m on the ballasted preset, 3.8 m on the paper's track; infinite on a rail without
    supports. Supports that vary along X: the softest one's k_f (its bowl reaches furthest)."""
    n = len(scene.support_positions)
    # supports that vary along X: the softest support's bowl, the widest
    k_f = float(np.min(scene.support_values.static_stiffness, initial=np.inf)) * n / (
        scene.rail.length) if n else 0.0
    if k_f <= 0.0:
        return math.inf
    beta = (k_f / (4.0 * scene.rail.bending_stiffness)) ** 0.25
    return math.log(1.0 / END_DECAY) / beta


def clear_stretch(scene: Scene) -> tuple[float, float] | None:
    """(first, last) bay middle [m] at least :func:`end_clearance` from both rail ends, between
    which the vehicle's rear wheel starts and its leading wheel ends; None if the fixed rail
    leaves less than one support bay between its clearances for the vehicle (the paper's 5 m
    rail: then a run covers the whole rail, and is measured whole, as the paper does) or on
    a travelling window (no rail ends)."""
    if scene.window is not None:
        return None
    d, L = scene.supports.spacing, scene.rail.length
    rear, front = scene.active_vehicle.span
    c = end_clearance(scene)
    if not math.isfinite(c) or L - (front - rear) - 2.0 * c < d:
        return None
    first = (math.ceil(c / d - 0.5 - 1e-9) + 0.5) * d
    last = (math.floor((L - c) / d - 0.5 + 1e-9) + 0.5) * d
    if last - first < (front - rear) + d * (1.0 - 1e-9):
        return None
    return first, last


def default_start(scene: Scene) -> float:
    """Default start of the rear (or only) wheel's centre [m]: the middle of the first support
    bay clear of the rail's end (:func:`clear_stretch`: 5.1 m on the ballasted preset), or, on
    a rail too short for that, the middle of the first bay, d_s / 2 (0.25 m for the paper's
    scene; the middle of the rail if it is shorter than a bay)."""
    clear = clear_stretch(scene)
    if clear is not None:
        return clear[0]
    half_bay = 0.5 * scene.supports.spacing
    return half_bay if half_bay < scene.rail.length else 0.5 * scene.rail.length


def default_end(scene: Scene, x_start: float) -> float:
    """Default end of the leading (or only) wheel's centre [m]: the middle of the last bay
    clear of the rail's end (:func:`clear_stretch`: 24.9 m on the ballasted preset), or of the
    last bay, L - d_s / 2 (4.75 m for the paper's scene); not before ``x_start`` [m]."""
    clear = clear_stretch(scene)
    end = clear[1] if clear is not None else scene.rail.length - 0.5 * scene.supports.spacing
    return max(end, x_start)


def start_position(scene: Scene, x_start) -> float:
    """``x_start`` [m] checked against the rail, or :func:`default_start` if None."""
    if x_start is None:
        return default_start(scene)
    return v.number("x_start", x_start, low=0.0, high=scene.rail.length, unit="m")


def startup_length(scene: Scene, speed: float) -> float:
    """Distance [m] over which the start-up transient of a run at ``speed`` [m/s] decays to
    STARTUP_DECAY = 1/e of its start: one decay length v / (zeta w). A run starts from the
    static state, not the moving one, and the difference rings out at the decay rate zeta w of
    the wheel's bounce on the track (the P2 resonance), the most lightly damped wheel/track
    mode. zeta w is half the half-power bandwidth of the lowest peak of the wheel's
    response on the track, |1 / (-M w^2 + 1 / (1/k + alpha(w)))| with the track's point
    receptance alpha at a mid-span (:func:`trackwheel.receptance` on :func:`frequency_mesh`):
    57 Hz and zeta w = 19 1/s on the ballasted preset, so 4.4 m at 300 km/h (the run's dynamic
    factor measured from there is within 0.4 % of the steady one at 300-400 km/h). Infinite
    where the peak has no half-power band within 1 Hz .. 1.5 x :func:`highest_frequency` (an
    undamped track never settles); 0 at speed 0."""
    speed = check_speed(speed)
    if speed == 0.0:
        return 0.0
    rate = _bounce_decay_rate(scene)
    return math.inf if rate <= 0.0 else speed * math.log(1.0 / STARTUP_DECAY) / rate


def _bounce_decay_rate(scene: Scene) -> float:
    """zeta w [1/s] of the wheel's bounce on the track (see :func:`startup_length`), 0 if none
    is found."""
    f_hi = highest_frequency(scene)
    f = np.geomspace(1.0, 1.5 * f_hi, 1500)
    track = scene if scene.window is None else scene.windowed(None)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        ne = frequency_mesh(track, f[-1])
    pos = np.asarray(track.support_positions)
    x = 0.5 * track.rail.length
    if pos.size:
        j = int(np.argmin(np.abs(pos - x)))
        nxt = pos[j + 1] if j + 1 < pos.size else track.rail.length
        x = 0.5 * (pos[j] + nxt)
    model = kernel.rail_model(track, ne)
    try:
        a = np.asarray(_core.receptance(model, kernel.beam_params(track), [x], [x],
                                        f.tolist()))[:, 0]
    except RuntimeError:  # an undamped resonance hit exactly
        return 0.0
    w = 2.0 * math.pi * f
    h = np.abs(1.0 / (-scene.wheel.mass * w * w + 1.0 / (1.0 / scene.contact_stiffness + a)))
    peaks = np.flatnonzero((h[1:-1] > h[:-2]) & (h[1:-1] >= h[2:])) + 1
    if peaks.size == 0:
        return 0.0
    k = int(peaks[0])
    half = h[k] / math.sqrt(2.0)
    below = np.flatnonzero(h[:k] < half)
    above = np.flatnonzero(h[k:] < half)
    if below.size == 0 or above.size == 0:
        return 0.0
    lo, hi = int(below[-1]), k + int(above[0])
    # the half-power frequencies, interpolated in log |h| between the grid's points
    f_lo = np.interp(math.log(half), np.log(h[lo:lo + 2]), f[lo:lo + 2])
    f_hi_ = np.interp(math.log(half), np.log(h[hi - 1:hi + 1])[::-1], f[hi - 1:hi + 1][::-1])
    return math.pi * (f_hi_ - f_lo)


def measured_stretch(scene: Scene, speed: float, x_start: float, x_end: float
                     ) -> tuple[float, float] | None:
    """The part of a run [m] that ``trackwheel.analyse`` measures by default, as positions of
    the vehicle's reference point (the one wheel's centre), for a run from ``x_start`` to
    ``x_end`` [m] at ``speed`` [m/s]: where every wheel is at least :func:`end_clearance` from
    both rail ends (on a travelling window: everywhere), from :func:`startup_length` after
    the start on -- or, where that leaves less than a support bay (a short passage over a
    defect, say), from the start, the transient included. None (measure the whole run) where
    the fixed rail is too short to leave a bay clear of its ends (the paper's scene: measured
    whole, as the paper does), where less than a bay of the run is clear of them, or at speed
    0."""
    d = scene.supports.spacing
    lo, hi = x_start, x_end
    if scene.window is None:
        if clear_stretch(scene) is None:
            return None
        rear, front = scene.active_vehicle.span
        c = end_clearance(scene)
        lo, hi = max(lo, c - rear), min(hi, scene.rail.length - c - front)
    if hi - lo < d * (1.0 - 1e-9):
        return None
    after = x_start + startup_length(scene, speed)
    return (max(lo, after) if hi - after >= d * (1.0 - 1e-9) else lo), hi
