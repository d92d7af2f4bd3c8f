"""Move tables: a grid graph as one bit mask of allowed moves per cell, when every move has one cost.

On a flat occupancy grid (and on any graph built with a cost per move, not
per edge) the CSR arrays say little that the move itself does not: the target
of an edge is ``u + shift`` and its cost is the move's cost. A
:class:`MoveTable` keeps only which moves each cell may make, one bit per
move, so an expansion of :func:`~pathzoo_exact.search_loop.astar_moves_batch`
reads one byte (on 8-connected grids) instead of an ``indptr`` pair and
about eight node ids and eight weights. On ``8room_000`` (512 x 512) this made
the A* kernel about 1.5 times faster; the search is bound by memory, not by
arithmetic.

The table is only built when it describes the graph *exactly*; every edge is
checked once, in one pass:

- the edges of a node come in ascending move order (the order
  :func:`~pathzoo.grid.graph.build_graph` writes them, and the order the
  kernel tries the bits), so the search visits neighbours in the same order;
- the edge's target is ``u + shift`` of its move;
- all edges of a move have bit-for-bit the same weight.

Otherwise (terrain, where lengths and energies vary per edge, or more than
63 moves, as in the 74-move air volumes) :func:`move_table` returns ``None``
and the planner keeps the CSR kernel. A table is built once per graph and
cost and kept while the graph lives (about 2 ms and one byte per cell on a
512 x 512 grid).
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from pathzoo.core.object_memo import ObjectMemo
from pathzoo.grid.graph import GridGraph

__all__ = ["MoveTable", "MAX_MOVES", "move_table"]

MAX_MOVES = 63
"""Most moves a table can hold: the kernel reads a mask as a signed 64-bit integer."""

_TABLES: "ObjectMemo[GridGraph, dict[str, MoveTable | None]]" = ObjectMemo()


@dataclass(frozen=True)
class MoveTable:
    """A grid graph whose edge costs depend on the move only.

    Attributes
    ----------
    mask : ndarray of uint8, uint16, uint32 or int64, shape (N,)
        Bit ``k`` is set when the node has the edge of move ``k``.
    shift : ndarray of int64, shape (K,)
        Flat node-id difference of each move.
    weight : ndarray of float64, shape (K,)
        Cost of each move (NaN for a move no node makes).
    cell : ndarray of int64, shape (K, 3)
        Each move as ``(dx, dy, dz)`` cells (column, row, layer).
    """

    mask: np.ndarray
    shift: np.ndarray
    weight: np.ndarray
    cell: np.ndarray

    @property
    def n_moves(self) -> int:
        """Number of moves ``K``, the most edges a node can have."""
        return len(self.shift)


@numba.njit(cache=True)
def _fill_mask(
    indptr: np.ndarray,
    indices: np.ndarray,
    offset_id: np.ndarray,
    weights: np.ndarray,
    shift: np.ndarray,
    mask: np.ndarray,
    weight: np.ndarray,
) -> bool:
    """Fill ``mask`` and ``weight`` (NaN on entry) from the CSR graph; False as soon as an edge breaks a rule of the module docstring."""
    seen = np.zeros(shift.shape[0], dtype=np.bool_)
    for u in range(indptr.shape[0] - 1):
        bits = np.int64(0)
        last = np.int64(-1)
        for e in range(indptr[u], indptr[u + 1]):
            k = np.int64(offset_id[e])
            if k <= last or indices[e] != u + shift[k]:
                return False
            if not seen[k]:
                seen[k] = True
                weight[k] = weights[e]
            elif weights[e] != weight[k]:
                return False
            bits |= np.int64(1) << k
            last = k
        mask[u] = bits
    return True


def _mask_dtype(n_moves: int) -> type:
    for dtype in (np.uint8, np.uint16, np.uint32):
        if n_moves <= 8 * np.dtype(dtype).itemsize:
            return dtype
    return np.int64


def _build(graph: GridGraph, cost: str) -> MoveTable | None:
    n_moves = len(graph.offsets)
    if n_moves > MAX_MOVES:
        return None
    shape = graph.shape
    strides = np.array([int(np.prod(shape[i + 1 :])) for i in range(len(shape))], dtype=np.int64)
    shift = graph.offsets.astype(np.int64) @ strides
    mask: np.ndarray = np.zeros(graph.n_nodes, dtype=_mask_dtype(n_moves))
    weight = np.full(n_moves, np.nan)
    if not _fill_mask(graph.indptr, graph.indices, graph.offset_id, graph.weights(cost), shift, mask, weight):
        return None
    cell = np.zeros((n_moves, 3), dtype=np.int64)
    cell[:, : len(shape)] = graph.offsets[:, ::-1]  # array-axis order (layer, row, col) -> (x, y, z)
    for arr in (mask, shift, weight, cell):
        arr.setflags(write=False)
    return MoveTable(mask=mask, shift=shift, weight=weight, cell=cell)


def move_table(graph: GridGraph, cost: str) -> MoveTable | None:
    """The :class:`MoveTable` of ``graph`` for edge cost ``cost``, or ``None`` when no table describes it exactly.

    Parameters
    ----------
    graph : GridGraph
        The scenario's neighbourhood graph.
    cost : {"length", "energy"}
        Which edge weights (:meth:`GridGraph.weights`) the table must reproduce.

    Built on the first call for a graph and cost, then reused while the
    graph lives.
    """
    tables = _TABLES.value(graph, dict)
    if cost not in tables:
        tables[cost] = _build(graph, cost)
    return tables[cost]
