"""Terrain geometry: the bilinear ground surface, segment profiles and exact slope bounds.

The ground is the bilinear interpolant of the cell-centre heights: between the
four centres ``(i, j), (i+1, j), (i, j+1), (i+1, j+1)`` (a *patch*, in lattice
coordinates ``X = x - 1/2``, ``Y = y - 1/2`` with ``x, y`` in cell units) the
height is ``z = a + b X + c Y + d X Y``, and outside the ring of centres the
surface continues flat (coordinates clamped to the border centres). Along a
straight segment inside one patch the height is quadratic in the distance
travelled, so its slope is linear and takes its extremes at the ends of the
piece. :func:`segment_slope_range` cuts a segment at every patch boundary it
crosses and evaluates the slope at both ends of every piece: the exact range of
the ground slope along the whole segment, not a sample of it.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo.core.tolerances import TOUCH_EPS_CELLS

__all__ = [
    "bilinear_elevation",
    "path_profile",
    "segments_profile",
    "segment_profile",
    "segment_slope_range",
    "path_slope_ranges",
    "lattice_slope_range",
    "segments_slope_range",
    "neighbour_slope_range",
    "MAX_PIECE_CELLS",
]

MAX_PIECE_CELLS = math.sqrt(2.0) + 1e-9
"""Longest horizontal piece (in cells) a segment is split into for lengths and energy.

A move between 8-neighbours is never split, so its length and energy are
exactly those of the graph edge between the two cell centres.
"""

_EPS = TOUCH_EPS_CELLS


def bilinear_elevation(elevation: np.ndarray, xy_cells: np.ndarray) -> np.ndarray:
    """Bilinear interpolation of cell-centre heights at points given in cell units.

    Points outside the ring of cell centres are clamped to the border centres.
    A neighbour whose weight is zero is never read, so a point on the line
    between two centres does not see a NaN cell beside it; NaN heights with a
    non-zero weight propagate.
    """
    h, w = elevation.shape
    x = np.clip(np.asarray(xy_cells[:, 0], dtype=np.float64) - 0.5, 0.0, w - 1.0)
    y = np.clip(np.asarray(xy_cells[:, 1], dtype=np.float64) - 0.5, 0.0, h - 1.0)
    c0 = np.floor(x).astype(np.int64)
    r0 = np.floor(y).astype(np.int64)
    c1 = np.minimum(c0 + 1, w - 1)
    r1 = np.minimum(r0 + 1, h - 1)
    fx = x - c0
    fy = y - r0
    with np.errstate(invalid="ignore"):
        top = np.where(fx == 0, elevation[r0, c0], elevation[r0, c0] * (1 - fx) + elevation[r0, c1] * fx)
        bot = np.where(fx == 0, elevation[r1, c0], elevation[r1, c0] * (1 - fx) + elevation[r1, c1] * fx)
        return np.where(fy == 0, top, top * (1 - fy) + bot * fy)


def path_profile(
    elevation: np.ndarray | None, path: np.ndarray, cell_size: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """3-D lengths and signed mean slopes (radians) of the pieces of every segment of a ground path.

    This is the *driven profile* used for lengths and energy. Each segment is
    split into equal pieces no longer than :data:`MAX_PIECE_CELLS` cells;
    heights come from :func:`bilinear_elevation`. Without elevation every
    segment is one flat piece. Vectorised over the whole path. Slope *limits*
    are judged on the exact ground slope instead (:func:`segment_slope_range`).
    The pieces of a segment depend on that segment alone: they are
    :func:`segments_profile`'s for it.

    Returns
    -------
    lengths, slopes : ndarray
        One entry per piece, in path order.
    segment : ndarray of int
        Index of the segment each piece belongs to.
    """
    pts = np.asarray(path, dtype=np.float64)[:, :2]
    return segments_profile(elevation, pts[:-1], pts[1:], cell_size)


def segments_profile(
    elevation: np.ndarray | None, starts: np.ndarray, ends: np.ndarray, cell_size: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The pieces of :func:`path_profile` of the separate segments ``starts[i]`` to ``ends[i]`` (world ``x, y``).

    Every operation is element by element, so a segment's pieces are the
    same to the last bit whichever other segments come with it. Heights are
    read once at each of the ``n + 1`` points ``start + (j / n) (end - start)``
    of a segment of ``n`` pieces (a piece ends where the next one starts).

    Returns
    -------
    lengths, slopes, segment : ndarray
        As :func:`path_profile`'s, ``segment`` indexing ``starts``.
    """
    starts = np.asarray(starts, dtype=np.float64)[:, :2]
    d = np.asarray(ends, dtype=np.float64)[:, :2] - starts
    horiz = np.hypot(d[:, 0], d[:, 1])
    if elevation is None:
        return horiz, np.zeros(len(horiz)), np.arange(len(horiz))
    n = np.maximum(1, np.ceil(horiz / cell_size / MAX_PIECE_CELLS - 1e-12)).astype(np.int64)
    segment = np.repeat(np.arange(len(horiz)), n)
    on = np.repeat(np.arange(len(horiz)), n + 1)  # the segment of each of the n + 1 points
    j = np.arange(len(on)) - np.repeat(np.cumsum(n + 1) - (n + 1), n + 1)
    z = bilinear_elevation(elevation, (starts[on] + (j / n[on])[:, None] * d[on]) / cell_size)
    a = np.arange(len(segment)) + segment  # piece i of segment s starts at point i + s
    dz = z[a + 1] - z[a]
    dh = horiz[segment] / n[segment]
    flat = dh == 0.0  # a repeated waypoint: no length, no slope
    dz = np.where(flat, 0.0, dz)
    return np.sqrt(dh * dh + dz * dz), np.arctan2(dz, dh), segment


def segment_profile(
    elevation: np.ndarray | None, p0: np.ndarray, p1: np.ndarray, cell_size: float
) -> tuple[np.ndarray, np.ndarray]:
    """3-D lengths and signed mean slopes (radians) of the pieces of one ground segment.

    The one-segment case of :func:`path_profile`.
    """
    lengths, slopes, _ = path_profile(elevation, np.stack([np.asarray(p0, float)[:2], np.asarray(p1, float)[:2]]), cell_size)
    return lengths, slopes


@numba.njit(cache=True)
def _axis_cell(m: float, n: int) -> tuple[int, bool]:
    # lattice cell of coordinate m on an axis of n centres: (index, whether the surface varies along it)
    if n == 1 or m <= 0.0:
        return 0, False
    if m >= n - 1.0:
        return n - 1, False
    return min(int(math.floor(m)), n - 2), True


@numba.njit(cache=True)
def _weight(f: float) -> float:
    # fractional lattice coordinate; within the margin of a centre line it is that line
    # (a neighbour's weight becomes 0, so a NaN beside the line is not read)
    if f <= _EPS:
        return 0.0
    if f >= 1.0 - _EPS:
        return 1.0
    return f


@numba.njit(cache=True)
def _grad(z: np.ndarray, i: int, j: int, vary_x: bool, vary_y: bool, u: float, v: float, ex: float, ey: float) -> float:
    # derivative of the bilinear height along (ex, ey) at lattice offset (u, v) in patch (i, j);
    # terms with a zero factor are skipped so that a NaN with no weight is never read
    g = 0.0
    if vary_x and ex != 0.0:
        dzx = 0.0
        if v != 1.0:
            dzx += (z[j, i + 1] - z[j, i]) * (1.0 - v)
        if vary_y and v != 0.0:
            dzx += (z[j + 1, i + 1] - z[j + 1, i]) * v
        g += dzx * ex
    if vary_y and ey != 0.0:
        dzy = 0.0
        if u != 1.0:
            dzy += (z[j + 1, i] - z[j, i]) * (1.0 - u)
        if vary_x and u != 0.0:
            dzy += (z[j + 1, i + 1] - z[j, i + 1]) * u
        g += dzy * ey
    return g


@numba.njit(cache=True)
def _on_lattice_diagonal(xa: float, ya: float, xb: float, yb: float, w: int, h: int) -> int:
    # +1 if the segment lies on a line X - Y = k, -1 on X + Y = k (k integer, within the margin),
    # inside the ring of centres; 0 otherwise
    if xa == xb or min(xa, xb) < -_EPS or max(xa, xb) > w - 1 + _EPS or min(ya, yb) < -_EPS or max(ya, yb) > h - 1 + _EPS:
        return 0
    for sign in (1, -1):
        ka, kb = xa - sign * ya, xb - sign * yb
        k = round(ka)
        if abs(ka - k) <= _EPS and abs(kb - k) <= _EPS:
            return sign
    return 0


@numba.njit(cache=True)
def _snap(a: float) -> float:
    # a lattice coordinate within the margin of a centre is that centre
    k = round(a)
    return float(k) if abs(a - k) <= _EPS else a


@numba.njit(cache=True)
def _diagonal_step_inside(z: np.ndarray, m: int, k: int, sign: int) -> bool:
    # whether the lattice step from column m to m + 1 on the line X - sign * Y = k has both centres in the grid
    h, w = z.shape
    r0 = (m - k) if sign == 1 else (k - m)
    r1 = (m + 1 - k) if sign == 1 else (k - m - 1)
    return 0 <= m and m + 1 <= w - 1 and 0 <= min(r0, r1) and max(r0, r1) <= h - 1


@numba.njit(cache=True)
def _lattice_diagonal_range(z: np.ndarray, xa: float, ya: float, xb: float, yb: float, sign: int) -> tuple[float, float]:
    # the papers' slope between diagonal neighbours: linear between consecutive centres on the line
    k = round(xa - sign * ya)
    lo_x, hi_x = _snap(min(xa, xb)), _snap(max(xa, xb))
    direction = 1.0 if xb > xa else -1.0
    first = int(math.floor(lo_x))
    stop = max(int(math.ceil(hi_x)), first + 1)
    if not (_diagonal_step_inside(z, first, k, sign) and _diagonal_step_inside(z, stop - 1, k, sign)):
        # a segment within the margin of a lattice node on the grid's edge (it snaps to the node):
        # the step on its line that ends at the node, or none when the line leaves the grid both ways
        if not _diagonal_step_inside(z, first - 1, k, sign):
            return 0.0, 0.0
        first, stop = first - 1, first
    g_lo, g_hi = math.inf, -math.inf
    for m in range(first, stop):
        r0 = (m - k) if sign == 1 else (k - m)
        r1 = (m + 1 - k) if sign == 1 else (k - m - 1)
        g = direction * (z[r1, m + 1] - z[r0, m]) / math.sqrt(2.0)
        if not math.isfinite(g):
            return math.nan, math.nan
        g_lo, g_hi = min(g_lo, g), max(g_hi, g)
    return g_lo, g_hi


@numba.njit(cache=True)
def _crossings(a0: float, da: float, n: int) -> tuple[int, int, int]:
    # the centre lines k = 0 .. n - 1 the run a0 -> a0 + da meets, in the order it meets them:
    # (first k, k one past the last, step); an empty run when da == 0
    if da == 0.0:
        return 0, 0, 1
    lo, hi = min(a0, a0 + da), max(a0, a0 + da)
    first, last = max(0, int(math.ceil(lo))), min(n - 1, int(math.floor(hi)))
    if last < first:
        return 0, 0, 1
    if da > 0.0:
        return first, last + 1, 1
    return last, first - 1, -1


@numba.njit(cache=True)
def _crossing_t(k: int, end: int, step: int, a0: float, da: float) -> float:
    # the segment parameter of centre line k (t grows with each step), or 2 once the run is done
    if k == end:
        return 2.0
    return (k - a0) / da


@numba.njit(cache=True)
def neighbour_slope_range(z: np.ndarray, r: int, c: int, dr: int, dc: int) -> tuple[float, float]:
    """:func:`segment_slope_range` of the move from the centre of cell ``(r, c)`` to its neighbour ``(r + dr, c + dc)``.

    ``dr, dc`` in ``{-1, 0, 1}``, not both 0, and both cells inside the
    grid. The same result bit for bit, the general path's arithmetic for
    these segments only: the step between the two centres on a lattice
    diagonal (:func:`_lattice_diagonal_range`), or the one piece of a
    straight move, which lies in one patch on a centre line. The graph
    builder calls it for every candidate edge.
    """
    h, w = z.shape
    if dr != 0 and dc != 0:  # on a lattice diagonal: the step between the two centres, from left to right
        if dc == 1:
            g = 1.0 * (z[r + dr, c + dc] - z[r, c]) / math.sqrt(2.0)
        else:
            g = -1.0 * (z[r, c] - z[r + dr, c + dc]) / math.sqrt(2.0)
        if not math.isfinite(g):
            return math.nan, math.nan
        return g, g
    if dr == 0:  # along a row: the piece lies in patch (i, j) at v = 0
        i, j = min(c, c + dc), r
        g = 0.0 + (0.0 + (z[j, i + 1] - z[j, i]) * (1.0 - 0.0)) * float(dc)
        vary_other = 0 < r < h - 1
        ex, ey = float(dc), 0.0
    else:  # along a column: patch (i, j) at u = 0
        i, j = c, min(r, r + dr)
        vary_other = 0 < c < w - 1
        g = 0.0 + (0.0 + (z[j + 1, i] - z[j, i]) * (1.0 - 0.0)) * float(dr)
        ex, ey = 0.0, float(dr)
    if not math.isfinite(g):
        return math.nan, math.nan
    twist = 0.0
    if vary_other:
        twist = abs(z[j, i] + z[j + 1, i + 1] - z[j, i + 1] - z[j + 1, i])
        if not math.isfinite(twist):
            twist = 0.0
    widen = 2.0 * _EPS * twist * (abs(ex) + abs(ey))
    return g - widen, g + widen


@numba.njit(cache=True)
def segment_slope_range(z: np.ndarray, x0: float, y0: float, x1: float, y1: float) -> tuple[float, float]:
    """Least and greatest ground gradient along a segment (height units per cell travelled).

    ``z`` is the cell-centre height grid ``[row, col]``; the segment is in cell
    units. On a diagonal line of the centre lattice (the line through diagonal
    neighbours' centres) the ground is linear between consecutive centres:
    the slope between diagonal neighbours that the papers and the graph use.
    Everywhere else the range is exact for the bilinear surface (see the module
    docstring) up to the coordinate margin
    :data:`~pathzoo.core.tolerances.TOUCH_EPS_CELLS`, whose effect (at most
    the margin times the patch's twist) is added to both ends. NaN when the
    segment uses a height that is missing. A zero-length segment has range
    ``(0, 0)``.

    A segment between the centres of two neighbouring cells (the graph's
    moves) takes a shortcut, :func:`neighbour_slope_range`, with the same
    result bit for bit (``tests/core/test_validation.py`` compares the two
    on every move of several terrains).
    """
    h, w = z.shape
    dx, dy = x1 - x0, y1 - y0
    c, r = x0 - 0.5, y0 - 0.5
    if (abs(dx) == 1.0 or dx == 0.0) and (abs(dy) == 1.0 or dy == 0.0) and (dx != 0.0 or dy != 0.0) \
            and c == math.floor(c) and r == math.floor(r) and 0.0 <= min(c, c + dx) and max(c, c + dx) <= w - 1.0 \
            and 0.0 <= min(r, r + dy) and max(r, r + dy) <= h - 1.0:
        return neighbour_slope_range(z, int(r), int(c), int(dy), int(dx))
    return _segment_slope_range(z, x0, y0, x1, y1)


@numba.njit(cache=True)
def _segment_slope_range(z: np.ndarray, x0: float, y0: float, x1: float, y1: float) -> tuple[float, float]:
    # the general path of segment_slope_range
    h, w = z.shape
    dx, dy = x1 - x0, y1 - y0
    length = math.hypot(dx, dy)
    if length == 0.0:
        return 0.0, 0.0
    ex, ey = dx / length, dy / length
    X0, Y0 = x0 - 0.5, y0 - 0.5
    dX, dY = dx, dy
    diagonal = _on_lattice_diagonal(X0, Y0, X0 + dX, Y0 + dY, w, h)
    if diagonal != 0:
        return _lattice_diagonal_range(z, X0, Y0, X0 + dX, Y0 + dY, diagonal)
    # breakpoints: where the segment crosses a centre line X = k or Y = k, visited in increasing t by
    # merging the two axes' runs (each is monotonic in t), so no list is built and sorted
    kx, kx_end, sx = _crossings(X0, dX, w)
    ky, ky_end, sy = _crossings(Y0, dY, h)
    g_lo, g_hi = math.inf, -math.inf
    ta = 0.0
    while True:
        tx = _crossing_t(kx, kx_end, sx, X0, dX)
        ty = _crossing_t(ky, ky_end, sy, Y0, dY)
        if tx <= ty:
            tb = tx
            kx += sx
        else:
            tb = ty
            ky += sy
        if tb >= 1.0:
            tb = 1.0
        elif tb <= 0.0:
            continue
        if tb > ta:
            tm = 0.5 * (ta + tb)
            i, vary_x = _axis_cell(X0 + tm * dX, w)
            j, vary_y = _axis_cell(Y0 + tm * dY, h)
            twist = 0.0
            if vary_x and vary_y:
                twist = abs(z[j, i] + z[j + 1, i + 1] - z[j, i + 1] - z[j + 1, i])
                if not math.isfinite(twist):
                    twist = 0.0
            for t in (ta, tb):
                u = _weight(X0 + t * dX - i) if vary_x else 0.0
                v = _weight(Y0 + t * dY - j) if vary_y else 0.0
                g = _grad(z, i, j, vary_x, vary_y, u, v, ex, ey)
                if not math.isfinite(g):
                    return math.nan, math.nan
                widen = 2.0 * _EPS * twist * (abs(ex) + abs(ey))
                g_lo = min(g_lo, g - widen)
                g_hi = max(g_hi, g + widen)
            ta = tb
        if tb >= 1.0:
            break
    return g_lo, g_hi


@numba.njit(cache=True)
def _path_slope_ranges(z: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    n = len(u) - 1
    lo = np.empty(n)
    hi = np.empty(n)
    for k in range(n):
        lo[k], hi[k] = segment_slope_range(z, u[k, 0], u[k, 1], u[k + 1, 0], u[k + 1, 1])
    return lo, hi


def path_slope_ranges(elevation: np.ndarray, path_cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`segment_slope_range` for every segment of a polyline in cell units (one compiled pass)."""
    return _path_slope_ranges(np.ascontiguousarray(elevation, dtype=np.float64), np.ascontiguousarray(path_cells[:, :2], dtype=np.float64))


def segments_slope_range(elevation: np.ndarray, a_cells: np.ndarray, b_cells: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`segment_slope_range` of many independent segments ``a[k] -> b[k]`` (cell units, one compiled pass)."""
    return _segment_pairs_slope(
        np.ascontiguousarray(elevation, dtype=np.float64),
        np.ascontiguousarray(a_cells[:, :2], dtype=np.float64),
        np.ascontiguousarray(b_cells[:, :2], dtype=np.float64),
    )


def lattice_slope_range(elevation: np.ndarray, offset: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Gradient range of the move from every cell centre by ``offset = (d_row, d_col)``.

    Arrays of shape ``(H, W)`` in height units per cell travelled (NaN where
    the target is outside the grid or a height is missing): the graph builder
    uses them so that its edges obey exactly the rule the validator applies.
    """
    h, w = elevation.shape
    rows, cols = np.mgrid[0:h, 0:w]
    dr, dc = offset
    src = np.stack([cols.ravel() + 0.5, rows.ravel() + 0.5], axis=1)
    dst = src + np.array([dc, dr], dtype=np.float64)
    inside = (dst[:, 0] > 0) & (dst[:, 0] < w) & (dst[:, 1] > 0) & (dst[:, 1] < h)
    lo, hi = _segment_pairs_slope(np.ascontiguousarray(elevation, dtype=np.float64), src, dst)
    lo[~inside] = np.nan
    hi[~inside] = np.nan
    return lo.reshape(h, w), hi.reshape(h, w)


@numba.njit(cache=True)
def _segment_pairs_slope(z: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    lo = np.empty(len(a))
    hi = np.empty(len(a))
    for k in range(len(a)):
        lo[k], hi[k] = segment_slope_range(z, a[k, 0], a[k, 1], b[k, 0], b[k, 1])
    return lo, hi
