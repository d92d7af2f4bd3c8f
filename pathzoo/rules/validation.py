"""The whole check of a returned path: the judge every planner faces.

A path is valid when

- it is a finite ``(N, d)`` array with ``N >= 1``;
- it starts at the scenario's start and ends at its goal (to
  :data:`~pathzoo.core.tolerances.ENDPOINT_TOLERANCE_CELLS`; the short
  connectors are checked for collisions too);
- every point lies inside the map, and every segment touches no blocked cell,
  not even at a corner or within the margin (:mod:`pathzoo.rules.collision`);
- on terrain the exact ground slope along every segment, and in air volumes
  the pitch of every segment, are within the vehicle's limits
  (:mod:`pathzoo.rules.slope`);
- the heading changes within any stretch shorter than one cell add up to at
  most the turn limit (:mod:`pathzoo.rules.turns`);
- on dynamic scenarios the timed path, waiting at its first point from time
  0, never comes within any moving obstacle's radius, and never moves faster
  than cruise speed (:mod:`pathzoo.rules.timing`).

The cheap whole-path tests (shape, bounds) run first, and each rule is one
vectorised or compiled pass, so judging costs at most the path's size times
the map's diameter.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from pathzoo.core.tolerances import ENDPOINT_TOLERANCE_CELLS
from pathzoo.rules.collision import colliding_segments, collision_problem, outside_point
from pathzoo.rules.slope import slope_problem, steep_segments
from pathzoo.rules.timing import obstacle_problem, path_times, timed_path_problem, times_problem
from pathzoo.rules.turns import turn_problem
from pathzoo.rules.wording import fmt_point

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["Validation", "validate_path", "segment_problem"]


@dataclass(frozen=True)
class Validation:
    """Outcome of :func:`validate_path`."""

    valid: bool
    reason: str = ""

    def __bool__(self) -> bool:
        return self.valid


def segment_problem(
    scenario: "Scenario", p0: np.ndarray, p1: np.ndarray, t0: float = 0.0, t1: float | None = None
) -> str | None:
    """Describe why the segment ``p0 -> p1`` is not allowed, or return ``None``.

    Checks the map's bounds, the closed-cell collision rule, slope or pitch
    limits and moving obstacles. ``t0``/``t1`` are the departure and arrival
    times (default arrival: at cruise speed). Turn limits involve several
    segments and are checked only on whole paths.
    """
    p0 = np.asarray(p0, dtype=np.float64)
    p1 = np.asarray(p1, dtype=np.float64)
    ends = np.stack([p0, p1])
    if not np.isfinite(ends).all():
        return f"segment {fmt_point(p0)} -> {fmt_point(p1)} has a NaN or infinite coordinate"
    k = outside_point(scenario, ends)
    if k is not None:
        return f"point {fmt_point(ends[k])} lies outside the map or on its edge"
    problem = collision_problem(scenario, p0, p1) or slope_problem(scenario, p0, p1)
    if problem is None and scenario.moving_obstacles:
        if t1 is None:
            t1 = t0 + float(np.linalg.norm(p1 - p0)) / scenario.vehicle.cruise_speed
        found = obstacle_problem(scenario, p0[None, :2], p1[None, :2], np.array([t0]), np.array([t1]))
        problem = None if found is None else found[1]
    return problem


def _with_connectors(scenario: "Scenario", path: np.ndarray) -> np.ndarray:
    """The path with the start and goal added where its ends are only close to them."""
    head = [] if np.array_equal(path[0], scenario.start) else [scenario.start[None, :]]
    tail = [] if np.array_equal(path[-1], scenario.goal) else [scenario.goal[None, :]]
    return np.vstack([*head, path, *tail]) if head or tail else path


def validate_path(scenario: "Scenario", path: object, times: object = None) -> Validation:
    """Check a planner's path against the scenario; see the module docstring.

    Returns
    -------
    Validation
        ``valid`` and, when invalid, a one-line ``reason``.
    """
    try:
        arr = np.asarray(path, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        return Validation(False, "path is not a numeric array")
    if arr.ndim != 2 or arr.shape[1] != scenario.dim or len(arr) < 1:
        return Validation(False, f"path must have shape (N, {scenario.dim}) with N >= 1, got {arr.shape}")
    if not np.isfinite(arr).all():
        return Validation(False, "path contains NaN or infinite coordinates")
    tol = ENDPOINT_TOLERANCE_CELLS * scenario.cell_size
    if np.max(np.abs(arr[0] - scenario.start)) > tol:
        return Validation(False, f"path starts at {fmt_point(arr[0])}, not at the start {fmt_point(scenario.start)}")
    if np.max(np.abs(arr[-1] - scenario.goal)) > tol:
        return Validation(False, f"path ends at {fmt_point(arr[-1])}, not at the goal {fmt_point(scenario.goal)}")
    if times is not None:
        problem, t = times_problem(scenario, arr, times)
        if problem is not None:
            return Validation(False, problem)
    else:
        t = path_times(scenario, arr)
    k = outside_point(scenario, arr)
    if k is not None:
        return Validation(False, f"point {k} {fmt_point(arr[k])} lies outside the map or on its edge")
    geo = _with_connectors(scenario, arr)
    flagged = colliding_segments(scenario, geo) | steep_segments(scenario, geo)
    if flagged.any():
        i = int(np.argmax(flagged))
        reason = collision_problem(scenario, geo[i], geo[i + 1]) or slope_problem(scenario, geo[i], geo[i + 1])
        return Validation(False, f"segment {i}: {reason}")
    problem = turn_problem(scenario, arr) or timed_path_problem(scenario, arr, t)
    if problem is not None:
        return Validation(False, problem)
    return Validation(True)
