"""Compiled state and motion checks for OMPL: the judge's segment and slope rules as one numba call each.

OMPL calls a Python motion validator once per motion; everything that call
does beyond crossing into Python happens here, in one compiled call on
arrays prepared once per ``plan()``:

- :func:`segment_clear`: the closed-cell collision rule of
  :func:`pathzoo.grid.segments.segment_blocked_2d` (with its margin), on
  cell units (``tests/ompl/test_ompl_validator.py`` checks that it agrees
  with :func:`~pathzoo.rules.segment_problem`);
- :func:`terrain_motion_clear`: the same rule, then the slope limits over the
  exact gradient range of the segment,
  :func:`pathzoo.grid.terrain.segment_slope_range`, the function the judge
  uses. It is conservative: a segment is refused when its slope comes within
  :data:`SLOPE_MARGIN_DEG` of a limit, so rounding can only make OMPL
  stricter than the judge, never laxer.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo.grid.segments import segment_blocked_2d
from pathzoo.grid.terrain import segment_slope_range

__all__ = ["SLOPE_MARGIN_DEG", "segment_clear", "terrain_motion_clear"]

SLOPE_MARGIN_DEG = 1e-6
"""Degrees by which a motion's slope must stay inside the vehicle's climb and descent limits."""


@numba.njit(cache=True)
def segment_clear(blocked: np.ndarray, cell_size: float, x0: float, y0: float, x1: float, y1: float) -> bool:
    """The closed-cell collision rule of the validator for a world-coordinate segment, without numpy overhead."""
    return not segment_blocked_2d(blocked, x0 / cell_size, y0 / cell_size, x1 / cell_size, y1 / cell_size)


@numba.njit(cache=True)
def terrain_motion_clear(
    blocked: np.ndarray,
    elevation: np.ndarray,
    cell_size: float,
    max_climb_deg: float,
    max_descent_deg: float,
    x0: float,
    y0: float,
    x1: float,
    y1: float,
) -> bool:
    """:func:`segment_clear`, then the segment's gradient range within the limits minus :data:`SLOPE_MARGIN_DEG`."""
    if not segment_clear(blocked, cell_size, x0, y0, x1, y1):
        return False
    g_lo, g_hi = segment_slope_range(elevation, x0 / cell_size, y0 / cell_size, x1 / cell_size, y1 / cell_size)
    if not (math.isfinite(g_lo) and math.isfinite(g_hi)):
        return False
    climb = math.degrees(math.atan2(g_hi, cell_size))
    descent = math.degrees(math.atan2(-g_lo, cell_size))
    return climb <= max_climb_deg - SLOPE_MARGIN_DEG and descent <= max_descent_deg - SLOPE_MARGIN_DEG


def compile_now() -> None:
    """Compile both checks for read-only maps now, at import, not inside a timed ``plan()``."""
    blocked = np.zeros((2, 2), dtype=bool)
    blocked.setflags(write=False)
    elevation = np.zeros((2, 2))
    elevation.setflags(write=False)
    segment_clear(blocked, 1.0, 0.5, 0.5, 1.5, 1.5)
    terrain_motion_clear(blocked, elevation, 1.0, 30.0, 30.0, 0.5, 0.5, 1.5, 1.5)
