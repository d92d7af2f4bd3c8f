"""DSACO's compiled colony tables: the allowed-move records per (node, heading class) and the run's state.

:class:`MoveTable` holds, per node and class of incoming heading, one record
per move the turn limit allows, built the first time an ant needs it
(:func:`build_list`); :class:`ColonyRun` is what a run carries from one call
of :func:`pathzoo_aco.dsaco_colony.run_colony` to the next. How the walk
reads them is told in :mod:`pathzoo_aco.dsaco_colony`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

__all__ = ["MoveTable", "ColonyRun", "build_list"]

_LEVEL_ROOM = 1 << 22
"""At most this many candidates kept for the nodes along a walk (:class:`ColonyRun`); deeper levels that do not
fit are read again. Room for every level of the longest walk (nodes times the largest degree) when that is less."""

@dataclass(frozen=True, eq=False)
class MoveTable:
    """A node's moves, and per (node, heading class) a record of each move the turn limit allows.

    Heading classes are the distinct rows of the turn table (row ``K``, no
    previous move, included). The list of node ``c`` and class ``k`` holds one
    record per edge of ``c`` whose move the turn table allows, in the
    adjacency's order (the order in which the generic walk considers them):
    its target node, adjacency position, weight and move. It is built the
    first time an ant stands on ``c`` with a heading of class ``k`` and
    appended to the record arrays, so the lists a walk reads lie one after
    another in memory, each in one run of cache lines, and no edge the turn
    limit refuses is ever read. Without a turn table (every move allowed) a
    list would copy the node's adjacency, so there are no records: the walk
    reads the adjacency in place.

    Attributes
    ----------
    adj_ptr, node, weight, move : ndarray
        The adjacency (the walk engine's, of the rules): CSR pointer (as
        uint32 when the positions fit: half the cache lines, and no read
        checks for a negative index), and per position the target node,
        weight ``weight_mul`` and move id.
    edge : ndarray of int
        Per adjacency position its graph edge id; empty when they are equal.
    move_class : ndarray of int64, shape (K + 1,)
        Class of every previous move.
    class_row : ndarray of int64
        A previous move (row of the turn table) standing for each class.
    head : ndarray of int32 or int64, shape (nodes * classes, 2)
        Per list (row ``c * classes + k``): its first record and its length
        plus 1; ``(0, 0)`` until built (allocated zeroed: pages cost memory
        only once a list on them is built) No rows without a turn table.
    to_rec : structured ndarray with fields ``node``, ``place``, ``weight``
        The records: target node (uint32 for int32 node ids), adjacency position and weight, side by side
        (the fields a step reads for every candidate: one run of memory).
        Allocated for every list there could be and written only as lists are
        built, so untouched pages cost no memory. Empty without a turn table.
    to_move : ndarray
        Per record its move (read for the chosen one only).
    to_next : ndarray of int64
        Per record of a move that sets the heading, where the list the ant
        reads after taking it starts (shifted left 16 bits) and its length
        plus 1, once an ant has looked it up; 0 until then. That list depends
        only on the record (target node, heading of its move), so later ants
        skip the random read of ``head``. Empty (not used) when a list's place
        or length would not fit.
    filled : ndarray of int64, shape (1,)
        Records in use.
    """

    adj_ptr: np.ndarray
    node: np.ndarray
    weight: np.ndarray
    move: np.ndarray
    edge: np.ndarray
    move_class: np.ndarray
    class_row: np.ndarray
    head: np.ndarray
    to_rec: np.ndarray
    to_move: np.ndarray
    to_next: np.ndarray
    filled: np.ndarray

    @classmethod
    def of(cls, adjacency: tuple, turn: np.ndarray) -> "MoveTable":
        """The table of an adjacency ``(adj_ptr, adj_node, adj_edge or None, adj_offset, weight_mul, _)``
        (:meth:`~pathzoo_aco.engine.walk.WalkEngine.adjacency`) and a turn table ``(K + 1, K)`` of zeros and
        ones (or ``(0, 0)``: one class, every move allowed)."""
        adj_ptr, adj_node, adj_edge, adj_offset, w_mul = adjacency[:5]
        n_nodes = len(adj_ptr) - 1
        if turn.size == 0:  # every list is the node's adjacency, read in place: no records
            move_class = np.zeros(1, dtype=np.int64)
            class_row = np.zeros(1, dtype=np.int64)
            records = 0
        else:
            _, first, inverse = np.unique(turn, axis=0, return_index=True, return_inverse=True)
            move_class = inverse.reshape(-1).astype(np.int64)
            class_row = first.astype(np.int64)
            per_move = np.bincount(adj_offset, minlength=turn.shape[1])  # every list there could be, at most
            records = int(((turn[class_row] > 0.0) @ per_move).sum())
        degree = int(np.diff(adj_ptr).max(initial=0))
        index = np.int32 if max(records, len(adj_node)) < 2**31 - 1 else np.int64
        edge = np.zeros(0, dtype=np.int64) if adj_edge is None else adj_edge
        node_ids = np.uint32 if adj_node.dtype == np.int32 else adj_node.dtype  # unsigned: no negative-index fix-up
        if len(adj_node) < 2**32 - 1:  # unsigned 32-bit list pointers: half the cache lines, no negative-index fix-up
            adj_ptr = adj_ptr.astype(np.uint32)
        return cls(adj_ptr, adj_node, w_mul, adj_offset, edge, move_class, class_row,
                   np.zeros((n_nodes * len(class_row) if turn.size else 0, 2), dtype=index),
                   np.empty(records, dtype=np.dtype([("node", node_ids), ("place", index),
                                                     ("weight", w_mul.dtype)])),
                   np.empty(records, dtype=adj_offset.dtype),
                   np.empty(records if records < 2**47 and degree < 2**16 - 1 else 0, dtype=np.int64),
                   np.zeros(1, dtype=np.int64))


@dataclass
class ColonyRun:
    """The state a run carries from one :func:`run_colony` call to the next (arrays changed in place).

    Attributes
    ----------
    scale : ndarray, shape (1,)
        The trail's global scale (:class:`~pathzoo_aco.engine.pheromone.Pheromone`).
    best_cost : ndarray, shape (1,)
        Fitness of the best walk so far.
    best_edges : ndarray of int64
        Its edges, ``best_edges[:counters[3]]``.
    counters : ndarray of int64, shape (6,)
        Next iteration, walks started, ant steps, length of the best walk,
        1 once an ant has searched the start's whole component (no turn rule),
        and the stamp of the next iteration's first walk.
    stamps : ndarray of uint8, shape (1, nodes)
        Tabu stamps; the walks of an iteration stamp their nodes with the
        next numbers from ``counters[5]`` on, and the stamps are cleared (the
        numbering starting again from 1) before an iteration whose numbers
        would pass 255. int32 once an iteration has more than 255 ants.
    stack, stack_prev : ndarray, shape (1, nodes + 1)
        Work space of the walks: the adjacency positions and headings along the walk.
    cand, cand_w, level_first, level_count, level_more : ndarray
        The candidates (records) and their weights of every node on the walk,
        one level per depth: level ``d`` starts at ``level_first[d]`` and
        holds ``level_count[d]`` of them (-1: not kept, no room);
        ``level_more[d]`` says whether an open move of that node weighed 0.
        When the walk steps back to a node after a dead end, the same
        candidates less the nodes stamped since are exactly what reading its
        list again would give (the trail does not change during a walk, and
        the sums run in the same order), unless none is left and an open move
        weighed 0: then the list is read again. The upper half of ``cand`` is
        room for a step whose level does not fit below.
    node_max : ndarray
        Per node, at least the largest stored trail ``x`` of its edges. When
        ``scale * node_max[c] <= τmin`` every trail leaving ``c`` reads as
        exactly ``τmin`` (the clamp), so a step from ``c`` skips the trail.
        Most nodes are there a few dozen iterations into a run: only the
        iteration-best walk deposits.
    node_even : ndarray of bool
        Per node, whether every stored trail of its edges equals
        ``node_max`` (true until a deposit on one of them: the trail starts
        even and evaporation and renormalisation treat every entry alike), so
        a step from it computes the trail and its power once for the list.
    """

    scale: np.ndarray
    best_cost: np.ndarray
    best_edges: np.ndarray
    counters: np.ndarray
    stamps: np.ndarray
    stack: np.ndarray
    stack_prev: np.ndarray
    cand: np.ndarray
    cand_w: np.ndarray
    level_first: np.ndarray
    level_count: np.ndarray
    level_more: np.ndarray
    node_max: np.ndarray
    node_even: np.ndarray

    @classmethod
    def start(cls, n_nodes: int, max_degree: int, trail: np.ndarray, scale: float) -> "ColonyRun":
        """A run before its first iteration, on ``n_nodes`` nodes with at most ``max_degree`` moves each,
        with the stored ``trail`` and its scale."""
        room = 2 * max(max_degree, min(n_nodes * max_degree, _LEVEL_ROOM))
        even = trail.size > 0 and trail.min() == trail.max()  # every entry the same
        return cls(np.array([scale]), np.array([np.inf]), np.zeros(max(n_nodes, 1), dtype=np.int64),
                   np.array([0, 0, 0, 0, 0, 1], dtype=np.int64), np.zeros((1, n_nodes), dtype=np.uint8),
                   np.zeros((1, n_nodes + 1), dtype=np.int64), np.zeros((1, n_nodes + 1), dtype=np.int64),
                   np.zeros(room, dtype=np.int64), np.zeros(room), np.zeros(n_nodes + 1, dtype=np.int64),
                   np.zeros(n_nodes + 1, dtype=np.int64), np.zeros(n_nodes + 1, dtype=np.bool_),
                   np.full(n_nodes, trail.max(initial=0.0)),
                   np.full(n_nodes, even))


@numba.njit(cache=True)
def build_list(c, k, h, adj_ptr, node, weight, move, turn, class_row, head, to_rec, to_move,
                to_next, filled):
    """Append the records of node ``c``'s list for heading class ``k`` (list ``h``): its edges whose move the
    turn table allows, in their adjacency order."""
    row = class_row[k]
    use_turn = turn.shape[0] > 0
    r = filled[0]
    head[h, 0] = r
    for q in range(adj_ptr[c], adj_ptr[c + 1]):
        if use_turn and turn[row, move[q]] <= 0.0:
            continue
        to_rec[r].node = node[q]
        to_rec[r].place = q
        to_rec[r].weight = weight[q]
        to_move[r] = move[q]
        if to_next.size:
            to_next[r] = 0
        r += 1
    head[h, 1] = r - head[h, 0] + 1
    filled[0] = r
