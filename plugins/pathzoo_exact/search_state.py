"""The state of one exact search, kept in NumPy arrays between batches, and what starts and ends a batch.

The search state lives in plain NumPy arrays (:class:`SearchState`), so the
Python driver can run the search in batches of expansions and look at the
clock between batches. Each batch kernel
(:mod:`pathzoo_exact.search_loop`) starts with :func:`begin_batch` and ends
with :func:`end_batch`, and returns one of the statuses here.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numba
import numpy as np

from pathzoo_exact.heap import order_key

__all__ = ["SearchState", "RUNNING", "FOUND", "EXHAUSTED", "HEAP_FULL", "begin_batch", "end_batch", "run_batch"]

RUNNING = 0
"""The batch ended before the search did."""
FOUND = 1
"""The target was expanded: its ``g`` is optimal."""
EXHAUSTED = 2
"""The open list ran empty: the target is unreachable."""
HEAP_FULL = 3
"""The heap has no room for another expansion: grow it (:meth:`SearchState.grow_heap`) and resume."""


@numba.njit(cache=True)
def begin_batch(
    g: np.ndarray,
    parent: np.ndarray,
    closed: np.ndarray,
    heap_node: np.ndarray,
    heap_f: np.ndarray,
    heap_g: np.ndarray,
    counters: np.ndarray,
) -> int:
    """The heap size a batch starts from, after doing the (re)start :meth:`SearchState.restart` left to it, if any.

    A start marks every node unseen and open and puts only its source (cost
    0) on the open list. Every batch kernel starts here: a restart done by the
    first batch costs no call of its own, and a search on a small map takes a
    few microseconds, about as long as one more compiled call from Python.
    """
    source = counters[2]
    if source >= 0:
        g[:] = np.inf
        closed[:] = False
        g[source] = 0.0
        parent[source] = -1
        heap_node[0] = source
        heap_f[0] = order_key(0.0)
        heap_g[0] = order_key(0.0)
        counters[0] = 1
        counters[1] = 0
        counters[2] = -1
    return counters[0]


@dataclass
class SearchState:
    """Mutable arrays of one search, resumed batch after batch.

    Attributes
    ----------
    g : ndarray of float64, shape (N,)
        Best known cost from the source (``inf`` when unseen).
    parent : ndarray of int64, shape (N,)
        Predecessor on the best known path; ``-1`` for the source. Nodes
        never reached are left uninitialised (nothing reads them), which spares
        writing (and page-faulting) 8 bytes per node in every search.
    closed : ndarray of bool, shape (N,)
        Whether each node has been expanded.
    heap : ndarray of int64, shape (3, capacity)
        The binary heap, one row each for the node, the key ``f`` and the
        tie-breaker ``g`` of a slot; the keys are :func:`~pathzoo_exact.heap.order_key` values.
    counters : ndarray of int64, shape (3,)
        ``[heap size, expanded nodes, source of a start the next batch does first (-1: none)]``.
    """

    g: np.ndarray
    parent: np.ndarray
    closed: np.ndarray
    heap: np.ndarray
    counters: np.ndarray

    @property
    def arrays(self) -> tuple[np.ndarray, ...]:
        """The five arrays in the order above: the batch kernels' trailing arguments."""
        return self.g, self.parent, self.closed, self.heap, self.counters

    @classmethod
    def start(cls, n_nodes: int, source: int, heap_capacity: int = 4096) -> "SearchState":
        """A fresh state whose first batch starts the search from ``source`` (see :meth:`restart`)."""
        state = cls(
            g=np.empty(n_nodes),
            parent=np.empty(n_nodes, dtype=np.int64),
            closed=np.empty(n_nodes, dtype=np.bool_),
            heap=np.empty((3, 0), dtype=np.int64),
            counters=np.zeros(3, dtype=np.int64),
        )
        state.restart(source, heap_capacity)
        return state

    def restart(self, source: int, heap_capacity: int = 4096) -> None:
        """Forget the search and start a new one from ``source`` in the same node arrays.

        The arrays, the expansion count included, are set by the next batch
        (:func:`begin_batch`): here only the source is noted (one write from
        Python). Until then only :attr:`expanded` (0) may be read.
        """
        self._heap_of(heap_capacity)
        self.counters[2] = source

    def _heap_of(self, capacity: int) -> None:
        """A heap of ``capacity`` slots (a new one only when the capacity differs)."""
        if self.heap.shape[1] != capacity:
            self.heap = np.empty((3, capacity), dtype=np.int64)

    def grow_heap(self) -> None:
        """Double the heap's capacity, keeping its entries."""
        size = int(self.counters[0])
        new = np.empty((3, 2 * self.heap.shape[1]), dtype=np.int64)
        new[:, :size] = self.heap[:, :size]
        self.heap = new

    @property
    def expanded(self) -> int:
        """Number of nodes expanded so far (0 before a restarted search's first batch)."""
        return 0 if self.counters[2] >= 0 else int(self.counters[1])


@numba.njit(cache=True)
def end_batch(counters: np.ndarray, size: int, expanded: int, status: int) -> int:
    """Store the heap size and expansion count of a batch; returns its final status."""
    counters[0] = size
    counters[1] += expanded
    if status == RUNNING and size == 0:
        return EXHAUSTED
    return status


def run_batch(kernel: Callable[..., int], args: tuple, max_degree: int, state: SearchState, max_expansions: int) -> int:
    """Advance a search by one batch with a batch kernel.

    Parameters
    ----------
    kernel : callable
        :func:`~pathzoo_exact.search_loop.astar_batch` or a kernel with the same trailing arguments.
    args : tuple
        The kernel's leading (problem) arguments.
    max_degree : int
        Upper bound on a node's out-degree.
    state : SearchState
        The search to advance.
    max_expansions : int
        Expansions allowed in this batch.
    """
    return kernel(*args, *state.arrays, max_expansions, max_degree)
