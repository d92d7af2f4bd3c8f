"""Slope limits: the ground slope on terrain and the pitch in air volumes.

On terrain the ground is the bilinear surface through the cell-centre heights
(:mod:`pathzoo.grid.terrain`). The slope a vehicle meets at a point of a segment
is the surface's derivative along the segment; its whole range over the
segment is computed exactly (:func:`~pathzoo.grid.terrain.segment_slope_range`),
so no bump between two waypoints can hide. In air volumes the pitch of a
straight segment is constant. No angle tolerance is allowed: an angle computed
above the limit is a violation.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pathzoo.grid.slope_limit import slope_exceeds
from pathzoo.grid.terrain import path_slope_ranges, segment_slope_range
from pathzoo.rules.wording import fmt_point

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["steep_segments", "slope_problem", "segment_pitch_deg"]


def segment_pitch_deg(d: np.ndarray) -> np.ndarray:
    """Pitch (degrees, unsigned) of air segments with displacement rows ``(dx, dy, dz)``."""
    d = np.atleast_2d(np.asarray(d, dtype=np.float64))
    return np.degrees(np.arctan2(np.abs(d[:, 2]), np.hypot(d[:, 0], d[:, 1])))


def steep_segments(scenario: "Scenario", path: np.ndarray) -> np.ndarray:
    """For each segment, whether it breaks a slope or pitch limit (vectorised over the path)."""
    n = len(path) - 1
    if scenario.kind == "terrain":
        assert scenario.elevation is not None  # every terrain scenario has one (checked when it was built)
        lo, hi = path_slope_ranges(scenario.elevation, path / scenario.cell_size)
        return slope_exceeds(lo, hi, scenario.cell_size, scenario.vehicle)
    if scenario.dim == 3:
        return segment_pitch_deg(np.diff(path, axis=0)) > scenario.vehicle.max_pitch_deg
    return np.zeros(n, dtype=bool)


def slope_problem(scenario: "Scenario", p0: np.ndarray, p1: np.ndarray) -> str | None:
    """Why the segment ``p0 -> p1`` breaks a slope or pitch limit, or ``None``."""
    v = scenario.vehicle
    where = f"segment {fmt_point(p0)} -> {fmt_point(p1)}"
    if scenario.dim == 3:
        pitch = float(segment_pitch_deg(np.asarray(p1) - np.asarray(p0))[0])
        if pitch > v.max_pitch_deg:
            return f"{where} pitches {pitch:.3f} deg > limit {v.max_pitch_deg}"
        return None
    if scenario.kind != "terrain":
        return None
    cs = scenario.cell_size
    u0, u1 = np.asarray(p0, dtype=np.float64) / cs, np.asarray(p1, dtype=np.float64) / cs
    lo, hi = segment_slope_range(np.ascontiguousarray(scenario.elevation), u0[0], u0[1], u1[0], u1[1])
    if not slope_exceeds(np.array([lo]), np.array([hi]), cs, v)[0]:
        return None
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return f"{where} crosses ground without elevation"
    climb = math.degrees(math.atan2(hi, cs))
    if climb > v.max_climb_deg:
        return f"{where} climbs {climb:.3f} deg > limit {v.max_climb_deg}"
    return f"{where} descends {math.degrees(math.atan2(-lo, cs)):.3f} deg > limit {v.max_descent_deg}"
