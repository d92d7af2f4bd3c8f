"""Moving obstacles as plain arrays, with their position and exact clearance from a moving vehicle, for compiled walks.

:class:`pathzoo.core.MovingObstacle` answers these questions in numpy for
the validator; an ant asks them for every candidate move, so here they are
compiled. Both use the same model: each obstacle drives its closed route
(:attr:`MovingObstacle.cycle`) at constant speed, so between the times it
passes a route point its position is linear in time, and so is its offset
from a vehicle driving one straight segment at constant speed; the minimum
distance on each such piece has a closed form. The tests check both
functions against :meth:`MovingObstacle.position` and
:meth:`MovingObstacle.min_distance`.

The compiled functions have one exit, read each array on every path and
raise nothing: numba then prunes the reference counts of their array
arguments. Otherwise every call costs two atomic operations per array, which
took about 6 % of ``fgdaco.scenario3``'s CPU time (``docs/planners/aco.fgdaco.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from pathzoo.core.moving import MovingObstacle

__all__ = ["UNDER", "ObstacleArrays", "pack_obstacles", "route_clearance", "obstacle_position", "obstacle_min_distance",
           "floored_mod"]

UNDER = 1.0 - 1e-12
"""Shrinks a measured distance that only serves as a bound, so that ``sqrt`` (faster than ``hypot``) stays below it.

The rounding of either is below 1e-15 of the distance; the bound only decides which exact checks run.
"""


@dataclass(frozen=True, eq=False)
class ObstacleArrays:
    """Every obstacle's route, padded to a common length.

    Attributes
    ----------
    points : ndarray, shape (n, P, 2)
        Route points (the first ``count[k]`` rows of obstacle ``k``).
    cum : ndarray, shape (n, P)
        Cumulative route distance at each point, metres.
    count : ndarray of int64, shape (n,)
        Route points per obstacle.
    speed, phase, radius : ndarray, shape (n,)
        m/s, s and m.
    """

    points: np.ndarray
    cum: np.ndarray
    count: np.ndarray
    speed: np.ndarray
    phase: np.ndarray
    radius: np.ndarray

    @property
    def n(self) -> int:
        """Number of obstacles."""
        return int(self.count.size)


def pack_obstacles(obstacles: Sequence[MovingObstacle]) -> ObstacleArrays:
    """Pack a scenario's moving obstacles (possibly none) into :class:`ObstacleArrays`."""
    n = len(obstacles)
    width = max((len(ob.cycle[0]) for ob in obstacles), default=1)
    points = np.zeros((n, max(width, 2), 2))  # two points at least: the compiled functions read a whole piece
    cum = np.zeros((n, max(width, 2)))
    count = np.zeros(n, dtype=np.int64)
    for k, ob in enumerate(obstacles):
        route, dist = ob.cycle
        points[k, : len(route)] = route
        cum[k, : len(route)] = dist
        count[k] = len(route)
    as_array = lambda name: np.array([float(getattr(ob, name)) for ob in obstacles])  # noqa: E731
    return ObstacleArrays(points, cum, count, as_array("speed"), as_array("phase_s"), as_array("radius"))


def route_clearance(obstacles: ObstacleArrays, points: np.ndarray) -> np.ndarray:
    """A lower bound, whatever the time, on each point's distance to each obstacle's disc: ``(n_points, n)``.

    The distance from the point to the obstacle's whole route, less its
    radius, shrunk by 1e-12 relative so that rounding never puts it above
    the distance to the disc at any moment.
    """
    points = np.asarray(points, dtype=np.float64)
    out = np.empty((len(points), obstacles.n))
    for k in range(obstacles.n):
        route = obstacles.points[k, : obstacles.count[k]]
        best = np.hypot(*(points - route[0]).T)
        for a, b in zip(route[:-1], route[1:]):
            ab = b - a
            denom = float(ab @ ab)
            u = np.clip((points - a) @ ab / denom, 0.0, 1.0) if denom > 0.0 else np.zeros(len(points))
            best = np.minimum(best, np.hypot(*(points - a - u[:, None] * ab).T))
        out[:, k] = best * (1.0 - 1e-12) - obstacles.radius[k]
    return out


@intrinsic
def _fma(typingctx, a, b, c):
    """``a * b + c`` rounded once (LLVM's ``llvm.fma.f64``: one instruction where the CPU has FMA)."""
    sig = types.float64(types.float64, types.float64, types.float64)

    def codegen(context, builder, signature, args):
        double = ir.DoubleType()
        fma = builder.module.declare_intrinsic("llvm.fma", [double], ir.FunctionType(double, [double] * 3))
        return builder.call(fma, args)

    return sig, codegen


@numba.njit(cache=True)
def floored_mod(a, b):
    """``a % b`` (Python's floored modulo), bit for bit, mostly without the library's ``fmod`` call.

    For ``a >= 0 < b`` the result is ``a - n b`` with ``n`` the integer part
    of ``a / b``, and that number is exactly representable, so one fused
    multiply-add gives it exactly once ``n`` is right. Since rounding is
    monotonic and integers below 2**53 are representable, ``q = floor(a / b)``
    is ``n`` or ``n + 1`` (when the rounded quotient reaches the next
    integer); ``n + 1`` leaves a negative remainder and is corrected. Other
    signs, non-finite numbers and quotients of 2**52 or more take ``%`` itself.
    """
    q = 4503599627370496.0  # 2**52
    if a >= 0.0 and 0.0 < b < math.inf:
        q = np.floor(a / b)  # a float (math.floor gives an int64, which overflows)
    r = 0.0
    if q < 4503599627370496.0:
        r = _fma(-q, b, a)
        if r < 0.0:
            r = _fma(1.0 - q, b, a)
        r += 0.0  # a zero remainder is +0.0, as Python's (a = -0.0 gives -0.0 otherwise)
    else:
        r = a % b
    return r


@numba.njit(cache=True)
def _locate(cum, count, speed, phase, k, t):
    """Route distance ``s`` at time ``t`` and the index ``i`` of the route piece holding it (``-1``: parked)."""
    n = count[k]
    total = cum[k, n - 1]
    v = speed[k]
    shift = phase[k]
    s = 0.0
    i = -1
    if n >= 2 and total != 0.0 and v != 0.0:
        s = floored_mod((t + shift) * v, total)
        i = 0
        while i < n - 2 and cum[k, i + 1] <= s:
            i += 1
    return s, i


@numba.njit(cache=True)
def _point_on(points, cum, k, i, s):
    """Point at route distance ``s`` on piece ``i`` of obstacle ``k``'s route (its first point if ``i < 0``)."""
    j = max(i, 0)  # every array is read on every path (routes are padded to two points at least)
    ax = points[k, j, 0]
    ay = points[k, j, 1]
    bx = points[k, j + 1, 0]
    by = points[k, j + 1, 1]
    s0 = cum[k, j]
    s1 = cum[k, j + 1]
    x = ax
    y = ay
    if i >= 0:
        length = s1 - s0
        u = (s - s0) / length if length > 0.0 else 0.0
        x = ax + u * (bx - ax)
        y = ay + u * (by - ay)
    return x, y


@numba.njit(cache=True)
def obstacle_position(points, cum, count, speed, phase, k, t):
    """Centre ``(x, y)`` of obstacle ``k`` at time ``t`` (as :meth:`MovingObstacle.position`)."""
    s, i = _locate(cum, count, speed, phase, k, t)
    return _point_on(points, cum, k, i, s)


@numba.njit(cache=True)
def _closest(ax, ay, bx, by):
    """Distance from the origin to the segment ``a -> b``."""
    dx = bx - ax
    dy = by - ay
    dd = dx * dx + dy * dy
    u = 0.0
    if dd > 0.0:
        u = min(max(-(ax * dx + ay * dy) / dd, 0.0), 1.0)
    return math.hypot(ax + u * dx, ay + u * dy)


@numba.njit(cache=True, error_model="numpy")  # its divisions are by non-zero numbers: no raise paths
def obstacle_min_distance(points, cum, count, speed, phase, k, x0, y0, x1, y1, t0, t1):
    """Least distance from obstacle ``k``'s centre to a vehicle driving ``(x0, y0) -> (x1, y1)`` during ``[t0, t1]``.

    As :meth:`MovingObstacle.min_distance`: the interval is cut where the
    obstacle passes a route point, and on each piece the offset between
    vehicle and obstacle is linear in time.
    """
    s, i = _locate(cum, count, speed, phase, k, t0)
    ox, oy = _point_on(points, cum, k, i, s)
    ax = x0 - ox
    ay = y0 - oy
    best = math.hypot(ax, ay)
    span = t1 - t0
    ta = t0
    last = count[k] - 1
    v = speed[k]
    more = t1 > t0
    while more:
        tb = t1
        if i >= 0:
            tb = min(t1, ta + (cum[k, i + 1] - s) / v)
        if i >= 0 and tb < t1:  # the obstacle reaches route point i + 1 before the vehicle arrives
            ox, oy = points[k, i + 1, 0], points[k, i + 1, 1]
            i = i + 1 if i + 1 < last else 0
            s = cum[k, i]
        else:
            s_end = s + (tb - ta) * v if i >= 0 else 0.0
            ox, oy = _point_on(points, cum, k, i, s_end)
        f = (tb - t0) / span
        bx = x0 + f * (x1 - x0) - ox
        by = y0 + f * (y1 - y0) - oy
        best = min(best, _closest(ax, ay, bx, by))
        more = tb < t1
        ta = tb
        ax = bx
        ay = by
    return best
