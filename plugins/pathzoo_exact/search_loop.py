"""The A* loop of the exact planners, and its batch kernels: CSR edges, move tables and Theta*'s line of sight.

Dijkstra is this A* with the zero heuristic. The search comes in two forms
that make the same comparisons, pushes and pops, so give bit-identical
results: :func:`astar_batch` reads a CSR graph, and
:func:`astar_moves_batch` reads a move table (:mod:`pathzoo_exact.moves`),
which is faster where every move has one cost; :func:`thetastar_batch` is
Theta*. All three are one loop (:func:`search_loop`) over the open list
(:mod:`pathzoo_exact.heap`), run in batches on a
:class:`~pathzoo_exact.search_state.SearchState`, for a problem packed by
:func:`~pathzoo_exact.problem.search_problem`.
"""

from __future__ import annotations

import math
from typing import Callable

import numba
import numpy as np
from llvmlite import ir
from llvmlite.binding import llvm_version_info
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

from pathzoo.grid.segments import segment_blocked_2d
from pathzoo_exact.heap import heap_pop, heap_push, order_key
from pathzoo_exact.problem import H_EUCLID, cell_heuristic, heuristic
from pathzoo_exact.search_state import EXHAUSTED, FOUND, HEAP_FULL, RUNNING, begin_batch, end_batch

__all__ = [
    "next_open",
    "CSR_STEP",
    "MOVES_STEP",
    "SIGHT_STEP",
    "search_loop",
    "astar_batch",
    "astar_moves_batch",
    "thetastar_batch",
]

_ZERO = np.uint64(0)
_ONE = np.uint64(1)
_PREFETCH = "llvm.prefetch.p0" if llvm_version_info >= (15,) else "llvm.prefetch.p0i8"
"""LLVM's prefetch intrinsic, named for its pointer argument: opaque pointers from LLVM 15 (numba >= 0.59 allows both)."""


@intrinsic
def _trailing_zeros(typingctx, x):
    """Index of the lowest set bit of a uint64 (64 when none is set): one instruction."""

    def codegen(context, builder, signature, args):
        return builder.cttz(args[0], ir.Constant(ir.IntType(1), 0))

    return types.uint64(types.uint64), codegen


@intrinsic
def _prefetch(typingctx, arr, index):
    """Ask the processor to bring ``arr[index]`` into its caches: no effect on any result, and no fault.

    A prefetch of a slot outside the array is allowed (the instruction never
    faults), so the caller need not check its index.
    """
    if not isinstance(arr, types.Array) or not isinstance(index, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        data = context.make_array(signature.args[0])(context, builder, args[0]).data
        slot = builder.gep(data, [context.cast(builder, args[1], signature.args[1], types.intp)])
        byte_ptr = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        prefetch = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(ir.VoidType(), [byte_ptr, i32, i32, i32]), _PREFETCH)
        # read, keep in every cache level, data
        builder.call(prefetch, [builder.bitcast(slot, byte_ptr), ir.Constant(i32, 0), ir.Constant(i32, 3), ir.Constant(i32, 1)])
        return context.get_dummy_value()

    return types.void(arr, index), codegen


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


CSR_STEP = 0
"""Step rule of :func:`search_loop`: relax the edges of a CSR graph (:func:`astar_batch`)."""
MOVES_STEP = 1
"""Step rule of :func:`search_loop`: relax the moves of a move table (:func:`astar_moves_batch`)."""
SIGHT_STEP = 2
"""Step rule of :func:`search_loop`: Theta*'s, a successor seeing its parent's parent links to it (:func:`thetastar_batch`)."""


def search_loop(rule: int) -> Callable[..., int]:
    """The A* loop of expansions of one step rule, compiled with only that rule's step.

    The loop takes the rule's graph arrays (see ``doc``), the problem's
    ``ints`` and ``reals`` (:func:`~pathzoo_exact.problem.search_problem`), the five
    :attr:`~pathzoo_exact.search_state.SearchState.arrays`, ``max_expansions`` and ``max_degree``.
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
                if size > 0:  # the likely next node: its rows of g on their way while this node's are read
                    top = heap_node[0]
                    _prefetch(g, top - dims[2])
                    _prefetch(g, top)
                    _prefetch(g, top + dims[2])
                    _prefetch(mask, top)
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
    :attr:`~pathzoo_exact.search_state.SearchState.arrays`, ``max_expansions``, ``max_degree``. Nodes
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
