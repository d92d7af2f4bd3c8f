"""Tiny scenarios of every kind, made in code: the conformance checks and every warm-up plan on them.

They sit in the core, below both the harness (whose workers warm up on them)
and the conformance kit (:func:`pathzoo.testing.check_scenario`), so
neither imports the other.

Each kind has a reachable variant (a wall forces a detour, and the start is
deliberately *not* a cell centre, so a planner must prepend the exact start)
and an unreachable variant (the goal cell is free but walled in).
The maps are small enough that a stochastic planner solves them within a few
iterations.
"""

from __future__ import annotations

import numpy as np

from pathzoo.core.moving import MovingObstacle
from pathzoo.core.scenario import SCENARIO_KINDS, Scenario
from pathzoo.core.vehicle import VehicleModel
from pathzoo.core.errors import InvalidScenarioError

__all__ = ["check_scenario"]


def _wall_in(occ: np.ndarray, cell: tuple[int, ...]) -> None:
    """Block every neighbour of ``cell`` (the cell itself stays free)."""
    lo = [max(0, c - 1) for c in cell]
    hi = [min(n, c + 2) for c, n in zip(cell, occ.shape)]
    occ[tuple(slice(a, b) for a, b in zip(lo, hi))] = True
    occ[cell] = False


def _grid2d(reachable: bool, kind: str) -> Scenario:
    occ = np.zeros((10, 10), dtype=bool)
    occ[0:7, 5] = True  # a wall with a gap in rows 7..9
    start, goal = np.array([1.3, 1.7]), np.array([8.5, 1.5])
    if not reachable:
        _wall_in(occ, (1, 8))
    obstacles: tuple[MovingObstacle, ...] = ()
    if kind == "dynamic":
        # a slow disc patrolling the gap the path must use
        obstacles = (MovingObstacle(radius=0.6, waypoints=np.array([[3.0, 8.5], [8.0, 8.5]]), speed=0.5),)
    return Scenario(
        id=f"testing.{kind}{'' if reachable else '.unreachable'}",
        kind=kind,  # type: ignore[arg-type]
        occupancy=occ,
        cell_size=1.0,
        start=start,
        goal=goal,
        moving_obstacles=obstacles,
        description=f"conformance-kit {kind} map, 10x10 cells",
    )


def _terrain(reachable: bool) -> Scenario:
    rows, cols = np.mgrid[0:10, 0:10]
    # a gentle hill: steepest slope about 17 degrees, below the 25 degree limit
    elevation = 3.0 * np.exp(-((rows - 5.0) ** 2 + (cols - 3.0) ** 2) / 18.0)
    occ = np.zeros((10, 10), dtype=bool)
    occ[0:7, 5] = True
    if not reachable:
        _wall_in(occ, (1, 8))
    return Scenario(
        id=f"testing.terrain{'' if reachable else '.unreachable'}",
        kind="terrain",
        occupancy=occ,
        cell_size=2.0,
        start=np.array([2.6, 3.4]),
        goal=np.array([17.0, 3.0]),
        elevation=elevation,
        vehicle=VehicleModel(max_climb_deg=25.0, max_descent_deg=25.0),
        description="conformance-kit terrain map, 10x10 cells of 2 m with a hill",
    )


def _air3d(reachable: bool) -> Scenario:
    occ = np.zeros((4, 8, 8), dtype=bool)
    occ[0:3, :, 4] = True  # a wall the vehicle must climb over (layer 3 is open)
    if not reachable:
        _wall_in(occ, (0, 4, 7))
    return Scenario(
        id=f"testing.air3d{'' if reachable else '.unreachable'}",
        kind="air3d",
        occupancy=occ,
        cell_size=1.0,
        vertical_cell_size=1.0,
        start=np.array([0.7, 3.3, 0.5]),
        goal=np.array([7.5, 4.5, 0.5]),
        description="conformance-kit air volume, 4x8x8 voxels",
    )


def check_scenario(kind: str, *, reachable: bool = True) -> Scenario:
    """A tiny scenario of the given kind, freshly built on every call.

    Parameters
    ----------
    kind : {"grid2d", "terrain", "air3d", "dynamic"}
        Scenario kind.
    reachable : bool
        When False, the goal cell is free but enclosed by blocked cells.

    Raises
    ------
    InvalidScenarioError
        For an unknown kind.
    """
    if kind in ("grid2d", "dynamic"):
        return _grid2d(reachable, kind)
    if kind == "terrain":
        return _terrain(reachable)
    if kind == "air3d":
        return _air3d(reachable)
    raise InvalidScenarioError(f"unknown kind {kind!r}; allowed: {', '.join(SCENARIO_KINDS)}", field="kind")
