"""Horn's (1981) 3 x 3 terrain gradients, compiled: the costly part of the ``ggaco`` pack's slope map."""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["horn_gradients"]


@numba.njit(cache=True)
def horn_gradients(z: np.ndarray, scale: float, lo: int, hi: int) -> tuple[np.ndarray, np.ndarray]:
    """Horn's ``dz/dx`` and ``dz/dy`` of rows ``lo:hi``: the 3 x 3 neighbours ``a b c / d . f / g h i`` weighted 1-2-1.

    A neighbour outside the grid is the nearest edge cell, a missing (NaN)
    one the centre; ``scale`` is ``8 * cell_size``. The sums are taken in
    the order ``((c + 2 f) + i) - ((a + 2 d) + g)``.
    """
    h, w = z.shape
    dzdx = np.empty((hi - lo, w))
    dzdy = np.empty((hi - lo, w))
    for r in range(lo, hi):
        up, down = max(r - 1, 0), min(r + 1, h - 1)
        for col in range(w):
            left, right = max(col - 1, 0), min(col + 1, w - 1)
            centre = z[r, col]
            a = _or_centre(z[up, left], centre)
            b = _or_centre(z[up, col], centre)
            c = _or_centre(z[up, right], centre)
            d = _or_centre(z[r, left], centre)
            f = _or_centre(z[r, right], centre)
            g = _or_centre(z[down, left], centre)
            hh = _or_centre(z[down, col], centre)
            i = _or_centre(z[down, right], centre)
            dzdx[r - lo, col] = ((c + 2.0 * f + i) - (a + 2.0 * d + g)) / scale
            dzdy[r - lo, col] = ((g + 2.0 * hh + i) - (a + 2.0 * b + c)) / scale
    return dzdx, dzdy


@numba.njit(cache=True)
def _or_centre(value: float, centre: float) -> float:
    return value if math.isfinite(value) else centre
