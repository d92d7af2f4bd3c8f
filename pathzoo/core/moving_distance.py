"""Compiled minimum distance between a vehicle segment and a moving obstacle's looping route (numba).

Kept apart from :mod:`pathzoo.core.moving` so that importing the data types
(and so the ``pathzoo`` command's parser) does not import numba; only
:meth:`pathzoo.core.moving.MovingObstacle.min_distances` loads this module.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["min_distances"]


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
def min_distances(cycle, cum, speed, phase, p0, p1, t0, t1, max_pieces):
    """Minimum distance from a looping obstacle to each vehicle segment ``p0[i]`` at ``t0[i]`` -> ``p1[i]`` at ``t1[i]``.

    ``cycle`` and ``cum`` are the obstacle's closed route and cumulative arc
    lengths, ``speed`` and ``phase`` its motion; see
    :meth:`pathzoo.core.moving.MovingObstacle.min_distance` for exactness and
    the ``max_pieces`` fallback.
    """
    out = np.empty(p0.shape[0])
    for i in range(p0.shape[0]):
        out[i] = _min_distance(cycle, cum, speed, phase, p0[i, 0], p0[i, 1], p1[i, 0], p1[i, 1], t0[i], t1[i], max_pieces)
    return out
