"""A vehicle's slope limits against gradient ranges: the verdict every graph edge and path segment gets.

The ranges come from :mod:`pathzoo.grid.terrain` (exact bounds of the ground
slope along a move or segment, in height units per cell); a range breaks a
limit when the angle ``atan2(gradient, cell_size)`` of one of its ends is over
the vehicle's climb or descent limit, computed only where a comparison with
the limit's gradient cannot decide (:func:`slope_limit_band`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numba
import numpy as np

if TYPE_CHECKING:
    from pathzoo.core.vehicle import VehicleModel

__all__ = ["slope_exceeds", "slope_limit_band"]


def slope_exceeds(grad_lo: np.ndarray, grad_hi: np.ndarray, cell_size: float, vehicle: "VehicleModel") -> np.ndarray:
    """Whether gradient ranges (height units per cell) break the vehicle's climb or descent limit.

    No tolerance: an angle computed above the limit is a violation, and a
    missing height (NaN) is one too. The angle is ``atan2(gradient, cell_size)``,
    the same expression for a graph edge and for any segment.
    """
    lo = np.asarray(grad_lo, dtype=np.float64)
    hi = np.asarray(grad_hi, dtype=np.float64)
    ok = _angle_within(hi, cell_size, vehicle.max_climb_deg)
    ok &= _angle_within(-lo, cell_size, vehicle.max_descent_deg)
    return ~ok


_CUT_MARGIN = 1e-6
"""Relative band around a limit's gradient inside which :func:`_angle_within` computes the angle itself."""


def slope_limit_band(cell_size: float, limit_deg: float) -> tuple[float, float]:
    """Gradients ``(below, above)`` that bracket a slope limit: what :func:`slope_exceeds` decides by comparison.

    ``degrees(arctan2(grad, cell_size)) <= limit_deg`` holds for every
    gradient below ``below`` and fails for every gradient above ``above``
    (and for NaN); only gradients in ``[below, above]`` need the expression
    itself. The angle grows with the gradient, so away from the gradient
    ``cut`` of the limit a comparison with ``cut`` decides: the band is a
    relative :data:`_CUT_MARGIN` around it, which moves the angle by at
    least ``57.3 * sin(2 limit) / 2 * 1e-6`` degrees, some 1e-9 degrees for
    limits between 0.001 and 89.999 degrees, far more than the rounding of
    ``arctan2`` and ``degrees`` (about 1e-14 degrees). Other limits have no
    such cut: when the angle of the largest finite gradient is within the
    limit (a limit of 90 degrees), every finite gradient is, and only an
    infinite one is left to the expression; otherwise, and for an unusual
    cell size, every gradient is.
    """
    if not 0.0 < cell_size < math.inf:
        return -math.inf, math.inf
    if 0.001 <= limit_deg <= 89.999:
        cut = cell_size * math.tan(math.radians(limit_deg))
        return cut * (1.0 - _CUT_MARGIN), cut * (1.0 + _CUT_MARGIN)
    steepest = np.degrees(np.arctan2(np.array([np.finfo(np.float64).max]), cell_size))[0]
    return (math.inf, math.inf) if steepest <= limit_deg else (-math.inf, math.inf)


def _angle_within(grad: np.ndarray, cell_size: float, limit_deg: float) -> np.ndarray:
    """``degrees(arctan2(grad, cell_size)) <= limit_deg`` elementwise (False for NaN), with the angle rarely computed.

    Gradients outside :func:`slope_limit_band`'s band are decided by
    comparison; only those inside get the angle's own expression, so every
    answer is the expression's.
    """
    below, above = slope_limit_band(cell_size, limit_deg)
    with np.errstate(invalid="ignore"):
        ok, near = _split_at_cut(np.ravel(grad), below, above)
        ok[near] = np.degrees(np.arctan2(grad.ravel()[near], cell_size)) <= limit_deg
    return ok.reshape(grad.shape)


@numba.njit(cache=True)
def _split_at_cut(grad: np.ndarray, below: float, above: float) -> tuple[np.ndarray, np.ndarray]:
    """``grad < below`` per value, and the positions of the values within ``[below, above]`` (one pass, no temporaries)."""
    ok = np.empty(grad.size, dtype=np.bool_)
    near = np.empty(grad.size, dtype=np.int64)
    m = 0
    for i in range(grad.size):
        g = grad[i]
        ok[i] = g < below
        if g >= below and g <= above:
            near[m] = i
            m += 1
    return ok, near[:m]
