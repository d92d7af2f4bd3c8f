"""The exact any-angle optimum of a 2-D grid under the closed-cell rule: Polyanya on a rectangle mesh.

What is computed
----------------
A valid path (``docs/corner-rule.md``) may not touch any blocked cell's
closed square, so the valid paths form an open set and there is no shortest
one; the optimum is an *infimum*, attained by a *limit path* that may touch
blocked cells (slide along an edge, turn at a corner) but never enters a
blocked cell, never runs along the edge between two blocked cells and never
crosses a *pinch* (a grid point where two blocked cells meet diagonally).
Every valid path is at least as long, and valid paths come arbitrarily
close to it.

How
---
:func:`anyangle_path` runs Polyanya (:mod:`pathzoo.grid.polyanya`) on the
map's rectangle mesh (:mod:`pathzoo.grid.navmesh`, built once per scenario
by :func:`~pathzoo.grid.navmesh.scenario_mesh`), in exact integer arithmetic
on a lattice of ``scale`` units per cell, the smallest power of two on which
both endpoints lie (2 for cell centres; endpoints within :data:`SNAP_CELLS`
of the lattice are moved onto it). Every segment of the result is then
checked with :func:`pathzoo.grid.visibility_graph.visible`, the independent
exact segment test of the visibility-graph search. Endpoints so fine that
``scale * max(H, W)`` exceeds :data:`~pathzoo.grid.polyanya.MAX_LATTICE_EXTENT`
are searched with the visibility graph instead on maps of at most
:data:`MAX_VISIBILITY_CELLS` cells, and refused on larger ones; maps larger
than :data:`MAX_EXACT_CELLS` are refused.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Literal

import numpy as np

from pathzoo.grid.navmesh import NavMesh, navigation_mesh
from pathzoo.grid.polyanya import MAX_LATTICE_EXTENT, polyanya_search
from pathzoo.grid.segments import to_cell_units
from pathzoo.grid.visibility_graph import SCALE, visibility_search, visible

__all__ = [
    "SCALE",
    "MAX_EXACT_CELLS",
    "MAX_VISIBILITY_CELLS",
    "SNAP_CELLS",
    "AnyAngleError",
    "SearchCapReached",
    "AnyAnglePath",
    "anyangle_path",
]

MAX_EXACT_CELLS = 4096 * 4096
"""Largest map (in cells) searched: its mesh takes about 10 bytes per cell (160 MB here)."""

SNAP_CELLS = 1e-9
"""Endpoints this close (per axis, in cells) to Polyanya's lattice are searched from the lattice point.

A cell centre of a map whose cell size is no power of two comes out of the
division by the cell size a rounding error (about 1e-13 cell) away from its
half-integer. The optimum from the moved endpoints differs from the true one
by at most the distance moved, and the returned path keeps the exact endpoints.
"""

MAX_VISIBILITY_CELLS = 256 * 256
"""Largest map on which the visibility graph (cost N**1.5 to N**2 in the cells N) is searched."""


class AnyAngleError(ValueError):
    """The exact any-angle optimum is not computed for this input (not a 2-D grid, or a map too large)."""


class SearchCapReached(RuntimeError):
    """The search stopped at its expansion cap before it could prove the optimum."""


@dataclass(frozen=True, eq=False)
class AnyAnglePath:
    """The limit path of the any-angle optimum.

    Attributes
    ----------
    path : ndarray of shape (N, 2)
        World coordinates from exactly the start to exactly the goal; inner
        vertices are obstacle corners, which the path touches.
    length : float
        Its Euclidean length in metres: the infimum of valid path lengths.
    corners : ndarray of shape (N - 2, 2) of int64
        The inner vertices as grid points ``(x, y)`` in cells.
    expansions : int
        Search nodes expanded (Polyanya) or vertices expanded (visibility graph).
    """

    path: np.ndarray
    length: float
    corners: np.ndarray
    expansions: int


def _lattice(ends: np.ndarray, side: int) -> tuple[int, np.ndarray] | None:
    """The smallest usable power-of-two scale putting both endpoints within :data:`SNAP_CELLS` of its lattice.

    Returns the scale and the endpoints moved onto the lattice, or None when
    even the finest lattice allowed by :data:`MAX_LATTICE_EXTENT` is too coarse.
    """
    if not np.isfinite(ends).all():
        return None
    scale = 1
    while scale * side <= MAX_LATTICE_EXTENT:
        snapped = np.round(ends * scale) / scale
        if (np.abs(snapped - ends) <= SNAP_CELLS).all():
            return scale, snapped
        scale *= 2
    return None


def _polyanya(
    blocked: np.ndarray, ends: np.ndarray, scale: int, get_mesh: Callable[[], NavMesh] | None, cap: int
) -> tuple[np.ndarray | None, int, bool]:
    h, w = blocked.shape
    if not all(0.0 <= x <= w and 0.0 <= y <= h for x, y in ends):
        return None, 0, True  # outside the map: touches the border's blocked cells
    mesh = navigation_mesh(blocked) if get_mesh is None else get_mesh()
    if mesh.shape != blocked.shape:
        raise ValueError(f"the navigation mesh is for a {mesh.shape} grid, not {blocked.shape}")
    start, goal = ((int(x * scale), int(y * scale)) for x, y in ends)
    points, _, expansions, finished = polyanya_search(mesh, scale, start, goal, cap)
    if points is None:
        return None, expansions, finished
    for (px, py), (qx, qy) in zip(points[:-1], points[1:]):
        if not visible(blocked, scale, px, py, qx, qy):
            raise AnyAngleError(f"internal check: a segment of the Polyanya path fails the exact test: {points}")
    return np.array(points, dtype=np.float64) / scale, expansions, True


def anyangle_path(
    blocked: np.ndarray,
    start: np.ndarray,
    goal: np.ndarray,
    cell_size: float,
    max_expansions: int | None = None,
    mesh: Callable[[], NavMesh] | None = None,
    method: Literal["polyanya", "visibility"] = "polyanya",
) -> AnyAnglePath | None:
    """The exact any-angle optimum from ``start`` to ``goal`` (world coordinates), or None if unreachable.

    World coordinates become cell units with
    :func:`pathzoo.grid.segments.to_cell_units`, as the validator converts them.

    Parameters
    ----------
    max_expansions
        Caps the search nodes expanded.
    mesh
        A function returning the map's navigation mesh (e.g. the scenario's
        cached :func:`~pathzoo.grid.navmesh.scenario_mesh`), called only when
        Polyanya runs; without it the mesh is built here.
    method
        ``"polyanya"`` (default), or ``"visibility"``: the visibility-graph
        search, the independent reference of the tests (maps up to
        :data:`MAX_VISIBILITY_CELLS` cells).

    Raises
    ------
    AnyAngleError
        When the map is not 2-D or too large for the method, or the endpoints
        are too fine a fraction of a cell for Polyanya's lattice on a map
        larger than :data:`MAX_VISIBILITY_CELLS`.
    SearchCapReached
        When ``max_expansions`` nodes were expanded before the goal was reached.
    """
    blocked = np.ascontiguousarray(blocked, dtype=np.bool_)
    if blocked.ndim != 2:
        raise AnyAngleError(f"the any-angle optimum needs a 2-D grid, got {blocked.ndim}-D")
    h, w = blocked.shape
    limit = MAX_EXACT_CELLS if method == "polyanya" else MAX_VISIBILITY_CELLS
    if blocked.size > limit:
        raise AnyAngleError(f"map of {h}x{w} cells is larger than the {limit} cells the exact any-angle search covers")
    start_xy = np.asarray(start, dtype=np.float64)[:2]
    goal_xy = np.asarray(goal, dtype=np.float64)[:2]
    ends = to_cell_units(np.stack([start_xy, goal_xy]), cell_size)
    cap = np.iinfo(np.int64).max if max_expansions is None else int(max_expansions)
    lattice = _lattice(ends, max(h, w)) if method == "polyanya" else None
    cells: np.ndarray | None
    if np.array_equal(ends[0], ends[1]):
        cells, expansions, finished = ends.copy(), 0, True  # as the visibility graph answers it
    elif lattice is not None:
        cells, expansions, finished = _polyanya(blocked, lattice[1], lattice[0], mesh, cap)
    elif blocked.size <= MAX_VISIBILITY_CELLS:
        cells, expansions, finished = visibility_search(blocked, ends[0], ends[1], cap)
    else:
        raise AnyAngleError(
            f"the endpoints are not within {SNAP_CELLS} cell of a lattice of 1/{MAX_LATTICE_EXTENT // max(h, w)} "
            f"cell, which the exact search of a {h}x{w} map needs"
        )
    if not finished:
        raise SearchCapReached(f"the any-angle search expanded {expansions} nodes without reaching the goal")
    if cells is None:
        return None
    xy = cells * cell_size
    xy[0], xy[-1] = start_xy, goal_xy
    length = float(np.hypot(*np.diff(xy, axis=0).T).sum()) if len(xy) > 1 else 0.0
    xy.setflags(write=False)
    inner = np.round(cells[1:-1]).astype(np.int64).reshape(-1, 2)
    return AnyAnglePath(path=xy, length=length, corners=inner, expansions=expansions)
