"""The exact any-angle optimum of a 2-D grid by A* on a lazy visibility graph (the reference search of the tests).

What is computed
----------------
A valid path (``docs/corner-rule.md``) may not touch any blocked cell's
closed square. The set of valid paths is open, so the shortest valid path
does not exist; its length is an *infimum*, approached by paths hugging
obstacle corners ever more closely. This module computes that infimum and
a *limit path* attaining it: a polyline that may touch blocked cells'
boundaries (slide along an edge, turn at a corner) but

- never enters a blocked cell's interior,
- never runs along an edge shared by two blocked cells (the inside of a wall),
- never passes through a *pinch*: a grid point where two blocked cells touch
  diagonally and leave no gap, since no valid path can cross there.

Every valid path is at least as long as the limit path, and valid paths
come arbitrarily close to it, so its length is the exact any-angle optimum.

Algorithm
---------
The limit path bends only at *convex corners*: grid points where exactly
one of the four surrounding cells is blocked (cells outside the map count
as blocked); a grid point with two or more blocked cells around it leaves
no reflex angle of free space to turn around. The vertices are these
corners, the start and the goal. Two vertices are joined when the segment
between them passes the limit-path rules above (:func:`visible`, exact
integer arithmetic) and is tangent to the blocked cell at each corner end
(the standard bitangent pruning of visibility graphs: a shortest path
turning at a corner keeps the corner's blocked cell on the inside of the
turn). A* with the straight-line heuristic searches this graph, checking
an edge's visibility only when it would improve the target's distance.

Every visibility test is exact integer arithmetic: corners are scaled by
:data:`SCALE`, and segments from the start or goal by a power of two that
makes their float coordinates integers (compiled int64 code on the
1/:data:`SCALE` lattice, where every cell centre lies; Python integers
elsewhere). Distances are floats.

Cost: each expansion scans every vertex (a quick tangency test, then the
visibility walk for the survivors that could improve), about N**1.5 to
N**2 in the number of cells N. :mod:`pathzoo.grid.anyangle` uses it only
for endpoints off the lattice its Polyanya search needs, on small maps;
the tests use it as the independent check of that search. :func:`visible`
also checks every segment of the paths Polyanya returns.
"""

from __future__ import annotations

import heapq
import math

import numba
import numpy as np

__all__ = ["SCALE", "convex_corners", "visible", "visibility_search"]

SCALE = 1024
"""Integer units per cell for corner-to-corner tests and endpoints on the 1/SCALE lattice."""


@numba.njit(cache=True)
def _blk(blocked: np.ndarray, r: int, c: int) -> bool:
    h, w = blocked.shape
    return r < 0 or c < 0 or r >= h or c >= w or blocked[r, c]


@numba.njit(cache=True)
def _along_line(blocked: np.ndarray, line: int, k_lo: int, k_end: int, vertical: bool) -> bool:
    # a segment lying on grid line `line` (x = line if vertical, else y = line) over the unit pieces k_lo..k_end-1:
    # every piece needs a free cell on one side, and every grid point between two pieces needs one side free
    # on both pieces (otherwise it is a pinch or the inside of a wall)
    for k in range(k_lo, k_end):
        if vertical:
            a, b = _blk(blocked, k, line - 1), _blk(blocked, k, line)
        else:
            a, b = _blk(blocked, line - 1, k), _blk(blocked, line, k)
        if a and b:
            return False
        if k + 1 < k_end:
            if vertical:
                a2, b2 = _blk(blocked, k + 1, line - 1), _blk(blocked, k + 1, line)
            else:
                a2, b2 = _blk(blocked, line - 1, k + 1), _blk(blocked, line, k + 1)
            if (a or a2) and (b or b2):
                return False
    return True


@numba.njit(cache=True)
def visible(blocked: np.ndarray, s: int, px: int, py: int, qx: int, qy: int) -> bool:
    """True when the segment may be part of a limit path (integer units, ``s`` per cell).

    The segment's relative interior must avoid every blocked cell's interior,
    every edge between two blocked cells and every pinch point; its
    endpoints are not checked. ``blocked`` is indexed ``[row, col]`` with
    ``x`` along columns; cells outside the grid are blocked.
    """
    if px > qx or (px == qx and py > qy):
        px, py, qx, qy = qx, qy, px, py
    dx = qx - px
    dy = qy - py
    if dx == 0 and dy == 0:
        return True
    if dx == 0:
        if px % s == 0:
            return _along_line(blocked, px // s, py // s, -((-qy) // s), True)
        c = px // s
        for r in range(py // s, -((-qy) // s)):
            if _blk(blocked, r, c):
                return False
        return True
    if dy == 0:
        if py % s == 0:
            return _along_line(blocked, py // s, px // s, -((-qx) // s), False)
        r = py // s
        for c in range(px // s, -((-qx) // s)):
            if _blk(blocked, r, c):
                return False
        return True
    den = s * dx  # y = Y / dx, so row boundaries r*s sit at Y = r*den
    for c in range(px // s, -((-qx) // s)):
        xa = max(px, c * s)
        xb = min(qx, (c + 1) * s)
        ya = py * dx + (xa - px) * dy
        yb = py * dx + (xb - px) * dy
        ylo, yhi = min(ya, yb), max(ya, yb)
        for r in range(ylo // den, -((-yhi) // den)):
            if _blk(blocked, r, c):
                return False
        x = (c + 1) * s
        if x < qx:
            num = py * dx + (x - px) * dy
            if num % den == 0:  # passes through the grid point (c + 1, j)
                j = num // den
                if dy > 0:
                    pinch = _blk(blocked, j, c) and _blk(blocked, j - 1, c + 1)
                else:
                    pinch = _blk(blocked, j - 1, c) and _blk(blocked, j, c + 1)
                if pinch:
                    return False
    return True


def convex_corners(blocked: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Grid points with exactly one blocked cell around them, and the direction of that cell.

    Returns
    -------
    points : ndarray of shape (K, 2) of int64
        ``(x, y)`` in cells.
    quadrant : ndarray of shape (K, 2) of int64
        ``(sx, sy)`` in {-1, +1}: the blocked cell lies towards ``+sx`` in x and ``+sy`` in y.
    """
    h, w = blocked.shape
    pad = np.ones((h + 2, w + 2), dtype=np.int8)
    pad[1:-1, 1:-1] = blocked
    # grid point (x, y) is surrounded by padded cells [y:y+2, x:x+2] (cell (r, c) is pad[r + 1, c + 1])
    ul, ur, ll, lr = pad[:-1, :-1], pad[:-1, 1:], pad[1:, :-1], pad[1:, 1:]  # rows y-1 / y, cols x-1 / x
    count = ul + ur + ll + lr
    ys, xs = np.nonzero(count == 1)
    sx = np.where(ur[ys, xs] | lr[ys, xs], 1, -1)
    sy = np.where(ll[ys, xs] | lr[ys, xs], 1, -1)
    return np.stack([xs, ys], axis=1).astype(np.int64), np.stack([sx, sy], axis=1).astype(np.int64)


@numba.njit(cache=True)
def _search(
    blocked: np.ndarray,
    fx: np.ndarray,
    fy: np.ndarray,
    qx: np.ndarray,
    qy: np.ndarray,
    start_sees: np.ndarray,
    goal_sees: np.ndarray,
    max_expansions: int,
) -> tuple[np.ndarray, int, bool]:
    # A* from vertex 0 (start) to vertex 1 (goal) over vertices at (fx, fy) (cell units; corners are integers);
    # qx = qy = 0 for start and goal (no tangency condition); the endpoints' visibility is given
    # (start_sees[v], goal_sees[v]), corner-to-corner visibility is tested here on the SCALE lattice.
    # Returns the parent array (-1 = unreached), the number of expansions and whether the search finished
    # (goal reached or open list empty) within max_expansions.
    n = len(fx)
    expansions = 0
    g = np.full(n, np.inf)
    parent = np.full(n, -1, dtype=np.int64)
    closed = np.zeros(n, dtype=np.bool_)
    gx, gy = fx[1], fy[1]
    g[0] = 0.0
    heap = [(math.hypot(fx[0] - gx, fy[0] - gy), 0)]
    while heap:
        _, u = heapq.heappop(heap)
        if closed[u]:
            continue
        if u == 1:
            return parent, expansions, True
        if expansions >= max_expansions:
            return parent, expansions, False
        expansions += 1
        closed[u] = True
        ux, uy, usx, usy = fx[u], fy[u], qx[u], qy[u]
        for v in range(n):
            if closed[v]:
                continue
            dx = fx[v] - ux
            dy = fy[v] - uy
            t = dx * dy
            if t * usx * usy > 0 or t * qx[v] * qy[v] > 0:
                continue  # not tangent at u's or v's corner
            cand = g[u] + math.hypot(dx, dy)
            if cand >= g[v]:
                continue
            if u == 0:
                seen = start_sees[v]
            elif v == 1:
                seen = goal_sees[u]
            else:
                seen = visible(
                    blocked, SCALE, int(ux) * SCALE, int(uy) * SCALE, int(fx[v]) * SCALE, int(fy[v]) * SCALE
                )
            if not seen:
                continue
            g[v] = cand
            parent[v] = u
            heapq.heappush(heap, (cand + math.hypot(fx[v] - gx, fy[v] - gy), v))
    return parent, expansions, True


@numba.njit(cache=True)
def _sees_corners(blocked: np.ndarray, s: int, px: int, py: int, cx: np.ndarray, cy: np.ndarray) -> np.ndarray:
    out = np.empty(len(cx), dtype=np.bool_)
    for k in range(len(cx)):
        out[k] = visible(blocked, s, px, py, cx[k] * s, cy[k] * s)
    return out


def _endpoint_visibility(blocked: np.ndarray, point: np.ndarray, ends: np.ndarray, corners: np.ndarray) -> np.ndarray:
    """Whether ``point`` sees each of the two ``ends`` (cell units) and each of the integer ``corners``.

    Exact for any floats: a float is a dyadic rational, so scaling by the
    largest power of two among the denominators (at least :data:`SCALE`)
    makes every coordinate an integer. On the 1/:data:`SCALE` lattice (every
    cell centre) the corners are tested in compiled int64 code; otherwise
    with :func:`visible`'s Python version on Python's unbounded integers.
    """
    coords = [float(v) for v in (*point, *np.ravel(ends))]
    scale = max([SCALE] + [v.as_integer_ratio()[1] for v in coords])

    def scaled(v: float) -> int:
        num, den = v.as_integer_ratio()
        return num * (scale // den)

    px, py = scaled(coords[0]), scaled(coords[1])
    exact = visible.py_func
    sees_ends = [exact(blocked, scale, px, py, scaled(coords[k]), scaled(coords[k + 1])) for k in (2, 4)]
    if scale == SCALE:
        sees_corners = _sees_corners(blocked, SCALE, px, py, corners[:, 0], corners[:, 1])
    else:
        sees_corners = np.array(
            [exact(blocked, scale, px, py, int(x) * scale, int(y) * scale) for x, y in corners], dtype=np.bool_
        )
    return np.concatenate([np.array(sees_ends, dtype=np.bool_), sees_corners])


def visibility_search(
    blocked: np.ndarray, start: np.ndarray, goal: np.ndarray, max_expansions: int
) -> tuple[np.ndarray | None, int, bool]:
    """The limit path from ``start`` to ``goal`` (cell units), the expanded vertices and whether the search finished.

    The path is an ``(N, 2)`` array in cell units from exactly ``start`` to
    exactly ``goal``, or None when the goal is unreachable or the search
    stopped at ``max_expansions`` expansions before reaching it (then the
    third value is False).
    """
    corners, quadrant = convex_corners(blocked)
    cells = np.concatenate([np.stack([start, goal]), corners.astype(np.float64)])
    qx = np.concatenate([[0, 0], quadrant[:, 0]]).astype(np.int64)
    qy = np.concatenate([[0, 0], quadrant[:, 1]]).astype(np.int64)
    if np.array_equal(cells[0], cells[1]):
        return cells[:2].copy(), 0, True
    start_sees = _endpoint_visibility(blocked, cells[0], cells[:2], corners)
    goal_sees = _endpoint_visibility(blocked, cells[1], cells[:2], corners)
    fx, fy = np.ascontiguousarray(cells[:, 0]), np.ascontiguousarray(cells[:, 1])
    parent, expansions, finished = _search(blocked, fx, fy, qx, qy, start_sees, goal_sees, max_expansions)
    if not finished or parent[1] < 0:
        return None, expansions, finished
    order = [1]
    while order[-1] != 0:
        order.append(int(parent[order[-1]]))
    return cells[order[::-1]], expansions, True
