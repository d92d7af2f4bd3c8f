"""The walks of a colony whose ants go one after another: one body, compiled once per kind of trail.

Most colonies send their ants one after another, and this module walks them
with exactly the semantics of the generic kernel
(:func:`pathzoo_aco.engine.walk_generic.generic_colony`) on that path: the same candidates
in the same order, the same weights, sums and random draws, the same dead
ends, budgets and counters. It leaves out what that path never needs (racing
ants, pre-choice additions). The body is written once
(:func:`sequential_colony`) and compiled as two kernels:

- :func:`weighted_colony`, the common case: no ant changes the trail while
  the colony walks (AS, MMAS, G-Ant; IACA with ``decr = 0``), so every
  edge's weight is computed once before the colony (:meth:`WalkEngine.colony_weights
  <pathzoo_aco.engine.walk.WalkEngine.colony_weights>`) and a step reads one
  array per edge.
- :func:`local_colony`: each ant changes the trail of every entry it crosses
  (``τ <- keep τ + add``: ACS, IACA), so the next ant, and the same ant later
  in its walk, weigh edges by the trail as it is at that step. With a trail
  exponent other than 1, the power ``τ ** tau_exp`` of an entry is computed
  once and kept (``powers``, valid where ``power_stamp`` holds this colony's
  number) until a local update writes the entry: a node trail (IACA) is read
  by every edge into the node, so a step needs about one call of ``pow``
  instead of up to eight. The kept value is the same double.

Which kernel a body becomes is a constant of the closure, so numba drops the
other kernel's branches before it compiles: each kernel is the loop written
out for its case, with nothing called per step (a step shared through
compiled helpers costs a call or reference counts per step).

Both fetch ahead: once an ant knows its candidate edges, and before it
draws, it asks the cache for the edge lists (and weights, or trail entries
and factors) of every node it may step to next. On a large map those lists
are mostly outside the core's own caches, and a step would wait for them.
"""

from __future__ import annotations

from typing import Callable

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import (ABORTED, DONE, EXHAUSTED, NEED_SPACE, REACHED, RUNNING, STUCK,
                                         stop_before_step)
from pathzoo_aco.engine.prefetch import prefetch
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.steps import (choose, heaviest, heuristic_candidates, local_update, read_trail, roulette,
                                      trail_power)

__all__ = ["sequential_colony", "weighted_colony", "local_colony", "unsigned_lists", "Adjacency",
           "FETCH_AHEAD_FROM"]

Adjacency = tuple[np.ndarray, np.ndarray, "np.ndarray | None", np.ndarray, np.ndarray, np.ndarray]
"""``(adj_ptr, adj_node, adj_edge, adj_offset, weight_mul, weight_add)`` of
:meth:`WalkEngine.adjacency <pathzoo_aco.engine.walk.WalkEngine.adjacency>`; ``adj_edge`` is None when the
lists are the whole graph."""

FETCH_AHEAD_FROM = 1 << 17
"""Listed edges above which :func:`local_colony` fetches ahead; smaller lists stay in the core's caches, where it
only costs."""


def unsigned_lists(problem: ColonyProblem, indices: np.ndarray, adjacency: Adjacency) -> tuple[np.ndarray | None, ...]:
    """``indices`` and ``adjacency`` (:meth:`WalkEngine.adjacency <pathzoo_aco.engine.walk.WalkEngine.adjacency>`)
    as the kernels of this module read them: node ids (int32 arrays) viewed as uint32, and the list pointers as
    uint32 (:attr:`ColonyProblem.indptr32`) when the lists are the graph's own. An unsigned index needs no
    fix-up for negative values at every read, and 32-bit pointers take half the cache lines of 64-bit ones.
    """
    adj_ptr, adj_node = adjacency[:2]
    if adj_ptr is problem.graph.indptr and problem.indptr32.dtype == np.int32:
        adj_ptr = problem.indptr32.view(np.uint32)
    return (indices.view(np.uint32), adj_ptr, adj_node.view(np.uint32), *adjacency[2:])


def sequential_colony(local: bool) -> Callable[..., int]:
    """The kernel that moves a colony's ants one after another: :func:`local_colony` if ``local``, else
    :func:`weighted_colony`.

    The kernel returns ``DONE`` or ``NEED_SPACE`` (grow ``flat``, call
    again). Its arguments are those of the generic kernel on its sequential
    path without pre-choice additions (``indices``, ``adj_ptr`` and
    ``adj_node`` as :func:`unsigned_lists` gives them), with ``stamp``,
    ``stack_e`` and ``stack_prev`` the one row the ants share (the stacks
    have room for the longest simple walk, so they never grow). ``weights``
    holds each list position's weight before the turn factor (None for
    :func:`local_colony`, which reads the trail ``x`` instead and ignores
    ``weights``; :func:`weighted_colony` ignores the trail and local-update
    arguments). ``powers`` and ``power_stamp`` have one entry per trail
    entry; an entry whose stamp equals ``colony`` (a number no earlier call
    used with these arrays) holds the power of its trail value. ``counters``
    holds (next ant, ants started, steps taken, a finished walk waiting for
    room in ``flat``), so a call resumes where the previous one stopped.
    """

    def kernel(indices, adj_ptr, adj_node, adj_edge, adj_offset, w_mul, w_add, weights, horizontal, turn,
               x, scale, lo, hi, on_nodes, tau_exp, q0, local_keep, local_add, powers, power_stamp, colony,
               start, goal, backtrack, max_steps, allowance, walk_base,
               stamp, stack_e, stack_prev, cand_w, depth, steps, flags, counters, flat, offsets):
        n_ants = flags.size
        use_turn = turn.shape[0] > 0
        no_prev = turn.shape[0] - 1
        has_add = w_add.size > 0
        if local:
            do_local = local_keep != 1.0 or local_add != 0.0
            bounded = lo > 0.0 or hi < np.inf
            keep_powers = tau_exp != 1.0
            lo_pow = lo**tau_exp
            fetch_ahead = adj_node.size > FETCH_AHEAD_FROM
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
                flag = stop_before_step(c, goal, n, max_steps, total, allowance)
                if flag != RUNNING:
                    break
                # ------------------------------------------------------ one step
                e0 = adj_ptr[c]
                e1 = adj_ptr[c + 1]
                nc = 0
                n_open = 0  # allowed neighbours, whatever their weight
                total_w = 0.0
                best_w = -1.0
                best_i = 0
                for q in range(e0, e1):
                    j = adj_node[q]
                    if stamp[j] == wid:  # most neighbours on a long walk: test before touching the trail
                        continue
                    f = 1.0
                    if use_turn:
                        f = turn[pv, adj_offset[q]]
                        if f <= 0.0:
                            continue
                    n_open += 1
                    if not local:
                        w = weights[q] * f if use_turn else weights[q]
                    else:
                        if on_nodes:
                            k = np.int64(j)
                        elif adj_edge is None:
                            k = np.int64(q)
                        else:
                            k = np.int64(adj_edge[q])
                        if keep_powers:  # the trail's power, kept per entry
                            if power_stamp[k] != colony:
                                powers[k] = trail_power(read_trail(scale, x[k], lo, hi, bounded), tau_exp, lo, lo_pow)
                                power_stamp[k] = colony
                            w = powers[k] * w_mul[q]
                        else:
                            w = read_trail(scale, x[k], lo, hi, bounded) * w_mul[q]
                        if has_add:
                            w += w_add[q]
                        if use_turn:
                            w *= f
                    if w > 0.0:
                        if local:
                            heavier = w > best_w  # the first of the heaviest, kept without a branch for the q0 rule
                            best_w = w if heavier else best_w
                            best_i = nc if heavier else best_i
                        cand_q[nc] = q
                        cand_w[nc] = w
                        total_w += w
                        nc += 1
                if nc == 0 and n_open > 0:  # maybe every trail is 0: weigh the allowed edges by the heuristic alone
                    nc, total_w = heuristic_candidates(e0, e1, adj_node, w_mul, w_add, adj_offset, turn, pv, stamp,
                                                       wid, cand_q, cand_w, 0)
                    if local:
                        best_i = heaviest(cand_w, 0, nc)
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
                    if not local:
                        for i in range(nc):  # the next node is one of these: fetch its list while the choice is made
                            ahead = adj_ptr[adj_node[cand_q[i]]]
                            prefetch(weights, ahead)
                            prefetch(weights, ahead + 7)  # its first eight weights span one or two lines
                            prefetch(adj_node, ahead)
                        pick = cand_q[choose(cand_w, nc, total_w, q0)]
                    else:
                        for i in range(nc if fetch_ahead else 0):
                            ahead = adj_ptr[adj_node[cand_q[i]]]
                            prefetch(adj_node, ahead)
                            prefetch(w_mul, ahead)
                            if not on_nodes and adj_edge is None:  # the edge trail in list order
                                prefetch(x, ahead)
                                prefetch(x, ahead + 7)  # its first eight entries span one or two lines
                        if q0 > 0.0 and np.random.random() < q0:  # ``choose``'s draws, its heaviest found above
                            pick = cand_q[best_i]
                        else:
                            pick = cand_q[roulette(cand_w, 0, nc, total_w)]
                    c = adj_node[pick]
                    stamp[c] = wid
                    sel = pick if adj_edge is None else adj_edge[pick]
                    stack_e[d] = sel
                    if use_turn:
                        o = adj_offset[pick]
                        if horizontal[o]:
                            pv = o
                        stack_prev[d] = pv
                    d += 1
                    if local and do_local:
                        k = np.int64(c) if on_nodes else np.int64(sel)
                        local_update(x, k, scale, lo, hi, local_keep, local_add)
                        if keep_powers:
                            power_stamp[k] = 0  # its power is computed again when next read
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

    kernel.__qualname__ = kernel.__name__ = "local_colony" if local else "weighted_colony"  # names its cache files
    what = "ants mark the trail as they go" if local else "weights stay fixed while it walks"
    kernel.__doc__ = f"The kernel of :func:`sequential_colony` for a colony whose {what}."
    return numba.njit(cache=True)(kernel)

weighted_colony = sequential_colony(False)
local_colony = sequential_colony(True)
