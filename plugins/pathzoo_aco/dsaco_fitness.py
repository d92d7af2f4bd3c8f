"""DSACO's fitness (eq. 20) and flight constraints (eqs. 2-3) of every walk of a colony, each in one compiled pass."""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["walk_fitness", "infeasible_walks"]


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


@numba.njit(cache=True)
def infeasible_walks(flat, offsets, reached, edge_length, offset_id, cells, l_max, l_min):
    """Eqs. 2-3 per walk: longer than ``l_max``, or a straight segment other than the last shorter than ``l_min``.

    Lengths are in horizontal cells (``edge_length / cells`` per step); a
    limit of 0 is off. The sums are taken step by step in ``flat`` order, as
    ``np.cumsum`` (the walk length, a difference of one running sum over all
    walks) and ``np.bincount`` (each segment, from 0) take them, so the
    verdicts equal those of the array version this replaced (per-walk
    differences of ``np.cumsum`` and per-segment ``np.bincount``; checked by
    ``benchmarks/identity.py``). Walks that did not reach the goal count as
    too long when ``l_max`` is on.
    """
    n = offsets.size - 1
    bad = np.zeros(n, dtype=np.bool_)
    if l_max > 0.0:
        acc = 0.0
        for a in range(n):
            start = acc
            for p in range(offsets[a], offsets[a + 1]):
                acc += edge_length[flat[p]] / cells
            if not reached[a] or acc - start > l_max * (1.0 + 1e-12):
                bad[a] = True
    if l_min > 0.0:
        for a in range(n):
            p = offsets[a]
            while p < offsets[a + 1]:  # one straight segment: a run of the same move
                move = offset_id[flat[p]]
                length = 0.0
                while p < offsets[a + 1] and offset_id[flat[p]] == move:
                    length += edge_length[flat[p]] / cells
                    p += 1
                if p < offsets[a + 1] and length < l_min * (1.0 - 1e-12):  # the walk's last segment is exempt
                    bad[a] = True
    return bad
