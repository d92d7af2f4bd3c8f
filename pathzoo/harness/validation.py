"""The harness's own check of a returned path: the judge every planner faces.

A path is valid when

- it is a finite ``(N, d)`` array with ``N >= 1``;
- it starts at the scenario's start and ends at its goal (to 1e-6 cells);
- every segment stays inside the map and touches no blocked cell, not even
  at a corner (:mod:`pathzoo.grid.segments`);
- on terrain, every piece of every segment respects the vehicle's climb and
  descent limits (:func:`pathzoo.grid.terrain.segment_profile`);
- in air volumes, every segment respects the pitch limit;
- every heading change respects the vehicle's turn limit;
- on dynamic scenarios, the timed path keeps at least each moving obstacle's
  radius from its centre at every instant (exact, piecewise-linear check), and
  never moves faster than cruise speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pathzoo.core.scenario import Scenario
from pathzoo.grid.segments import blocked_segments, first_blocked_cell_2d, segment_blocked_3d, to_cell_units
from pathzoo.grid.terrain import path_profile, segment_profile
from pathzoo.metrics.geometry import turn_angles

__all__ = ["Validation", "validate_path", "segment_problem", "path_times", "ENDPOINT_TOLERANCE_CELLS"]

ENDPOINT_TOLERANCE_CELLS = 1e-6
_ANGLE_EPS_DEG = 1e-7


@dataclass(frozen=True)
class Validation:
    """Outcome of :func:`validate_path`."""

    valid: bool
    reason: str = ""

    def __bool__(self) -> bool:
        return self.valid


def _fmt(p: np.ndarray) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in p) + ")"


def segment_problem(
    scenario: Scenario, p0: np.ndarray, p1: np.ndarray, t0: float = 0.0, t1: float | None = None
) -> str | None:
    """Describe why the segment ``p0 -> p1`` is not allowed, or return ``None``.

    Checks the closed-cell collision rule, slope or pitch limits and moving
    obstacles. ``t0``/``t1`` are the departure and arrival times (default
    arrival: at cruise speed).
    """
    if scenario.dim == 3:
        u0 = to_cell_units(p0, scenario.cell_sizes)
        u1 = to_cell_units(p1, scenario.cell_sizes)
        if segment_blocked_3d(scenario.blocked, u0, u1):
            return f"segment {_fmt(p0)} -> {_fmt(p1)} touches a blocked voxel or leaves the volume"
        horiz = float(np.hypot(*(p1[:2] - p0[:2])))
        pitch = math.degrees(math.atan2(abs(float(p1[2] - p0[2])), horiz)) if horiz or p1[2] != p0[2] else 0.0
        if pitch > scenario.vehicle.max_pitch_deg + _ANGLE_EPS_DEG:
            return f"segment {_fmt(p0)} -> {_fmt(p1)} pitches {pitch:.3f} deg > limit {scenario.vehicle.max_pitch_deg}"
        return None
    u0 = to_cell_units(p0, scenario.cell_size)
    u1 = to_cell_units(p1, scenario.cell_size)
    r, c = first_blocked_cell_2d(scenario.blocked, u0[0], u0[1], u1[0], u1[1])
    if r != -2:
        h, w = scenario.shape
        what = "leaves the map at" if not (0 <= r < h and 0 <= c < w) else "touches blocked cell"
        return f"segment {_fmt(p0)} -> {_fmt(p1)} {what} (row {r}, col {c})"
    if scenario.kind == "terrain":
        _, slopes = segment_profile(scenario.elevation, p0, p1, scenario.cell_size)
        deg = np.degrees(slopes)
        v = scenario.vehicle
        if np.any(~np.isfinite(deg)):
            return f"segment {_fmt(p0)} -> {_fmt(p1)} crosses cells without elevation"
        if deg.max() > v.max_climb_deg + _ANGLE_EPS_DEG:
            return f"segment {_fmt(p0)} -> {_fmt(p1)} climbs {deg.max():.3f} deg > limit {v.max_climb_deg}"
        if -deg.min() > v.max_descent_deg + _ANGLE_EPS_DEG:
            return f"segment {_fmt(p0)} -> {_fmt(p1)} descends {-deg.min():.3f} deg > limit {v.max_descent_deg}"
    if scenario.moving_obstacles:
        if t1 is None:
            t1 = t0 + float(np.linalg.norm(p1 - p0)) / scenario.vehicle.cruise_speed
        for k, ob in enumerate(scenario.moving_obstacles):
            d = ob.min_distance(p0, p1, t0, t1)
            if d < ob.radius - 1e-9:
                return (
                    f"segment {_fmt(p0)} -> {_fmt(p1)} during t=[{t0:.3f}, {t1:.3f}] s comes within {d:.3f} m "
                    f"of moving obstacle {k} (radius {ob.radius})"
                )
    return None


def _suspect_segments(scenario: Scenario, path: np.ndarray) -> np.ndarray:
    """Indices of the segments :func:`segment_problem` may reject, found in vectorised passes.

    Collisions, slopes and pitch are screened for the whole path at once with
    the very functions ``segment_problem`` uses, so only flagged segments are
    examined one by one (to word the reason). Moving obstacles depend on time,
    so on dynamic scenarios every segment is examined.
    """
    n = len(path) - 1
    if scenario.moving_obstacles:
        return np.arange(n)
    flagged = blocked_segments(scenario.blocked, to_cell_units(path, scenario.cell_sizes))
    v = scenario.vehicle
    if scenario.kind == "terrain":
        _, slopes, seg = path_profile(scenario.elevation, path, scenario.cell_size)
        deg = np.degrees(slopes)
        with np.errstate(invalid="ignore"):
            bad = ~np.isfinite(deg) | (deg > v.max_climb_deg + _ANGLE_EPS_DEG) | (-deg > v.max_descent_deg + _ANGLE_EPS_DEG)
        flagged[seg[bad]] = True
    elif scenario.dim == 3:
        d = np.diff(path, axis=0)
        pitch = np.degrees(np.arctan2(np.abs(d[:, 2]), np.hypot(d[:, 0], d[:, 1])))
        flagged |= pitch > v.max_pitch_deg + _ANGLE_EPS_DEG
    return np.flatnonzero(flagged)


def path_times(scenario: Scenario, path: np.ndarray) -> np.ndarray:
    """Arrival times when driving the path at cruise speed without stopping."""
    if len(path) < 2:
        return np.zeros(len(path))
    seg = np.linalg.norm(np.diff(path, axis=0), axis=1)
    return np.concatenate([[0.0], np.cumsum(seg)]) / scenario.vehicle.cruise_speed


def validate_path(scenario: Scenario, path: object, times: object = None) -> Validation:
    """Check a planner's path against the scenario; see the module docstring.

    Returns
    -------
    Validation
        ``valid`` and, when invalid, a one-line ``reason``.
    """
    try:
        arr = np.asarray(path, dtype=np.float64)
    except (TypeError, ValueError):
        return Validation(False, "path is not a numeric array")
    if arr.ndim != 2 or arr.shape[1] != scenario.dim or len(arr) < 1:
        return Validation(False, f"path must have shape (N, {scenario.dim}) with N >= 1, got {arr.shape}")
    if not np.isfinite(arr).all():
        return Validation(False, "path contains NaN or infinite coordinates")
    tol = ENDPOINT_TOLERANCE_CELLS * scenario.cell_size
    if np.max(np.abs(arr[0] - scenario.start)) > tol:
        return Validation(False, f"path starts at {_fmt(arr[0])}, not at the start {_fmt(scenario.start)}")
    if np.max(np.abs(arr[-1] - scenario.goal)) > tol:
        return Validation(False, f"path ends at {_fmt(arr[-1])}, not at the goal {_fmt(scenario.goal)}")
    if times is not None:
        t = np.asarray(times, dtype=np.float64).reshape(-1)
        if t.shape != (len(arr),) or not np.isfinite(t).all():
            return Validation(False, f"times must be {len(arr)} finite values")
        if t[0] < 0 or np.any(np.diff(t) < 0):
            return Validation(False, "times must start at >= 0 and never decrease")
        seg = np.linalg.norm(np.diff(arr, axis=0), axis=1)
        dt = np.diff(t)
        too_fast = seg > scenario.vehicle.cruise_speed * dt * (1 + 1e-9) + 1e-12
        if np.any(too_fast):
            k = int(np.argmax(too_fast))
            return Validation(False, f"segment {k} is driven faster than cruise speed {scenario.vehicle.cruise_speed} m/s")
    else:
        t = path_times(scenario, arr)
    if len(arr) == 1:
        return Validation(True)
    for k in _suspect_segments(scenario, arr):
        problem = segment_problem(scenario, arr[k], arr[k + 1], float(t[k]), float(t[k + 1]))
        if problem is not None:
            return Validation(False, f"segment {k}: {problem}")
    turns = np.degrees(turn_angles(arr[:, :2]))  # horizontal heading changes
    if len(turns) and turns.max() > scenario.vehicle.max_turn_deg + _ANGLE_EPS_DEG:
        return Validation(False, f"a heading change of {turns.max():.3f} deg exceeds the turn limit {scenario.vehicle.max_turn_deg}")
    return Validation(True)
