"""The walks of a colony whose edge weights stay fixed while it walks: the common case, compiled on its own.

AS, MMAS and G-Ant (and IACA with ``decr = 0``) send their ants one after
another, and no ant changes the trail while the colony walks, so every edge's
weight is computed once before the colony (:meth:`WalkEngine.colony_weights
<pathzoo_aco.engine.walk.WalkEngine.colony_weights>`). :func:`weighted_colony`
walks such a colony with exactly the semantics of the generic kernel
(:func:`pathzoo_aco.engine.walk._colony`) on that path: the same candidates in
the same order, the same sums, the same random draws, dead ends, budgets and
counters. It leaves out what that path never needs (racing ants, trail reads,
local and pre-choice updates), and it fetches ahead: once an ant knows its
candidate edges, and before it draws, it asks the cache for the edge lists and
weights of every node it may step to next. On a large map those lists are
mostly outside the core's own caches, and the generic kernel waited for them
at the start of each step.
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import ABORTED, DONE, EXHAUSTED, NEED_SPACE, REACHED, RUNNING, STEP_CAP, STUCK
from pathzoo_aco.engine.prefetch import prefetch
from pathzoo_aco.engine.problem import ColonyProblem

__all__ = ["weighted_colony", "unsigned_lists", "choose", "Adjacency"]

Adjacency = tuple[np.ndarray, np.ndarray, "np.ndarray | None", np.ndarray, np.ndarray, np.ndarray]
"""``(adj_ptr, adj_node, adj_edge, adj_offset, weight_mul, weight_add)`` of
:meth:`WalkEngine.adjacency <pathzoo_aco.engine.walk.WalkEngine.adjacency>`; ``adj_edge`` is None when the
lists are the whole graph."""


@numba.njit(cache=True, inline="always")
def choose(cand_w, nc, total_w, q0):
    """Index of the candidate an ant takes among ``cand_w[:nc]`` (weights summing to ``total_w``), eq. 14's rule.

    With probability ``q0`` the first of the heaviest; otherwise a roulette
    draw, falling back to the last candidate should rounding leave the draw
    past every running sum. One or two draws from numba's generator, in the
    same order in every kernel that calls this.
    """
    if q0 > 0.0 and np.random.random() < q0:
        best = -1.0
        pick = nc - 1
        for i in range(nc):
            if cand_w[i] > best:
                best = cand_w[i]
                pick = i
        return pick
    r = np.random.random() * total_w
    acc = 0.0
    for i in range(nc):
        acc += cand_w[i]
        if r < acc:
            return i
    return nc - 1


def unsigned_lists(problem: ColonyProblem, indices: np.ndarray, adjacency: Adjacency) -> tuple[np.ndarray | None, ...]:
    """``indices`` and ``adjacency`` (:meth:`WalkEngine.adjacency <pathzoo_aco.engine.walk.WalkEngine.adjacency>`)
    as :func:`weighted_colony` reads them: node ids (int32 arrays) viewed as uint32, and the list pointers as
    uint32 (:attr:`ColonyProblem.indptr32`) when the lists are the graph's own. An unsigned index needs no
    fix-up for negative values at every read, and 32-bit pointers take half the cache lines of 64-bit ones.
    """
    adj_ptr, adj_node = adjacency[:2]
    if adj_ptr is problem.graph.indptr and problem.indptr32.dtype == np.int32:
        adj_ptr = problem.indptr32.view(np.uint32)
    return (indices.view(np.uint32), adj_ptr, adj_node.view(np.uint32), *adjacency[2:])


@numba.njit(cache=True)
def weighted_colony(indices, adj_ptr, adj_node, adj_edge, adj_offset, w_mul, w_add, weights, horizontal, turn,
                    q0, start, goal, backtrack, max_steps, allowance, walk_base,
                    stamp, stack_e, stack_prev, cand_w, depth, steps, flags, counters, flat, offsets):
    """Move the colony's ants one after another; return ``DONE`` or ``NEED_SPACE`` (grow ``flat``, call again).

    The arguments are those of the generic kernel on its sequential,
    precomputed-weights path (``weights`` holds each list position's weight
    before the turn factor), with ``stamp``, ``stack_e`` and ``stack_prev``
    the one row the ants share (the stacks have room for the longest simple
    walk, so they never grow). ``indices``, ``adj_ptr`` and ``adj_node`` come
    from :func:`unsigned_lists`.
    ``counters`` holds (next ant, ants started, steps taken, a finished walk
    waiting for room in ``flat``), so a call resumes where the previous one
    stopped.
    """
    n_ants = flags.size
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1
    has_add = w_add.size > 0
    cand_q = np.empty(cand_w.size, dtype=adj_ptr.dtype)  # the candidates' list positions, typed as the pointers
    a = counters[0]
    total = counters[2]
    if counters[3] > 0:  # copy the walk that waited for room in ``flat``
        base = offsets[a]
        for p in range(depth[a]):
            flat[base + p] = stack_e[p]
        offsets[a + 1] = base + depth[a]
        counters[3] = 0
        a += 1
    while a < n_ants:
        wid = walk_base + a
        flags[a] = RUNNING
        counters[1] += 1
        stamp[start] = wid
        c = np.uint32(start)  # node ids are uint32, so ``c`` keeps one type
        d = 0
        pv = no_prev
        n = 0
        flag = RUNNING
        while True:
            if c == goal:
                flag = REACHED
                break
            if n >= max_steps:
                flag = STEP_CAP
                break
            if total >= allowance:
                flag = ABORTED
                break
            # ---------------------------------------------------------- one step
            e0 = adj_ptr[c]
            e1 = adj_ptr[c + 1]
            nc = 0
            n_open = 0  # allowed neighbours, whatever their weight
            total_w = 0.0
            for q in range(e0, e1):
                if stamp[adj_node[q]] == wid:
                    continue
                if use_turn:
                    f = turn[pv, adj_offset[q]]
                    if f <= 0.0:
                        continue
                    w = weights[q] * f
                else:
                    w = weights[q]
                n_open += 1
                if w > 0.0:
                    cand_q[nc] = q
                    cand_w[nc] = w
                    total_w += w
                    nc += 1
            if nc == 0 and n_open > 0:  # maybe every trail is 0: weigh the allowed edges by the heuristic alone
                for q in range(e0, e1):
                    if stamp[adj_node[q]] == wid:
                        continue
                    f = turn[pv, adj_offset[q]] if use_turn else 1.0
                    w = f * (w_mul[q] + (w_add[q] if has_add else 0.0))  # the generic kernel's expression
                    if w > 0.0:
                        cand_q[nc] = q
                        cand_w[nc] = w
                        total_w += w
                        nc += 1
            if nc == 0:  # dead end
                if not backtrack:
                    flag = STUCK
                    break
                if d == 0:
                    flag = EXHAUSTED
                    break
                d -= 1
                c = indices[stack_e[d - 1]] if d > 0 else np.uint32(start)
                if use_turn:
                    pv = stack_prev[d - 1] if d > 0 else no_prev
            else:
                for i in range(nc):  # the next node is one of these: fetch its list while the choice is made
                    ahead = adj_ptr[adj_node[cand_q[i]]]
                    prefetch(weights, ahead)
                    prefetch(weights, ahead + 7)  # its first eight weights span one or two lines
                    prefetch(adj_node, ahead)
                pick = cand_q[choose(cand_w, nc, total_w, q0)]
                c = adj_node[pick]
                stamp[c] = wid
                stack_e[d] = pick if adj_edge is None else adj_edge[pick]
                if use_turn:
                    o = adj_offset[pick]
                    if horizontal[o]:
                        pv = o
                    stack_prev[d] = pv
                d += 1
            n += 1
            total += 1
        depth[a] = d
        steps[a] = n
        counters[2] = total
        flags[a] = flag
        if flag == REACHED:
            if offsets[a] + d > flat.size:
                counters[0] = a
                counters[3] = 1
                return NEED_SPACE
            for p in range(d):
                flat[offsets[a] + p] = stack_e[p]
        offsets[a + 1] = offsets[a] + (d if flag == REACHED else 0)
        if flag == ABORTED or (flag == EXHAUSTED and not use_turn):  # the ants after it never start
            for b in range(a + 1, n_ants):
                flags[b] = ABORTED
                offsets[b + 1] = offsets[a + 1]
            break
        a += 1
    counters[0] = a
    return DONE
