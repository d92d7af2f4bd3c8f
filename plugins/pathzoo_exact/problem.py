"""What a search looks for, packed for the kernels: the target, the grid's shape and the heuristic.

A kernel's arguments are few arrays: the problem's scalars and small vectors
packed in two (:func:`search_problem`), the state's arrays, the graph's. A
call from Python costs about 60 ns per argument to type-check and unbox, as
much as a search of a few nodes, and short searches are called one per
``plan()``. The heuristics (:func:`cell_heuristic`, :func:`heuristic`) are
compiled into the search loops.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = [
    "H_ZERO",
    "H_OCTILE",
    "H_EUCLID",
    "cell_heuristic",
    "heuristic",
    "grid_dims",
    "goal_cell",
    "search_problem",
    "PROBLEM_INTS",
    "PROBLEM_REALS",
]

H_ZERO = 0
"""Zero heuristic (Dijkstra)."""
H_OCTILE = 1
"""Octile distance on the ``x, y`` axes (``z`` ignored)."""
H_EUCLID = 2
"""Euclidean distance on the ``x, y, z`` axes."""

_SQRT2_M1 = math.sqrt(2.0) - 1.0


@numba.njit(cache=True)
def cell_heuristic(col: int, row: int, layer: int, goal: np.ndarray, mode: int, steps: np.ndarray, scale: float) -> float:
    """Heuristic from the cell ``(col, row, layer)`` to the cell ``goal = (x, y, z)``.

    ``steps`` holds the metres per cell along ``x, y, z``. The distance
    (octile or Euclidean, see :data:`H_OCTILE`, :data:`H_EUCLID`) is
    multiplied by ``scale``; :data:`H_ZERO` gives 0.
    """
    if mode == H_ZERO:
        return 0.0
    dx = abs(col - goal[0]) * steps[0]
    dy = abs(row - goal[1]) * steps[1]
    if mode == H_OCTILE:
        return scale * (max(dx, dy) + _SQRT2_M1 * min(dx, dy))
    dz = abs(layer - goal[2]) * steps[2]
    return scale * math.sqrt(dx * dx + dy * dy + dz * dz)


@numba.njit(cache=True, inline="always")
def heuristic(node: int, goal: np.ndarray, mode: int, dims: np.ndarray, steps: np.ndarray, scale: float) -> float:
    """:func:`cell_heuristic` of the flat node id ``node`` of a grid of shape ``dims = (L, H, W)``."""
    if mode == H_ZERO:
        return 0.0
    w = dims[2]
    if dims[0] == 1:  # one integer division instead of three on 2-D grids
        layer = 0
        rest = node
    else:
        layer = node // (dims[1] * w)
        rest = node - layer * dims[1] * w
    row = rest // w
    return cell_heuristic(rest - row * w, row, layer, goal, mode, steps, scale)


def grid_dims(shape: tuple[int, ...]) -> np.ndarray:
    """A grid's ``shape`` as the kernels take it: ``dims = (L, H, W)``, one layer on 2-D grids."""
    return np.array((1,) * (3 - len(shape)) + tuple(shape), dtype=np.int64)


def goal_cell(target: int, dims: np.ndarray) -> np.ndarray:
    """``(x, y, z)`` = (column, row, layer) of flat node ``target`` in a grid of shape ``dims = (L, H, W)``."""
    _, h, w = (int(d) for d in dims)
    layer, rest = divmod(int(target), h * w)
    row, col = divmod(rest, w)
    return np.array([col, row, layer], dtype=np.int64)


PROBLEM_INTS = 8
"""Length of :func:`search_problem`'s ``ints``; the kernels read no further (more may follow)."""
PROBLEM_REALS = 4
"""Length of :func:`search_problem`'s ``reals``; the kernels read no further (more may follow)."""


def search_problem(target: int, dims: np.ndarray, steps: np.ndarray, mode: int, scale: float) -> tuple[np.ndarray, np.ndarray]:
    """The ``ints, reals`` arguments of the batch kernels: where the search ends and its heuristic.

    Parameters
    ----------
    target : int
        The goal's node id.
    dims : ndarray of int64, shape (3,)
        The grid's shape ``(L, H, W)`` (:func:`grid_dims`).
    steps : ndarray of float64, shape (3,)
        Metres per cell along ``x, y, z``.
    mode : int
        :data:`H_ZERO`, :data:`H_OCTILE` or :data:`H_EUCLID`.
    scale : float
        Factor of the heuristic's distance.

    Returns
    -------
    ints : ndarray of int64, shape (8,)
        ``target``, ``mode``, the goal's cell ``(x, y, z)`` (:func:`goal_cell`), ``dims``.
    reals : ndarray of float64, shape (4,)
        ``steps``, ``scale``.
    """
    ints = np.array([target, mode, *goal_cell(target, dims), *dims], dtype=np.int64)
    return ints, np.array([*steps, scale], dtype=np.float64)
