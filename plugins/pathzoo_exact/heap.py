"""The open list of the exact searches: a lazy binary heap of ``(f, g, node)`` with integer keys.

The heap is *lazy*: a node whose cost improves is pushed again instead of
having its key decreased, and stale entries are skipped when popped (the
node is already closed, :func:`~pathzoo_exact.search_loop.next_open`). On
``8room_000`` this was about 1.5 times faster than an indexed heap with
decrease-key, because sifting moves fewer arrays. The heap starts small (a
search front is much smaller than the graph) and a batch returns
:data:`~pathzoo_exact.search_state.HEAP_FULL` when an expansion might not
fit, so the driver doubles it and resumes.

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

import numba
import numpy as np
from llvmlite import ir
from numba import types
from numba.extending import intrinsic

__all__ = ["order_key", "heap_push", "heap_pop"]

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
