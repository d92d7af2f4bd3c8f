"""Clearance map: Euclidean distance transform of the free space."""

from __future__ import annotations

import numpy as np
from scipy import ndimage

__all__ = ["clearance_map"]


def clearance_map(blocked: np.ndarray, sampling: np.ndarray) -> np.ndarray:
    """Distance (metres) from every cell centre to the nearest blocked cell centre.

    The grid is padded with one ring of blocked cells, so the map border acts as
    an obstacle. Blocked cells have clearance 0.

    Parameters
    ----------
    blocked : ndarray of bool
        Blocked cells.
    sampling : sequence of float
        Cell size along each array axis (``[row, col]`` or ``[layer, row, col]``).
    """
    padded = np.pad(~blocked, 1, constant_values=False)
    dist = ndimage.distance_transform_edt(padded, sampling=np.asarray(sampling, dtype=np.float64))
    inner = tuple(slice(1, -1) for _ in range(blocked.ndim))
    out = np.ascontiguousarray(dist[inner])
    out.setflags(write=False)
    return out
