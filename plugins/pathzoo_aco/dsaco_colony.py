"""DSACO's whole colony in one compiled call: walks, fitness and best-ant update of many iterations at once.

The generic loop (:meth:`AntColonyPlanner.plan`) crosses from Python into
compiled code three times per iteration and its walk kernel scans every edge
of a node, asking the turn table about each. On ``dsaco.complex`` that is 42
edges per step, most of them refused by the 60° turn limit. This module runs
the same colony with these changes, which leave every result bit-identical:

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

The walk is the engine's one walk body, compiled for these lists and
levels (:func:`~pathzoo_aco.engine.walk_kernel.record_colony`, one call per
iteration): for the rules DSACO builds (product rule, ``q0``, turn table of
zeros and ones, edge trails in ``[τmin, τmax]``, no local update, ants one
after another) it takes the same candidates in the same order, the same
random draws and the same sums as the generic loop.
``tests/aco/test_dsaco_colony.py`` and
``benchmarks/identity.py`` check that paths, costs, step and evaluation
counts equal the generic loop's.
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.dsaco_fitness import infeasible_walks, walk_fitness
from pathzoo_aco.dsaco_tables import ColonyRun, MoveTable
from pathzoo_aco.engine import EXHAUSTED, REACHED
from pathzoo_aco.engine.outcomes import FRESH, NEED_SPACE
from pathzoo_aco.engine.walk_kernel import record_colony

__all__ = ["run_colony"]

_RENORMALISE_BELOW = 1e-150
"""As :data:`pathzoo_aco.engine.pheromone._RENORMALISE_BELOW`: fold the trail's scale back below this."""


@numba.njit(cache=True)
def _colony_run(lists, horizontal, turn, own, edge, node, graph_indices, graph_offset_id, edge_length, height,
                turn_angle, cells, f1, f2, f3, l_max, l_min, x, scale, lo, hi, rho, tau_exp, q, start, goal, backtrack,
                max_steps, seeds, q0s, ps, ants, first, stop_at, best_cost, best_edges, counters, largest, stamps,
                stack, stack_prev, cand_w, node_max, node_even):
    """Iterations ``counters[0]`` to ``stop_at - 1``; the schedule starts at iteration ``first``
    (see :func:`run_colony`)."""
    flat = np.zeros(1024, dtype=np.int64)  # storage places of the iteration's walks
    flat_edges = np.zeros(1024, dtype=np.int64)  # the same as graph edge ids
    use_turn = turn.shape[0] > 0
    no_float = np.zeros(0)
    no_stamp = np.zeros(0, dtype=np.int32)
    no_int = np.zeros(0, dtype=np.int64)  # where racing ants would keep their node and heading
    it = counters[0]
    while it < stop_at:
        n_ants = ants[it - first]
        np.random.seed(seeds[it - first])
        if counters[5] + n_ants > largest + 1:  # the walk stamps would overflow: forget the last ones
            stamps[:] = 0
            counters[5] = 1
        offsets = np.zeros(n_ants + 1, dtype=np.int64)
        depth = np.zeros(n_ants, dtype=np.int64)
        steps = np.zeros(n_ants, dtype=np.int64)
        flags = np.full(n_ants, FRESH, dtype=np.int8)
        walks = np.zeros(4, dtype=np.int64)
        while record_colony(*lists, None, horizontal, turn, x, scale[0], lo, hi, False, tau_exp, q0s[it - first], 1.0,
                            0.0, no_float, no_float, no_stamp, 0, start, goal, backtrack, max_steps, 2**62, False,
                            counters[5], stamps, stack, stack_prev, cand_w, no_int, depth, no_int, steps, flags, walks,
                            flat, offsets, own) == NEED_SPACE:  # a walk that reached the goal needs room in ``flat``
            size = max(2 * flat.size, offsets[walks[0]] + depth[walks[0]])
            grown = np.zeros(size, dtype=np.int64)
            grown[: flat.size] = flat
            flat = grown
            flat_edges = np.zeros(size, dtype=np.int64)
        counters[5] += n_ants
        counters[1] += walks[1]
        counters[2] += walks[2]
        reached = flags == REACHED
        exhausted = False  # the goal is unreachable (then the others never started)
        for a in range(n_ants):
            exhausted = exhausted or (flags[a] == EXHAUSTED and not use_turn)
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
    targets = t.node.view(np.uint32) if t.node.dtype == np.int32 else t.node  # unsigned: no negative-index fix-up
    empty = np.zeros(0)
    lists: tuple[np.ndarray | None, ...]
    if turn.size:  # the lists are the records: their fields as the kernel's lists
        lists = (targets, t.adj_ptr, t.to_rec["node"], t.to_rec["place"], t.to_move, t.to_rec["weight"], empty)
    else:  # every list is the node's adjacency, read in place
        lists = (targets, t.adj_ptr, targets, None, t.move, t.weight, empty)
    if ants.max(initial=0) > 255 and run.stamps.dtype == np.uint8:  # byte stamps tell 255 walks apart
        run.stamps = np.zeros(run.stamps.shape, dtype=np.int32)
        run.counters[5] = 1
    own = (run.node_max, run.node_even, t.head, t.to_next, t.filled, t.to_rec, t.move_class, t.class_row, t.weight,
           t.move, run.cand, run.level_first, run.level_count, run.level_more)
    _colony_run(lists, horizontal, turn, own, t.edge, targets, *fitness, x, run.scale, lo, hi, rho, tau_exp, q, start,
                goal, backtrack, max_steps, seeds, q0s, ps, ants, first, stop_at, run.best_cost, run.best_edges,
                run.counters, np.iinfo(run.stamps.dtype).max, run.stamps, run.stack, run.stack_prev, run.cand_w,
                run.node_max, run.node_even)
