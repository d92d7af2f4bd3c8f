"""Timed paths: their times, the cruise speed and the moving obstacles.

A timed path is driven linearly between waypoints: the vehicle is at
``path[k]`` at ``times[k]``. Before its first time it **waits at its first
point from time 0**, so a late start is checked like any other wait. Every
moving obstacle must stay farther than its radius plus the margin
``TOUCH_EPS_CELLS * cell_size`` from the vehicle at every instant of
``[0, times[-1]]``; the distance is exact (or, on a very long interval, a lower
bound that does not depend on the duration; see
:meth:`pathzoo.core.moving.MovingObstacle.min_distances`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pathzoo.core.tolerances import SPEED_ROUNDING, TOUCH_EPS_CELLS
from pathzoo.rules.wording import fmt_point

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["path_times", "times_problem", "obstacle_problem", "timed_path_problem"]


def path_times(scenario: "Scenario", path: np.ndarray) -> np.ndarray:
    """Arrival times when driving the path at cruise speed from time 0 without stopping."""
    if len(path) < 2:
        return np.zeros(len(path))
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    return np.concatenate([[0.0], np.cumsum(seg)]) / scenario.vehicle.cruise_speed


def times_problem(scenario: "Scenario", path: np.ndarray, times: object) -> tuple[str | None, np.ndarray]:
    """Check planner-given times; return ``(reason or None, times as floats)``."""
    try:
        t = np.asarray(times, dtype=np.float64).reshape(-1)
    except (TypeError, ValueError):
        return "times is not a numeric array", np.zeros(0)
    if t.shape != (len(path),) or not np.isfinite(t).all():
        return f"times must be {len(path)} finite values", t
    if t[0] < 0 or np.any(np.diff(t) < 0):
        return "times must start at >= 0 and never decrease", t
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    too_fast = seg > scenario.vehicle.cruise_speed * np.diff(t) * (1 + SPEED_ROUNDING)
    if np.any(too_fast):
        k = int(np.argmax(too_fast))
        return f"segment {k} is driven faster than cruise speed {scenario.vehicle.cruise_speed} m/s", t
    return None, t


def _reason(p0: np.ndarray, p1: np.ndarray, t0: float, t1: float, d: float, k: int, radius: float) -> str:
    motion = f"waits at {fmt_point(p0)}" if np.array_equal(p0, p1) else f"segment {fmt_point(p0)} -> {fmt_point(p1)}"
    return f"{motion} during t=[{t0:.3f}, {t1:.3f}] s comes within {d:.3f} m of moving obstacle {k} (radius {radius})"


def obstacle_problem(
    scenario: "Scenario", p0: np.ndarray, p1: np.ndarray, t0: np.ndarray, t1: np.ndarray
) -> tuple[int, str] | None:
    """First of the timed segments ``p0[i] -> p1[i]`` during ``[t0[i], t1[i]]`` that meets a moving obstacle.

    Returns ``(i, reason)`` or ``None``. One compiled pass per obstacle.
    """
    margin = TOUCH_EPS_CELLS * scenario.cell_size
    worst: tuple[int, str] | None = None
    for k, ob in enumerate(scenario.moving_obstacles):
        d = ob.min_distances(p0, p1, t0, t1)
        hit = d < ob.radius + margin
        if hit.any():
            i = int(np.argmax(hit))
            if worst is None or i < worst[0]:
                worst = (i, _reason(p0[i], p1[i], float(t0[i]), float(t1[i]), float(d[i]), k, ob.radius))
    return worst


def timed_path_problem(scenario: "Scenario", path: np.ndarray, t: np.ndarray) -> str | None:
    """Why the timed path meets a moving obstacle, counting the wait at its first point from time 0."""
    if not scenario.moving_obstacles:
        return None
    p0 = np.vstack([path[:1], path[:-1]])
    p1 = np.vstack([path[:1], path[1:]])
    t0 = np.concatenate([[0.0], t[:-1]])
    t1 = np.concatenate([[t[0]], t[1:]])
    found = obstacle_problem(scenario, p0[:, :2], p1[:, :2], t0, t1)
    if found is None:
        return None
    i, reason = found
    return reason if i == 0 else f"segment {i - 1}: {reason}"
