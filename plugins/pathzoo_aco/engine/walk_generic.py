"""The generic walk kernel: every colony the specialised kernels do not take, racing ants and pre-choice gains.

Each ant keeps a tabu list (a per-walk stamp on every node it has entered), so
its walk is a simple path and never needs loop removal. At a dead end (no
allowed neighbour) it either steps back along its walk, the dead end staying
tabu, or is dropped (:attr:`WalkRules.backtrack <pathzoo_aco.engine.rules.WalkRules.backtrack>`).
A walk that backtracks to the start with nothing left has searched the start's whole component: without
a turn rule that proves the goal unreachable.

Ants walk one after another (each to the goal or until it stops), or, when
:attr:`WalkRules.race <pathzoo_aco.engine.rules.WalkRules.race>` is set, in lock step (one step each per
round) until the first of them reaches the goal; the others are then marked :data:`OUTRUN`. The step rules
(trail weight, heuristic fallback, draw) are those of :mod:`pathzoo_aco.engine.steps`, inlined.
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import (ABORTED, DONE, EXHAUSTED, FRESH, NEED_SPACE, OUTRUN, REACHED, RUNNING,
                                         STUCK, stop_before_step)
from pathzoo_aco.engine.steps import choose, heuristic_candidates, local_update, read_trail, trail_power

__all__ = ["generic_colony", "fill_weights"]


@numba.njit(cache=True, inline="always")
def _add_candidate(q, w, cand_q, cand_w, nc, total_w):
    """Append list position ``q`` of weight ``w`` to the candidates if ``w > 0``; return the new count and total."""
    if w > 0.0:
        cand_q[nc] = q
        cand_w[nc] = w
        return nc + 1, total_w + w
    return nc, total_w


@numba.njit(cache=True)
def generic_colony(indices, offset_id, adj_ptr, adj_node, adj_edge, adj_offset, w_mul, w_add, weights, horizontal,
                   turn, x, scale, lo, hi, on_nodes,
                   tau_exp, q0, local_keep, local_add, pre_add,
                   start, goal, backtrack, max_steps, allowance, race, walk_base,
                   stamps, stacks, prevs, cand_q, cand_w,
                   cur, depth, prev, steps, flags, counters, flat, offsets):
    """Move the colony's ants; return ``DONE`` or ``NEED_SPACE`` (grow ``stacks`` or ``flat``, call again).

    One after another (``race`` False: an ant walks until it stops, then the
    next starts; one stamp row and one stack row serve them all), or in lock
    step (``race`` True: one step per ant per round, a stamp and stack row
    per ant, until the first reaches the goal; every ant stamps its own row
    with ``walk_base``, which may then be a byte). All state lives in the
    arrays; ``counters`` holds (next ant, ants started, steps taken, a
    finished walk waiting for room in ``flat``), so a call resumes where the
    previous one stopped.

    ``indices`` and ``offset_id`` are the graph's per-edge target node and
    move; ``adj_ptr``/``adj_node`` list, per node, the edges an ant may ever
    take and their targets (CSR), ``adj_offset``, ``w_mul``, ``w_add`` their
    moves and weights in the same order (:meth:`WalkEngine.adjacency
    <pathzoo_aco.engine.walk.WalkEngine.adjacency>`); the candidates are kept as list positions in ``cand_q``.
    Position ``q`` of that list is graph edge ``adj_edge[q]`` (edges of
    weight 0 left out), or edge ``q`` when ``adj_edge`` is None (numba then
    compiles the kernel without the lookup). ``weights``, when not None,
    holds each position's weight before the turn factor, filled by
    :func:`fill_weights` for a trail that no ant changes while it walks.
    """
    n_ants = flags.size
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1
    has_add = w_add.size > 0
    has_pre = pre_add.size > 0
    do_local = local_keep != 1.0 or local_add != 0.0
    bounded = lo > 0.0 or hi < np.inf
    lo_pow = lo**tau_exp
    a = counters[0]
    total = counters[2]
    if counters[3] > 0:  # copy the walk that waited for room in ``flat``
        base = offsets[a]
        for p in range(depth[a]):
            flat[base + p] = stacks[0, p]
        offsets[a + 1] = base + depth[a]
        counters[3] = 0
        a += 1
    while True:
        if a >= n_ants:
            if not race:
                break
            a = 0
            running = False
            for b in range(n_ants):
                running = running or flags[b] == RUNNING
            if not running:
                break
        if flags[a] >= 0:  # a race walk that has stopped
            a += 1
            continue
        row = a if race else 0
        stamp = stamps[row]
        stack_e = stacks[row]
        stack_prev = prevs[row]
        wid = walk_base if race else walk_base + a  # racing ants have a stamp row each
        if flags[a] == FRESH:
            flags[a] = RUNNING
            counters[1] += 1
            cur[a] = start
            depth[a] = 0
            prev[a] = no_prev
            steps[a] = 0
            stamp[start] = wid
        c = cur[a]
        d = depth[a]
        pv = prev[a]
        n = steps[a]
        flag = RUNNING
        full = False  # stopped before a step for want of room on the stack (not after a race step that filled it)
        while True:
            flag = stop_before_step(c, goal, n, max_steps, total, allowance)
            if flag != RUNNING:
                break
            if d >= stack_e.size:
                full = True
                break  # no room on the stack: the caller grows it
            # ---------------------------------------------------------- one step
            e0 = adj_ptr[c]
            e1 = adj_ptr[c + 1]
            nc = 0
            n_open = 0  # allowed neighbours, whatever their weight
            total_w = 0.0
            for q in range(e0, e1):
                if adj_edge is None:  # pruned at compile time: one specialisation per case
                    e = q
                else:
                    e = adj_edge[q]
                j = adj_node[q]
                if weights is not None:  # the colony's weights, computed before it started
                    if stamp[j] == wid:
                        continue
                    f = 1.0
                    if use_turn:
                        f = turn[pv, adj_offset[q]]
                        if f <= 0.0:
                            continue
                    n_open += 1
                    nc, total_w = _add_candidate(q, weights[q] * f if use_turn else weights[q], cand_q, cand_w, nc,
                                                 total_w)
                    continue
                k = j if on_nodes else e
                if has_pre:  # added to every edge leaving the cell, tabu or not, before the choice
                    t = min(max(min(max(scale * x[k], lo), hi) + pre_add[q], lo), hi)
                    x[k] = t / scale
                    if stamp[j] == wid:
                        continue
                elif stamp[j] == wid:  # most neighbours on a long walk: test before touching the trail
                    continue
                f = 1.0
                if use_turn:  # the turn table is small: test it before reading the trail too
                    f = turn[pv, adj_offset[q]]
                    if f <= 0.0:
                        continue
                if not has_pre:
                    t = read_trail(scale, x[k], lo, hi, bounded)
                n_open += 1
                w = trail_power(t, tau_exp, lo, lo_pow) * w_mul[q]
                if has_add:
                    w += w_add[q]
                if use_turn:
                    w *= f
                nc, total_w = _add_candidate(q, w, cand_q, cand_w, nc, total_w)
            if nc == 0 and n_open > 0:  # maybe every trail is 0: weigh the allowed edges by the heuristic alone
                nc, total_w = heuristic_candidates(e0, e1, adj_node, w_mul, w_add, adj_offset, turn, pv, stamp, wid,
                                                   cand_q, cand_w, 0)
            if nc == 0:  # dead end
                if not backtrack:
                    flag = STUCK
                    break
                if d == 0:
                    flag = EXHAUSTED
                    break
                d -= 1
                c = indices[stack_e[d - 1]] if d > 0 else start
                if use_turn:
                    pv = stack_prev[d - 1] if d > 0 else no_prev
            else:
                pick = cand_q[choose(cand_w, nc, total_w, q0)]
                if adj_edge is None:
                    sel = pick
                else:
                    sel = adj_edge[pick]
                c = indices[sel]
                stamp[c] = wid
                stack_e[d] = sel
                if use_turn:
                    o = offset_id[sel]
                    if horizontal[o]:
                        pv = o
                    stack_prev[d] = pv
                d += 1
                if do_local:
                    k = c if on_nodes else sel
                    local_update(x, k, scale, lo, hi, local_keep, local_add)
            n += 1
            total += 1
            if race:
                if c == goal:
                    flag = REACHED
                break
        cur[a] = c
        depth[a] = d
        prev[a] = pv
        steps[a] = n
        counters[2] = total
        if full:  # resume with this ant, which has not stepped yet (a racing ant's step waits until then)
            counters[0] = a
            return NEED_SPACE
        if flag == RUNNING:  # a race ant that took its step
            a += 1
            continue
        flags[a] = flag
        stop = flag == ABORTED or (flag == EXHAUSTED and not use_turn) or (race and flag == REACHED)
        if not race:
            if flag == REACHED:
                if offsets[a] + d > flat.size:
                    counters[0] = a
                    counters[3] = 1
                    return NEED_SPACE
                for p in range(d):
                    flat[offsets[a] + p] = stack_e[p]
            offsets[a + 1] = offsets[a] + (d if flag == REACHED else 0)
        if stop:
            for b in range(n_ants):  # the others: never started, stopped, or outrun in a race
                if flags[b] == FRESH or (flags[b] == RUNNING and flag != REACHED):
                    flags[b] = ABORTED
                elif flags[b] == RUNNING:
                    flags[b] = OUTRUN
                if not race and b > a:
                    offsets[b + 1] = offsets[a + 1]
            break
        a += 1
    counters[0] = a
    return DONE


@numba.njit(cache=True)
def fill_weights(out, adj_node, adj_edge, w_mul, w_add, x, scale, lo, hi, on_nodes, tau_exp):
    """Each listed edge's weight ``τ ** tau_exp * w_mul (+ w_add)`` into ``out``, as :func:`generic_colony` has it.

    The same operations in the same order, so the doubles are identical; the
    walks of a colony whose trail does not change while it walks (no
    ``pre_add``, no local update) then read one array per edge instead of the
    trail, both factors and a power.
    """
    has_add = w_add.size > 0
    bounded = lo > 0.0 or hi < np.inf
    lo_pow = lo**tau_exp
    for q in range(out.size):
        if adj_edge is None:
            e = q
        else:
            e = adj_edge[q]
        k = adj_node[q] if on_nodes else e
        w = trail_power(read_trail(scale, x[k], lo, hi, bounded), tau_exp, lo, lo_pow) * w_mul[q]
        if has_add:
            w += w_add[q]
        out[q] = w
