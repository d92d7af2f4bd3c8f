"""The ant walk of every colony of the engine: one body, compiled once per kind of colony.

Each ant keeps a tabu list (a per-walk stamp on every node it has entered),
so its walk is a simple path and never needs loop removal. At a dead end (no
allowed neighbour) it either steps back along its walk, the dead end staying
tabu, or is dropped (:attr:`WalkRules.backtrack <pathzoo_aco.engine.rules.WalkRules.backtrack>`). A walk that
backtracks to the start with nothing left has searched the start's whole
component: without a turn rule that proves the goal unreachable. The step
rules (trail weight, heuristic fallback, draw, local update) are those of
:mod:`pathzoo_aco.engine.steps`, inlined.

The body is written once (:func:`colony_kernel`) and compiled as six
kernels, by four constants of its closure:

- :func:`weighted_colony`, the common case: ants go one after another and
  none changes the trail while the colony walks (AS, MMAS, G-Ant; IACA with
  ``decr = 0``), so every edge's weight is computed once before the colony
  (:func:`fill_weights`) and a step reads one array per edge.
- :func:`local_colony`: ants go one after another and each changes the trail
  of every entry it crosses (``τ <- keep τ + add``: ACS, IACA), so the next
  ant, and the same ant later in its walk, weigh edges by the trail as it is
  at that step. With a trail exponent other than 1, the power ``τ **
  tau_exp`` of an entry is computed once and kept (``powers``, valid where
  ``power_stamp`` holds this colony's number) until a local update writes
  the entry: a node trail (IACA) is read by every edge into the node, so a
  step needs about one call of ``pow`` instead of up to eight. The kept
  value is the same double.
- :func:`generic_colony`: GGACO's colonies, whose ants may race in lock step
  (one step each per round, until the first reaches the goal; the others are
  then marked ``OUTRUN``) and add a pre-choice gain to the trail of every
  edge leaving their node before they choose.
- :func:`generic_weighted_colony`: racing ants on weights fixed before the
  colony.
- :func:`timed_colony`: :func:`local_colony` for ants that keep time among
  moving obstacles (:class:`~pathzoo_aco.fgdaco_walk.TimedWalkEngine`):
  at each node an ant measures the obstacles that may matter, the candidate
  scan refuses an edge a moving obstacle would hit while it is driven and
  re-weighs an edge near one by FGDACO's fuzzy priority, a step advances
  the clock, and each depth's candidates are kept for the steps back
  (trail powers are not kept: a timed colony reads too few entries twice).
- :func:`record_colony`: :func:`local_colony` for DSACO's compiled colony
  (:mod:`pathzoo_aco.dsaco_colony`): the list of a node is that of its
  allowed moves under the ant's heading (records built the first time an
  ant needs them, linked to the list their move leads to), a node whose
  trails all read the same weighs its list with one trail power, and each
  depth's candidates are kept while they fit, for the steps back.

Numba drops the branches of the other kinds before it compiles, so each
kernel is the loop written out for its case, with nothing called per step (a
step shared through compiled helpers costs a call or reference counts per
step).

The kernels fetch ahead: once an ant knows its candidate edges, and before
it draws, it asks the cache for the edge lists (and weights, or trail entries
and factors) of every node it may step to next. On a large map those lists
are mostly outside the core's own caches, and a step would wait for them.
A general kernel also fetches the gains of those lists, and the tabu stamps
and list pointers of the node one step further in the same direction
(``2 j - c`` for a step from ``c`` to ``j``, a grid's ids): a racing ant's
next step reads them after every other ant has taken its own, time enough
for them to arrive.
"""

from __future__ import annotations

import math
from typing import Callable

import numba
import numpy as np

from pathzoo_aco.dsaco_tables import build_list
from pathzoo_aco.engine.outcomes import (ABORTED, DONE, EXHAUSTED, FRESH, NEED_SPACE, OUTRUN, REACHED, RUNNING,
                                         STUCK, stop_before_step)
from pathzoo_aco.engine.prefetch import prefetch
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.steps import (choose, heaviest, heuristic_candidates, kept_candidates, local_update,
                                      read_trail, roulette, trail_power)
from pathzoo_aco.fgdaco_fuzzy import clipped_centroid, fired_strengths, rule_ceilings
from pathzoo_aco.fgdaco_moving import UNDER, obstacle_min_distance, obstacle_position

__all__ = ["colony_kernel", "weighted_colony", "local_colony", "generic_colony", "generic_weighted_colony",
           "timed_colony", "record_colony", "KERNELS", "fill_weights", "unsigned_lists", "Adjacency",
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


def colony_kernel(local: bool, general: bool, timed: bool = False, records: bool = False) -> Callable[..., int]:
    """The walk body compiled for one kind of colony (see the module docstring for the six kernels).

    ``local``: ants weigh each edge from the trail ``x`` at the step they
    read it and may mark it as they go; otherwise every edge's weight before
    the turn factor was computed before the colony (``weights``,
    :func:`fill_weights`). ``general``: racing ants and pre-choice additions
    are possible; otherwise ants go one after another and nothing but the
    local update writes the trail. Each flag is a constant of the closure, so
    numba drops the branches of the other kinds before it compiles.
    ``timed`` (with ``local`` and not ``general``): each ant keeps time among
    moving obstacles, as :mod:`pathzoo_aco.fgdaco_walk` describes; the
    kernel's last argument ``own`` is then
    :meth:`TimedWalkEngine.timing <pathzoo_aco.fgdaco_walk.TimedWalkEngine.timing>`,
    the lists are the whole graph
    (``adj_edge`` None), ``cand_w`` has a level of candidate slots per depth,
    and a node whose open edges all weigh 0 is a dead end (no
    heuristic-alone fallback). ``records`` (with ``local`` and not
    ``general``): DSACO's ants, as :mod:`pathzoo_aco.dsaco_colony` describes;
    the lists are then the records of a
    :class:`~pathzoo_aco.dsaco_tables.MoveTable` (``adj_node``, ``adj_edge``
    and ``w_mul`` their target, place and weight fields, ``adj_offset`` their
    moves, ``indices`` the table's targets by place; without a turn table
    the lists are the adjacency read in place, ``adj_edge`` None), the trail
    ``x`` and the walks in ``flat`` are in places (adjacency positions), and
    ``own`` holds ``(node_max, node_even, head, to_next, filled, to_rec,
    move_class, class_row, weight, move, cand, level_first, level_count,
    level_more)`` of the table and its
    :class:`~pathzoo_aco.dsaco_tables.ColonyRun`. The kernel's last argument
    ``own`` is None for the other kernels.

    The kernel returns ``DONE`` or ``NEED_SPACE`` (grow ``flat``, or a
    racing ant's stacks, and call again). ``indices``, ``adj_ptr`` and
    ``adj_node`` are as :func:`unsigned_lists` gives them, the other lists as
    :meth:`WalkEngine.adjacency <pathzoo_aco.engine.walk.WalkEngine.adjacency>` (list position ``q`` is graph
    edge ``adj_edge[q]``, or edge ``q`` when ``adj_edge`` is None: numba then
    compiles the kernel without the lookup). ``weights`` is None for a
    ``local`` kernel. ``pre_add`` (read by a ``general`` kernel) is added to
    the trail of every edge leaving the ant's node, tabu or not, before it
    chooses. ``powers`` and ``power_stamp`` have one entry per trail entry;
    an entry whose stamp equals ``colony`` (a number no earlier call used
    with these arrays) holds the power of its trail value (kept by
    :func:`local_colony` for a trail exponent other than 1).

    Ants walk one after another (``race`` False: row 0 of ``stamps``,
    ``stacks`` and ``prevs`` serves them all, and an ant walks until it
    stops; the stacks have room for the longest simple walk), or, in a
    ``general`` kernel with ``race``, in lock step: one step per ant per
    round, a row per ant, every ant stamping with ``walk_base``, until the
    first reaches the goal (the others end ``OUTRUN``). ``cur``, ``depth``,
    ``prev`` and ``steps`` hold each ant's node, walk length, heading and
    steps, ``flags`` its state (``FRESH`` before it starts); ``counters``
    holds (next ant, ants started, steps taken, a finished walk waiting for
    room in ``flat``), so a call resumes where the previous one stopped.
    """

    def kernel(indices, adj_ptr, adj_node, adj_edge, adj_offset, w_mul, w_add, weights, horizontal, turn,
               x, scale, lo, hi, on_nodes, tau_exp, q0, local_keep, local_add, pre_add, powers, power_stamp, colony,
               start, goal, backtrack, max_steps, allowance, race, walk_base,
               stamps, stacks, prevs, cand_w, cur, depth, prev, steps, flags, counters, flat, offsets, own):
        n_ants = flags.size
        use_turn = turn.shape[0] > 0
        no_prev = turn.shape[0] - 1
        has_add = w_add.size > 0
        if local:
            do_local = local_keep != 1.0 or local_add != 0.0
            bounded = lo > 0.0 or hi < np.inf
            # pre-choice additions write the trail at every step; a timed colony reads too few entries twice to repay
            keep_powers = tau_exp != 1.0 and not general and not timed and not records
            lo_pow = lo**tau_exp
            fetch_ahead = adj_node.size > FETCH_AHEAD_FROM
            if general:
                has_pre = pre_add.size > 0
        if timed:  # the clock, the moving obstacles and FGDACO's fuzzy priority (see :func:`colony_kernel`)
            (length, speed, t_head, tail, node_xy, ob_points, ob_cum, ob_count, ob_speed, ob_phase, ob_radius,
             route_gap, sensing, target_in, angle_in, clear_in, beta, vertices, rule_table, cons, area_w, moment_w,
             stack_t, stack_gap, level_n, gap, near_ids, ob_ahead, fuzzy_memo) = own
            degree = cand_w.size // stacks.shape[1]  # candidate slots per depth
            n_obs = ob_count.size
            max_len = 0.0
            for q in range(length.size):
                max_len = max(max_len, length[q])
            shrink = np.empty(n_obs)  # per metre the ant drives, a gap shrinks by at most this much
            reach = np.empty(n_obs)  # a gap beyond this cannot matter for any move from here
            for ob in range(n_obs):
                shrink[ob] = 1.0 + ob_speed[ob] / speed
                reach[ob] = max_len * shrink[ob] + sensing
        if records:  # DSACO's lists of records, trail per list and levels of candidates (see :func:`colony_kernel`)
            (node_max, node_even, head, to_next, filled, to_rec, move_class, class_row, list_weight, list_move, cand_q,
             level_first, level_n, level_more) = own
            room = cand_w.size // 2  # levels below, one step's candidates above
            n_classes = class_row.size
            link = use_turn and to_next.size > 0  # lists' places fit in to_next (see MoveTable)
            fetch_ahead = not use_turn  # the lists of the nodes an ant may step to are the adjacency's
        else:
            cand_q = np.empty(cand_w.size, dtype=adj_ptr.dtype)  # the candidates' list positions, typed as the pointers
        stamp = stamps[0]
        stack_e = stacks[0]
        stack_prev = prevs[0]
        a = counters[0]
        total = counters[2]
        if counters[3] > 0:  # copy the walk that waited for room in ``flat``
            base = offsets[a]
            for p in range(depth[a]):
                flat[base + p] = stack_e[p]
            offsets[a + 1] = base + depth[a]
            counters[3] = 0
            a += 1
        while True:
            if a >= n_ants:
                if not general or not race:
                    break
                a = 0  # the next round of a race
                running = False
                for b in range(n_ants):
                    running = running or flags[b] == RUNNING
                if not running:
                    break
            if general:
                if flags[a] >= 0:  # a race walk that has stopped
                    a += 1
                    continue
                if race:  # racing ants have a stamp row and stack each, and all stamp with ``walk_base``
                    stamp = stamps[a]
                    stack_e = stacks[a]
                    stack_prev = prevs[a]
            wid = walk_base if general and race else walk_base + a
            if flags[a] == FRESH:
                flags[a] = RUNNING
                counters[1] += 1
                stamp[start] = wid
                if general:  # only a general kernel's ants stop mid-walk and resume
                    cur[a] = start
                    depth[a] = 0
                    prev[a] = no_prev
                    steps[a] = 0
            c = np.uint32(cur[a] if general else start)  # node ids are uint32, so ``c`` keeps one type
            d = depth[a] if general else 0
            pv = prev[a] if general else no_prev
            n = steps[a] if general else 0
            flag = RUNNING
            full = False  # stopped before a step for want of room on the stack (not after a race step that filled it)
            if timed:
                t_cur = t_head  # the ant's clock at ``c``
                timed_out = False  # some edge was refused because of a moving obstacle
                returned = False  # just stepped back to ``c``: same node, same time, same weights as at the first visit
                gap[:] = -np.inf  # lower bounds on each obstacle's distance (edge to centre of node) now: unknown
            if records:
                returned = False  # just stepped back to ``c``: its candidates are kept at its level
                level_first[0] = 0
                known = 0  # where the list of the node the ant arrived at starts (<< 16), its length + 1; 0: look up
                via = -1  # the record the ant arrived by, when it should learn where that list is
            while True:
                flag = stop_before_step(c, goal, n, max_steps, total, allowance)
                if flag != RUNNING:
                    break
                if general and d >= stack_e.size:  # no room on a racing ant's stack: the caller grows it
                    full = True
                    break
                # ------------------------------------------------------ one step
                if not records:  # DSACO's list is found below, only when it is read
                    e0 = adj_ptr[c]
                    e1 = adj_ptr[c + 1]
                if timed:
                    lv = d * degree  # a timed ant keeps each depth's candidates, for its steps back
                elif records:
                    lv = level_first[d]  # DSACO's levels lie one after another
                else:
                    lv = 0
                nc = 0
                n_open = 0  # allowed neighbours, whatever their weight
                total_w = 0.0
                best_w = -1.0
                best_i = lv
                scan = True
                if (timed or records) and returned and level_n[d] >= 0:  # the candidates kept at this level
                    nc, total_w, best_i = kept_candidates(cand_q, cand_w, lv, level_n[d], adj_node, stamp, wid)
                    scan = False  # they are the first visit's, less the nodes stamped since
                    if records:  # none left: a dead end, unless an open move weighed 0 (the heuristic may choose)
                        scan = nc == 0 and level_more[d]
                if scan:
                    if records:
                        if not use_turn:  # the list is the node's adjacency
                            e0 = adj_ptr[c]
                            e1 = adj_ptr[c + 1]
                        elif known > 0:  # the record the ant came by knows where this list is
                            e0 = known >> 16
                            e1 = e0 + (known & 0xFFFF) - 1
                        else:  # the list of (c, class of its heading), built the first time an ant needs it
                            h = c * n_classes + move_class[pv]
                            if head[h, 1] == 0:
                                build_list(c, move_class[pv], h, adj_ptr, indices, list_weight, list_move, turn,
                                           class_row, head, to_rec, adj_offset, to_next, filled)
                            e0 = head[h, 0]
                            e1 = e0 + head[h, 1] - 1
                            if via >= 0:
                                to_next[via] = (np.int64(e0) << 16) | np.int64(head[h, 1])
                        known = 0
                        via = -1
                        cached = lv + e1 - e0 <= room
                        if not cached:  # no room to keep them: written past the levels, scanned again after a dead end
                            lv = room
                        # one trail power for the whole list when every trail from c reads the same
                        per_edge = not node_even[c] and scale * node_max[c] > lo
                        tp = trail_power(lo if scale * node_max[c] <= lo else read_trail(scale, node_max[c], lo, hi,
                                                                                         bounded), tau_exp, lo, lo_pow)
                    if timed:  # the obstacles that may touch a move from here or come within sensing range of its end
                        cx = node_xy[c, 0]
                        cy = node_xy[c, 1]
                        n_near = 0
                        for ob in range(n_obs):
                            if gap[ob] < reach[ob]:  # the bound says nothing: measure, unless the route is out of reach
                                if route_gap[c, ob] >= reach[ob]:
                                    gap[ob] = route_gap[c, ob]
                                    continue
                                ox, oy = obstacle_position(ob_points, ob_cum, ob_count, ob_speed, ob_phase, ob, t_cur)
                                dx = cx - ox
                                dy = cy - oy
                                gap[ob] = math.sqrt(dx * dx + dy * dy) * UNDER - ob_radius[ob]
                                if gap[ob] < reach[ob]:
                                    near_ids[n_near] = ob
                                    ob_ahead[n_near, 0, 0] = -1.0  # no arrival position of this obstacle computed yet
                                    ob_ahead[n_near, 1, 0] = -1.0
                                    n_near += 1
                        for ob in range(n_obs):  # restored on a step back to here (a loop: a slice costs a count)
                            stack_gap[d, ob] = gap[ob]
                    for q in range(e0, e1):
                        j = adj_node[q]
                        if local and general and has_pre:  # added to every edge leaving the node, tabu or not
                            k = np.int64(j) if on_nodes else np.int64(q) if adj_edge is None else np.int64(adj_edge[q])
                            t = min(max(read_trail(scale, x[k], lo, hi, True) + pre_add[q], lo), hi)
                            x[k] = t / scale
                        if stamp[j] == wid:  # most neighbours on a long walk: test before touching the trail
                            continue
                        f = 1.0
                        if use_turn and not records:  # DSACO's records are the moves the turn table allows
                            f = turn[pv, adj_offset[q]]
                            if f <= 0.0:
                                continue
                        if timed:  # refused if a moving obstacle comes within its radius while the ant drives it
                            near = clear_in[j]  # the obstacle input of the fuzzy priority at ``j``
                            free = True
                            dt = 0.0
                            t_next = t_cur
                            if n_near > 0 or j == goal:  # the move's timing and end matter only near obstacles
                                dt = length[q] / speed
                                t_next = t_cur + dt
                            jx = 0.0
                            jy = 0.0
                            if n_near > 0:
                                jx = node_xy[j, 0]
                                jy = node_xy[j, 1]
                            for i in range(n_near):
                                ob = near_ids[i]
                                bound = gap[ob] - length[q] - ob_speed[ob] * dt  # least possible gap during the move
                                if bound <= 0.0 and obstacle_min_distance(ob_points, ob_cum, ob_count, ob_speed,
                                                                          ob_phase, ob, cx, cy, jx, jy, t_cur,
                                                                          t_next) < ob_radius[ob]:
                                    free = False
                                    break
                                if bound < near * sensing:  # moves of one length arrive together: reuse the position
                                    slot = 0 if ob_ahead[i, 0, 0] == dt or ob_ahead[i, 0, 0] < 0.0 else 1
                                    if ob_ahead[i, slot, 0] != dt:
                                        ox, oy = obstacle_position(ob_points, ob_cum, ob_count, ob_speed, ob_phase, ob,
                                                                   t_next)
                                        ob_ahead[i, slot, 0] = dt
                                        ob_ahead[i, slot, 1] = ox
                                        ob_ahead[i, slot, 2] = oy
                                    ox = ob_ahead[i, slot, 1]
                                    oy = ob_ahead[i, slot, 2]
                                    near = min(near, max(math.hypot(jx - ox, jy - oy) - ob_radius[ob], 0.0) / sensing)
                            if free and j == goal and tail[4] > 0.0:  # and the last piece, to the exact goal
                                for ob in range(n_obs):
                                    if obstacle_min_distance(ob_points, ob_cum, ob_count, ob_speed, ob_phase, ob,
                                                             tail[0], tail[1], tail[2], tail[3], t_next,
                                                             t_next + tail[4]) < ob_radius[ob]:
                                        free = False
                                        break
                            if not free:
                                timed_out = True
                                continue
                        n_open += 1
                        if not local:
                            w = weights[q] * f if use_turn else weights[q]
                        elif records:  # DSACO: the list's one trail power, unless the node's trails differ
                            if per_edge:
                                tp = trail_power(read_trail(scale, x[q if adj_edge is None else adj_edge[q]], lo, hi,
                                                            bounded), tau_exp, lo, lo_pow)
                            w = tp * w_mul[q]
                        else:
                            if not general or not has_pre:  # the entry of the trail the edge reads
                                k = (np.int64(j) if on_nodes else np.int64(q) if adj_edge is None
                                     else np.int64(adj_edge[q]))
                            h = w_mul[q]  # the heuristic factor
                            if timed and near < clear_in[j]:  # FGDACO's fuzzy priority_one, in two exact steps
                                if fuzzy_memo[q, 0, 3] == 0.0:  # first time: the ceilings; no strengths seen yet
                                    rule_ceilings(target_in[j], angle_in[q], vertices, rule_table, fuzzy_memo, q)
                                    fuzzy_memo[q, 0, 3] = 1.0
                                    fuzzy_memo[q, 3, 0] = np.nan
                                    fuzzy_memo[q, 3, 1] = np.nan
                                    fuzzy_memo[q, 3, 2] = np.nan
                                s0, s1, s2 = fired_strengths(fuzzy_memo, q, near, vertices)
                                if s0 != fuzzy_memo[q, 3, 0] or s1 != fuzzy_memo[q, 3, 1] or s2 != fuzzy_memo[q, 3, 2]:
                                    fuzzy_memo[q, 3, 0] = s0
                                    fuzzy_memo[q, 3, 1] = s1
                                    fuzzy_memo[q, 3, 2] = s2
                                    fuzzy_memo[q, 3, 3] = clipped_centroid(s0, s1, s2, cons, area_w, moment_w)**beta
                                h = fuzzy_memo[q, 3, 3]
                            if keep_powers:  # the trail's power, kept per entry
                                if power_stamp[k] != colony:
                                    powers[k] = trail_power(read_trail(scale, x[k], lo, hi, bounded), tau_exp, lo,
                                                            lo_pow)
                                    power_stamp[k] = colony
                                w = powers[k] * h
                            else:
                                if not general or not has_pre:
                                    t = read_trail(scale, x[k], lo, hi, bounded)
                                # without kept powers the exponent of untimed ants one after another is 1
                                w = (trail_power(t, tau_exp, lo, lo_pow) if general or timed else t) * h
                            if has_add:
                                w += w_add[q]
                            if use_turn:
                                w *= f
                        if w > 0.0:
                            if local:
                                heavier = w > best_w  # the first of the heaviest, kept without a branch for the q0 rule
                                best_w = w if heavier else best_w
                                best_i = lv + nc if heavier else best_i
                            cand_q[lv + nc] = q
                            cand_w[lv + nc] = w
                            total_w += w
                            nc += 1
                    if records:
                        level_more[d] = n_open > nc
                    # maybe every trail is 0: weigh the allowed edges by the heuristic alone (not a timed ant's rule)
                    if not timed and nc == 0 and n_open > 0:
                        if records:
                            level_more[d] = False  # a record's turn factor is 1: the weight alone
                        nc, total_w = heuristic_candidates(e0, e1, adj_node, w_mul, w_add, adj_offset, turn, pv, stamp,
                                                           wid, cand_q, cand_w, lv)
                        if local:
                            best_i = heaviest(cand_w, lv, nc)
                    if records:
                        level_n[d] = nc if cached else -1
                elif records:
                    level_n[d] = nc
                if timed:
                    level_n[d] = nc
                if timed or records:
                    returned = False
                if nc == 0:  # dead end
                    if not backtrack:
                        flag = STUCK
                        break
                    if d == 0:
                        flag = EXHAUSTED
                        if timed and timed_out:  # an edge refused at one time may be free at another: no proof
                            flag = STUCK
                        break
                    d -= 1
                    c = indices[stack_e[d - 1]] if d > 0 else np.uint32(start)
                    if use_turn:
                        pv = stack_prev[d - 1] if d > 0 else no_prev
                    if timed:  # back at the node's earlier time, with the obstacle bounds measured there
                        t_cur = stack_t[d - 1] if d > 0 else t_head
                        for ob in range(n_obs):
                            gap[ob] = stack_gap[d, ob]
                    if timed or records:
                        returned = True
                    if records:
                        known = 0
                        via = -1
                else:
                    if not local:
                        for i in range(nc):  # the next node is one of these: fetch its list while the choice is made
                            ahead = adj_ptr[adj_node[cand_q[i]]]
                            prefetch(weights, ahead)
                            prefetch(weights, ahead + 7)  # its first eight weights span one or two lines
                            prefetch(adj_node, ahead)
                        pick = cand_q[choose(cand_w, nc, total_w, q0)]
                    else:
                        for i in range(lv, lv + nc if fetch_ahead else lv):
                            ahead = adj_ptr[adj_node[cand_q[i]]]
                            prefetch(adj_node, ahead)
                            prefetch(w_mul, ahead)
                            if general and has_pre:  # the gains added to every edge leaving the next node
                                prefetch(pre_add, ahead)
                            if general:  # racing ants: the stamps and list pointers one node further on
                                further = 2 * np.int64(adj_node[cand_q[i]]) - np.int64(c)  # a grid's ids: ahead
                                prefetch(stamp, further)
                                prefetch(adj_ptr, further)
                            if not records and not on_nodes and adj_edge is None:  # the edge trail in list order
                                prefetch(x, ahead)
                                prefetch(x, ahead + 7)  # its first eight entries span one or two lines
                        if q0 > 0.0 and np.random.random() < q0:  # ``choose``'s draws, its heaviest found above
                            pick = cand_q[best_i]
                        else:
                            pick = cand_q[roulette(cand_w, lv, nc, total_w)]
                    c = adj_node[pick]
                    stamp[c] = wid
                    sel = pick if adj_edge is None else adj_edge[pick]
                    stack_e[d] = sel
                    if use_turn:
                        o = adj_offset[pick]
                        if horizontal[o]:
                            pv = o
                            if records and link:  # the next list follows from the record alone
                                known = to_next[pick]
                                via = pick if known == 0 else -1
                        stack_prev[d] = pv
                    if timed:  # the clock runs; each gap shrinks by at most the distance both have moved
                        t_cur += length[sel] / speed
                        stack_t[d] = t_cur
                        for ob in range(n_obs):
                            gap[ob] -= length[sel] * shrink[ob]
                    d += 1
                    if records:
                        level_first[d] = lv + nc if level_n[d - 1] >= 0 else level_first[d - 1]
                    if local and do_local:
                        k = np.int64(c) if on_nodes else np.int64(sel)
                        local_update(x, k, scale, lo, hi, local_keep, local_add)
                        if keep_powers:
                            power_stamp[k] = 0  # its power is computed again when next read
                n += 1
                total += 1
                if general and race:  # one step per ant and round
                    if c == goal:
                        flag = REACHED
                    break
            depth[a] = d
            steps[a] = n
            if general:
                cur[a] = c
                prev[a] = pv
            counters[2] = total
            if general:
                if full:  # resume with this ant, which has not stepped yet (a racing ant's step waits until then)
                    counters[0] = a
                    return NEED_SPACE
                if flag == RUNNING:  # a racing ant that took its step
                    a += 1
                    continue
            flags[a] = flag
            if not general or not race:
                if flag == REACHED:
                    if offsets[a] + d > flat.size:
                        counters[0] = a
                        counters[3] = 1
                        return NEED_SPACE
                    for p in range(d):
                        flat[offsets[a] + p] = stack_e[p]
                offsets[a + 1] = offsets[a] + (d if flag == REACHED else 0)
            if flag == ABORTED or (flag == EXHAUSTED and (timed or not use_turn)) or (general and race
                                                                                  and flag == REACHED):
                for b in range(n_ants):  # the others: never started, stopped, or outrun in a race
                    if flags[b] == FRESH or (flags[b] == RUNNING and flag != REACHED):
                        flags[b] = ABORTED
                    elif flags[b] == RUNNING:
                        flags[b] = OUTRUN
                    if b > a and (not general or not race):
                        offsets[b + 1] = offsets[a + 1]
                break
            a += 1
        counters[0] = a
        return DONE

    kernel.__qualname__ = kernel.__name__ = NAMES[local, general, timed, records]  # names its cache files
    kernel.__doc__ = f"The kernel of :func:`colony_kernel` for {WHAT[local, general, timed, records]}."
    return numba.njit(cache=True)(kernel)


NAMES = {(False, False, False, False): "weighted_colony", (True, False, False, False): "local_colony",
         (True, True, False, False): "generic_colony", (False, True, False, False): "generic_weighted_colony",
         (True, False, True, False): "timed_colony", (True, False, False, True): "record_colony"}
"""The name of each kernel of :func:`colony_kernel`, by ``(local, general, timed, records)``."""

WHAT = {(False, False, False, False): "ants going one after another on weights fixed while they walk",
        (True, False, False, False): "ants going one after another that mark the trail as they go",
        (True, True, False, False): "racing ants or pre-choice additions, weighing the trail at each step",
        (False, True, False, False): "racing ants on weights fixed while they walk",
        (True, False, True, False): "ants going one after another that keep time among moving obstacles",
        (True, False, False, True): "DSACO's ants, reading lists of the moves its turn limit allows"}
"""What each kernel of :func:`colony_kernel` walks, by ``(local, general, timed, records)``."""

weighted_colony = colony_kernel(False, False)
local_colony = colony_kernel(True, False)
generic_colony = colony_kernel(True, True)
generic_weighted_colony = colony_kernel(False, True)
timed_colony = colony_kernel(True, False, timed=True)
record_colony = colony_kernel(True, False, records=True)

KERNELS = {(False, False, False): weighted_colony, (True, False, False): local_colony,
           (True, True, False): generic_colony, (False, True, False): generic_weighted_colony,
           (True, False, True): timed_colony}
"""The kernels of :func:`colony_kernel` by ``(local, general, timed)``."""


@numba.njit(cache=True)
def fill_weights(out, adj_node, adj_edge, w_mul, w_add, x, scale, lo, hi, on_nodes, tau_exp):
    """Each listed edge's weight ``τ ** tau_exp * w_mul (+ w_add)`` into ``out``, as a ``local`` kernel of
    :func:`colony_kernel` has it.

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
