"""DSACO's fitness (eq. 20) of every walk of a colony in one compiled pass."""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["walk_fitness"]


@numba.njit(cache=True)
def walk_fitness(flat, offsets, reached, indices, offset_id, edge_length, height, turn_angle, start, cells,
                 f1, f2, f3):
    """Eq. 20 per walk in one pass: the same operations, in the same order, as
    :meth:`pathzoo_aco.dsaco.DSACO.fitness_terms`.

    Per position: ``f1 ℓ/cells + f2 (h_i + h_j)/2 + f3 turn``; walks are
    totalled as differences of one running sum over ``flat`` (as
    :func:`pathzoo_aco.dsaco._per_walk`), so the costs are bit-identical to the array version.
    """
    n = offsets.size - 1
    cum = np.empty(flat.size + 1)
    cum[0] = 0.0
    acc = 0.0
    for a in range(n):
        i = start  # the segment's first node and the walk's previous move
        move = -1
        for p in range(offsets[a], offsets[a + 1]):
            e = flat[p]
            j = indices[e]
            turn = 0.0 if move < 0 else turn_angle[move, offset_id[e]]
            acc += f1 * (edge_length[e] / cells) + f2 * (0.5 * (height[i] + height[j])) + f3 * turn
            cum[p + 1] = acc
            i = j
            move = offset_id[e]
    out = np.empty(n)
    for a in range(n):
        out[a] = cum[offsets[a + 1]] - cum[offsets[a]] if reached[a] else np.inf
    return out
