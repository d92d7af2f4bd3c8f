"""The step rules every ant walk shares: weights, candidates, the draw, the local update.

Every compiled walk of the family (the kernels of
:func:`~pathzoo_aco.engine.walk_kernel.colony_kernel`, FGDACO's timed walks
among them, and DSACO's colony) lists an ant's candidate
edges, weighs them, falls back on the heuristic when every trail weight is 0,
draws one by eq. 14's rule and, after a dead end, some take again the
candidates kept from their first visit of the node. Each of those rules is
written here once.

They are compiled with ``inline="always"``: numba pastes their code into the
walk that calls them before it compiles it, so a step calls nothing (a call
through numba's dispatch costs a call and reference counts per step), and
the constants and array types of each walk specialise the pasted code like
its own. They take numbers and arrays the walk already holds, so every walk
computes the same doubles in the same order and draws the same random
numbers as before.

Pushing the chosen edge on the walk and stepping back after a dead end stay
written in each walk: an array handed to an inlined helper whose body
branches keeps a reference count there (numba's pruning of counts does not
remove it across the helper's branches), and on moves made at every step,
or at every step back, that count costs more than the rest of the move.
The draws keep one such count on ``cand_w`` per step (their loop is such a
branch): written out by hand in a walk they would save it, at the price of a
second copy of eq. 14's rule. ``benchmarks/aco.py`` (the floor table) is
where such a cost shows.
"""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["read_trail", "trail_power", "roulette", "heaviest", "choose", "heuristic_candidates", "kept_candidates",
           "local_update"]


@numba.njit(cache=True, inline="always")
def read_trail(scale, stored, lo, hi, bounded):
    """The trail a stored value stands for (:class:`~pathzoo_aco.engine.pheromone.Pheromone`'s read): ``scale *
    stored``, clamped to ``[lo, hi]`` when the trail is ``bounded``."""
    t = scale * stored
    if bounded:
        t = min(max(t, lo), hi)
    return t


@numba.njit(cache=True, inline="always")
def trail_power(t, tau_exp, lo, lo_pow):
    """``t ** tau_exp`` for a trail value ``t`` already within its bounds (``lo_pow`` is ``lo ** tau_exp``).

    Trails resting on the floor ``lo`` share one power; an exponent of 1
    takes none.
    """
    if tau_exp == 1.0:
        return t
    if t <= lo:
        return lo_pow
    return t**tau_exp


@numba.njit(cache=True, inline="always")
def heaviest(cand_w, first, nc):
    """Index of the first of the heaviest among ``cand_w[first:first + nc]`` (weights > 0): eq. 14's greedy pick."""
    best = -1.0
    pick = first + nc - 1
    for i in range(first, first + nc):
        if cand_w[i] > best:
            best = cand_w[i]
            pick = i
    return pick


@numba.njit(cache=True, inline="always")
def roulette(cand_w, first, nc, total_w):
    """Index drawn among ``cand_w[first:first + nc]`` (summing to ``total_w``) with probability proportional to
    its weight; one draw from numba's generator.

    The last candidate when rounding leaves the draw past every running sum.
    """
    r = np.random.random() * total_w
    acc = 0.0
    for i in range(first, first + nc):
        acc += cand_w[i]
        if r < acc:
            return i
    return first + nc - 1


@numba.njit(cache=True, inline="always")
def choose(cand_w, nc, total_w, q0):
    """Index of the candidate an ant takes among ``cand_w[:nc]`` (weights summing to ``total_w``), eq. 14's rule.

    With probability ``q0`` the first of the heaviest (:func:`heaviest`);
    otherwise a :func:`roulette` draw. One or two draws from numba's
    generator, in the same order in every walk.
    """
    if q0 > 0.0 and np.random.random() < q0:
        return heaviest(cand_w, 0, nc)
    return roulette(cand_w, 0, nc, total_w)


@numba.njit(cache=True, inline="always")
def heuristic_candidates(r0, r1, node, weight_mul, weight_add, move, turn, pv, stamp, wid, cand, cand_w, first):
    """The candidates of an ant whose every open move weighed 0 by its trail: weighed by the heuristic alone.

    Entries ``r0`` to ``r1 - 1`` of a list of moves (target ``node``, weights
    ``weight_mul`` and ``weight_add``, which may be empty, and ``move`` id);
    a move into a node stamped ``wid`` is closed, and with a turn table (rows
    > 0) it weighs ``turn[pv, move] * (weight_mul + weight_add)``. The entries
    of weight > 0 go to ``cand[first:]`` and their weights to ``cand_w[first:]``
    in list order; returns their count and the sum of their weights.
    """
    use_turn = turn.shape[0] > 0
    has_add = weight_add.size > 0
    nc = 0
    total_w = 0.0
    for r in range(r0, r1):
        if stamp[node[r]] == wid:
            continue
        f = turn[pv, move[r]] if use_turn else 1.0
        w = f * (weight_mul[r] + (weight_add[r] if has_add else 0.0))
        if w > 0.0:
            cand[first + nc] = r
            cand_w[first + nc] = w
            total_w += w
            nc += 1
    return nc, total_w


@numba.njit(cache=True, inline="always")
def local_update(x, k, scale, lo, hi, keep, add):
    """ACS's local update of trail entry ``k`` just crossed, ``τ <- keep τ + add``, read and written within
    ``[lo, hi]`` (``x`` holds the trail over ``scale``)."""
    t = keep * min(max(scale * x[k], lo), hi) + add
    x[k] = min(max(t, lo), hi) / scale


@numba.njit(cache=True, inline="always")
def kept_candidates(cand, cand_w, first, count, node, stamp, wid):
    """The candidates an ant listed on its first visit of a node it has stepped back to, less the moves into
    nodes it has stamped (``wid``) since.

    ``cand[first:first + count]`` (moves whose target is ``node[move]``) and
    their weights are compacted in place, in their order, which is what
    listing the node's moves again would give while the trail stays as it
    was. Returns their count, the sum of their weights (in list order) and
    the index of the first of the heaviest (``first`` when none is left).
    """
    nc = 0
    total_w = 0.0
    best_w = -1.0
    best = first
    for i in range(first, first + count):
        if stamp[node[cand[i]]] == wid:
            continue
        w = cand_w[i]
        cand[first + nc] = cand[i]
        cand_w[first + nc] = w
        total_w += w
        if w > best_w:
            best_w = w
            best = first + nc
        nc += 1
    return nc, total_w, best
