"""Conservative segment-versus-grid tests under the closed-cell (no corner cutting) rule.

A cell is the *closed* square ``[c, c+1] x [r, r+1]`` in cell units (voxels:
closed cubes). A segment is blocked if it touches any blocked cell, even at a
single boundary point, or comes within :data:`~pathzoo.core.tolerances.TOUCH_EPS_CELLS`
of one (per axis): every test here runs against the cells grown by that margin,
so floating-point rounding (far smaller) can only make it reject more. For a diagonal move between the centres of two
8-neighbours the segment passes through the shared corner, so it touches all
four cells: exactly the MovingAI rule that a diagonal needs both orthogonal
neighbours free. The same functions serve graph construction, line-of-sight
for any-angle planners and the harness's validator, so they always agree.

All coordinates here are in *cell units* (world coordinates divided by the
cell size); see :func:`to_cell_units`. Cells outside the grid count as blocked.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo.core.tolerances import TOUCH_EPS_CELLS

__all__ = [
    "to_cell_units",
    "segment_blocked_2d",
    "segment_blocked_3d",
    "first_blocked_cell_2d",
    "count_blocked_cells_2d",
    "blocked_segments",
    "touched_cells_2d",
    "touched_cells_3d",
]

_EPS = TOUCH_EPS_CELLS


def to_cell_units(points: np.ndarray, cell_size: float | np.ndarray) -> np.ndarray:
    """Convert world coordinates to cell units (a plain division, no snapping).

    Nothing is snapped: the rounding of the division (about 1e-16 relative)
    is covered by the margin the tests here add around every blocked cell.
    """
    return np.asarray(points, dtype=np.float64) / cell_size


@numba.njit(cache=True)
def _cell_range(lo: float, hi: float) -> tuple[int, int]:
    # cells [k, k+1] grown by _EPS on both sides that intersect [lo, hi]
    return int(math.ceil(lo - _EPS)) - 1, int(math.floor(hi + _EPS))


@numba.njit(cache=True)
def _scan_2d(blocked: np.ndarray, x0: float, y0: float, x1: float, y1: float, first_only: bool) -> tuple[int, int, int]:
    # walk the closed cells the segment touches, column by column from its left end;
    # return (number of blocked or out-of-grid cells, row, col of the first one or -2, -2)
    h, w = blocked.shape
    if x0 > x1:
        x0, x1 = x1, x0
        y0, y1 = y1, y0
    dx = x1 - x0
    dy = y1 - y0
    count, first_r, first_c = 0, -2, -2
    c_lo, c_hi = _cell_range(x0, x1)
    for c in range(c_lo, c_hi + 1):
        xa = max(x0, c - _EPS)
        xb = min(x1, c + 1 + _EPS)
        if dx == 0.0:
            ya, yb = y0, y1
        else:
            ya = y0 + (xa - x0) * dy / dx
            yb = y0 + (xb - x0) * dy / dx
        if ya > yb:
            ya, yb = yb, ya
        r_lo, r_hi = _cell_range(ya, yb)
        for r in range(r_lo, r_hi + 1):
            if r < 0 or c < 0 or r >= h or c >= w or blocked[r, c]:
                if count == 0:
                    first_r, first_c = r, c
                count += 1
                if first_only:
                    return count, first_r, first_c
    return count, first_r, first_c


@numba.njit(cache=True)
def first_blocked_cell_2d(blocked: np.ndarray, x0: float, y0: float, x1: float, y1: float) -> tuple[int, int]:
    """Return ``(row, col)`` of the first blocked cell the segment touches, or ``(-2, -2)``.

    Out-of-grid cells are blocked and may be returned with indices outside the
    grid. ``blocked`` is a boolean array indexed ``[row, col]``; ``x`` is the
    column axis and ``y`` the row axis, both in cell units.
    """
    _, r, c = _scan_2d(blocked, x0, y0, x1, y1, True)
    return r, c


@numba.njit(cache=True)
def count_blocked_cells_2d(blocked: np.ndarray, x0: float, y0: float, x1: float, y1: float) -> int:
    """Number of blocked or out-of-grid cells the segment touches (cell units).

    Zero exactly when :func:`segment_blocked_2d` is False; the count grows with
    how deep the segment cuts into obstacles, which penalty-based optimisers use
    as a collision measure.
    """
    return _scan_2d(blocked, x0, y0, x1, y1, False)[0]


@numba.njit(cache=True)
def segment_blocked_2d(blocked: np.ndarray, x0: float, y0: float, x1: float, y1: float) -> bool:
    """True if the segment touches a blocked or out-of-grid cell (cell units)."""
    r, _ = first_blocked_cell_2d(blocked, x0, y0, x1, y1)
    return r != -2


def touched_cells_2d(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    """All cells ``(row, col)`` whose closed square the segment touches or comes within the margin of (cell units)."""
    if x0 > x1:
        x0, x1, y0, y1 = x1, x0, y1, y0
    dx, dy = x1 - x0, y1 - y0
    out = []
    c_lo, c_hi = _cell_range(x0, x1)
    for c in range(c_lo, c_hi + 1):
        xa, xb = max(x0, c - _EPS), min(x1, c + 1 + _EPS)
        ya, yb = (y0, y1) if dx == 0.0 else (y0 + (xa - x0) * dy / dx, y0 + (xb - x0) * dy / dx)
        ya, yb = min(ya, yb), max(ya, yb)
        r_lo, r_hi = _cell_range(ya, yb)
        for r in range(r_lo, r_hi + 1):
            out.append((r, c))
    return np.array(out, dtype=np.int64).reshape(-1, 2)


@numba.njit(cache=True)
def _slab(p: float, d: float, lo: float, hi: float) -> tuple[float, float]:
    # parameters t in [0, 1] with lo <= p + t d <= hi (empty when first > second)
    if d == 0.0:
        if p < lo or p > hi:
            return 1.0, 0.0
        return 0.0, 1.0
    t1 = (lo - p) / d
    t2 = (hi - p) / d
    if t1 > t2:
        t1, t2 = t2, t1
    return max(0.0, t1), min(1.0, t2)


@numba.njit(cache=True)
def _voxels_3d(p0: np.ndarray, p1: np.ndarray) -> np.ndarray:
    # voxels (z, y, x) whose cube, grown by the margin, the segment meets: x slabs, then
    # y rows inside each, then the z range, so the work grows with the voxels passed
    d = p1 - p0
    found = [(0, 0, 0) for _ in range(0)]
    cx_lo, cx_hi = _cell_range(min(p0[0], p1[0]), max(p0[0], p1[0]))
    for cx in range(cx_lo, cx_hi + 1):
        ta, tb = _slab(p0[0], d[0], cx - _EPS, cx + 1 + _EPS)
        if ta > tb:
            continue
        ya, yb = p0[1] + ta * d[1], p0[1] + tb * d[1]
        cy_lo, cy_hi = _cell_range(min(ya, yb), max(ya, yb))
        for cy in range(cy_lo, cy_hi + 1):
            ua, ub = _slab(p0[1], d[1], cy - _EPS, cy + 1 + _EPS)
            ua, ub = max(ua, ta), min(ub, tb)
            if ua > ub:
                continue
            za, zb = p0[2] + ua * d[2], p0[2] + ub * d[2]
            cz_lo, cz_hi = _cell_range(min(za, zb), max(za, zb))
            for cz in range(cz_lo, cz_hi + 1):
                found.append((cz, cy, cx))
    out = np.empty((len(found), 3), dtype=np.int64)
    for i in range(len(found)):
        out[i, 0], out[i, 1], out[i, 2] = found[i]
    return out


@numba.njit(cache=True)
def segment_blocked_3d(blocked: np.ndarray, p0: np.ndarray, p1: np.ndarray) -> bool:
    """True if the segment touches (or comes within the margin of) a blocked or out-of-grid voxel.

    ``blocked`` is indexed ``[z, y, x]``; ``p0`` and ``p1`` are ``(x, y, z)`` in
    cell units (each axis divided by its own cell size).
    """
    nz, ny, nx = blocked.shape
    for v in _voxels_3d(p0, p1):
        cz, cy, cx = v[0], v[1], v[2]
        if cx < 0 or cy < 0 or cz < 0 or cx >= nx or cy >= ny or cz >= nz or blocked[cz, cy, cx]:
            return True
    return False


def touched_cells_3d(p0: np.ndarray, p1: np.ndarray) -> np.ndarray:
    """All voxels ``(z, y, x)`` whose closed cube the segment touches or comes within the margin of (cell units)."""
    return _voxels_3d(np.asarray(p0, dtype=np.float64), np.asarray(p1, dtype=np.float64))


@numba.njit(cache=True)
def _blocked_segments_2d(blocked: np.ndarray, u: np.ndarray) -> np.ndarray:
    out = np.zeros(len(u) - 1, dtype=np.bool_)
    for k in range(len(u) - 1):
        out[k] = segment_blocked_2d(blocked, u[k, 0], u[k, 1], u[k + 1, 0], u[k + 1, 1])
    return out


@numba.njit(cache=True)
def _blocked_segments_3d(blocked: np.ndarray, u: np.ndarray) -> np.ndarray:
    out = np.zeros(len(u) - 1, dtype=np.bool_)
    for k in range(len(u) - 1):
        out[k] = segment_blocked_3d(blocked, u[k], u[k + 1])
    return out


def blocked_segments(blocked: np.ndarray, path_cells: np.ndarray) -> np.ndarray:
    """For each segment of a polyline (in cell units), whether it touches a blocked cell.

    One compiled pass over the whole path: :func:`segment_blocked_2d` for 2-D
    grids, :func:`segment_blocked_3d` for volumes (``path_cells`` columns in
    ``x, y[, z]`` order).
    """
    u = np.ascontiguousarray(path_cells, dtype=np.float64)
    if blocked.ndim == 2:
        return _blocked_segments_2d(blocked, u)
    return _blocked_segments_3d(blocked, u)
