"""Where a run starts and ends: the wheel-centre (or the vehicle's reference point) start X_0
[m] and the simulated time [s] from the start and either the end, the distance or the duration,
checked against the rail; on a travelling window the track is unbounded ahead, and
:func:`window_params` places the window.
"""

from __future__ import annotations

import math

from .. import _core
from ..base import validate as v
from ..scene import Scene
from .stretch import default_end, default_start, start_position


def _end_of(x0: float, x_end, distance):
    """``x_end``, or ``x0 + distance`` [m] from the resolved start ``x0`` (one of them)."""
    if distance is None:
        return x_end
    if x_end is not None:
        raise ValueError("give x_end or distance, not both")
    return x0 + v.number("distance", distance, low=0.0, low_open=True, unit="m")


def _window_passage(scene: Scene, speed: float, x_start, x_end, duration, distance):
    """(X_0, time) on a travelling window: the track is unbounded ahead, X >= 0 for every
    wheel; default start: the rear wheel in the middle of the first bay; default end: one
    window length on."""
    rear, _ = scene.active_vehicle.span
    lo = -rear
    x0 = 0.5 * scene.supports.spacing - rear if x_start is None else v.number(
        "x_start", x_start, low=lo, unit="m")
    if duration is not None:
        return x0, v.number("duration", duration, low=0.0, low_open=True, unit="s")
    if speed == 0.0:
        raise ValueError("speed = 0: give duration [s] (x_end cannot be reached)")
    if distance is not None:
        x1 = x0 + v.number("distance", distance, low=0.0, low_open=True, unit="m")
        if x_end is not None:
            raise ValueError("give x_end or distance, not both")
    else:
        x1 = x0 + scene.rail.length if x_end is None else v.number(
            "x_end", x_end, low=lo, unit="m")
    if x1 <= x0:
        raise ValueError(f"x_end = {x1} m must be greater than x_start = {x0} m")
    return x0, (x1 - x0) / speed


def window_params(scene: Scene, ne: int, x0: float):
    """The kernel's window for a run of ``scene`` on ``ne`` elements from X_0 = ``x0``: the
    rear wheel held in the bay after ``bays_behind`` bays; the origin a whole number of bays,
    so the supports stand where they stand on a fixed rail from X = 0."""
    w, d = scene.window, scene.supports.spacing
    rear, _ = scene.active_vehicle.span
    n_bays = round(scene.rail.length / d)
    if ne % n_bays:
        raise ValueError(f"n_elements = {ne} must be a multiple of the window's {n_bays} bays "
                         "(a whole number of elements per bay)")
    p = _core.WindowParams()
    p.bay = d
    p.elements_per_bay = ne // n_bays
    p.hold = (w.bays_behind + 1) * d
    p.origin = (math.floor((x0 + rear) / d + 1e-9) - w.bays_behind) * d
    return p


def passage(scene: Scene, speed: float, x_start, x_end, duration,
             distance=None) -> tuple[float, float]:
    """(X_0 [m], simulated time [s]) from the start and either the end, the distance or the
    duration."""
    if scene.window is not None:
        return _window_passage(scene, speed, x_start, x_end, duration, distance)
    L = scene.rail.length
    rear, front = scene.active_vehicle.span
    if distance is not None:
        x_end = _end_of(start_position(scene, x_start) if scene.vehicle is None else (
            default_start(scene) - rear if x_start is None else x_start), x_end, distance)
    if scene.vehicle is not None:
        return _vehicle_passage(scene, speed, x_start, x_end, duration, rear, front)
    x0 = start_position(scene, x_start)
    x1 = default_end(scene, x0) if x_end is None and duration is None else x_end
    return x0, _time_to_end(scene, speed, x0, x1, duration, (0.0, L), 0.0)


def _vehicle_passage(scene: Scene, speed: float, x_start, x_end, duration, rear: float,
                     front: float) -> tuple[float, float]:
    """(X_0, time) for a vehicle: X_0 places its reference point (x = 0); every wheel must stay
    on the rail. Defaults: the rear wheel starts in the middle of the first support bay, the
    leading wheel ends in the middle of the last."""
    L = scene.rail.length
    lo, hi = -rear, L - front
    if hi < lo:
        raise ValueError(f"the vehicle's wheels span {front - rear:.4g} m, longer than the "
                         f"rail ({L} m): lengthen Scene.rail.length")
    x0 = default_start(scene) - rear if x_start is None else v.number(
        "x_start", x_start, low=lo, high=hi, unit="m")
    x1 = (max(default_end(scene, x0 + front) - front, x0)
          if x_end is None and duration is None else x_end)
    return x0, _time_to_end(scene, speed, x0, x1, duration, (lo, hi), front)


def _time_to_end(scene: Scene, speed: float, x0: float, x_end, duration,
                 allowed: tuple[float, float], front: float) -> float:
    """Simulated time [s] from X_0 = ``x0`` to ``x_end`` (validated in ``allowed`` [m]) or for
    ``duration`` [s], checking that the leading wheel, ``front`` [m] ahead of X_0, stays on
    the rail."""
    lo, hi = allowed
    L, who = scene.rail.length, "wheel" if scene.vehicle is None else "leading wheel"
    if duration is not None:
        t_end = v.number("duration", duration, low=0.0, low_open=True, unit="s")
        if x0 + speed * t_end > hi:
            raise ValueError(f"duration = {duration} s takes the {who} to X = "
                             f"{x0 + front + speed * t_end:.4g} m, beyond the rail end {L} m")
        return t_end
    if speed == 0.0:
        raise ValueError("speed = 0: give duration [s] (x_end cannot be reached)")
    x1 = v.number("x_end", x_end, low=lo, high=hi, unit="m")
    if x1 <= x0:
        room = ("" if scene.vehicle is None else " (the rail leaves the vehicle no room to "
                f"move; allowed x range [{lo:.4g}, {hi:.4g}] m)")
        raise ValueError(f"x_end = {x1} m must be greater than x_start = {x0} m{room}")
    return (x1 - x0) / speed
