"""Moving obstacles whose positions are deterministic functions of time."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["MovingObstacle"]


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

    def breakpoints(self, t0: float, t1: float) -> np.ndarray:
        """Times in ``(t0, t1)`` where the obstacle changes direction (sorted)."""
        period = self.period_s
        if not np.isfinite(period) or t1 <= t0:
            return np.empty(0)
        knots = self._cum / self.speed - self.phase_s
        k0 = np.floor((t0 - knots.max()) / period)
        k1 = np.ceil((t1 - knots.min()) / period)
        cycles = np.arange(k0, k1 + 1)[:, None] * period + knots[None, :]
        times = np.unique(cycles.ravel())
        return times[(times > t0) & (times < t1)]

    def min_distance(self, p0: np.ndarray, p1: np.ndarray, t0: float, t1: float) -> float:
        """Exact minimum distance to a vehicle moving linearly from ``p0`` at ``t0`` to ``p1`` at ``t1``.

        Both motions are piecewise linear in time, so the relative position is
        linear between breakpoints and its minimum norm has a closed form.
        """
        p0 = np.asarray(p0, dtype=np.float64)
        p1 = np.asarray(p1, dtype=np.float64)
        if t1 <= t0:
            return float(np.linalg.norm(p0 - self.position(t0)))
        ts = np.concatenate([[t0], self.breakpoints(t0, t1), [t1]])
        frac = (ts - t0) / (t1 - t0)
        veh = p0[None, :] + frac[:, None] * (p1 - p0)[None, :]
        rel = veh - self.position(ts)
        a, b = rel[:-1], rel[1:]
        d = b - a
        dd = np.einsum("ij,ij->i", d, d)
        with np.errstate(invalid="ignore", divide="ignore"):
            u = np.where(dd > 0, np.clip(-np.einsum("ij,ij->i", a, d) / dd, 0.0, 1.0), 0.0)
        closest = a + u[:, None] * d
        return float(np.sqrt(np.einsum("ij,ij->i", closest, closest)).min())
