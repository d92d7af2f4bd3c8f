"""DSACO's whole colony in one compiled call: walks, fitness and best-ant update of many iterations at once.

The generic loop (:meth:`AntColonyPlanner.plan`) crosses from Python into
compiled code three times per iteration and its walk kernel scans every edge
of a node, asking the turn table about each. On ``dsaco.complex`` that is 42
edges per step, most of them refused by the 60° turn limit. This module runs
the same colony with three changes that leave every result bit-identical:

- **allowed-move lists** per (node, incoming heading): the positions of the
  node's edges that the turn limit lets through, in their original order,
  built the first time an ant stands on that node with that heading and kept
  per scenario and configuration (:class:`MoveTable`). A step scans only
  those, so no edge is refused by the turn table inside the walk;
- **moves stored by heading**: each node's edges (target, weight, trail) are
  stored sorted by heading, so the moves one heading allows are read from one
  or two runs of memory (:class:`MoveTable`);
- **one call for many iterations**: the walks, the fitness (eq. 20) and the
  flight constraints (eqs. 2-3) by the kernels of
  :mod:`pathzoo_aco.dsaco_fitness`, the best-so-far walk, evaporation and
  the iteration-best deposit (eqs. 16-18) run in compiled code; the
  per-iteration numbers that come from Python (the seeds drawn from the
  planner's ``rng``, ``q0`` of eq. 15, ``p`` of eq. 19, the ants of each
  iteration) are computed beforehand by the same Python functions as the
  generic loop uses.

The walk follows :func:`pathzoo_aco.engine.walk._colony` operation for
operation for the rules DSACO builds (product rule, ``q0``, turn table of
zeros and ones, edge trails in ``[τmin, τmax]``, no local update, ants one
after another): the same candidates in the same order, the same random draws,
the same sums. ``tests/aco/test_dsaco_colony.py`` and
``benchmarks/identity.py`` check that paths, costs, step and evaluation
counts equal the generic loop's.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from pathzoo_aco.dsaco_fitness import infeasible_walks, walk_fitness
from pathzoo_aco.engine import EXHAUSTED, REACHED, STEP_CAP, STUCK

__all__ = ["MoveTable", "ColonyRun", "run_colony"]

_RENORMALISE_BELOW = 1e-150
"""As :data:`pathzoo_aco.engine.pheromone._RENORMALISE_BELOW`: fold the trail's scale back below this."""


@numba.njit(cache=True)
def _heading_layout(adj_ptr, adj_node, adj_edge, adj_offset, w_mul, rank, node, weight, edge, move, place):
    """Fill the storage arrays: each node's adjacency positions sorted by ``rank`` of their moves.

    ``node``, ``weight``, ``edge``, ``move`` get the target, weight, graph
    edge id and move of each storage place; ``place[q]`` the place of
    adjacency position ``q`` relative to its node's first.
    """
    slot = np.empty(rank.size, dtype=np.int64)
    for c in range(adj_ptr.size - 1):
        e0 = adj_ptr[c]
        slot[:] = -1
        for q in range(e0, adj_ptr[c + 1]):
            slot[rank[adj_offset[q]]] = q
        m = 0
        for r in range(rank.size):
            q = slot[r]
            if q < 0:
                continue
            s = e0 + m
            node[s] = adj_node[q]
            weight[s] = w_mul[q]
            edge[s] = q if adj_edge is None else adj_edge[q]
            move[s] = adj_offset[q]
            place[q] = m
            m += 1


@dataclass(frozen=True, eq=False)
class MoveTable:
    """A node's moves stored by heading, and per (node, heading class) the moves the turn limit allows.

    **Storage.** Each node's edges (the walk engine's adjacency of the rules)
    are stored sorted by the heading of their move, so the moves one heading
    class allows lie in one or two runs of memory rather than spread over the
    node's whole block (the walk reads fewer cache lines per step). The trail
    is kept in the same order. The order in which an ant *considers* the
    moves is unchanged: the original one.

    **Allowed lists.** Heading classes are the distinct rows of the turn table
    (row ``K``, no previous move, included). The list of node ``c`` and class
    ``k`` holds the storage places (relative to the node's first) of the
    edges whose move the turn table allows, in the original order; it is
    built the first time an ant stands on ``c`` with a heading of class ``k``.

    Attributes
    ----------
    node, weight, edge, move : ndarray
        Per storage place: target node, weight ``weight_mul``, graph edge id and move id.
    place : ndarray of uint8 or uint16
        Per original adjacency position: its storage place relative to its node's first.
    adj_ptr, adj_offset : ndarray
        The adjacency's CSR pointer and per-position moves (original order).
    move_class : ndarray of int64, shape (K + 1,)
        Class of every previous move.
    class_row : ndarray of int64
        A previous move (row of the turn table) standing for each class.
    pool : ndarray like ``place``
        The lists, each after a header: node ``c``'s list of class ``k`` has
        its header at ``(adj_ptr[c] + c) * classes + k * (degree(c) + 1)``:
        0 until the list is built (the array is allocated zeroed, so its pages
        cost memory only once a list on them is built), then the list's
        length plus 1. Header and list share a cache line.
    """

    node: np.ndarray
    weight: np.ndarray
    edge: np.ndarray
    move: np.ndarray
    place: np.ndarray
    adj_ptr: np.ndarray
    adj_offset: np.ndarray
    move_class: np.ndarray
    class_row: np.ndarray
    pool: np.ndarray

    @classmethod
    def of(cls, adjacency: tuple, offsets: np.ndarray, turn: np.ndarray) -> "MoveTable":
        """The table of an adjacency ``(adj_ptr, adj_node, adj_edge or None, adj_offset, weight_mul, _)``
        (:meth:`~pathzoo_aco.engine.walk.WalkEngine.adjacency`), the graph's move offsets and a turn table
        ``(K + 1, K)`` of zeros and ones (or ``(0, 0)``: one class, every move allowed)."""
        adj_ptr, adj_node, adj_edge, adj_offset, w_mul = adjacency[:5]
        n_nodes = len(adj_ptr) - 1
        if turn.size == 0:
            move_class = np.zeros(1, dtype=np.int64)
            class_row = np.zeros(1, dtype=np.int64)
        else:
            _, first, inverse = np.unique(turn, axis=0, return_index=True, return_inverse=True)
            move_class = inverse.reshape(-1).astype(np.int64)
            class_row = first.astype(np.int64)
        heading = np.arctan2(offsets[:, -2], offsets[:, -1])
        vertical = (offsets[:, -2:] == 0).all(axis=1)
        rank = np.empty(len(offsets), dtype=np.int64)
        rank[np.lexsort((np.arange(len(offsets)), heading, vertical))] = np.arange(len(offsets))
        degree = int(np.diff(adj_ptr).max()) if n_nodes else 0
        small = np.uint8 if degree < 255 else np.uint16 if degree < 65535 else np.uint32
        size = len(adj_node)
        node, weight, edge = np.empty_like(adj_node), np.empty_like(w_mul), np.empty(size, dtype=np.int64)
        move, place = np.empty_like(adj_offset), np.empty(size, dtype=small)
        _heading_layout(adj_ptr, adj_node, adj_edge, adj_offset, w_mul, rank, node, weight, edge, move, place)
        return cls(node, weight, edge, move, place, adj_ptr, adj_offset, move_class, class_row,
                   np.zeros((size + n_nodes) * len(class_row), dtype=small))


@dataclass
class ColonyRun:
    """The state a run carries from one :func:`run_colony` call to the next (arrays changed in place).

    Attributes
    ----------
    scale : ndarray, shape (1,)
        The trail's global scale (:class:`~pathzoo_aco.engine.pheromone.Pheromone`).
    best_cost : ndarray, shape (1,)
        Fitness of the best walk so far.
    best_edges : ndarray of int64
        Its edges, ``best_edges[:counters[3]]``.
    counters : ndarray of int64, shape (5,)
        Next iteration, walks started, ant steps, length of the best walk, and
        1 once an ant has searched the start's whole component (no turn rule).
    stamps : ndarray of int32
        Tabu stamps; walk ``w`` stamps its nodes with ``w``.
    stack, stack_prev, cand, cand_w : ndarray
        Work space of the walks: the storage places and headings along the
        walk, and the candidates of one step with their weights.
    node_max : ndarray
        Per node, at least the largest stored trail ``x`` of its edges. When
        ``scale * node_max[c] <= τmin`` every trail leaving ``c`` reads as
        exactly ``τmin`` (the clamp), so a step from ``c`` skips the trail.
        Most nodes are there a few dozen iterations into a run: only the
        iteration-best walk deposits.
    """

    scale: np.ndarray
    best_cost: np.ndarray
    best_edges: np.ndarray
    counters: np.ndarray
    stamps: np.ndarray
    stack: np.ndarray
    stack_prev: np.ndarray
    cand: np.ndarray
    cand_w: np.ndarray
    node_max: np.ndarray

    @classmethod
    def start(cls, n_nodes: int, max_degree: int, trail: np.ndarray, scale: float) -> "ColonyRun":
        """A run before its first iteration, on ``n_nodes`` nodes with at most ``max_degree`` moves each,
        with the stored ``trail`` and its scale."""
        k = max(max_degree, 1)
        return cls(np.array([scale]), np.array([np.inf]), np.zeros(max(n_nodes, 1), dtype=np.int64),
                   np.zeros(5, dtype=np.int64), np.full(n_nodes, -1, dtype=np.int32),
                   np.zeros(n_nodes + 1, dtype=np.int64), np.zeros(n_nodes + 1, dtype=np.int64),
                   np.zeros(k, dtype=np.int64), np.zeros(k), np.full(n_nodes, trail.max(initial=0.0)))


@numba.njit(cache=True)
def _build_list(c, k, base, adj_ptr, adj_offset, place, turn, class_row, pool):
    """Fill node ``c``'s list for heading class ``k`` (header at ``base``): the places of its edges whose move
    the turn table allows, in their original order."""
    row = class_row[k]
    use_turn = turn.shape[0] > 0
    m = 0
    for q in range(adj_ptr[c], adj_ptr[c + 1]):
        if use_turn and turn[row, adj_offset[q]] <= 0.0:
            continue
        m += 1
        pool[base + m] = place[q]
    pool[base] = m + 1


@numba.njit(cache=True)
def _walk_ant(wid, node, weight, move, place, adj_ptr, adj_offset, horizontal, turn, move_class, class_row,
              pool, x, node_max, scale, lo, hi, tau_exp, q0, start, goal, backtrack, max_steps, stamp, stack,
              stack_prev, cand, cand_w):
    """One ant from ``start``; returns ``(outcome, depth, steps)``, the storage places it took in ``stack[:depth]``.

    Step for step :func:`pathzoo_aco.engine.walk._colony` for one ant walking
    alone, reading the allowed list of (node, heading) instead of the node's
    whole adjacency.
    """
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1 if use_turn else 0
    n_classes = class_row.size
    bounded = lo > 0.0 or hi < np.inf
    lo_pow = lo**tau_exp
    d = 0
    pv = no_prev
    n = 0
    stamp[start] = wid
    c = start
    while True:
        if c == goal:
            return REACHED, d, n
        if n >= max_steps:
            return STEP_CAP, d, n
        k = move_class[pv]
        e0 = adj_ptr[c]
        base = (e0 + c) * n_classes + k * (adj_ptr[c + 1] - e0 + 1)
        if pool[base] == 0:
            _build_list(c, k, base, adj_ptr, adj_offset, place, turn, class_row, pool)
        m = pool[base] - 1
        base += 1
        at_floor = scale * node_max[c] <= lo  # every trail from c reads as lo
        nc = 0
        n_open = 0
        total_w = 0.0
        for i in range(m):
            s = e0 + pool[base + i]
            if stamp[node[s]] == wid:
                continue
            if at_floor:
                t = lo
            else:
                t = scale * x[s]
                if bounded:
                    t = min(max(t, lo), hi)
            n_open += 1
            if tau_exp == 1.0:
                w = t * weight[s]
            elif t <= lo:
                w = lo_pow * weight[s]
            else:
                w = t**tau_exp * weight[s]
            if w > 0.0:
                cand[nc] = s
                cand_w[nc] = w
                total_w += w
                nc += 1
        if nc == 0 and n_open > 0:  # every trail weight underflowed: the heuristic alone
            for i in range(m):
                s = e0 + pool[base + i]
                if stamp[node[s]] == wid:
                    continue
                w = weight[s]
                if w > 0.0:
                    cand[nc] = s
                    cand_w[nc] = w
                    total_w += w
                    nc += 1
        if nc == 0:  # dead end
            if not backtrack:
                return STUCK, d, n
            if d == 0:
                return EXHAUSTED, d, n
            d -= 1
            c = node[stack[d - 1]] if d > 0 else start
            if use_turn:
                pv = stack_prev[d - 1] if d > 0 else no_prev
        else:
            sel = cand[nc - 1]
            if q0 > 0.0 and np.random.random() < q0:
                best = -1.0
                for i in range(nc):
                    if cand_w[i] > best:
                        best = cand_w[i]
                        sel = cand[i]
            else:
                r = np.random.random() * total_w
                acc = 0.0
                for i in range(nc):
                    acc += cand_w[i]
                    if r < acc:
                        sel = cand[i]
                        break
            c = node[sel]
            stamp[c] = wid
            stack[d] = sel
            if use_turn:
                o = move[sel]
                if horizontal[o]:
                    pv = o
                stack_prev[d] = pv
            d += 1
        n += 1


@numba.njit(cache=True)
def _colony_run(node, weight, edge, move, place, adj_ptr, adj_offset, move_class, class_row, pool,
                horizontal, turn, graph_indices, graph_offset_id, edge_length, height, turn_angle, cells, f1, f2, f3,
                l_max, l_min, x, scale, lo, hi, rho, tau_exp, q, start, goal, backtrack, max_steps,
                seeds, q0s, ps, ants, first, stop_at, best_cost, best_edges, counters, stamps, stack, stack_prev, cand,
                cand_w, node_max):
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
            wid = counters[1] + a  # walk ids never repeat within a run
            flag, d, n = _walk_ant(wid, node, weight, move, place, adj_ptr, adj_offset, horizontal, turn,
                                   move_class, class_row, pool, x, node_max, scale[0], lo, hi, tau_exp,
                                   q0s[it - first], start, goal, backtrack, max_steps, stamps, stack, stack_prev,
                                   cand, cand_w)
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
            flat_edges[i] = edge[flat[i]]
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
    _colony_run(t.node, t.weight, t.edge, t.move, t.place, t.adj_ptr, t.adj_offset, t.move_class, t.class_row,
                t.pool, horizontal, turn, *fitness, x, run.scale, lo, hi, rho, tau_exp, q, start, goal,
                backtrack, max_steps, seeds, q0s, ps, ants, first, stop_at, run.best_cost, run.best_edges, run.counters,
                run.stamps, run.stack, run.stack_prev, run.cand, run.cand_w, run.node_max)
