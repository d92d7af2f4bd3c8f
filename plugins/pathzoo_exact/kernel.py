"""Numba kernel shared by the exact planners: a binary heap and a resumable A* search.

Dijkstra is this A* with the zero heuristic. The search comes in two forms
that make the same comparisons, pushes and pops, so give bit-identical
results: :func:`astar_batch` reads a CSR graph, and
:func:`astar_moves_batch` reads a move table (:mod:`pathzoo_exact.moves`),
which is faster where every move has one cost. The search state lives in
plain NumPy arrays (:class:`SearchState`), so the Python driver can run the
search in batches of expansions and look at the clock between batches.

A kernel's arguments are few arrays: the problem's scalars and small vectors
packed in two (:func:`search_problem`), the heap's three columns in one. A
call from Python costs about 60 ns per argument to type-check and unbox, as
much as a search of a few nodes, and short searches are called one per
``plan()``.

The heap is *lazy*: a node whose cost improves is pushed again instead of
having its key decreased, and stale entries are skipped when popped (the
node is already closed). On ``8room_000`` this was about 1.5 times faster
than an indexed heap with decrease-key, because sifting moves fewer arrays. The heap
starts small (a search front is much smaller than the graph) and the kernel
returns :data:`HEAP_FULL` when an expansion might not fit, so the driver
doubles it and resumes.

Heap order is ``f`` ascending, ties broken towards the larger ``g`` (the node
deeper along its path), which keeps A* on open grids from expanding whole
plateaus of equal ``f``. Ties never change the optimal cost, only which of
several optimal paths is returned.

The heap stores ``f`` and ``g`` as integers (:func:`order_key`), not floats:
read as unsigned integers, two keys compare in the same order as the two
floats they stand for, so every comparison, and hence every push, pop and
path, is what it is with float keys. The test "comes before" (``f``
ascending, then ``g`` descending) is then one comparison of two unsigned
128-bit numbers (:func:`_comes_before`), one compare and one
subtract-with-borrow on the chain of dependent steps of every heap level,
where float keys take several compares and their logic.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from pathzoo.grid.segments import segment_blocked_2d

__all__ = [
    "SearchState",
    "H_ZERO",
    "H_OCTILE",
    "H_EUCLID",
    "RUNNING",
    "FOUND",
    "EXHAUSTED",
    "HEAP_FULL",
    "order_key",
    "cell_heuristic",
    "heuristic",
    "grid_dims",
    "goal_cell",
    "search_problem",
    "PROBLEM_INTS",
    "PROBLEM_REALS",
    "heap_push",
    "heap_pop",
    "next_open",
    "begin_batch",
    "end_batch",
    "CSR_STEP",
    "MOVES_STEP",
    "SIGHT_STEP",
    "search_loop",
    "astar_batch",
    "astar_moves_batch",
    "thetastar_batch",
    "trace_path",
    "run_batch",
]

H_ZERO = 0
"""Zero heuristic (Dijkstra)."""
H_OCTILE = 1
"""Octile distance on the ``x, y`` axes (``z`` ignored)."""
H_EUCLID = 2
"""Euclidean distance on the ``x, y, z`` axes."""

RUNNING = 0
"""The batch ended before the search did."""
FOUND = 1
"""The target was expanded: its ``g`` is optimal."""
EXHAUSTED = 2
"""The open list ran empty: the target is unreachable."""
HEAP_FULL = 3
"""The heap has no room for another expansion: grow it (:meth:`SearchState.grow_heap`) and resume."""

_SQRT2_M1 = math.sqrt(2.0) - 1.0
_ZERO = np.uint64(0)
_ONE = np.uint64(1)
_SIGN = np.int64(-(1 << 63))


@intrinsic
def _float_bits(typingctx, x):
    """The IEEE-754 bit pattern of a float64, read as an int64 (no conversion: a register move)."""

    def codegen(context, builder, signature, args):
        return builder.bitcast(args[0], context.get_value_type(types.int64))

    return types.int64(types.float64), codegen


@intrinsic
def _trailing_zeros(typingctx, x):
    """Index of the lowest set bit of a uint64 (64 when none is set): one instruction."""

    def codegen(context, builder, signature, args):
        return builder.cttz(args[0], ir.Constant(ir.IntType(1), 0))

    return types.uint64(types.uint64), codegen


@intrinsic
def _comes_before(typingctx, f1, g1, f0, g0):
    """1 (uint64) when the heap entry ``(f1, g1)`` comes before ``(f0, g0)``, else 0: ``f`` ascending, then ``g`` descending.

    That is ``f1 < f0 or (f1 == f0 and g1 > g0)``. Float keys are compared
    as floats, in that expression. Integer keys (:func:`order_key`) are
    compared as unsigned 64-bit integers, and the whole test is one
    comparison of two unsigned 128-bit numbers, ``(f1, g0) < (f0, g1)``
    (high half, low half): one compare and one subtract-with-borrow, where
    the expression takes three compares and their logic, on the chain of
    dependent steps of every heap level.
    """
    keys = (f1, g1, f0, g0)
    if all(isinstance(k, types.Integer) for k in keys):
        kind = types.int64
    elif all(isinstance(k, (types.Integer, types.Float)) for k in keys):
        kind = types.float64
    else:
        return None

    def codegen(context, builder, signature, args):
        f1, g1, f0, g0 = (context.cast(builder, v, t, kind) for v, t in zip(args, signature.args))
        if kind == types.float64:
            less = builder.fcmp_ordered("<", f1, f0)
            tie = builder.and_(builder.fcmp_ordered("==", f1, f0), builder.fcmp_ordered(">", g1, g0))
            return builder.zext(builder.or_(less, tie), ir.IntType(64))
        wide = ir.IntType(128)

        def pair(high: ir.Value, low: ir.Value) -> ir.Value:
            return builder.or_(builder.shl(builder.zext(high, wide), ir.Constant(wide, 64)), builder.zext(low, wide))

        return builder.zext(builder.icmp_unsigned("<", pair(f1, g0), pair(f0, g1)), ir.IntType(64))

    return types.uint64(f1, g1, f0, g0), codegen


@numba.njit(cache=True)
def order_key(x: float) -> int:
    """A 64-bit key that, read as an unsigned integer, compares with other keys exactly as the float ``x`` with theirs.

    A non-negative float's bit pattern, read as an unsigned integer, grows
    with the float; with its sign bit flipped it lies above every negative
    float's pattern with all its bits flipped, and those grow with the
    float too (their magnitude bits fall). So for all floats other than
    NaN, ``order_key(a) < order_key(b)`` as unsigned integers exactly when
    ``a < b``, and the keys are equal exactly when the floats are, with one
    exception: ``-0.0`` gets a key below ``+0.0``'s. No heap key is ever
    ``-0.0``: a search starts at ``g = +0.0``, and under round-to-nearest a
    sum is ``-0.0`` only when both terms are, so neither ``g + weight`` nor
    ``g + h`` can be. Negative floats do occur: Z*
    (``pathzoo_rivals.zstar``) searches reduced costs that rounding can
    leave slightly below zero. NaN keys never reach the heap (``cand < g``
    is false for a NaN ``cand``). The key is returned, and stored in the
    heap's int64 arrays, as the int64 of the same bits.
    """
    bits = _float_bits(x)
    return bits ^ ((bits >> 63) | _SIGN)


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
        heap_f[0] = _SIGN  # order_key(0.0)
        heap_g[0] = _SIGN
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
        tie-breaker ``g`` of a slot; the keys are :func:`order_key` values.
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


@numba.njit(cache=True, inline="always")
def heap_push(heap_node: np.ndarray, heap_f: np.ndarray, heap_g: np.ndarray, size: int, node: int, f: int | float, g: int | float) -> int:
    """Push ``node`` with key ``f`` (ties: larger ``g`` first) on a heap of ``size`` entries; returns the new size.

    The keys are floats, or :func:`order_key` integers in arrays of int64
    (the search kernels'), compared as unsigned integers; :func:`_comes_before`
    orders two entries. Slots are unsigned here and in :func:`heap_pop`,
    which says why.
    """
    i = np.uint64(size)
    while i > _ZERO:
        p = (i - _ONE) >> _ONE
        if not _comes_before(f, g, heap_f[p], heap_g[p]):
            break
        heap_node[i] = heap_node[p]
        heap_f[i] = heap_f[p]
        heap_g[i] = heap_g[p]
        i = p
    heap_node[i] = node
    heap_f[i] = f
    heap_g[i] = g
    return size + 1


@numba.njit(cache=True, inline="always")
def heap_pop(heap_node: np.ndarray, heap_f: np.ndarray, heap_g: np.ndarray, size: int) -> int:
    """Remove the first entry of a heap of ``size > 0`` entries and return its node (the size drops by one).

    Bottom-up deletion: the hole left at the root walks down along the better
    children to a leaf, then the last entry is sifted up from there. The last
    entry usually belongs near the bottom, so this saves comparisons. The heap
    size is passed in and out of the kernels as a local variable, which lets
    the compiler keep it in a register.

    Slot indices are unsigned 64-bit integers. With signed ones numba must
    allow for negative (from-the-end) indices and adds a correction to every
    address, which sits on the loop's critical path: unsigned slots made the
    heap's pushes and pops about 20 % faster (replayed on the searches of
    ``8room_000``), with the same comparisons and so the same order.
    """
    top = heap_node[0]
    size -= 1
    if size == 0:
        return top
    n = np.uint64(size)
    i = _ZERO
    c = _ONE
    while c + _ONE < n:  # two children: the better one, chosen without a branch (a coin toss for the predictor)
        c += _comes_before(heap_f[c + _ONE], heap_g[c + _ONE], heap_f[c], heap_g[c])
        heap_node[i] = heap_node[c]
        heap_f[i] = heap_f[c]
        heap_g[i] = heap_g[c]
        i = c
        c = i + i + _ONE
    if c < n:  # one child, the last entry
        heap_node[i] = heap_node[c]
        heap_f[i] = heap_f[c]
        heap_g[i] = heap_g[c]
        i = c
    # the hole at slot i is the free slot of a heap of i entries: push the last entry there
    heap_push(heap_node, heap_f, heap_g, np.int64(i), heap_node[n], heap_f[n], heap_g[n])
    return top


@numba.njit(cache=True, inline="always")
def next_open(
    closed: np.ndarray, heap_node: np.ndarray, heap_f: np.ndarray, heap_g: np.ndarray, size: int, room: int
) -> tuple[int, int, int]:
    """Pop stale entries until an open node comes out, and close it.

    Returns ``(node, size, status)``: ``status`` is :data:`RUNNING` with the
    node to expand, or :data:`EXHAUSTED` (empty heap) or :data:`HEAP_FULL`
    (the heap holds more than ``room`` entries: the heap's slots less the
    pushes of one expansion) with node ``-1``.
    """
    while True:
        if size == 0:
            return -1, size, EXHAUSTED
        if size > room:
            return -1, size, HEAP_FULL
        u = heap_pop(heap_node, heap_f, heap_g, size)
        size -= 1
        if not closed[np.uint64(u)]:
            closed[np.uint64(u)] = True
            return u, size, RUNNING


@numba.njit(cache=True)
def end_batch(counters: np.ndarray, size: int, expanded: int, status: int) -> int:
    """Store the heap size and expansion count of a batch; returns its final status."""
    counters[0] = size
    counters[1] += expanded
    if status == RUNNING and size == 0:
        return EXHAUSTED
    return status


CSR_STEP = 0
"""Step rule of :func:`search_loop`: relax the edges of a CSR graph (:func:`astar_batch`)."""
MOVES_STEP = 1
"""Step rule of :func:`search_loop`: relax the moves of a move table (:func:`astar_moves_batch`)."""
SIGHT_STEP = 2
"""Step rule of :func:`search_loop`: Theta*'s, a successor seeing its parent's parent links to it (:func:`thetastar_batch`)."""


def search_loop(rule: int) -> Callable[..., int]:
    """The A* loop of expansions of one step rule, compiled with only that rule's step.

    The loop takes the rule's graph arrays (see ``doc``), the problem's
    ``ints`` and ``reals`` (:func:`search_problem`), the five
    :attr:`SearchState.arrays`, ``max_expansions`` and ``max_degree``.
    It pops the best open node (:func:`next_open`), stops at the target and
    otherwise relaxes the node's edges by the rule. ``rule`` is a constant
    of the closure, so numba drops the other rules' steps before it
    compiles: the kernel is the loop written out for that rule, with no call
    per expansion (a shared step called through numba, even one inlined by
    numba, costs a call or reference counts on every expansion). Returns
    :data:`RUNNING`, :data:`FOUND`, :data:`EXHAUSTED` or :data:`HEAP_FULL`.

    The loop takes its arguments as ``*args``, which numba packs into a
    tuple on every call from Python; the batch kernels (:func:`astar_batch`,
    ...) name their arguments and call it, compiled into them.
    """

    def batch(*args):
        ints, reals, g, parent, closed, heap, counters, max_expansions, max_degree = args[-9:]
        target = ints[0]
        mode = ints[1]
        goal = ints[2:5]
        dims = ints[5:8]
        steps = reals[0:3]
        scale = reals[3]
        heap_node = heap[0]
        heap_f = heap[1]
        heap_g = heap[2]
        if rule == CSR_STEP:
            indptr, indices, weights = args[:-9]
        elif rule == MOVES_STEP:
            mask, move_shift, move_weight, move_cell = args[:-9]
            w = np.uint64(dims[2])
            plane = np.uint64(dims[1]) * w
        else:
            indptr, indices, weights, blocked = args[:-9]
            width = dims[2]
            cs = steps[0]
        size = begin_batch(g, parent, closed, heap_node, heap_f, heap_g, counters)
        status = RUNNING
        done = 0
        room = heap_node.shape[0] - max_degree  # the largest heap an expansion may start from
        while done < max_expansions:
            u, size, status = next_open(closed, heap_node, heap_f, heap_g, size, room)
            if status != RUNNING:
                break
            done += 1
            if u == target:
                status = FOUND
                break
            if rule == CSR_STEP:
                ui = np.uint64(u)  # unsigned indices spare numba's negative-index correction (see heap_pop)
                gu = g[ui]
                for e in range(indptr[ui], indptr[ui + _ONE]):
                    v = indices[np.uint64(e)]
                    j = np.uint64(v)
                    cand = gu + weights[np.uint64(e)]
                    if cand < g[j] and not closed[j]:
                        g[j] = cand
                        parent[j] = u
                        f = cand + heuristic(v, goal, mode, dims, steps, scale)
                        size = heap_push(heap_node, heap_f, heap_g, size, v, order_key(f), order_key(cand))
            elif rule == MOVES_STEP:
                ui = np.uint64(u)
                gu = g[ui]
                # unsigned divisions: numba's signed ``//`` rounds towards minus infinity, which costs a correction
                layer_u = ui // plane
                rest = ui - layer_u * plane
                row_u = rest // w
                col = np.int64(rest - row_u * w)
                row = np.int64(row_u)
                layer = np.int64(layer_u)
                bits = np.uint64(mask[ui])
                while bits != _ZERO:  # the set bits, lowest first: no test (and no mispredicted branch) per absent move
                    k = _trailing_zeros(bits)
                    bits &= bits - _ONE
                    v = u + move_shift[k]
                    j = np.uint64(v)  # an unsigned index spares numba's negative-index correction (see heap_pop)
                    cand = gu + move_weight[k]
                    if cand < g[j] and not closed[j]:
                        g[j] = cand
                        parent[j] = u
                        h = cell_heuristic(col + move_cell[k, 0], row + move_cell[k, 1], layer + move_cell[k, 2], goal,
                                           mode, steps, scale)
                        size = heap_push(heap_node, heap_f, heap_g, size, v, order_key(cand + h), order_key(cand))
            else:
                p = parent[u]
                pr = p // width
                pc = p % width
                for e in range(indptr[u], indptr[u + 1]):
                    v = indices[e]
                    if closed[v]:
                        continue
                    vr = v // width
                    vc = v % width
                    if p >= 0 and not segment_blocked_2d(blocked, pc + 0.5, pr + 0.5, vc + 0.5, vr + 0.5):
                        cand = g[p] + cs * math.hypot(float(vc - pc), float(vr - pr))
                        via = p
                    else:
                        cand = g[u] + weights[e]
                        via = u
                    if cand < g[v]:
                        g[v] = cand
                        parent[v] = via
                        f = cand + heuristic(v, goal, H_EUCLID, dims, steps, 1.0)
                        size = heap_push(heap_node, heap_f, heap_g, size, v, order_key(f), order_key(cand))
        return end_batch(counters, size, done, status)

    batch.__qualname__ = batch.__name__ = ("csr_loop", "moves_loop", "sight_loop")[rule]
    return numba.njit(cache=True)(batch)


_CSR_LOOP = search_loop(CSR_STEP)
_MOVES_LOOP = search_loop(MOVES_STEP)
_SIGHT_LOOP = search_loop(SIGHT_STEP)


@numba.njit(cache=True)
def astar_batch(indptr: np.ndarray, indices: np.ndarray, weights: np.ndarray, ints: np.ndarray, reals: np.ndarray,
                g: np.ndarray, parent: np.ndarray, closed: np.ndarray, heap: np.ndarray, counters: np.ndarray,
                max_expansions: int, max_degree: int) -> int:
    """A* on a CSR graph, up to ``max_expansions`` expansions (see :func:`search_loop`).

    Arguments: ``indptr, indices, weights``, the problem's ``ints, reals``
    (:func:`search_problem`: target, heuristic), the five
    :attr:`SearchState.arrays`, ``max_expansions``, ``max_degree``. Nodes
    are closed when expanded and never reopened, which is exact for a
    consistent heuristic (and for Dijkstra). ``max_degree`` bounds the
    pushes of one expansion.
    """
    return _CSR_LOOP(indptr, indices, weights, ints, reals, g, parent, closed, heap, counters, max_expansions,
                     max_degree)


@numba.njit(cache=True)
def astar_moves_batch(mask: np.ndarray, move_shift: np.ndarray, move_weight: np.ndarray, move_cell: np.ndarray,
                      ints: np.ndarray, reals: np.ndarray, g: np.ndarray, parent: np.ndarray, closed: np.ndarray,
                      heap: np.ndarray, counters: np.ndarray, max_expansions: int, max_degree: int) -> int:
    """:func:`astar_batch` on a grid whose edge costs depend on the move only (see :mod:`pathzoo_exact.moves`).

    Arguments: ``mask, move_shift, move_weight, move_cell``, then those of
    :func:`astar_batch` from ``ints`` on. Bit ``k`` of ``mask[u]`` says
    that node ``u`` has the edge of move ``k``, to node ``u +
    move_shift[k]`` at cost ``move_weight[k]``; ``move_cell[k]`` is the move
    as ``(dx, dy, dz)`` cells. Moves are tried in ascending ``k``, the order
    of the CSR edges, so every comparison, push and pop is that of
    :func:`astar_batch` on the same graph and the result is bit-identical.
    It reads one mask per expansion instead of the CSR row, and derives the
    neighbours' cells from the expanded cell (no division per push).
    """
    return _MOVES_LOOP(mask, move_shift, move_weight, move_cell, ints, reals, g, parent, closed, heap, counters,
                       max_expansions, max_degree)


@numba.njit(cache=True)
def thetastar_batch(indptr: np.ndarray, indices: np.ndarray, weights: np.ndarray, blocked: np.ndarray,
                    ints: np.ndarray, reals: np.ndarray, g: np.ndarray, parent: np.ndarray, closed: np.ndarray,
                    heap: np.ndarray, counters: np.ndarray, max_expansions: int, max_degree: int) -> int:
    """Theta* (:mod:`pathzoo_exact.thetastar`) on a 2-D CSR graph (see :func:`search_loop`).

    Arguments: ``indptr, indices, weights, blocked``, then those of
    :func:`astar_batch` from ``ints`` on. The grid is ``(1, H, W)``, the
    steps ``(cell_size, cell_size, 0)``, and ``blocked`` the occupancy grid
    that :func:`pathzoo.grid.segments.segment_blocked_2d` reads for line of
    sight; the heuristic is the Euclidean distance (the problem's mode and
    scale are not read).
    """
    return _SIGHT_LOOP(indptr, indices, weights, blocked, ints, reals, g, parent, closed, heap, counters,
                       max_expansions, max_degree)


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


def run_batch(kernel: Callable[..., int], args: tuple, max_degree: int, state: SearchState, max_expansions: int) -> int:
    """Advance a search by one batch with a batch kernel.

    Parameters
    ----------
    kernel : callable
        :func:`astar_batch` or a kernel with the same trailing arguments.
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

