"""A navigation mesh of a 2-D grid's free space: rectangles of free cells, each a convex polygon.

The free cells are cut into rectangles (maximal runs of free cells along a
row, stacked while the run below has the same extent). Each rectangle is a
convex polygon whose boundary lists every grid point where the cell across
its side changes (another rectangle, or a blocked cell), so every polygon
edge has exactly one neighbour: a polygon, or an obstacle (``-1``). Two
rectangles that touch at one grid point only (a *pinch*, where two blocked
cells meet diagonally) share no edge, so nothing crosses there; the edge
between two blocked cells belongs to no polygon. That is the closed-cell
rule's free space (``docs/corner-rule.md``) with its boundary: a path may
slide along a polygon edge or touch a vertex, as limit paths do.

Vertices are grid points, numbered ``y * (W + 1) + x``; a polygon's
vertices run in the order of positive orientation in ``(x, y)``
coordinates: ``cross(v[i+1] - v[i], p - v[i]) > 0`` for every point ``p``
inside it. A vertex is a *corner* (a place where a shortest path may turn)
when exactly one of its four cells is blocked (cells outside the map count
as blocked).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numba
import numpy as np

from pathzoo.core.object_memo import ObjectMemo

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["NavMesh", "navigation_mesh", "scenario_mesh", "polygons_at"]


@dataclass(frozen=True, eq=False)
class NavMesh:
    """Convex polygons covering a grid's free cells, with their adjacency.

    Attributes
    ----------
    shape : tuple of int
        ``(H, W)`` of the grid.
    cell_polygon : ndarray of shape (H, W) of int32
        The polygon of each free cell, -1 for blocked cells.
    offsets : ndarray of shape (P + 1,) of int64
        Polygon ``p``'s edges are ``offsets[p]:offsets[p + 1]`` in the flat arrays.
    vertex : ndarray of int64
        Flat: each polygon's vertices (grid point ids ``y * (W + 1) + x``) in order.
    neighbour : ndarray of int64
        Flat: the polygon across the edge from ``vertex[i]`` to the next vertex, -1 for an obstacle.
    twin : ndarray of int64
        Flat: the position of the same edge within the neighbour's vertex list, -1 for an obstacle.
    corner : ndarray of shape ((H + 1) * (W + 1),) of int32
        For grid points with exactly one blocked cell around them, their
        number among these corners; -1 for every other grid point.
    n_corners : int
        Number of corners.
    component : ndarray of shape (P,) of int64
        The connected component of each polygon (polygons joined by an
        edge); a limit path joins two points only within one component.
    """

    shape: tuple[int, int]
    cell_polygon: np.ndarray
    offsets: np.ndarray
    vertex: np.ndarray
    neighbour: np.ndarray
    twin: np.ndarray
    corner: np.ndarray
    n_corners: int
    component: np.ndarray

    @property
    def n_polygons(self) -> int:
        """Number of polygons."""
        return len(self.offsets) - 1


@numba.njit(cache=True)
def _rectangles(blocked: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    # rectangles of free cells: runs along rows, extended downwards while the next row has the same run
    h, w = blocked.shape
    cell = np.full((h, w), -1, dtype=np.int32)
    rect = np.empty((h * w, 4), dtype=np.int64)  # x0, y0, x1, y1 (cells x0..x1-1, rows y0..y1-1)
    n = 0
    for y in range(h):
        x = 0
        while x < w:
            if blocked[y, x]:
                x += 1
                continue
            s = x
            while x < w and not blocked[y, x]:
                x += 1
            r = cell[y - 1, s] if y > 0 else -1
            if r < 0 or rect[r, 0] != s or rect[r, 2] != x:
                r = n
                rect[r, 0], rect[r, 1], rect[r, 2] = s, y, x
                n += 1
            rect[r, 3] = y + 1
            cell[y, s:x] = r
    return cell, rect[:n].copy()


@numba.njit(cache=True)
def _id(cell: np.ndarray, r: int, c: int) -> int:
    h, w = cell.shape
    if r < 0 or c < 0 or r >= h or c >= w:
        return -1
    return cell[r, c]


@numba.njit(cache=True)
def _boundaries(cell: np.ndarray, rect: np.ndarray, fill: bool, offsets: np.ndarray,
                vertex: np.ndarray, neighbour: np.ndarray) -> int:
    # walk every rectangle's sides in order (top left->right, right top->bottom, bottom right->left,
    # left bottom->top), with a vertex wherever the cell across the side changes; count only unless `fill`
    w1 = cell.shape[1] + 1
    k = 0
    for p in range(len(rect)):
        x0, y0, x1, y1 = rect[p, 0], rect[p, 1], rect[p, 2], rect[p, 3]
        if fill:
            offsets[p] = k
        # top side, y = y0, cells above in row y0 - 1
        for x in range(x0, x1):
            if x == x0 or _id(cell, y0 - 1, x - 1) != _id(cell, y0 - 1, x):
                if fill:
                    vertex[k], neighbour[k] = y0 * w1 + x, _id(cell, y0 - 1, x)
                k += 1
        # right side, x = x1, cells to the right in column x1
        for y in range(y0, y1):
            if y == y0 or _id(cell, y - 1, x1) != _id(cell, y, x1):
                if fill:
                    vertex[k], neighbour[k] = y * w1 + x1, _id(cell, y, x1)
                k += 1
        # bottom side, y = y1, cells below in row y1, walked from x1 down to x0
        for x in range(x1, x0, -1):
            if x == x1 or _id(cell, y1, x - 1) != _id(cell, y1, x):
                if fill:
                    vertex[k], neighbour[k] = y1 * w1 + x, _id(cell, y1, x - 1)
                k += 1
        # left side, x = x0, cells to the left in column x0 - 1, walked from y1 up to y0
        for y in range(y1, y0, -1):
            if y == y1 or _id(cell, y - 1, x0 - 1) != _id(cell, y, x0 - 1):
                if fill:
                    vertex[k], neighbour[k] = y * w1 + x0, _id(cell, y - 1, x0 - 1)
                k += 1
    if fill:
        offsets[len(rect)] = k
    return k


@numba.njit(cache=True)
def _components(offsets: np.ndarray, neighbour: np.ndarray) -> np.ndarray:
    # label the polygons joined through edges, by depth-first search
    n = len(offsets) - 1
    label = np.full(n, -1, dtype=np.int64)
    stack = np.empty(n, dtype=np.int64)
    count = 0
    for seed in range(n):
        if label[seed] >= 0:
            continue
        label[seed] = count
        top = 1
        stack[0] = seed
        while top > 0:
            top -= 1
            p = stack[top]
            for i in range(offsets[p], offsets[p + 1]):
                q = neighbour[i]
                if q >= 0 and label[q] < 0:
                    label[q] = count
                    stack[top] = q
                    top += 1
        count += 1
    return label


def navigation_mesh(blocked: np.ndarray) -> NavMesh:
    """The rectangle mesh of a 2-D boolean grid (``True`` = blocked, indexed ``[row, col]``)."""
    blocked = np.ascontiguousarray(blocked, dtype=np.bool_)
    h, w = blocked.shape
    cell, rect = _rectangles(blocked)
    count = _boundaries(cell, rect, False, np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0, np.int64))
    offsets = np.empty(len(rect) + 1, dtype=np.int64)
    vertex = np.empty(count, dtype=np.int64)
    neighbour = np.empty(count, dtype=np.int64)
    _boundaries(cell, rect, True, offsets, vertex, neighbour)
    # the edge from vertex[i] to the next vertex of its polygon, and its twin (the same two vertices reversed)
    poly_of = np.repeat(np.arange(len(rect)), np.diff(offsets))
    nxt = np.arange(count) + 1
    nxt[offsets[1:] - 1] = offsets[:-1]
    n_vertices = (h + 1) * (w + 1)
    key = vertex * n_vertices + vertex[nxt]
    order = np.argsort(key, kind="stable")
    wanted = vertex[nxt] * n_vertices + vertex
    pos = np.searchsorted(key, wanted, sorter=order)
    pos = np.minimum(pos, count - 1) if count else pos
    found = order[pos] if count else pos
    has = (neighbour >= 0) & (key[found] == wanted) if count else neighbour >= 0
    if not np.array_equal(has, neighbour >= 0) or not np.array_equal(poly_of[found[has]], neighbour[has]):
        raise AssertionError("navigation mesh: an edge has no matching twin in its neighbour")
    twin = np.where(has, found - offsets[neighbour.clip(0)], -1).astype(np.int64)
    pad = np.ones((h + 2, w + 2), dtype=np.int8)
    pad[1:-1, 1:-1] = blocked
    around = pad[:-1, :-1] + pad[:-1, 1:] + pad[1:, :-1] + pad[1:, 1:]
    is_corner = (around == 1).ravel()
    n_corners = int(is_corner.sum())
    corner = np.full(is_corner.shape, -1, dtype=np.int32)
    corner[is_corner] = np.arange(n_corners, dtype=np.int32)
    component = _components(offsets, neighbour)
    for a in (cell, offsets, vertex, neighbour, twin, corner, component):
        a.setflags(write=False)
    return NavMesh((h, w), cell, offsets, vertex, neighbour, twin, corner, n_corners, component)


def polygons_at(mesh: NavMesh, x: int, y: int, scale: int) -> np.ndarray:
    """The polygons whose closed area contains the point ``(x, y)`` given in units of ``1/scale`` cell."""
    h, w = mesh.shape
    cols = (x // scale - 1, x // scale) if x % scale == 0 else (x // scale,)
    rows = (y // scale - 1, y // scale) if y % scale == 0 else (y // scale,)
    found = {
        int(mesh.cell_polygon[r, c]) for r in rows for c in cols if 0 <= r < h and 0 <= c < w
    }
    found.discard(-1)
    return np.array(sorted(found), dtype=np.int64)


_meshes: "ObjectMemo[Scenario, NavMesh]" = ObjectMemo()


def scenario_mesh(scenario: "Scenario") -> NavMesh:
    """The navigation mesh of a 2-D scenario's blocked cells, built once per scenario object and kept while it lives."""
    return _meshes.value(scenario, lambda: navigation_mesh(scenario.blocked))
