"""Exact segment-versus-grid tests under the closed-cell (no corner cutting) rule.

A cell is the *closed* square ``[c, c+1] x [r, r+1]`` in cell units (voxels:
closed cubes). A segment is blocked if it touches any blocked cell, even at a
single boundary point. For a diagonal move between the centres of two
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

_SNAP = 1e-9


def to_cell_units(points: np.ndarray, cell_size: float | np.ndarray) -> np.ndarray:
    """Convert world coordinates to cell units, snapping near half-integers.

    Values within 1e-9 of a multiple of 0.5 are snapped onto it, so that
    cell-centre paths stay exact despite floating-point division.
    """
    u = np.asarray(points, dtype=np.float64) / cell_size
    twice = np.round(u * 2.0)
    return np.where(np.abs(u * 2.0 - twice) < _SNAP, twice / 2.0, u)


@numba.njit(cache=True)
def _cell_range(lo: float, hi: float) -> tuple[int, int]:
    # closed cells [k, k+1] that intersect [lo, hi]
    return int(math.ceil(lo)) - 1, int(math.floor(hi))


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
        xa = max(x0, float(c))
        xb = min(x1, float(c + 1))
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
    """All cells ``(row, col)`` whose closed square the segment touches (cell units)."""
    if x0 > x1:
        x0, x1, y0, y1 = x1, x0, y1, y0
    dx, dy = x1 - x0, y1 - y0
    out = []
    c_lo, c_hi = math.ceil(x0) - 1, math.floor(x1)
    for c in range(c_lo, c_hi + 1):
        xa, xb = max(x0, float(c)), min(x1, float(c + 1))
        ya, yb = (y0, y1) if dx == 0.0 else (y0 + (xa - x0) * dy / dx, y0 + (xb - x0) * dy / dx)
        ya, yb = min(ya, yb), max(ya, yb)
        for r in range(math.ceil(ya) - 1, math.floor(yb) + 1):
            out.append((r, c))
    return np.array(out, dtype=np.int64).reshape(-1, 2)


@numba.njit(cache=True)
def _segment_touches_box(p0: np.ndarray, d: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> bool:
    tmin, tmax = 0.0, 1.0
    for k in range(3):
        if d[k] == 0.0:
            if p0[k] < lo[k] or p0[k] > hi[k]:
                return False
        else:
            t1 = (lo[k] - p0[k]) / d[k]
            t2 = (hi[k] - p0[k]) / d[k]
            if t1 > t2:
                t1, t2 = t2, t1
            tmin = max(tmin, t1)
            tmax = min(tmax, t2)
            if tmin > tmax:
                return False
    return True


@numba.njit(cache=True)
def segment_blocked_3d(blocked: np.ndarray, p0: np.ndarray, p1: np.ndarray) -> bool:
    """True if the segment touches a blocked or out-of-grid voxel.

    ``blocked`` is indexed ``[z, y, x]``; ``p0`` and ``p1`` are ``(x, y, z)`` in
    cell units (each axis divided by its own cell size).
    """
    nz, ny, nx = blocked.shape
    d = p1 - p0
    lo = np.empty(3)
    hi = np.empty(3)
    ranges = np.empty((3, 2), dtype=np.int64)
    for k in range(3):
        a, b = min(p0[k], p1[k]), max(p0[k], p1[k])
        ranges[k, 0] = int(math.ceil(a)) - 1
        ranges[k, 1] = int(math.floor(b))
    for z in range(ranges[2, 0], ranges[2, 1] + 1):
        for y in range(ranges[1, 0], ranges[1, 1] + 1):
            for x in range(ranges[0, 0], ranges[0, 1] + 1):
                lo[0], lo[1], lo[2] = x, y, z
                hi[0], hi[1], hi[2] = x + 1, y + 1, z + 1
                if not _segment_touches_box(p0, d, lo, hi):
                    continue
                if x < 0 or y < 0 or z < 0 or x >= nx or y >= ny or z >= nz:
                    return True
                if blocked[z, y, x]:
                    return True
    return False


def touched_cells_3d(p0: np.ndarray, p1: np.ndarray) -> np.ndarray:
    """All voxels ``(z, y, x)`` whose closed cube the segment touches (cell units)."""
    p0 = np.asarray(p0, dtype=np.float64)
    p1 = np.asarray(p1, dtype=np.float64)
    d = p1 - p0
    lo = np.minimum(p0, p1)
    hi = np.maximum(p0, p1)
    rng = [range(math.ceil(lo[k]) - 1, math.floor(hi[k]) + 1) for k in range(3)]
    out = []
    for z in rng[2]:
        for y in rng[1]:
            for x in rng[0]:
                if _segment_touches_box(p0, d, np.array([x, y, z], float), np.array([x + 1, y + 1, z + 1], float)):
                    out.append((z, y, x))
    return np.array(out, dtype=np.int64).reshape(-1, 3)


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
