"""DSACO's whole colony in one compiled call: walks, fitness and best-ant update of many iterations at once.

The generic loop (:meth:`AntColonyPlanner.plan`) crosses from Python into
compiled code three times per iteration and its walk kernel scans every edge
of a node, asking the turn table about each. On ``dsaco.complex`` that is 42
edges per step, most of them refused by the 60° turn limit. This module runs
the same colony with three changes that leave every result bit-identical:

- **allowed-move records** per (node, incoming heading): one record
  (target, adjacency position, weight, move) per edge the turn limit lets
  through, in the original order, built the first time an ant stands on that
  node with that heading, appended one list after another and kept per
  scenario and configuration (:class:`~pathzoo_aco.dsaco_tables.MoveTable`). A step reads one run of
  records, so no edge is refused by the turn table inside the walk. Without
  a turn limit every list is the node's adjacency, read in place, and the
  lists of the nodes an ant may step to are asked of the cache before it
  draws (:func:`~pathzoo_aco.engine.prefetch.prefetch`);
- **one trail for a whole list** when every trail leaving the node reads the
  same (no deposit on them yet, or all at ``τmin``): the trail and its power
  are computed once for the node, not per edge
  (:attr:`ColonyRun.node_even <pathzoo_aco.dsaco_tables.ColonyRun.node_even>`);
- **records linked to the next list**: a record whose move sets the
  heading leads to one list only (its target's, for that heading), so it
  learns where that list lies the first time an ant takes it, and later ants
  skip the random read of the list heads (:attr:`MoveTable.to_next <pathzoo_aco.dsaco_tables.MoveTable.to_next>`);
- **candidates kept per depth**: after a dead end the ant steps back and
  chooses again on the node before; the candidates it had there, less the
  nodes stamped since, are what reading the list again would give, so they
  are taken from the walk's levels instead (:class:`~pathzoo_aco.dsaco_tables.ColonyRun`). Under the
  paper's step rule about half of all steps are such steps back. The first
  of the heaviest candidates (eq. 14's deterministic choice) is noted while
  they are listed, so that choice reads nothing more;
- **one call for many iterations**: the walks, the fitness (eq. 20) and the
  flight constraints (eqs. 2-3) by the kernels of
  :mod:`pathzoo_aco.dsaco_fitness`, the best-so-far walk, evaporation and
  the iteration-best deposit (eqs. 16-18) run in compiled code; the
  per-iteration numbers that come from Python (the seeds drawn from the
  planner's ``rng``, ``q0`` of eq. 15, ``p`` of eq. 19, the ants of each
  iteration) are computed beforehand by the same Python functions as the
  generic loop uses.

The walk follows :func:`pathzoo_aco.engine.walk_kernel.generic_colony` operation for
operation for the rules DSACO builds (product rule, ``q0``, turn table of
zeros and ones, edge trails in ``[τmin, τmax]``, no local update, ants one
after another): the same candidates in the same order, the same random draws,
the same sums, with the step rules of :mod:`pathzoo_aco.engine.steps`.
``tests/aco/test_dsaco_colony.py`` and
``benchmarks/identity.py`` check that paths, costs, step and evaluation
counts equal the generic loop's.
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.dsaco_fitness import infeasible_walks, walk_fitness
from pathzoo_aco.dsaco_tables import ColonyRun, MoveTable, build_list
from pathzoo_aco.engine import EXHAUSTED, REACHED, STEP_CAP, STUCK
from pathzoo_aco.engine.prefetch import prefetch
from pathzoo_aco.engine.steps import (heaviest, heuristic_candidates, kept_candidates, read_trail, roulette,
                                      trail_power)

__all__ = ["run_colony"]

_RENORMALISE_BELOW = 1e-150
"""As :data:`pathzoo_aco.engine.pheromone._RENORMALISE_BELOW`: fold the trail's scale back below this."""


@numba.njit(cache=True)
def _walk_ant(wid, adj_ptr, node, weight, move, horizontal, turn, move_class, class_row, head, to_rec, to_move,
              rec_node, rec_place, rec_weight, to_next, filled, x, node_max, node_even, scale, lo, hi, tau_exp, q0,
              start, goal, backtrack, max_steps, stamp,
              stack, stack_prev, cand, cand_w, level_first, level_count, level_more):
    """One ant from ``start``; returns ``(outcome, depth, steps)``, the adjacency positions it took in
    ``stack[:depth]``.

    Step for step :func:`pathzoo_aco.engine.walk_kernel.generic_colony` for one ant walking
    alone, reading the records of (node, heading) instead of the node's whole
    adjacency: ``rec_node``, ``rec_place`` and ``rec_weight`` are the fields
    of ``to_rec``, or without a turn table the adjacency's targets and weights
    (``rec_place`` empty: a list position is its own place). ``wid`` is the
    walk's stamp (see :attr:`ColonyRun.stamps`). The candidates of every node
    on the walk are kept, one level per depth in ``cand``/``cand_w``; a step
    back on a node after a dead end takes them again less those stamped
    since, rather than reading the list again (see :class:`ColonyRun`).
    """
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1 if use_turn else 0
    n_classes = class_row.size
    bounded = lo > 0.0 or hi < np.inf
    lo_pow = lo**tau_exp
    room = cand.size // 2  # levels below, one step's candidates above
    d = 0
    pv = no_prev
    n = 0
    back = False  # this step is on a node the walk stepped back to
    known = 0  # where the list of the node the ant arrived at starts (<< 16) and its length plus 1; 0: look it up
    via = -1  # the record the ant arrived by, when it should learn where that list is
    link = use_turn and to_next.size > 0  # lists' places fit in to_next (see MoveTable)
    stamp[start] = wid
    c = start
    level_first[0] = 0
    while True:
        if c == goal:
            return REACHED, d, n
        if n >= max_steps:
            return STEP_CAP, d, n
        p0 = level_first[d]
        nc = 0
        total_w = 0.0
        top_w = -1.0  # the first of the heaviest candidates (eq. 14's deterministic choice), found as they are listed
        top = -1
        scan = True
        if back and level_count[d] >= 0:  # the same candidates as before, less the nodes stamped since
            nc, total_w, kept_top = kept_candidates(cand, cand_w, p0, level_count[d], rec_node, stamp, wid)
            top = cand[kept_top]
            # none left: a dead end, unless some open move weighed 0 (then the heuristic alone may still choose)
            scan = nc == 0 and level_more[d]
        if scan:
            if not use_turn:  # the list is the node's adjacency
                r0 = adj_ptr[c]
                r1 = adj_ptr[c + 1]
            elif known > 0:  # the record the ant came by knows where this list is
                r0 = known >> 16
                r1 = r0 + (known & 0xFFFF) - 1
            else:
                h = c * n_classes + move_class[pv]
                if head[h, 1] == 0:
                    build_list(c, move_class[pv], h, adj_ptr, node, weight, move, turn, class_row, head, to_rec,
                                to_move, to_next, filled)
                r0 = head[h, 0]
                r1 = r0 + head[h, 1] - 1
                if via >= 0:
                    to_next[via] = (np.int64(r0) << 16) | np.int64(head[h, 1])
            known = 0
            via = -1
            cached = p0 + r1 - r0 <= room
            if not cached:  # no room to keep them: written past the levels, scanned again after a dead end
                p0 = room
            # one trail power for the whole list when every trail from c reads the same
            per_edge = not node_even[c] and scale * node_max[c] > lo
            tp = trail_power(lo if scale * node_max[c] <= lo else read_trail(scale, node_max[c], lo, hi, bounded),
                             tau_exp, lo, lo_pow)
            n_open = 0
            for r in range(r0, r1):
                if stamp[rec_node[r]] == wid:
                    continue
                if per_edge:
                    tp = trail_power(read_trail(scale, x[r if not use_turn else rec_place[r]], lo, hi, bounded),
                                     tau_exp, lo, lo_pow)
                n_open += 1
                w = tp * rec_weight[r]
                if w > 0.0:
                    cand[p0 + nc] = r
                    cand_w[p0 + nc] = w
                    total_w += w
                    if w > top_w:
                        top_w = w
                        top = r
                    nc += 1
            level_more[d] = n_open > nc
            if nc == 0 and n_open > 0:  # every trail weight underflowed: the heuristic alone
                level_more[d] = False  # a record's turn factor is 1: the weight alone
                nc, total_w = heuristic_candidates(r0, r1, rec_node, rec_weight, rec_weight[:0], to_move, turn, pv,
                                                   stamp, wid, cand, cand_w, p0)
                if nc > 0:
                    top = cand[heaviest(cand_w, p0, nc)]
            level_count[d] = nc if cached else -1
        else:
            level_count[d] = nc
        if nc == 0:  # dead end
            if not backtrack:
                return STUCK, d, n
            if d == 0:
                return EXHAUSTED, d, n
            d -= 1
            c = node[stack[d - 1]] if d > 0 else start
            if use_turn:
                pv = stack_prev[d - 1] if d > 0 else no_prev
            back = True
            known = 0
            via = -1
        else:
            if not use_turn:  # the next node is one of these: ask the cache for its list while the choice is made
                for i in range(p0, p0 + nc):
                    ahead = adj_ptr[rec_node[cand[i]]]
                    prefetch(rec_weight, ahead)
                    prefetch(rec_node, ahead)
            if q0 > 0.0 and np.random.random() < q0:
                sel = top
            else:
                sel = cand[roulette(cand_w, p0, nc, total_w)]
            c = rec_node[sel]
            stamp[c] = wid
            stack[d] = sel if not use_turn else rec_place[sel]
            fixed = True  # the next list follows from the record alone
            if use_turn:
                o = to_move[sel]
                if horizontal[o]:
                    pv = o
                else:
                    fixed = False  # a vertical move keeps the heading before it
                stack_prev[d] = pv
            if fixed and link:
                known = to_next[sel]
                via = sel if known == 0 else -1
            d += 1
            level_first[d] = p0 + nc if level_count[d - 1] >= 0 else level_first[d - 1]
            back = False
        n += 1


@numba.njit(cache=True)
def _colony_run(adj_ptr, node, weight, move, edge, move_class, class_row, head, to_rec, to_move, rec_node, rec_place,
                rec_weight, to_next, filled,
                horizontal, turn, graph_indices, graph_offset_id, edge_length, height, turn_angle, cells, f1, f2, f3,
                l_max, l_min, x, scale, lo, hi, rho, tau_exp, q, start, goal, backtrack, max_steps,
                seeds, q0s, ps, ants, first, stop_at, best_cost, best_edges, counters, stamps, stack, stack_prev, cand,
                cand_w, level_first, level_count, level_more, node_max, node_even):
    """Iterations ``counters[0]`` to ``stop_at - 1``; the schedule starts at iteration ``first``
    (see :func:`run_colony`)."""
    flat = np.zeros(1024, dtype=np.int64)  # storage places of the iteration's walks
    flat_edges = np.zeros(1024, dtype=np.int64)  # the same as graph edge ids
    use_turn = turn.shape[0] > 0
    it = counters[0]
    while it < stop_at:
        n_ants = ants[it - first]
        np.random.seed(seeds[it - first])
        offsets = np.zeros(n_ants + 1, dtype=np.int64)
        reached = np.zeros(n_ants, dtype=np.bool_)
        started = 0
        exhausted = False
        for a in range(n_ants):
            wid = (counters[1] + a) % 255  # walks are counted over the run; a byte stamp tells 255 apart
            if wid == 0:  # a new round of stamps: forget the last one's
                stamps[:] = 0
            flag, d, n = _walk_ant(np.uint8(wid + 1), adj_ptr, node, weight, move, horizontal, turn, move_class,
                                   class_row, head, to_rec, to_move, rec_node, rec_place, rec_weight, to_next,
                                   filled, x, node_max, node_even, scale[0], lo, hi, tau_exp, q0s[it - first],
                                   start, goal, backtrack, max_steps, stamps, stack, stack_prev, cand, cand_w,
                                   level_first, level_count, level_more)
            started += 1
            counters[2] += n
            if flag == REACHED:
                if offsets[a] + d > flat.size:
                    size = max(2 * flat.size, offsets[a] + d)
                    grown = np.zeros(size, dtype=np.int64)
                    grown[: flat.size] = flat
                    flat = grown
                    flat_edges = np.zeros(size, dtype=np.int64)
                flat[offsets[a] : offsets[a] + d] = stack[:d]
                reached[a] = True
            offsets[a + 1] = offsets[a] + (d if flag == REACHED else 0)
            if flag == EXHAUSTED and not use_turn:  # the goal is unreachable: the others never start
                exhausted = True
                offsets[a + 1 :] = offsets[a + 1]
                break
        counters[1] += started
        it += 1
        for i in range(offsets[n_ants]):
            flat_edges[i] = edge[flat[i]] if edge.size else flat[i]
        costs = walk_fitness(flat_edges, offsets, reached, graph_indices, graph_offset_id, edge_length, height,
                             turn_angle, start, cells, f1, f2, f3)
        if l_max > 0.0 or l_min > 0.0:  # eqs. 2-3
            costs[infeasible_walks(flat_edges, offsets, reached, edge_length, graph_offset_id, cells, l_max,
                                   l_min)] = np.inf
        k = np.argmin(costs)
        if np.isfinite(costs[k]) and costs[k] < best_cost[0]:
            best_cost[0] = costs[k]
            best_edges[: offsets[k + 1] - offsets[k]] = flat_edges[offsets[k] : offsets[k + 1]]
            counters[3] = offsets[k + 1] - offsets[k]
        s = scale[0] * (1.0 - rho)  # eq. 16: evaporate everywhere (lazily, through the scale)
        if s < _RENORMALISE_BELOW:
            for i in range(x.size):
                x[i] = min(max(s * x[i], lo), hi)
            for c in range(node_max.size):  # the clamp is monotonic: still at least each node's largest
                node_max[c] = min(max(s * node_max[c], lo), hi)
            s = 1.0
        scale[0] = s
        if np.isfinite(costs[k]):  # eqs. 17-18: the iteration-best ant deposits, within the bounds
            p = ps[it - 1 - first]
            amount = q / ((1.0 - p) * costs[k] + p * best_cost[0])
            c = start
            for i in range(offsets[k], offsets[k + 1]):
                e = flat[i]
                t = min(max(s * x[e], lo), hi) + amount
                x[e] = min(max(t, lo), hi) / s
                node_max[c] = max(node_max[c], x[e])  # e leaves c
                node_even[c] = False
                c = node[e]
        if exhausted:
            counters[4] = 1
            break
    counters[0] = it


def run_colony(table: MoveTable, horizontal: np.ndarray, turn: np.ndarray, fitness: tuple, trail: tuple,
               rule: tuple, schedule: tuple, run: ColonyRun, first: int, stop_at: int) -> None:
    """Run iterations ``run.counters[0]`` to ``stop_at - 1`` (fewer if an ant proves the goal unreachable).

    Parameters
    ----------
    table : MoveTable
        The moves of the rules' adjacency and turn table (allowed lists filled as needed).
    horizontal, turn : ndarray
        Per move, whether it changes the heading; the turn table (zeros and ones, or empty).
    fitness : tuple
        ``(graph indices, graph offset_id, edge length, node height, turn angle, cell size, f1, f2, f3,
        l_max, l_min)``.
    trail : tuple
        ``(x, lo, hi, rho)``: the trail in the table's storage order, its bounds and evaporation rate;
        its scale lives in ``run.scale``.
    rule : tuple
        ``(tau_exp, q, start, goal, backtrack, max_steps)``.
    schedule : tuple
        Per iteration from ``first`` on: ``(seeds, q0, p, ants)``.
    run : ColonyRun
        Changed in place.
    first : int
        The iteration ``schedule`` starts with.
    stop_at : int
        Iteration to stop before (at most ``first`` plus the schedule's length).
    """
    t = table
    x, lo, hi, rho = trail
    tau_exp, q, start, goal, backtrack, max_steps = rule
    seeds, q0s, ps, ants = schedule
    if turn.size:  # the records' fields
        records = (t.to_rec["node"], t.to_rec["place"], t.to_rec["weight"])
    else:  # every list is the node's adjacency
        targets = t.node.view(np.uint32) if t.node.dtype == np.int32 else t.node  # unsigned: no negative-index fix-up
        records = (targets, np.zeros(0, dtype=t.to_rec["place"].dtype), t.weight)
    _colony_run(t.adj_ptr, t.node, t.weight, t.move, t.edge, t.move_class, t.class_row, t.head, t.to_rec, t.to_move,
                *records, t.to_next, t.filled, horizontal, turn, *fitness, x, run.scale, lo, hi, rho, tau_exp, q, start,
                goal, backtrack, max_steps, seeds, q0s, ps, ants, first, stop_at, run.best_cost, run.best_edges,
                run.counters, run.stamps, run.stack, run.stack_prev, run.cand, run.cand_w, run.level_first,
                run.level_count, run.level_more, run.node_max, run.node_even)
