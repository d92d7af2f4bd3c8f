"""The steps every kernel of ants walking one after another shares: when a walk stops, dead ends, the outcome.

:func:`~pathzoo_aco.engine.walk_weighted.weighted_colony` and
:func:`~pathzoo_aco.engine.walk_local.local_colony` differ in how an ant
weighs its candidate edges; everything around that is here, written once
with the generic kernel's semantics (:func:`pathzoo_aco.engine.walk._colony`)
and inlined into both (numba's ``inline="always"``, so a kernel pays no call).
Node ids are the unsigned 32-bit values of
:func:`~pathzoo_aco.engine.walk_weighted.unsigned_lists`.
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import ABORTED, EXHAUSTED, NEED_SPACE, REACHED, RUNNING, STEP_CAP, STUCK

__all__ = ["resume", "start_walk", "stop_before_step", "heuristic_candidates", "take_edge", "step_back",
           "record_walk", "NEXT_ANT", "STOP_COLONY"]

NEXT_ANT = -1
"""What :func:`record_walk` returns when the next ant may start."""
STOP_COLONY = -2
"""What :func:`record_walk` returns when no further ant starts (the walk aborted, or proved the goal unreachable)."""


@numba.njit(cache=True, inline="always")
def resume(counters, offsets, depth, stack_e, flat):
    """The ant a kernel call starts with; the walk that waited for room in ``flat`` is copied there first."""
    a = counters[0]
    if counters[3] > 0:
        base = offsets[a]
        for p in range(depth[a]):
            flat[base + p] = stack_e[p]
        offsets[a + 1] = base + depth[a]
        counters[3] = 0
        a += 1
    return a


@numba.njit(cache=True, inline="always")
def start_walk(a, walk_base, start, stamp, flags, counters):
    """Start ant ``a`` at the start node, stamped with its walk id; returns the id."""
    wid = walk_base + a
    flags[a] = RUNNING
    counters[1] += 1
    stamp[start] = wid
    return wid


@numba.njit(cache=True, inline="always")
def stop_before_step(c, goal, n, max_steps, total, allowance):
    """The outcome of a walk at node ``c`` after ``n`` of its steps and ``total`` of the call's, or ``RUNNING``."""
    if c == goal:
        return REACHED
    if n >= max_steps:
        return STEP_CAP
    if total >= allowance:
        return ABORTED
    return RUNNING


@numba.njit(cache=True, inline="always")
def heuristic_candidates(e0, e1, adj_node, adj_offset, w_mul, w_add, turn, pv, stamp, wid, cand_q, cand_w):
    """Candidates weighed by the heuristic alone (list positions ``e0:e1``): the count and the total weight.

    For a step whose allowed edges all weighed 0 (every trail 0), with the
    generic kernel's expression ``turn · (weight_mul + weight_add)``.
    """
    use_turn = turn.shape[0] > 0
    has_add = w_add.size > 0
    nc = 0
    total_w = 0.0
    for q in range(e0, e1):
        if stamp[adj_node[q]] == wid:
            continue
        f = turn[pv, adj_offset[q]] if use_turn else 1.0
        w = f * (w_mul[q] + (w_add[q] if has_add else 0.0))
        if w > 0.0:
            cand_q[nc] = q
            cand_w[nc] = w
            total_w += w
            nc += 1
    return nc, total_w


@numba.njit(cache=True, inline="always")
def take_edge(pick, d, pv, adj_node, adj_edge, adj_offset, horizontal, use_turn, stamp, wid, stack_e, stack_prev):
    """Cross the listed edge at position ``pick``: ``(node, graph edge, depth, heading)`` after the step.

    The node entered is stamped, the edge pushed on the walk, and with a turn
    rule the heading (the last horizontal move) pushed beside it.
    """
    c = adj_node[pick]
    stamp[c] = wid
    sel = pick if adj_edge is None else adj_edge[pick]
    stack_e[d] = sel
    if use_turn:
        o = adj_offset[pick]
        if horizontal[o]:
            pv = o
        stack_prev[d] = pv
    return c, sel, d + 1, pv


@numba.njit(cache=True, inline="always")
def step_back(backtrack, d, pv, indices, stack_e, stack_prev, start, no_prev, use_turn):
    """At a dead end: ``(RUNNING, node, depth, heading)`` one step back along the walk, or the walk's outcome.

    Without backtracking the ant is ``STUCK``; one that backs up to an empty
    walk has ``EXHAUSTED`` its component (the node returned is then the start).
    """
    if not backtrack:
        return STUCK, np.uint32(start), d, pv
    if d == 0:
        return EXHAUSTED, np.uint32(start), d, pv
    d -= 1
    c = indices[stack_e[d - 1]] if d > 0 else np.uint32(start)
    if use_turn:
        pv = stack_prev[d - 1] if d > 0 else no_prev
    return RUNNING, c, d, pv


@numba.njit(cache=True, inline="always")
def record_walk(a, flag, d, n, total, use_turn, stack_e, depth, steps, flags, counters, flat, offsets):
    """Store ant ``a``'s walk and outcome; :data:`NEXT_ANT`, :data:`STOP_COLONY` or ``NEED_SPACE``.

    A walk that reached the goal is copied into ``flat``; when it has no
    room there the kernel returns ``NEED_SPACE`` and copies it on the next
    call (:func:`resume`). After an aborted walk, or one that proved the goal
    unreachable, the ants after it never start.
    """
    n_ants = flags.size
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
    if flag == ABORTED or (flag == EXHAUSTED and not use_turn):
        for b in range(a + 1, n_ants):
            flags[b] = ABORTED
            offsets[b + 1] = offsets[a + 1]
        return STOP_COLONY
    return NEXT_ANT
