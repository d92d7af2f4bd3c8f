"""The batch kernels the exact planners call: a batch of a search and, when it reaches the target, the answer.

Each kernel here runs one batch of its :mod:`~pathzoo_exact.search_loop` kernel
and returns ``(status, expanded, cost, path)``: the batch's status, the
search's expansions so far, and, when the status is
:data:`~pathzoo_exact.search_state.FOUND`, the target's cost ``g`` and the path
(:func:`~pathzoo_exact.waypoints.waypoints`); otherwise ``0.0`` and an
empty path. A short search is then one compiled call from Python, not one
for the search, one for the path and two reads of the state's arrays: each
call from Python type-checks and unboxes its arguments, and each read of an
array element boxes it, which on a search of a few dozen nodes weighs as
much as the search.

The arguments are those of the batch kernel, with the path's ``layout``
and ``ends`` (:func:`~pathzoo_exact.waypoints.path_layout`,
:func:`~pathzoo_exact.waypoints.path_ends`) after the problem's ``ints`` and
``reals`` in the same two arrays (:func:`answer_problem`), where the batch
kernel does not read: two more arguments would cost about as much again as
the path.

These kernels are compiled with the code of :mod:`~pathzoo_exact.search_loop`,
:mod:`~pathzoo_exact.heap`, :mod:`~pathzoo_exact.problem`,
:mod:`~pathzoo_exact.search_state` and :mod:`~pathzoo_exact.waypoints`
inside them, and numba's on-disk cache checks only the file of the function
it caches: after editing any of those files, delete this package's
``__pycache__/*.nbi`` index files, or a stale copy of the search may be
loaded from the cache (the batch kernels of ``search_loop`` likewise hold
the heap's and the problem's code).
"""

from __future__ import annotations

from typing import Callable, NamedTuple

import numba
import numpy as np

from pathzoo_exact.problem import PROBLEM_INTS, PROBLEM_REALS
from pathzoo_exact.search_loop import astar_batch, astar_moves_batch, thetastar_batch
from pathzoo_exact.search_state import FOUND
from pathzoo_exact.waypoints import waypoints

__all__ = ["Batch", "answer_problem", "astar_answer", "astar_moves_answer", "thetastar_answer"]


class Batch(NamedTuple):
    """An answering kernel and its leading arguments: what advances one search of a planner."""

    kernel: Callable[..., tuple[int, int, float, np.ndarray]]
    """:func:`astar_answer`, :func:`astar_moves_answer` or :func:`thetastar_answer`."""
    args: tuple
    """The kernel's graph arrays, then the problem's ``ints, reals``."""
    max_degree: int
    """Upper bound on a node's out-degree."""


def answer_problem(ints: np.ndarray, reals: np.ndarray, layout: np.ndarray,
                   ends: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The ``ints, reals`` of an answering kernel: the batch kernel's (:func:`~pathzoo_exact.problem.search_problem`),
    then the path's ``layout`` and ``ends`` (flattened, row after row)."""
    return np.concatenate((ints, layout)).astype(np.int64), np.concatenate((reals, ends.ravel())).astype(np.float64)


@numba.njit(cache=True)
def _answer(status: int, ints: np.ndarray, reals: np.ndarray, g: np.ndarray, parent: np.ndarray,
            counters: np.ndarray) -> tuple[int, int, float, np.ndarray]:
    """``(status, expanded, cost, path)`` after a batch (see the module docstring)."""
    d = (reals.shape[0] - PROBLEM_REALS) // 3
    if status == FOUND:
        target = ints[0]
        layout = ints[PROBLEM_INTS:PROBLEM_INTS + 6]
        ends = reals[PROBLEM_REALS:].reshape((3, d))
        return status, counters[1], g[target], waypoints(parent, target, layout, ends)
    return status, counters[1], 0.0, np.empty((0, d))


@numba.njit(cache=True)
def astar_answer(indptr: np.ndarray, indices: np.ndarray, weights: np.ndarray, ints: np.ndarray, reals: np.ndarray,
                 g: np.ndarray, parent: np.ndarray, closed: np.ndarray, heap: np.ndarray, counters: np.ndarray,
                 max_expansions: int, max_degree: int) -> tuple[int, int, float, np.ndarray]:
    """:func:`~pathzoo_exact.search_loop.astar_batch`, and the answer when it finds the target."""
    status = astar_batch(indptr, indices, weights, ints, reals, g, parent, closed, heap, counters, max_expansions,
                         max_degree)
    return _answer(status, ints, reals, g, parent, counters)


@numba.njit(cache=True)
def astar_moves_answer(mask: np.ndarray, move_shift: np.ndarray, move_weight: np.ndarray, move_cell: np.ndarray,
                       ints: np.ndarray, reals: np.ndarray, g: np.ndarray, parent: np.ndarray, closed: np.ndarray,
                       heap: np.ndarray, counters: np.ndarray, max_expansions: int,
                       max_degree: int) -> tuple[int, int, float, np.ndarray]:
    """:func:`~pathzoo_exact.search_loop.astar_moves_batch`, and the answer when it finds the target."""
    status = astar_moves_batch(mask, move_shift, move_weight, move_cell, ints, reals, g, parent, closed, heap,
                               counters, max_expansions, max_degree)
    return _answer(status, ints, reals, g, parent, counters)


@numba.njit(cache=True)
def thetastar_answer(indptr: np.ndarray, indices: np.ndarray, weights: np.ndarray, blocked: np.ndarray,
                     ints: np.ndarray, reals: np.ndarray, g: np.ndarray, parent: np.ndarray, closed: np.ndarray,
                     heap: np.ndarray, counters: np.ndarray, max_expansions: int,
                     max_degree: int) -> tuple[int, int, float, np.ndarray]:
    """:func:`~pathzoo_exact.search_loop.thetastar_batch`, and the answer when it finds the target."""
    status = thetastar_batch(indptr, indices, weights, blocked, ints, reals, g, parent, closed, heap, counters,
                             max_expansions, max_degree)
    return _answer(status, ints, reals, g, parent, counters)
