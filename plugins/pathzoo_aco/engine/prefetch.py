"""A cache hint for compiled loops whose next reads are known before they are needed but follow no stride.

The hardware prefetchers follow streams and strides; a walk's next node, or
the trail entries along a walk, they cannot guess. A loop that knows them a
little in advance asks for their cache lines with :func:`prefetch` and does
other work while they arrive. A hint changes no value, so results are
bit-identical with or without it.
"""

from __future__ import annotations

from llvmlite import ir
from numba.core import cgutils, types
from numba.extending import intrinsic

__all__ = ["prefetch", "AHEAD"]

AHEAD = 16
"""Entries between the hint and the read in a loop that gathers along a walk (16 and 32 measured alike, 8 less)."""


@intrinsic
def prefetch(typingctx, arr, idx):
    """Ask the cache for the line holding ``arr[idx]`` (LLVM's ``llvm.prefetch``: a hint, never a fault).

    ``idx`` may lie outside the array (the hint is then wasted, nothing is read).
    """
    if not isinstance(arr, types.Array) or not isinstance(idx, types.Integer):
        return None

    def codegen(context, builder, signature, args):
        array = context.make_array(signature.args[0])(context, builder, args[0])
        where = builder.gep(array.data, [context.cast(builder, args[1], signature.args[1], types.intp)])
        byte_ptr = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        hint = cgutils.get_or_insert_function(builder.module, ir.FunctionType(ir.VoidType(), [byte_ptr, i32, i32, i32]),
                                              "llvm.prefetch.p0i8")
        builder.call(hint, [builder.bitcast(where, byte_ptr), i32(0), i32(3), i32(1)])  # read, keep, data
        return context.get_dummy_value()

    return types.void(arr, idx), codegen
