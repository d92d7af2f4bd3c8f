"""Bounded local repair of straight-segment paths: a blocked segment between nearby points is routed inside a small window.

The pure metaheuristics join their waypoints by straight segments. When a
segment touches a blocked cell and its two ends lie in free cells at most
``window`` cells apart (Chebyshev distance), :func:`repair_polylines`
replaces it by ``end -> centre of its cell -> ... -> centre of the other
end's cell -> other end``, the cells being a shortest 8-connected chain
(diagonals cost sqrt 2 and never cut a blocked corner, the MovingAI rule)
found by Dijkstra inside the box spanned by the two cells grown by
:data:`BOX_MARGIN` cells; of that piece, a greedy line-of-sight pull keeps
only the points needed for clear segments (each kept point reaches the
farthest later point of the piece it sees). The search therefore sees at most
``(window + 1 + 2 * BOX_MARGIN) ** 2`` cells, whatever the map's size: it is a
local repair, not a global shortest-path search, and a segment whose ends
are farther apart, or that cannot be routed inside its box, stays as it is
(and the cost penalises it).

The repaired polylines are then judged by the same penalised cost as any
other (:mod:`pathzoo_baselines.cost`); the repair only proposes. It runs on
the 2-D occupancy grids (``grid2d`` and ``dynamic``; moving obstacles are
left to the cost's time-of-passage check).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo_baselines.margin import segment_clear

__all__ = ["BOX_MARGIN", "window_route", "repair_polylines"]

BOX_MARGIN = 2
"""Cells by which the search box around a blocked segment's two end cells is grown on every side."""

_DR = np.array([0, -1, -1, -1, 0, 1, 1, 1], dtype=np.int64)
_DC = np.array([1, 1, 0, -1, -1, -1, 0, 1], dtype=np.int64)


@numba.njit(cache=True)
def window_route(blocked, r0, c0, r1, c1, window):
    """Shortest 8-connected chain of free cells ``(r0, c0) -> (r1, c1)`` inside their grown box, shape (k, 2).

    Returns an empty array when the cells are more than ``window`` apart,
    either is blocked, or no chain exists inside the box.
    """
    h, w = blocked.shape
    none = np.empty((0, 2), dtype=np.int64)
    if max(abs(r1 - r0), abs(c1 - c0)) > window or blocked[r0, c0] or blocked[r1, c1]:
        return none
    top = max(0, min(r0, r1) - BOX_MARGIN)
    left = max(0, min(c0, c1) - BOX_MARGIN)
    bh = min(h, max(r0, r1) + BOX_MARGIN + 1) - top
    bw = min(w, max(c0, c1) + BOX_MARGIN + 1) - left
    n = bh * bw
    dist = np.full(n, np.inf)
    parent = np.full(n, -1, dtype=np.int64)
    done = np.zeros(n, dtype=np.bool_)
    source = (r0 - top) * bw + (c0 - left)
    target = (r1 - top) * bw + (c1 - left)
    dist[source] = 0.0
    while True:
        u = -1
        best = np.inf
        for i in range(n):
            if not done[i] and dist[i] < best:
                best = dist[i]
                u = i
        if u < 0 or u == target:
            break
        done[u] = True
        ur, uc = u // bw, u % bw
        for k in range(8):
            vr, vc = ur + _DR[k], uc + _DC[k]
            if vr < 0 or vc < 0 or vr >= bh or vc >= bw or blocked[top + vr, left + vc]:
                continue
            diagonal = _DR[k] != 0 and _DC[k] != 0
            if diagonal and (blocked[top + ur, left + vc] or blocked[top + vr, left + uc]):
                continue
            v = vr * bw + vc
            cand = dist[u] + (math.sqrt(2.0) if diagonal else 1.0)
            if cand < dist[v]:
                dist[v] = cand
                parent[v] = u
    if not np.isfinite(dist[target]):
        return none
    count = 1
    v = target
    while v != source:
        v = parent[v]
        count += 1
    out = np.empty((count, 2), dtype=np.int64)
    v = target
    for i in range(count - 1, -1, -1):
        out[i, 0] = top + v // bw
        out[i, 1] = left + v % bw
        v = parent[v]
    return out


@numba.njit(cache=True)
def _pull_string(blocked, piece, margin, out, k):
    """Append the inner points of ``piece`` that a greedy line-of-sight pull keeps to ``out`` from row ``k``.

    From each kept point the next is the farthest point of the piece that a
    clear segment reaches (the next point always does: consecutive points
    of a routed piece are joined along free cells). The piece's last point
    is left for the caller. Returns the next free row.
    """
    last = piece.shape[0] - 1
    cur = 0
    while cur < last:
        nxt = cur + 1
        for j in range(last, cur + 1, -1):
            if segment_clear(blocked, piece[cur, 0], piece[cur, 1], piece[j, 0], piece[j, 1], margin):
                nxt = j
                break
        if nxt == last:
            break
        out[k, 0] = piece[nxt, 0]
        out[k, 1] = piece[nxt, 1]
        k += 1
        cur = nxt
    return k


@numba.njit(cache=True)
def repair_polylines(blocked, cells, window, margin):
    """Repair every polyline of ``cells`` (shape (n, m, 2), cell units ``x, y``); see the module docstring.

    Returns ``(out, lengths)``: ``out[i, :lengths[i]]`` is polyline ``i``
    repaired, and the rest of each row repeats its last point, so the rows
    share one length (zero-length tail segments add nothing to a length).
    """
    n, m = cells.shape[0], cells.shape[1]
    side = window + 1 + 2 * BOX_MARGIN
    cap = m + (m - 1) * (side * side + 1)
    out = np.empty((n, cap, 2))
    lengths = np.zeros(n, dtype=np.int64)
    for i in range(n):
        out[i, 0, 0] = cells[i, 0, 0]
        out[i, 0, 1] = cells[i, 0, 1]
        k = 1
        for s in range(m - 1):
            x0, y0, x1, y1 = cells[i, s, 0], cells[i, s, 1], cells[i, s + 1, 0], cells[i, s + 1, 1]
            if window > 0 and not segment_clear(blocked, x0, y0, x1, y1, margin):
                route = window_route(blocked, int(math.floor(y0)), int(math.floor(x0)),
                                     int(math.floor(y1)), int(math.floor(x1)), window)
                if route.shape[0] > 0:
                    piece = np.empty((route.shape[0] + 2, 2))
                    piece[0, 0], piece[0, 1] = x0, y0
                    piece[1:-1, 0] = route[:, 1] + 0.5
                    piece[1:-1, 1] = route[:, 0] + 0.5
                    piece[-1, 0], piece[-1, 1] = x1, y1
                    k = _pull_string(blocked, piece, margin, out[i], k)
            out[i, k, 0] = x1
            out[i, k, 1] = y1
            k += 1
        lengths[i] = k
    longest = 1
    for i in range(n):
        longest = max(longest, lengths[i])
    for i in range(n):
        for k in range(lengths[i], longest):
            out[i, k, 0] = out[i, lengths[i] - 1, 0]
            out[i, k, 1] = out[i, lengths[i] - 1, 1]
    return out[:, :longest], lengths


def _compile() -> None:
    """Compile for read-only maps at import, not inside a timed ``plan()``."""
    blocked = np.zeros((3, 3), dtype=bool)
    blocked[1, 1] = True
    blocked.setflags(write=False)
    repair_polylines(blocked, np.array([[[0.5, 0.5], [2.5, 2.5]]]), 4, 1e-6)


_compile()
