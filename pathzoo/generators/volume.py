"""Air volumes from terrain: voxels below the ground surface are blocked."""

from __future__ import annotations

import numpy as np

from pathzoo.generators.checks import check_number

__all__ = ["terrain_volume"]


def terrain_volume(elevation: np.ndarray, layers: int, vertical_cell_size: float) -> np.ndarray:
    """Occupancy ``(layers, H, W)`` of the air above a ground surface.

    Voxel ``(layer, row, col)`` spans heights ``[layer, layer + 1) x
    vertical_cell_size``; it is blocked when its bottom is below the ground
    height at the cell centre (so a voxel is free only if it lies wholly
    above the ground there), and every voxel of a column whose elevation is
    NaN (no data) is blocked. This is how DSACO's mountain model (eq. 1) is
    turned into a 3-D grid.

    Parameters
    ----------
    elevation : ndarray of shape (H, W)
        Ground height in metres.
    layers : int
        Number of voxel layers (>= 1).
    vertical_cell_size : float
        Voxel height in metres (> 0).
    """
    layers = int(check_number(layers, "layers", low=1, integer=True))
    vcs = check_number(vertical_cell_size, "vertical_cell_size", low=0.0, low_open=True)
    ground = np.asarray(elevation, dtype=np.float64)
    bottoms = np.arange(layers, dtype=np.float64)[:, None, None] * vcs
    with np.errstate(invalid="ignore"):
        return (bottoms < ground[None]) | ~np.isfinite(ground)[None]
