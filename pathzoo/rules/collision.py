"""The map's bounds and the closed-cell collision rule, for 2-D grids and air volumes."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pathzoo.core.tolerances import TOUCH_EPS_CELLS
from pathzoo.grid.segments import blocked_segments, first_blocked_cell_2d, segment_blocked_3d, to_cell_units
from pathzoo.rules.wording import fmt_point

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["outside_point", "colliding_segments", "collision_problem"]


def outside_point(scenario: "Scenario", path: np.ndarray) -> int | None:
    """Index of the first point that is not inside the map by more than the margin, or ``None``.

    Cells outside the map are blocked, so such a point always collides; this
    cheap test runs before any per-segment work, which is then bounded by the
    map's size.
    """
    u = to_cell_units(path, scenario.cell_sizes)
    size = np.array(scenario.shape[::-1], dtype=np.float64)
    inside = np.all((u > TOUCH_EPS_CELLS) & (u < size - TOUCH_EPS_CELLS), axis=1)
    if inside.all():
        return None
    return int(np.argmin(inside))


def colliding_segments(scenario: "Scenario", path: np.ndarray) -> np.ndarray:
    """For each segment, whether it touches a blocked cell (one compiled pass over the path)."""
    return blocked_segments(scenario.blocked, to_cell_units(path, scenario.cell_sizes))


def collision_problem(scenario: "Scenario", p0: np.ndarray, p1: np.ndarray) -> str | None:
    """Why the segment ``p0 -> p1`` breaks the closed-cell rule, or ``None``."""
    u0 = to_cell_units(p0, scenario.cell_sizes)
    u1 = to_cell_units(p1, scenario.cell_sizes)
    if scenario.dim == 3:
        if segment_blocked_3d(scenario.blocked, u0, u1):
            return f"segment {fmt_point(p0)} -> {fmt_point(p1)} touches a blocked voxel or leaves the volume"
        return None
    r, c = first_blocked_cell_2d(scenario.blocked, u0[0], u0[1], u1[0], u1[1])
    if r == -2:
        return None
    h, w = scenario.shape
    what = "leaves the map at" if not (0 <= r < h and 0 <= c < w) else "touches blocked cell"
    return f"segment {fmt_point(p0)} -> {fmt_point(p1)} {what} (row {r}, col {c})"
