"""Compiled state and motion checks for OMPL: the judge's segment and slope rules as one numba call each.

OMPL calls a Python motion validator once per motion; everything that call
does beyond crossing into Python happens here, in one compiled call on
arrays prepared once per ``plan()``:

- :func:`segment_clear`: the closed-cell collision rule of
  :func:`pathzoo.grid.segments.segment_blocked_2d`, on the validator's
  snapped cell units (``tests/ompl/test_ompl_validator.py`` checks both agree
  with :func:`~pathzoo.harness.validation.segment_problem`);
- :func:`terrain_motion_clear`: the same rule, then the slope limits over
  the pieces :func:`pathzoo.grid.terrain.path_profile` cuts the segment into,
  with the same bilinear heights. It is conservative: a piece is refused
  when its slope is within :data:`SLOPE_MARGIN_DEG` of a limit the judge
  would still accept, so floating-point differences between this loop and
  the judge's numpy code can only make OMPL stricter, never laxer.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo.grid.segments import segment_blocked_2d
from pathzoo.grid.terrain import MAX_PIECE_CELLS

__all__ = ["SLOPE_MARGIN_DEG", "segment_clear", "terrain_motion_clear"]

SLOPE_MARGIN_DEG = 1e-6
"""Degrees by which a motion's slope must stay inside the vehicle's climb and descent limits."""


@numba.njit(cache=True)
def _cell_unit(v: float, cell_size: float) -> float:
    # one coordinate of pathzoo.grid.segments.to_cell_units (snap within 1e-9 of a multiple of 0.5),
    # as a scalar numba function; tests/ompl/test_ompl_validator.py checks that they agree
    u = v / cell_size
    twice = np.round(u * 2.0)
    return twice / 2.0 if abs(u * 2.0 - twice) < 1e-9 else u


@numba.njit(cache=True)
def segment_clear(blocked: np.ndarray, cell_size: float, x0: float, y0: float, x1: float, y1: float) -> bool:
    """The closed-cell collision rule of the validator for a world-coordinate segment, without numpy overhead."""
    return not segment_blocked_2d(
        blocked,
        _cell_unit(x0, cell_size),
        _cell_unit(y0, cell_size),
        _cell_unit(x1, cell_size),
        _cell_unit(y1, cell_size),
    )


@numba.njit(cache=True)
def _height(elevation: np.ndarray, xc: float, yc: float) -> float:
    # pathzoo.grid.terrain.bilinear_elevation for one point in cell units
    h, w = elevation.shape
    x = min(max(xc - 0.5, 0.0), w - 1.0)
    y = min(max(yc - 0.5, 0.0), h - 1.0)
    c0 = min(int(math.floor(x)), max(w - 2, 0))
    r0 = min(int(math.floor(y)), max(h - 2, 0))
    c1 = min(c0 + 1, w - 1)
    r1 = min(r0 + 1, h - 1)
    fx = x - c0
    fy = y - r0
    if fx == 0:
        top, bot = elevation[r0, c0], elevation[r1, c0]
    else:
        top = elevation[r0, c0] * (1 - fx) + elevation[r0, c1] * fx
        bot = elevation[r1, c0] * (1 - fx) + elevation[r1, c1] * fx
    return top if fy == 0 else top * (1 - fy) + bot * fy


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
    """:func:`segment_clear`, then every piece's slope within the limits minus :data:`SLOPE_MARGIN_DEG`."""
    if not segment_clear(blocked, cell_size, x0, y0, x1, y1):
        return False
    dx = x1 - x0
    dy = y1 - y0
    horiz = math.hypot(dx, dy)
    if horiz == 0.0:
        return True
    n = max(1, int(math.ceil(horiz / cell_size / MAX_PIECE_CELLS - 1e-12)))
    dh = horiz / n
    climb = max_climb_deg - SLOPE_MARGIN_DEG
    descent = max_descent_deg - SLOPE_MARGIN_DEG
    za = _height(elevation, x0 / cell_size, y0 / cell_size)
    for k in range(n):
        t = (k + 1) / n
        zb = _height(elevation, (x0 + t * dx) / cell_size, (y0 + t * dy) / cell_size)
        deg = math.degrees(math.atan2(zb - za, dh))
        if not math.isfinite(deg) or deg > climb or -deg > descent:
            return False
        za = zb
    return True


def compile_now() -> None:
    """Compile both checks for read-only maps now, at import, not inside a timed ``plan()``."""
    blocked = np.zeros((2, 2), dtype=bool)
    blocked.setflags(write=False)
    elevation = np.zeros((2, 2))
    elevation.setflags(write=False)
    segment_clear(blocked, 1.0, 0.5, 0.5, 1.5, 1.5)
    terrain_motion_clear(blocked, elevation, 1.0, 30.0, 30.0, 0.5, 0.5, 1.5, 1.5)
