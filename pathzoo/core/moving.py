"""Moving obstacles whose positions are deterministic functions of time."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numba
import numpy as np

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["MovingObstacle", "EXACT_MAX_PIECES"]

EXACT_MAX_PIECES = 4096
"""Most direction changes of an obstacle examined one by one on a single vehicle segment.

Over a longer interval (a long wait, a very slow move) the minimum distance
is bounded from below by the distance between the vehicle's segment and the
obstacle's whole route, so the cost never depends on the duration.
"""


@numba.njit(cache=True)
def _point_segment_distance(px: float, py: float, ax: float, ay: float, bx: float, by: float) -> float:
    dx, dy = bx - ax, by - ay
    dd = dx * dx + dy * dy
    u = 0.0
    if dd > 0.0:
        u = min(1.0, max(0.0, ((px - ax) * dx + (py - ay) * dy) / dd))
    return math.hypot(px - ax - u * dx, py - ay - u * dy)


@numba.njit(cache=True)
def _orient(px: float, py: float, qx: float, qy: float, rx: float, ry: float) -> float:
    return (qx - px) * (ry - py) - (qy - py) * (rx - px)


@numba.njit(cache=True)
def _segment_segment_distance(a0x, a0y, a1x, a1y, b0x, b0y, b1x, b1y) -> float:
    # 0 when the segments cross properly, else the least endpoint-to-segment distance
    o1 = _orient(a0x, a0y, a1x, a1y, b0x, b0y)
    o2 = _orient(a0x, a0y, a1x, a1y, b1x, b1y)
    o3 = _orient(b0x, b0y, b1x, b1y, a0x, a0y)
    o4 = _orient(b0x, b0y, b1x, b1y, a1x, a1y)
    if ((o1 > 0.0 and o2 < 0.0) or (o1 < 0.0 and o2 > 0.0)) and ((o3 > 0.0 and o4 < 0.0) or (o3 < 0.0 and o4 > 0.0)):
        return 0.0
    return min(
        _point_segment_distance(a0x, a0y, b0x, b0y, b1x, b1y),
        _point_segment_distance(a1x, a1y, b0x, b0y, b1x, b1y),
        _point_segment_distance(b0x, b0y, a0x, a0y, a1x, a1y),
        _point_segment_distance(b1x, b1y, a0x, a0y, a1x, a1y),
    )


@numba.njit(cache=True)
def _route_distance(cycle, p0x, p0y, p1x, p1y) -> float:
    # least distance between the vehicle's segment and any point of the obstacle's route: a lower bound
    best = math.inf
    for k in range(cycle.shape[0] - 1):
        d = _segment_segment_distance(p0x, p0y, p1x, p1y, cycle[k, 0], cycle[k, 1], cycle[k + 1, 0], cycle[k + 1, 1])
        best = min(best, d)
    return best


@numba.njit(cache=True)
def _min_distance(cycle, cum, speed, phase, p0x, p0y, p1x, p1y, t0, t1, max_pieces):
    # exact minimum distance between a disc centre on its cycle and a vehicle moving
    # linearly from p0 at t0 to p1 at t1; a lower bound when the interval is too long
    k_count = cycle.shape[0]
    total = cum[k_count - 1]
    if t1 <= t0:  # no time passes: the vehicle is at p0 (moving in no time breaks the speed rule)
        p1x, p1y, t1 = p0x, p0y, t0
    if total == 0.0 or speed == 0.0:
        return _point_segment_distance(cycle[0, 0], cycle[0, 1], p0x, p0y, p1x, p1y)
    period = total / speed
    s = ((t0 + phase) * speed) % total
    if (t1 - t0) / period * (k_count - 1) > max_pieces or not math.isfinite(s):
        # too many pieces (or a time beyond float range): the distance to the whole route bounds it
        return _route_distance(cycle, p0x, p0y, p1x, p1y)
    k = 0
    while k < k_count - 2 and cum[k + 1] <= s:
        k += 1
    # rounding of the obstacle's position grows with the time: subtract a bound on it
    rounding = 1e-15 * ((abs(t0) + abs(t1) + abs(phase)) * speed + total)
    ta = t0
    best = math.inf
    for _ in range(max_pieces + 2 * k_count):  # a bound on the loop even when rounding stalls time
        seg_len = cum[k + 1] - cum[k]
        tb = min(t1, ta + (cum[k + 1] - s) / speed)
        sb = s + (tb - ta) * speed
        fa = 0.0 if seg_len == 0.0 else (s - cum[k]) / seg_len
        fb = 0.0 if seg_len == 0.0 else min(1.0, (sb - cum[k]) / seg_len)
        oax = cycle[k, 0] + fa * (cycle[k + 1, 0] - cycle[k, 0])
        oay = cycle[k, 1] + fa * (cycle[k + 1, 1] - cycle[k, 1])
        obx = cycle[k, 0] + fb * (cycle[k + 1, 0] - cycle[k, 0])
        oby = cycle[k, 1] + fb * (cycle[k + 1, 1] - cycle[k, 1])
        if t1 > t0:
            ga, gb = (ta - t0) / (t1 - t0), (tb - t0) / (t1 - t0)
        else:
            ga, gb = 0.0, 0.0
        vax, vay = p0x + ga * (p1x - p0x), p0y + ga * (p1y - p0y)
        vbx, vby = p0x + gb * (p1x - p0x), p0y + gb * (p1y - p0y)
        # relative motion is linear on [ta, tb]: distance from the origin to the segment rel_a -> rel_b
        best = min(best, _point_segment_distance(0.0, 0.0, vax - oax, vay - oay, vbx - obx, vby - oby))
        if tb >= t1:
            return max(0.0, best - rounding)
        ta = tb
        k += 1
        s = cum[k]
        if k == k_count - 1:
            k = 0
            s = 0.0
    return _route_distance(cycle, p0x, p0y, p1x, p1y)


@numba.njit(cache=True)
def _min_distances(cycle, cum, speed, phase, p0, p1, t0, t1, max_pieces):
    out = np.empty(p0.shape[0])
    for i in range(p0.shape[0]):
        out[i] = _min_distance(cycle, cum, speed, phase, p0[i, 0], p0[i, 1], p1[i, 0], p1[i, 1], t0[i], t1[i], max_pieces)
    return out


@dataclass(frozen=True, eq=False)
class MovingObstacle:
    """A disc that moves at constant speed along a polyline.

    Parameters
    ----------
    radius : float
        Disc radius in metres. A vehicle closer than this to the centre collides.
    waypoints : ndarray of shape (K, 2)
        World coordinates of the polyline, K >= 2 (K == 1 for a parked obstacle).
    speed : float
        Speed in m/s along the polyline.
    mode : {"pingpong", "loop"}
        ``pingpong`` goes back and forth; ``loop`` returns to the first
        waypoint and starts again.
    phase_s : float
        Time offset: the position at time ``t`` is the polyline position at
        ``t + phase_s``.
    """

    radius: float
    waypoints: np.ndarray
    speed: float
    mode: Literal["pingpong", "loop"] = "pingpong"
    phase_s: float = 0.0

    def __post_init__(self) -> None:
        wp = np.array(self.waypoints, dtype=np.float64)
        if wp.ndim != 2 or wp.shape[1] != 2 or len(wp) < 1 or not np.isfinite(wp).all():
            raise InvalidScenarioError("waypoints must be a finite (K, 2) array", field="moving_obstacles.waypoints")
        if not (self.radius > 0 and np.isfinite(self.radius)):
            raise InvalidScenarioError(f"must be > 0, got {self.radius!r}", field="moving_obstacles.radius")
        if not (self.speed >= 0 and np.isfinite(self.speed)):
            raise InvalidScenarioError(f"must be >= 0, got {self.speed!r}", field="moving_obstacles.speed")
        if self.mode not in ("pingpong", "loop"):
            raise InvalidScenarioError(f"must be 'pingpong' or 'loop', got {self.mode!r}", field="moving_obstacles.mode")
        if self.mode == "loop" and len(wp) > 1:
            wp = np.vstack([wp, wp[:1]])
        elif self.mode == "pingpong" and len(wp) > 1:
            wp = np.vstack([wp, wp[-2::-1]])
        wp.setflags(write=False)
        seg = np.linalg.norm(np.diff(wp, axis=0), axis=1)
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        cum.setflags(write=False)
        object.__setattr__(self, "_cycle", wp)
        object.__setattr__(self, "_cum", cum)

    @property
    def cycle(self) -> tuple[np.ndarray, np.ndarray]:
        """The closed route driven once per period: points ``(K', 2)`` and their cumulative distance ``(K',)`` in metres."""
        return self._cycle, self._cum

    @property
    def period_s(self) -> float:
        """Time for one full cycle (``inf`` for a parked obstacle)."""
        total = float(self._cum[-1])
        if total == 0.0 or self.speed == 0.0:
            return float("inf")
        return total / self.speed

    def position(self, t: np.ndarray | float) -> np.ndarray:
        """Centre position(s) at time(s) ``t``; shape ``t.shape + (2,)``."""
        t = np.asarray(t, dtype=np.float64)
        period = self.period_s
        if not np.isfinite(period):
            return np.broadcast_to(self._cycle[0], t.shape + (2,)).copy()
        s = np.mod((t + self.phase_s) * self.speed, self._cum[-1])
        x = np.interp(s, self._cum, self._cycle[:, 0])
        y = np.interp(s, self._cum, self._cycle[:, 1])
        return np.stack([x, y], axis=-1)

    def min_distance(self, p0: np.ndarray, p1: np.ndarray, t0: float, t1: float) -> float:
        """Minimum distance to a vehicle moving linearly from ``p0`` at ``t0`` to ``p1`` at ``t1``.

        Both motions are piecewise linear in time, so the relative position is
        linear between the obstacle's direction changes and its minimum norm
        has a closed form on each piece: the result is exact. When the interval
        holds more than :data:`EXACT_MAX_PIECES` direction changes, it is the
        distance between the vehicle's segment and the obstacle's whole route,
        a lower bound (exact for a vehicle waiting a full period or more).
        """
        return float(self.min_distances(np.reshape(p0, (1, 2)), np.reshape(p1, (1, 2)), np.array([t0]), np.array([t1]))[0])

    def min_distances(self, p0: np.ndarray, p1: np.ndarray, t0: np.ndarray, t1: np.ndarray) -> np.ndarray:
        """:meth:`min_distance` for many vehicle segments at once (one compiled pass).

        Parameters
        ----------
        p0, p1 : ndarray of shape (n, 2)
            Ends of the vehicle's segments, world coordinates.
        t0, t1 : ndarray of shape (n,)
            Departure and arrival times.
        """
        return _min_distances(
            self._cycle, self._cum, float(self.speed), float(self.phase_s),
            np.ascontiguousarray(p0, dtype=np.float64), np.ascontiguousarray(p1, dtype=np.float64),
            np.ascontiguousarray(t0, dtype=np.float64), np.ascontiguousarray(t1, dtype=np.float64), EXACT_MAX_PIECES,
        )
