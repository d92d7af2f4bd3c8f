"""Terrain geometry: bilinear heights, 3-D segment profiles and slopes."""

from __future__ import annotations

import math

import numpy as np

__all__ = ["bilinear_elevation", "path_profile", "segment_profile", "MAX_PIECE_CELLS"]

MAX_PIECE_CELLS = math.sqrt(2.0) + 1e-9
"""Longest horizontal piece (in cells) a segment is split into for slope checks.

A move between 8-neighbours is never split, so its slope is exactly the slope
of the graph edge between the two cell centres.
"""


def bilinear_elevation(elevation: np.ndarray, xy_cells: np.ndarray) -> np.ndarray:
    """Bilinear interpolation of cell-centre heights at points given in cell units.

    Points outside the ring of cell centres are clamped to the border centres.
    NaN heights propagate to the points that use them.
    """
    h, w = elevation.shape
    x = np.clip(np.asarray(xy_cells[:, 0], dtype=np.float64) - 0.5, 0.0, w - 1.0)
    y = np.clip(np.asarray(xy_cells[:, 1], dtype=np.float64) - 0.5, 0.0, h - 1.0)
    c0 = np.minimum(np.floor(x).astype(np.int64), max(w - 2, 0))
    r0 = np.minimum(np.floor(y).astype(np.int64), max(h - 2, 0))
    c1 = np.minimum(c0 + 1, w - 1)
    r1 = np.minimum(r0 + 1, h - 1)
    fx = x - c0
    fy = y - r0
    # exact at cell centres (fx or fy == 0 must not mix in a NaN neighbour)
    top = np.where(fx == 0, elevation[r0, c0], elevation[r0, c0] * (1 - fx) + elevation[r0, c1] * fx)
    bot = np.where(fx == 0, elevation[r1, c0], elevation[r1, c0] * (1 - fx) + elevation[r1, c1] * fx)
    return np.where(fy == 0, top, top * (1 - fy) + bot * fy)


def path_profile(
    elevation: np.ndarray | None, path: np.ndarray, cell_size: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """3-D lengths and signed slopes (radians) of the pieces of every segment of a ground path.

    Each segment is split into equal pieces no longer than
    :data:`MAX_PIECE_CELLS` cells; heights come from :func:`bilinear_elevation`.
    Without elevation every segment is one flat piece. Vectorised over the
    whole path.

    Returns
    -------
    lengths, slopes : ndarray
        One entry per piece, in path order.
    segment : ndarray of int
        Index of the segment each piece belongs to.
    """
    pts = np.asarray(path, dtype=np.float64)[:, :2]
    d = np.diff(pts, axis=0)
    horiz = np.hypot(d[:, 0], d[:, 1])
    if elevation is None:
        return horiz, np.zeros(len(horiz)), np.arange(len(horiz))
    n = np.maximum(1, np.ceil(horiz / cell_size / MAX_PIECE_CELLS - 1e-12)).astype(np.int64)
    segment = np.repeat(np.arange(len(horiz)), n)
    first = np.repeat(np.cumsum(n) - n, n)
    k = np.arange(len(segment)) - first
    nn = n[segment]
    a = pts[segment] + (k / nn)[:, None] * d[segment]
    b = pts[segment] + ((k + 1) / nn)[:, None] * d[segment]
    dz = bilinear_elevation(elevation, b / cell_size) - bilinear_elevation(elevation, a / cell_size)
    dh = horiz[segment] / nn
    flat = dh == 0.0  # a repeated waypoint: no length, no slope
    dz = np.where(flat, 0.0, dz)
    return np.sqrt(dh * dh + dz * dz), np.arctan2(dz, dh), segment


def segment_profile(
    elevation: np.ndarray | None, p0: np.ndarray, p1: np.ndarray, cell_size: float
) -> tuple[np.ndarray, np.ndarray]:
    """3-D lengths and signed slopes (radians) of the pieces of one ground segment.

    The one-segment case of :func:`path_profile`.
    """
    lengths, slopes, _ = path_profile(elevation, np.stack([np.asarray(p0, float)[:2], np.asarray(p1, float)[:2]]), cell_size)
    return lengths, slopes
