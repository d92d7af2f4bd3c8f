"""The path an exact search returns, built from its parent links in one compiled pass.

:func:`waypoints` gives what :func:`pathzoo.grid.paths.centre_path` gives for
the search's node path (after :func:`straight_run_ends` on ``grid2d``): the
cell centres, computed as :meth:`Scenario.point_of` computes them
(``(index + 0.5) * cell size`` per axis, the same two float operations), with
the start and goal points put in as ``centre_path`` puts them. Whether each
point lies on its cell centre is known per scenario
(:func:`pathzoo_exact.base.endpoints`), so nothing is decided here in Python,
and a small search does not pay a dozen NumPy calls to turn its nodes into a
path (``tests/exact/test_exact_waypoints.py`` compares the two on every case).
"""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["trace_path", "straight_run_ends", "waypoints", "path_layout", "path_ends"]


@numba.njit(cache=True)
def trace_path(parent: np.ndarray, target: int) -> np.ndarray:
    """Node ids from the source to ``target`` following ``parent`` links."""
    n = 0
    u = target
    while u != -1:
        n += 1
        u = parent[u]
    out = np.empty(n, dtype=np.int64)
    u = target
    for i in range(n - 1, -1, -1):
        out[i] = u
        u = parent[u]
    return out


@numba.njit(cache=True)
def straight_run_ends(nodes: np.ndarray, width: int) -> np.ndarray:
    """Mask of the waypoints to keep: both ends and every point where the direction changes.

    Parameters
    ----------
    nodes : ndarray of int64, shape (N,)
        Consecutive flat node ids of a 2-D grid.
    width : int
        Columns of the grid.
    """
    n = nodes.shape[0]
    keep = np.ones(n, dtype=np.bool_)
    for i in range(1, n - 1):
        r0, c0 = divmod(nodes[i - 1], width)
        r1, c1 = divmod(nodes[i], width)
        r2, c2 = divmod(nodes[i + 1], width)
        ar, ac, br, bc = r1 - r0, c1 - c0, r2 - r1, c2 - c1
        keep[i] = ar * bc - ac * br != 0 or ar * br + ac * bc <= 0  # a turn, or a reversal
    return keep


@numba.njit(cache=True)
def waypoints(parent: np.ndarray, target: int, layout: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """World path from the source to ``target`` along ``parent`` links, from exactly the start to exactly the goal.

    Parameters
    ----------
    parent : ndarray of int64
        The search's parent links (``-1`` at the source).
    target : int
        The goal's node id.
    layout : ndarray of int64, shape (6,)
        :func:`path_layout`: the grid's ``(layers, rows, columns)``, the
        columns of a 2-D grid whose straight runs lose their inner waypoints
        (:func:`straight_run_ends`; 0 keeps every cell centre), and whether
        the start and the goal replace their cells' centres (1) or are joined
        to them (0).
    ends : ndarray of float64, shape (3, d)
        :func:`path_ends`: metres per cell along ``x, y[, z]``
        (:attr:`Scenario.cell_sizes`), then the exact start and goal points.
    """
    nodes = trace_path(parent, target)
    n = nodes.shape[0]
    straight_width = layout[3]
    start_on_centre = layout[4] != 0
    goal_on_centre = layout[5] != 0
    if straight_width > 0:  # keep the turns, in place (scalar code: quick to compile in a fresh worker)
        keep = straight_run_ends(nodes, straight_width)
        kept = 0
        for i in range(n):
            if keep[i]:
                nodes[kept] = nodes[i]
                kept += 1
        n = kept
    d = ends.shape[1]
    if n == 1 and start_on_centre and goal_on_centre:  # both ends on one centre: still two points
        out = np.empty((2, d))
        for a in range(d):
            out[0, a] = ends[1, a]
            out[1, a] = ends[2, a]
        return out
    first = 0 if start_on_centre else 1
    out = np.empty((n + first + (0 if goal_on_centre else 1), d))
    w = layout[2]
    plane = layout[1] * w
    for i in range(n):
        layer = nodes[i] // plane
        rest = nodes[i] - layer * plane
        row = rest // w
        out[first + i, 0] = (np.float64(rest - row * w) + 0.5) * ends[0, 0]
        out[first + i, 1] = (np.float64(row) + 0.5) * ends[0, 1]
        if d == 3:
            out[first + i, 2] = (np.float64(layer) + 0.5) * ends[0, 2]
    last = first + n - 1 if goal_on_centre else first + n
    for a in range(d):
        out[0, a] = ends[1, a]  # the start replaces the first centre, or comes before it
        out[last, a] = ends[2, a]
    return out


def path_layout(dims: np.ndarray, straight_width: int, start_on_centre: bool, goal_on_centre: bool) -> np.ndarray:
    """The ``layout`` argument of :func:`waypoints`.

    Parameters
    ----------
    dims : ndarray of int64, shape (3,)
        Grid shape as ``(layers, rows, columns)`` (``layers`` is 1 on 2-D grids).
    straight_width : int
        Columns of a 2-D grid whose straight runs lose their inner waypoints; 0 keeps every cell centre.
    start_on_centre, goal_on_centre : bool
        Whether each end point replaces its cell's centre (else it is joined to it).
    """
    return np.array([*(int(d) for d in dims), straight_width, start_on_centre, goal_on_centre], dtype=np.int64)


def path_ends(sizes: np.ndarray, start: np.ndarray, goal: np.ndarray) -> np.ndarray:
    """The ``ends`` argument of :func:`waypoints`: cell sizes, start and goal point as the rows of one array."""
    return np.array([sizes, start, goal], dtype=np.float64)
