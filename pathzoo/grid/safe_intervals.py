"""Safe intervals of a cell centre and the earliest safe departure along an edge, among known moving obstacles (numba).

Both answer the question the judge asks of a timed path
(:func:`pathzoo.rules.timing.timed_path_problem`): does the vehicle come
closer to a moving disc than its radius plus a margin?

- :func:`stationary_unsafe_times` solves it in closed form for a vehicle
  waiting at one point: the obstacle moves linearly on each piece of its
  route, so the squared distance is a quadratic in time on each piece.
- :func:`safe_intervals` is the complement over all obstacles: the maximal
  times a vehicle may wait at a point;
- :func:`earliest_free_departure` finds the earliest departure time, within a
  window, at which driving a straight edge in a given time keeps clear of
  every obstacle. It asks the judge's own distance function
  (:func:`pathzoo.core.moving_distance.min_distances`) with the very numbers
  the returned path will carry, so a departure it accepts is one the judge
  accepts. The clearance ``f(t)`` of a departure at ``t`` changes at most as
  fast as the obstacle moves (``|f(t + h) - f(t)| <= w h``, ``w`` the
  obstacle's speed), so from a colliding departure no departure earlier than
  ``t + (r - f(t)) / w`` can be clear: the sweep jumps by that much, and by at
  least ``min_step`` seconds.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo.core.moving import EXACT_MAX_PIECES
from pathzoo.core.moving_distance import _point_segment_distance, _route_distance, min_distances

__all__ = ["ObstacleArrays", "obstacle_arrays", "stationary_unsafe_times", "safe_intervals", "route_distance",
           "earliest_free_departure"]


class ObstacleArrays:
    """The moving obstacles of a scenario packed for the compiled functions.

    Attributes
    ----------
    cycles : ndarray (P, 2)
        The closed routes of all obstacles, one after another.
    cums : ndarray (P,)
        Cumulative arc length along each route.
    bounds : ndarray of int64 (K + 1,)
        Obstacle ``k`` owns rows ``bounds[k]:bounds[k + 1]``.
    speeds, phases, radii : ndarray (K,)
        Speed (m/s), time offset (s), and radius plus the judge's margin (m).
    """

    def __init__(self, cycles: np.ndarray, cums: np.ndarray, bounds: np.ndarray, speeds: np.ndarray,
                 phases: np.ndarray, radii: np.ndarray) -> None:
        self.cycles, self.cums, self.bounds = cycles, cums, bounds
        self.speeds, self.phases, self.radii = speeds, phases, radii


def obstacle_arrays(obstacles: tuple, margin: float) -> ObstacleArrays:
    """Pack ``scenario.moving_obstacles``; each radius is increased by ``margin`` (the judge's touch margin)."""
    cycles = [ob.cycle[0] for ob in obstacles]
    cums = [ob.cycle[1] for ob in obstacles]
    bounds = np.concatenate([[0], np.cumsum([len(c) for c in cycles])]).astype(np.int64)
    empty = np.zeros((0, 2))
    return ObstacleArrays(
        np.ascontiguousarray(np.concatenate(cycles) if cycles else empty, dtype=np.float64),
        np.ascontiguousarray(np.concatenate(cums) if cums else np.zeros(0), dtype=np.float64),
        bounds,
        np.array([float(ob.speed) for ob in obstacles], dtype=np.float64),
        np.array([float(ob.phase_s) for ob in obstacles], dtype=np.float64),
        np.array([float(ob.radius) + margin for ob in obstacles], dtype=np.float64),
    )


@numba.njit(cache=True)
def route_distance(cycle: np.ndarray, p0x: float, p0y: float, p1x: float, p1y: float) -> float:
    """Least distance between the segment ``p0 -> p1`` and an obstacle's route: a bound that holds at every time."""
    if cycle.shape[0] == 1:
        return _point_segment_distance(cycle[0, 0], cycle[0, 1], p0x, p0y, p1x, p1y)
    return _route_distance(cycle, p0x, p0y, p1x, p1y)


@numba.njit(cache=True)
def stationary_unsafe_times(cycle: np.ndarray, cum: np.ndarray, speed: float, phase: float, cx: float, cy: float,
                            radius: float, horizon: float) -> np.ndarray:
    """Time intervals within ``[0, horizon]`` when the obstacle is closer than ``radius`` to the point ``(cx, cy)``.

    Returns an array ``(m, 2)`` of closed intervals in increasing order (they
    may touch). A parked obstacle gives ``[[0, horizon]]`` or nothing.
    """
    out = np.empty((0, 2))
    total = cum[cum.shape[0] - 1]
    if total == 0.0 or speed == 0.0:
        if math.hypot(cycle[0, 0] - cx, cycle[0, 1] - cy) < radius:
            out = np.array([[0.0, horizon]])
        return out
    if route_distance(cycle, cx, cy, cx, cy) >= radius:
        return out
    period = total / speed
    pieces = []
    n = math.floor(phase / period)  # the period in progress at t = 0 starts at n * period - phase <= 0
    start = n * period - phase
    while start <= horizon:
        for j in range(cycle.shape[0] - 1):
            seg = cum[j + 1] - cum[j]
            if seg == 0.0:
                continue
            t_a = start + cum[j] / speed
            t_b = start + cum[j + 1] / speed
            if t_b < 0.0 or t_a > horizon:
                continue
            ux, uy = (cycle[j + 1, 0] - cycle[j, 0]) / seg, (cycle[j + 1, 1] - cycle[j, 1]) / seg
            qx, qy = cycle[j, 0] - cx, cycle[j, 1] - cy
            # |q + u w tau|^2 < r^2  <=>  w^2 tau^2 + 2 w (u.q) tau + |q|^2 - r^2 < 0
            b = speed * (ux * qx + uy * qy)
            c = qx * qx + qy * qy - radius * radius
            disc = b * b - speed * speed * c
            if disc <= 0.0:
                continue
            root = math.sqrt(disc)
            lo = t_a + (-b - root) / (speed * speed)
            hi = t_a + (-b + root) / (speed * speed)
            lo, hi = max(lo, t_a, 0.0), min(hi, t_b, horizon)
            if lo <= hi:
                pieces.append((lo, hi))
        start += period
    if len(pieces) == 0:
        return out
    out = np.empty((len(pieces), 2))
    for i in range(len(pieces)):
        out[i, 0], out[i, 1] = pieces[i]
    return out


@numba.njit(cache=True)
def earliest_free_departure(cycles: np.ndarray, cums: np.ndarray, bounds: np.ndarray, speeds: np.ndarray,
                            phases: np.ndarray, radii: np.ndarray, p0x: float, p0y: float, p1x: float, p1y: float,
                            duration: float, lo: float, hi: float, min_step: float, max_steps: int) -> float:
    """Earliest departure ``t`` in ``[lo, hi]`` such that driving ``p0 -> p1`` during ``[t, t + duration]`` is clear.

    Clear means: the judge's minimum distance to every obstacle is at least
    its ``radii`` entry (radius plus margin). Returns -1 when no departure in
    the window is clear, or when ``max_steps`` looks did not settle it.
    Departures clear for less than ``min_step`` seconds can be stepped over.
    """
    n_obs = speeds.shape[0]
    relevant = np.zeros(n_obs, dtype=np.bool_)
    any_relevant = False
    for k in range(n_obs):
        cyc = cycles[bounds[k]:bounds[k + 1]]
        # a relative 1e-9 more than the radius: the two distance computations round differently
        if route_distance(cyc, p0x, p0y, p1x, p1y) < radii[k] * (1.0 + 1e-9) + 1e-12:
            relevant[k] = True
            any_relevant = True
    if not any_relevant:
        return lo if lo <= hi else -1.0
    p0 = np.array([[p0x, p0y]])
    p1 = np.array([[p1x, p1y]])
    t0 = np.empty(1)
    t1 = np.empty(1)
    t = lo
    for _ in range(max_steps):
        if t > hi:
            return -1.0
        t0[0] = t
        t1[0] = t + duration
        jump = 0.0
        for k in range(n_obs):
            if not relevant[k]:
                continue
            a, b = bounds[k], bounds[k + 1]
            d = min_distances(cycles[a:b], cums[a:b], speeds[k], phases[k], p0, p1, t0, t1, EXACT_MAX_PIECES)[0]
            if d < radii[k]:
                if speeds[k] == 0.0 or cums[b - 1] == 0.0:
                    return -1.0  # a parked obstacle never leaves
                jump = max(jump, (radii[k] - d) / speeds[k])
        if jump == 0.0:
            return t
        t += max(jump, min_step)
    return -1.0


def safe_intervals(obs: ObstacleArrays, point: np.ndarray, slack: float, horizon: float) -> np.ndarray:
    """Maximal intervals of ``[0, horizon]`` when a vehicle waiting at ``point`` is clear of every obstacle.

    Returns ``(m, 2)`` closed intervals ``[start, end]`` in increasing order,
    computed with every radius increased by ``slack`` metres.
    """
    unsafe = [stationary_unsafe_times(obs.cycles[obs.bounds[k]:obs.bounds[k + 1]], obs.cums[obs.bounds[k]:obs.bounds[k + 1]],
                                      float(obs.speeds[k]), float(obs.phases[k]), float(point[0]), float(point[1]),
                                      float(obs.radii[k]) + slack, horizon)
              for k in range(len(obs.speeds))]
    bad = np.concatenate(unsafe) if unsafe else np.zeros((0, 2))
    if len(bad) == 0:
        return np.array([[0.0, horizon]])
    bad = bad[np.argsort(bad[:, 0], kind="stable")]
    out: list[tuple[float, float]] = []
    free_from = 0.0
    for lo, hi in bad:
        if lo > free_from:
            out.append((free_from, float(np.nextafter(lo, -math.inf))))
        free_from = max(free_from, float(np.nextafter(hi, math.inf)))
    if free_from <= horizon:
        out.append((free_from, horizon))
    return np.array(out, dtype=np.float64).reshape(-1, 2)
