"""Moving obstacles whose positions are deterministic functions of time."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["MovingObstacle", "EXACT_MAX_PIECES"]

EXACT_MAX_PIECES = 4096
"""Most direction changes of an obstacle examined one by one on a single vehicle segment.

Over a longer interval (a long wait, a very slow move) the minimum distance
is bounded from below by the distance between the vehicle's segment and the
obstacle's whole route, so the cost never depends on the duration.
"""


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
    waypoints: ArrayLike
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
        self.cycle  # built now, from the waypoints as given

    @cached_property
    def cycle(self) -> tuple[np.ndarray, np.ndarray]:
        """The closed route driven once per period: points ``(K', 2)`` and their cumulative distances ``(K',)`` (m).

        Read-only arrays, kept on the instance (not a dataclass field, so
        neither the scenario's digest nor its file format sees them).
        """
        wp = np.array(self.waypoints, dtype=np.float64)
        if self.mode == "loop" and len(wp) > 1:
            wp = np.vstack([wp, wp[:1]])
        elif self.mode == "pingpong" and len(wp) > 1:
            wp = np.vstack([wp, wp[-2::-1]])
        wp.setflags(write=False)
        seg = np.linalg.norm(np.diff(wp, axis=0), axis=1)
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        cum.setflags(write=False)
        return wp, cum

    @property
    def period_s(self) -> float:
        """Time for one full cycle (``inf`` for a parked obstacle)."""
        total = float(self.cycle[1][-1])
        if total == 0.0 or self.speed == 0.0:
            return float("inf")
        return total / self.speed

    def position(self, t: np.ndarray | float) -> np.ndarray:
        """Centre position(s) at time(s) ``t``; shape ``t.shape + (2,)``."""
        t = np.asarray(t, dtype=np.float64)
        points, cum = self.cycle
        if not np.isfinite(self.period_s):
            return np.broadcast_to(points[0], t.shape + (2,)).copy()
        s = np.mod((t + self.phase_s) * self.speed, cum[-1])
        x = np.interp(s, cum, points[:, 0])
        y = np.interp(s, cum, points[:, 1])
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
        from pathzoo.core.moving_distance import min_distances  # numba, loaded on first use

        points, cum = self.cycle
        return min_distances(
            points, cum, float(self.speed), float(self.phase_s),
            np.ascontiguousarray(p0, dtype=np.float64), np.ascontiguousarray(p1, dtype=np.float64),
            np.ascontiguousarray(t0, dtype=np.float64), np.ascontiguousarray(t1, dtype=np.float64), EXACT_MAX_PIECES,
        )
