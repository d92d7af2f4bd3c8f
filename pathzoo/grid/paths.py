"""Turning a sequence of graph nodes into a world path from exactly the start to exactly the goal."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pathzoo.grid.terrain import path_profile

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["CENTRE_TOLERANCE_CELLS", "on_centre", "centre_path", "path_pieces"]

CENTRE_TOLERANCE_CELLS = 1e-9
"""An endpoint this close (in cells) to its cell centre stands in for that centre."""


def on_centre(scenario: "Scenario", point: np.ndarray, centre: np.ndarray) -> bool:
    """Whether ``point`` coincides with the cell centre ``centre`` (to :data:`CENTRE_TOLERANCE_CELLS`)."""
    tol = CENTRE_TOLERANCE_CELLS * min(scenario.cell_sizes.tolist())
    offsets = np.asarray(point, dtype=np.float64).tolist(), np.asarray(centre, dtype=np.float64).tolist()
    return all(abs(p - c) <= tol for p, c in zip(*offsets))  # Python floats: this runs a few times per plan()


def centre_path(scenario: "Scenario", nodes: np.ndarray) -> np.ndarray:
    """World path through the centres of ``nodes``, from exactly ``scenario.start`` to exactly ``scenario.goal``.

    Grid planners search between the *cells* of the start and goal. An
    endpoint on its cell centre replaces that centre; one elsewhere in its
    cell is joined to the centre by a short connector segment, which a planner
    on terrain or in the air must still check (slope and pitch limits). The
    path always has at least two points, ``start`` first and ``goal`` last.
    """
    pts = scenario.point_of(np.asarray(nodes, dtype=np.int64))
    if len(pts) == 1 and on_centre(scenario, scenario.start, pts[0]) and on_centre(scenario, scenario.goal, pts[0]):
        return np.stack([scenario.start, scenario.goal])  # both ends on one centre: still two points
    head = not on_centre(scenario, scenario.start, pts[0])
    tail = not on_centre(scenario, scenario.goal, pts[-1])
    if not head:
        pts[0] = scenario.start
    if not tail:
        pts[-1] = scenario.goal
    parts = [scenario.start[None, :]] * head + [pts] + [scenario.goal[None, :]] * tail
    return np.concatenate(parts)


def path_pieces(scenario: "Scenario", path: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """3-D lengths (m) and signed slopes (rad, uphill positive) of the pieces a path is driven in.

    - ``terrain``: each segment is split as in
      `pathzoo.grid.terrain.path_profile` (bilinear heights, pieces of
      at most √2 cells), the same profile the validator checks slopes on;
    - ``air3d``: one piece per segment, its 3-D length and pitch;
    - ``grid2d`` and ``dynamic``: one flat piece per segment.
    """
    pts = np.asarray(path, dtype=np.float64)
    if len(pts) < 2:
        return np.zeros(0), np.zeros(0)
    d = np.diff(pts, axis=0)
    if scenario.kind == "terrain":
        lengths, slopes, _ = path_profile(scenario.elevation, pts, scenario.cell_size)
        return lengths, slopes
    if scenario.kind == "air3d":
        horiz = np.hypot(d[:, 0], d[:, 1])
        return np.linalg.norm(d, axis=1), np.arctan2(d[:, 2], horiz)
    return np.linalg.norm(d, axis=1), np.zeros(len(d))
