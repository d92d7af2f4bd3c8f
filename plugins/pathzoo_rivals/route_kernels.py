"""Compiled loops of the route rivals: segment tests on a flat map, string-pulling, corner bridging, via routes.

The segment test is :meth:`pathzoo_rivals.routes.RouteProblem.segment_ok`'s
collision-only case (no slope can break a limit): both cells free and
:func:`~pathzoo.grid.segments.first_blocked_cell_2d` finding no blocked cell
between the two cell centres, with the centres converted to cell units by
the same float operations as ``Scenario.point_of`` followed by
``to_cell_units`` (``((col + 0.5) * cs) / cs``), so every verdict is the
Python one. String-pulling and corner bridging are the loops of
:meth:`RouteProblem.pull_string` and :func:`pathzoo_rivals.route_moves.leap`
over that test (string-pulling's verdicts kept in a table,
:func:`kept_segment_free`); :func:`via_route` joins the two shortest-path trees of a
route problem through one cell; :func:`blend_cells` is the geometry of the
SFLA leap (:func:`pathzoo_rivals.route_moves.leap`): two polylines resampled
by arc length as NumPy's ``cumsum``, ``linspace`` and ``interp`` do (the same
float operations in the same order), blended and snapped to cells.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo.grid.segments import first_blocked_cell_2d

SEEN_BITS = 21
"""Size of :func:`pull_string_free`'s table of segment verdicts: ``2 ** SEEN_BITS`` int64 slots (16 MiB)."""

__all__ = [
    "SEEN_BITS", "clearance_samples", "segment_free", "kept_segment_free", "route_free", "pull_string_free",
    "bridge_corners_free", "via_route", "resample", "blend_cells",
]


@numba.njit(cache=True)
def segment_free(blocked: np.ndarray, cs: float, u: int, v: int) -> bool:
    """Whether the segment between the centres of cells ``u`` and ``v`` (flat ids) touches no blocked cell.

    Between neighbours the answer is read off the cells: a straight step
    touches its two cells only, a diagonal one also the two cells sharing
    the corner it passes through (the closed-cell rule); longer segments are
    walked by :func:`~pathzoo.grid.segments.first_blocked_cell_2d`.
    """
    w = blocked.shape[1]
    ru, cu = u // w, u % w
    rv, cv = v // w, v % w
    if u == v or blocked[ru, cu] or blocked[rv, cv]:
        return False
    if abs(ru - rv) <= 1 and abs(cu - cv) <= 1:  # neighbours: a diagonal touches the two cells at its corner
        return not (blocked[ru, cv] or blocked[rv, cu])
    x0 = ((cu + 0.5) * cs) / cs
    y0 = ((ru + 0.5) * cs) / cs
    x1 = ((cv + 0.5) * cs) / cs
    y1 = ((rv + 0.5) * cs) / cs
    return first_blocked_cell_2d(blocked, x0, y0, x1, y1)[0] == -2


@numba.njit(cache=True)
def route_free(blocked: np.ndarray, cs: float, route: np.ndarray) -> bool:
    """Whether every segment of ``route`` passes :func:`segment_free`."""
    for i in range(len(route) - 1):
        if not segment_free(blocked, cs, route[i], route[i + 1]):
            return False
    return True


@numba.njit(cache=True)
def kept_segment_free(blocked: np.ndarray, cs: float, u: int, v: int, seen: np.ndarray) -> bool:
    """:func:`segment_free`, kept in ``seen``: a direct-mapped table of ``2 (u n + v) + verdict`` (``n`` cells).

    A slot holds the last segment hashed to it (``-1`` when empty); a segment
    found there is answered without its walk, any other is walked and replaces
    it. The verdict is the walk's in both cases. ``len(seen)`` is a power of
    two, at most ``2 ** 32``.
    """
    key = u * blocked.size + v
    slot = ((np.uint64(key) * np.uint64(0x9E3779B97F4A7C15)) >> np.uint64(32)) & np.uint64(len(seen) - 1)
    known = seen[slot]
    if known >= 0 and known >> 1 == key:
        return known & 1 == 1
    free = segment_free(blocked, cs, u, v)
    seen[slot] = 2 * key + (1 if free else 0)
    return free


@numba.njit(cache=True)
def pull_string_free(blocked: np.ndarray, cs: float, nodes: np.ndarray, seen: np.ndarray) -> np.ndarray:
    """:meth:`RouteProblem.pull_string` with :func:`segment_free` as the segment test, kept in ``seen``.

    ``seen`` is :func:`kept_segment_free`'s table (``2 ** SEEN_BITS`` entries):
    random routes share most of their cells, and string-pulling them tests the
    same segments again and again (on ``ggaco.case3`` a tenth of the tests are
    distinct, a sixth of the cells walked).
    """
    keep = np.empty(len(nodes), dtype=np.int64)
    keep[0] = nodes[0]
    k = 1
    anchor = 0
    i = 1
    while i < len(nodes):
        j = i
        while j + 1 < len(nodes) and kept_segment_free(blocked, cs, nodes[anchor], nodes[j + 1], seen):
            j += 1
        keep[k] = nodes[j]
        k += 1
        anchor = j
        i = j + 1
    return keep[:k].copy()


@numba.njit(cache=True)
def bridge_corners_free(blocked: np.ndarray, cs: float, cells: np.ndarray) -> np.ndarray:
    """:func:`pathzoo_rivals.route_moves._bridge_corners` with :func:`segment_free` as the segment test.

    Returns an empty array as soon as a step stays blocked (where the Python
    function returns ``None``), without looking at the steps after it.
    """
    w = blocked.shape[1]
    out = np.empty(2 * len(cells), dtype=np.int64)
    out[0] = cells[0]
    k = 1
    for i in range(1, len(cells)):
        v = cells[i]
        u = out[k - 1]
        if not segment_free(blocked, cs, u, v):
            ru, cu = u // w, u % w
            rv, cv = v // w, v % w
            if abs(ru - rv) != 1 or abs(cu - cv) != 1:
                return out[:0].copy()
            bridged = False
            for side in (ru * w + cv, rv * w + cu):
                if segment_free(blocked, cs, u, side) and segment_free(blocked, cs, side, v):
                    out[k] = side
                    k += 1
                    bridged = True
                    break
            if not bridged:
                return out[:0].copy()
        out[k] = v
        k += 1
    return out[:k].copy()


@numba.njit(cache=True)
def via_route(from_start: np.ndarray, to_goal: np.ndarray, via: int, goal: int, seen: np.ndarray) -> np.ndarray:
    """Cells of the shortest route through ``via``: the start tree's path to it, then the goal tree's path on.

    ``from_start[v]`` is ``v``'s predecessor on a shortest path from the
    start (``-1`` at the start), ``to_goal[v]`` its successor on a shortest
    path to ``goal``. Where the two halves meet again (a ``via`` in a cul-de-sac)
    the loop between is cut, so no cell appears twice. ``seen`` is a
    scratch array of ``-1`` per node, left as found.
    """
    n = 0
    u = via
    while u != -1:
        n += 1
        u = from_start[u]
    u = via
    while u != goal:
        u = to_goal[u]
        n += 1
    cells = np.empty(n, dtype=np.int64)
    u = via
    i = 0
    while u != -1:
        cells[i] = u
        i += 1
        u = from_start[u]
    cells[:i] = cells[:i][::-1].copy()
    u = via
    while u != goal:
        u = to_goal[u]
        cells[i] = u
        i += 1
    out = np.empty(n, dtype=np.int64)
    k = 0
    for c in cells:
        if seen[c] >= 0:  # a loop back to an earlier cell: drop what lies between
            for j in range(seen[c] + 1, k):
                seen[out[j]] = -1
            k = seen[c] + 1
            continue
        seen[c] = k
        out[k] = c
        k += 1
    for j in range(k):
        seen[out[j]] = -1
    return out[:k].copy()


@numba.njit(cache=True)
def clearance_samples(clearance: np.ndarray, pts: np.ndarray, steps: np.ndarray, cs: float) -> np.ndarray:
    """Clearances of the cells under ``pts[i] + (k / steps[i]) (pts[i + 1] - pts[i])``, ``k < steps[i]``, then ``pts[-1]``.

    The points of :meth:`RouteProblem.mean_clearance`, computed by the same
    float operations one point at a time; cells are clipped to the map.
    """
    h, w = clearance.shape
    out = np.empty(steps.sum() + 1)
    n = 0
    for i in range(len(steps)):
        dx = pts[i + 1, 0] - pts[i, 0]
        dy = pts[i + 1, 1] - pts[i, 1]
        for k in range(steps[i]):
            frac = k / steps[i]
            out[n] = clearance[min(max(int((pts[i, 1] + frac * dy) / cs), 0), h - 1),
                               min(max(int((pts[i, 0] + frac * dx) / cs), 0), w - 1)]
            n += 1
    out[n] = clearance[min(max(int(pts[-1, 1] / cs), 0), h - 1), min(max(int(pts[-1, 0] / cs), 0), w - 1)]
    return out


@numba.njit(cache=True)
def _interp(t: np.ndarray, s: np.ndarray, f: np.ndarray) -> np.ndarray:
    """``np.interp(t, s, f)`` for ``t`` ascending within ``[s[0], s[-1]]`` and ``s`` strictly ascending.

    NumPy's formula: slopes ``(f[j + 1] - f[j]) / (s[j + 1] - s[j])``, then
    ``slope (t - s[j]) + f[j]`` on the interval holding ``t``, ``f[j]`` where
    ``t`` is a knot ``s[j]`` or the last one.
    """
    m = len(s)
    slopes = np.empty(m - 1)
    for i in range(m - 1):
        slopes[i] = (f[i + 1] - f[i]) / (s[i + 1] - s[i])
    out = np.empty(len(t))
    j = 0
    for i in range(len(t)):
        x = t[i]
        while j + 1 < m and s[j + 1] <= x:
            j += 1
        out[i] = f[j] if j == m - 1 or s[j] == x else slopes[j] * (x - s[j]) + f[j]
    return out


@numba.njit(cache=True)
def resample(points: np.ndarray, n: int) -> np.ndarray:
    """``n`` points equally spaced by arc length along a polyline of distinct consecutive points (ends kept).

    The arc lengths are ``concatenate([0], cumsum(hypot(diff)))``, the
    parameters ``linspace(0, total, n)`` (``i * (total / (n - 1))``, the last
    one ``total``), the coordinates ``np.interp`` of them.
    """
    m = len(points)
    s = np.empty(m)
    s[0] = 0.0
    for i in range(1, m):
        piece = math.hypot(points[i, 0] - points[i - 1, 0], points[i, 1] - points[i - 1, 1])
        s[i] = piece if i == 1 else s[i - 1] + piece
    step = s[m - 1] / (n - 1)
    t = np.empty(n)
    for i in range(n):
        t[i] = float(i) * step + 0.0
    t[n - 1] = s[m - 1]
    out = np.empty((n, 2))
    out[:, 0] = _interp(t, s, np.ascontiguousarray(points[:, 0]))
    out[:, 1] = _interp(t, s, np.ascontiguousarray(points[:, 1]))
    return out


@numba.njit(cache=True)
def blend_cells(pa: np.ndarray, pb: np.ndarray, n: int, r: float, cs: float, h: int, w: int, start: int,
                goal: int) -> np.ndarray:
    """Cells under ``a + r (b - a)``, ``a`` and ``b`` the polylines ``pa`` and ``pb`` resampled to ``n`` points.

    A point goes to the cell ``(int(y / cs), int(x / cs))`` clipped to the
    map; the first cell is ``start``, the last ``goal``, and a cell equal to
    the one before it is left out.
    """
    a = resample(pa, n)
    b = resample(pb, n)
    cells = np.empty(n, dtype=np.int64)
    k = 0
    for i in range(n):
        x = a[i, 0] + r * (b[i, 0] - a[i, 0])
        y = a[i, 1] + r * (b[i, 1] - a[i, 1])
        cell = min(max(int(y / cs), 0), h - 1) * w + min(max(int(x / cs), 0), w - 1)
        if i == 0:
            cell = start
        elif i == n - 1:
            cell = goal
        if k == 0 or cell != cells[k - 1]:
            cells[k] = cell
            k += 1
    return cells[:k].copy()
