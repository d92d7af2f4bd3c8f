"""The walks of a colony whose ants mark the trail as they go (a local update), compiled on their own.

ACS and IACA send their ants one after another, and each ant changes the
trail of every entry it crosses (``τ <- keep τ + add``), so the next ant, and
the same ant later in its walk, weigh edges by the trail as it is at that
step: the weights cannot be computed once per colony as in
:mod:`~pathzoo_aco.engine.walk_weighted`. :func:`local_colony` walks such a
colony with exactly the semantics of the generic kernel
(:func:`pathzoo_aco.engine.walk._colony`) on that path: the same candidates
in the same order, the same weights, sums and random draws, the same local
updates, dead ends, budgets and counters. It leaves out racing ants and
pre-choice additions, which that path never needs, and it saves work in two
ways that change no value:

- **powers kept per entry**: with a trail exponent other than 1, the power
  ``τ ** tau_exp`` of an entry is computed once and kept (``powers``, valid
  where ``power_stamp`` holds this colony's number) until the entry is
  written by a local update. A node trail (IACA) is read by every edge into
  the node, so an ant's step needed up to eight calls of ``pow`` and now
  needs about one. The kept value is the same double: the power of the same
  bounded trail value, times the same factor.
- **fetching ahead**: once an ant knows its candidate edges, and before it
  draws, it asks the cache for the edge lists, trail entries and factors of
  every node it may step to next (as the weighted kernel does).
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import ABORTED, DONE, EXHAUSTED, NEED_SPACE, REACHED, RUNNING, STEP_CAP, STUCK
from pathzoo_aco.engine.prefetch import prefetch
from pathzoo_aco.engine.walk_weighted import choose

__all__ = ["local_colony", "FETCH_AHEAD_FROM"]

FETCH_AHEAD_FROM = 1 << 17
"""Listed edges above which the kernel fetches ahead; smaller lists stay in the core's caches, where it only costs."""


@numba.njit(cache=True)
def local_colony(indices, adj_ptr, adj_node, adj_edge, adj_offset, w_mul, w_add, horizontal, turn,
                 x, scale, lo, hi, on_nodes, tau_exp, q0, local_keep, local_add, powers, power_stamp, colony,
                 start, goal, backtrack, max_steps, allowance, walk_base,
                 stamp, stack_e, stack_prev, cand_w, depth, steps, flags, counters, flat, offsets):
    """Move the colony's ants one after another; return ``DONE`` or ``NEED_SPACE`` (grow ``flat``, call again).

    The arguments are those of the generic kernel on its sequential path
    without pre-choice additions (``indices``, ``adj_ptr`` and ``adj_node``
    as :func:`~pathzoo_aco.engine.walk_weighted.unsigned_lists` gives them),
    with ``stamp``, ``stack_e`` and ``stack_prev`` the one row the ants share
    (the stacks have room for the longest simple walk, so they never grow).
    ``powers`` and ``power_stamp`` have one entry per trail entry; an entry
    whose stamp equals ``colony`` (a number no earlier call used with these
    arrays) holds the power of its trail value. ``counters`` holds (next
    ant, ants started, steps taken, a finished walk waiting for room in
    ``flat``), so a call resumes where the previous one stopped.
    """
    n_ants = flags.size
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1
    has_add = w_add.size > 0
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
                if on_nodes:
                    k = np.int64(j)
                elif adj_edge is None:
                    k = np.int64(q)
                else:
                    k = np.int64(adj_edge[q])
                n_open += 1
                if keep_powers:  # the generic kernel's ``_trail_weight``, its power kept per entry
                    if power_stamp[k] != colony:
                        t = scale * x[k]
                        if bounded:
                            t = min(max(t, lo), hi)
                        powers[k] = lo_pow if t <= lo else t**tau_exp
                        power_stamp[k] = colony
                    w = powers[k] * w_mul[q]
                else:
                    t = scale * x[k]
                    if bounded:
                        t = min(max(t, lo), hi)
                    w = t * w_mul[q]
                if has_add:
                    w += w_add[q]
                if use_turn:
                    w *= f
                if w > 0.0:
                    heavier = w > best_w  # the first of the heaviest, kept without a branch for the q0 rule
                    best_w = w if heavier else best_w
                    best_i = nc if heavier else best_i
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
                for i in range(nc):
                    if cand_w[i] > best_w:
                        best_w = cand_w[i]
                        best_i = i
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
                for i in range(nc if fetch_ahead else 0):  # the next node is one of these: fetch its list now
                    ahead = adj_ptr[adj_node[cand_q[i]]]
                    prefetch(adj_node, ahead)
                    prefetch(w_mul, ahead)
                    if not on_nodes and adj_edge is None:  # the edge trail in list order
                        prefetch(x, ahead)
                        prefetch(x, ahead + 7)  # its first eight entries span one or two lines
                if q0 > 0.0 and np.random.random() < q0:  # :func:`choose`'s draws, its heaviest found in the scan
                    pick = cand_q[best_i]
                else:
                    pick = cand_q[choose(cand_w, nc, total_w, 0.0)]
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
                if do_local:
                    k = np.int64(c) if on_nodes else np.int64(sel)
                    t = local_keep * min(max(scale * x[k], lo), hi) + local_add
                    x[k] = min(max(t, lo), hi) / scale
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
