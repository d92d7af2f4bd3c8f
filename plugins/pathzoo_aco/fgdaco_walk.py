"""Timed ant walks among moving obstacles: FGDACO's walk engine for ``dynamic`` scenarios.

The shared kernel (:mod:`pathzoo_aco.engine.walk`) weighs edges by numbers
fixed before the colony; among moving obstacles an edge's worth depends on
*when* the ant would drive it. Here every ant carries its clock: it leaves
the exact start at ``t = 0``, reaches the start cell's centre after
``|start - centre| / v`` and every further node after the edge's length over
the vehicle's cruise speed ``v``, which is how the harness times the path it
returns (driven without stopping). Backtracking returns the ant to the
node's earlier time, since the returned path is the walk without its dead
ends.

For a candidate edge ``i -> j`` left at ``t_i`` and reached at ``t_j``:

- it is **forbidden** when a moving obstacle's centre comes closer than its
  radius during ``[t_i, t_j]`` (exact, :func:`obstacle_min_distance`; a quick
  bound skips obstacles that are too far away to matter); an edge into the
  goal also checks the final piece from the goal cell's centre to the exact
  goal;
- otherwise its weight is ``τ^α · priority^β`` where the priority is the
  planner's precomputed static one, unless a moving obstacle at ``t_j`` is
  nearer to ``j`` than every static obstacle: then the fuzzy inference is
  run again with that distance. That is :func:`priority_one`'s number,
  computed in two exact steps: the rules' ceilings from the edge's fixed
  target and angle inputs (:func:`rule_ceilings`, once per edge), then the
  firing strengths for the new obstacle input (:func:`fired_strengths`).
  The centroid depends on those three strengths only, so each edge keeps
  the last ones it saw and their priority (about half the centroids on
  ``fgdaco.scenario3`` are repeats: a very near obstacle saturates the
  input), beside its ceilings in one 4 x 4 record: two cache lines, since
  the walks wait on memory more than they compute.

An ant that backs up to a node is there again at the same time, with the
same trails: the candidates and weights of its first visit are reused, less
the nodes it has stamped since (the same list, in the same order, as
weighing them again), and the obstacle bounds of that visit are restored
instead of being measured again. The bounds only decide which exact checks
run; where a bound lets a check be skipped the check would have passed, so
the walks are the same (``benchmarks/identity.py``).

Per node and obstacle, :func:`route_clearance` (the distance to the
obstacle's whole route, whatever the time) is a bound kept from the start:
an obstacle whose route is out of reach from a node is not measured there.

A walk whose tabu list and backtracking exhaust the start's component
proves the goal unreachable only when no edge was refused for timing; such
walks end :data:`STUCK` rather than :data:`EXHAUSTED`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from pathzoo_aco.engine import ABORTED, EXHAUSTED, REACHED, STEP_CAP, STUCK, ColonyProblem, Pheromone, WalkEngine
from pathzoo_aco.engine import WalkRules, Walks
from pathzoo_aco.engine.steps import heaviest, kept_candidates, local_update, read_trail, roulette, trail_power
from pathzoo_aco.engine.walk import _seed
from pathzoo_aco.fgdaco_fuzzy import clipped_centroid, compiled_priority, fired_strengths, rule_ceilings
from pathzoo_aco.fgdaco_moving import obstacle_min_distance, obstacle_position, pack_obstacles, route_clearance

__all__ = ["TimedWalkEngine", "timed_product_engine"]

UNDER = 1.0 - 1e-12
"""Shrinks a measured distance that only serves as a bound, so that ``sqrt`` (faster than ``hypot``) stays below it.

The rounding of either is below 1e-15 of the distance; the bound only decides which exact checks run.
"""


@numba.njit(cache=True)
def _timed_walk(indptr, indices, offset_id, horizontal, turn, length,
                x, scale, lo, hi, tau_exp, w_mul, beta, q0, local_keep, local_add,
                start, goal, backtrack, max_steps, allowance, n_ants, walk_base,
                stamp, stack_e, stack_prev, stack_t, stack_gap, cand_e, cand_w, cand_n, gap, near_ids, ahead,
                flat, offsets, flags, steps_out,
                node_xy, speed, t_head, tail,
                ob_points, ob_cum, ob_count, ob_speed, ob_phase, ob_radius, route_gap,
                target_in, angle_in, clear_in, sensing, fuzzy_memo,
                vertices, rules, cons, area_w, moment_w):
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1
    do_local = local_keep != 1.0 or local_add != 0.0
    degree = cand_e.size // stack_e.size  # candidate slots per depth
    n_obs = ob_count.size
    lo_pow = lo**tau_exp
    max_len = 0.0
    for e in range(length.size):
        max_len = max(max_len, length[e])
    shrink = np.empty(n_obs)  # per metre the ant drives, a gap shrinks by at most this much
    reach = np.empty(n_obs)  # a gap beyond this cannot matter for any move from here
    for k in range(n_obs):
        shrink[k] = 1.0 + ob_speed[k] / speed
        reach[k] = max_len * shrink[k] + sensing
    total = 0
    a = 0
    while a < n_ants:
        wid = walk_base + a
        cur = start
        t_cur = t_head
        depth = 0
        prev = no_prev
        steps = 0
        flag = REACHED
        timed_out = False  # some edge was refused because of a moving obstacle
        stamp[start] = wid
        gap[:] = -np.inf  # lower bounds on each obstacle's distance (edge to centre of node) now: unknown
        returned = False  # the ant has just backed up to ``cur``: same node, same time, same weights as before
        while cur != goal:
            if steps >= max_steps:
                flag = STEP_CAP
                break
            if total >= allowance:
                flag = ABORTED
                break
            base = depth * degree
            nc = 0
            total_w = 0.0
            if returned:  # the candidates of the first visit, less the nodes stamped since, in the same order
                nc, total_w, _ = kept_candidates(cand_e, cand_w, base, cand_n[depth], indices, stamp, wid)
            else:
                cx = node_xy[cur, 0]
                cy = node_xy[cur, 1]
                n_near = 0  # obstacles that may touch a move from here or come within sensing range of its end
                for k in range(n_obs):
                    if gap[k] < reach[k]:  # the bound says nothing: measure, unless the whole route is out of reach
                        if route_gap[cur, k] >= reach[k]:
                            gap[k] = route_gap[cur, k]
                            continue
                        ox, oy = obstacle_position(ob_points, ob_cum, ob_count, ob_speed, ob_phase, k, t_cur)
                        dx = cx - ox
                        dy = cy - oy
                        gap[k] = math.sqrt(dx * dx + dy * dy) * UNDER - ob_radius[k]
                        if gap[k] < reach[k]:
                            near_ids[n_near] = k
                            ahead[n_near, 0, 0] = -1.0  # no arrival position of this obstacle computed yet
                            ahead[n_near, 1, 0] = -1.0
                            n_near += 1
                for k in range(n_obs):  # restored if the ant backs up to here (loops: a slice costs a reference count)
                    stack_gap[depth, k] = gap[k]
                for e in range(indptr[cur], indptr[cur + 1]):
                    j = indices[e]
                    if stamp[j] == wid:
                        continue
                    f = 1.0
                    if use_turn:
                        f = turn[prev, offset_id[e]]
                        if f <= 0.0:
                            continue
                    near = clear_in[j]
                    free = True
                    dt = 0.0
                    t_next = t_cur
                    if n_near > 0 or j == goal:  # the move's timing and end point matter only near obstacles
                        dt = length[e] / speed
                        t_next = t_cur + dt
                    jx = 0.0
                    jy = 0.0
                    if n_near > 0:
                        jx = node_xy[j, 0]
                        jy = node_xy[j, 1]
                    for q in range(n_near):
                        k = near_ids[q]
                        bound = gap[k] - length[e] - ob_speed[k] * dt  # least possible gap during the move
                        if bound <= 0.0 and obstacle_min_distance(ob_points, ob_cum, ob_count, ob_speed, ob_phase, k,
                                                                  cx, cy, jx, jy, t_cur, t_next) < ob_radius[k]:
                            free = False
                            break
                        if bound < near * sensing:  # moves of one length arrive together: reuse the position
                            slot = 0 if ahead[q, 0, 0] == dt or ahead[q, 0, 0] < 0.0 else 1
                            if ahead[q, slot, 0] != dt:
                                ox, oy = obstacle_position(ob_points, ob_cum, ob_count, ob_speed, ob_phase, k, t_next)
                                ahead[q, slot, 0] = dt
                                ahead[q, slot, 1] = ox
                                ahead[q, slot, 2] = oy
                            ox = ahead[q, slot, 1]
                            oy = ahead[q, slot, 2]
                            near = min(near, max(math.hypot(jx - ox, jy - oy) - ob_radius[k], 0.0) / sensing)
                    if free and j == goal and tail[4] > 0.0:
                        for k in range(n_obs):
                            d = obstacle_min_distance(ob_points, ob_cum, ob_count, ob_speed, ob_phase, k, tail[0],
                                                      tail[1], tail[2], tail[3], t_next, t_next + tail[4])
                            if d < ob_radius[k]:
                                free = False
                                break
                    if not free:
                        timed_out = True
                        continue
                    if near < clear_in[j]:  # the fuzzy inference of priority_one, in two exact steps
                        if fuzzy_memo[e, 0, 3] == 0.0:  # first time: the ceilings; no strengths seen yet
                            rule_ceilings(target_in[j], angle_in[e], vertices, rules, fuzzy_memo, e)
                            fuzzy_memo[e, 0, 3] = 1.0
                            fuzzy_memo[e, 3, 0] = np.nan
                            fuzzy_memo[e, 3, 1] = np.nan
                            fuzzy_memo[e, 3, 2] = np.nan
                        s0, s1, s2 = fired_strengths(fuzzy_memo, e, near, vertices)
                        if s0 != fuzzy_memo[e, 3, 0] or s1 != fuzzy_memo[e, 3, 1] or s2 != fuzzy_memo[e, 3, 2]:
                            fuzzy_memo[e, 3, 0] = s0
                            fuzzy_memo[e, 3, 1] = s1
                            fuzzy_memo[e, 3, 2] = s2
                            fuzzy_memo[e, 3, 3] = clipped_centroid(s0, s1, s2, cons, area_w, moment_w)**beta
                        h = fuzzy_memo[e, 3, 3]
                    else:
                        h = w_mul[e]
                    w = trail_power(read_trail(scale, x[e], lo, hi, True), tau_exp, lo, lo_pow) * h * f
                    if w > 0.0:
                        cand_e[base + nc] = e
                        cand_w[base + nc] = w
                        total_w += w
                        nc += 1
            cand_n[depth] = nc
            returned = False
            if nc == 0:  # dead end (at this time)
                if not backtrack:
                    flag = STUCK
                    break
                if depth == 0:
                    flag = STUCK if timed_out else EXHAUSTED
                    break
                depth -= 1
                cur = indices[stack_e[depth - 1]] if depth > 0 else start
                t_cur = stack_t[depth - 1] if depth > 0 else t_head
                for k in range(n_obs):
                    gap[k] = stack_gap[depth, k]
                returned = True
                if use_turn:
                    prev = stack_prev[depth - 1] if depth > 0 else no_prev
                steps += 1
                total += 1
                continue
            if q0 > 0.0 and np.random.random() < q0:  # ACS: the first of the heaviest
                sel = cand_e[heaviest(cand_w, base, nc)]
            else:
                sel = cand_e[roulette(cand_w, base, nc, total_w)]
            if do_local:  # ACS's local update on the edge just taken, as the static kernel does it
                local_update(x, sel, scale, lo, hi, local_keep, local_add)
            t_cur += length[sel] / speed
            for k in range(n_obs):  # the gap shrinks by at most the distance both have moved
                gap[k] -= length[sel] * shrink[k]
            cur = indices[sel]
            stamp[cur] = wid
            stack_e[depth] = sel
            stack_t[depth] = t_cur
            if use_turn:
                o = offset_id[sel]
                if horizontal[o]:
                    prev = o
                stack_prev[depth] = prev
            depth += 1
            steps += 1
            total += 1
        flags[a] = flag
        steps_out[a] = steps
        base = offsets[a]
        if flag == REACHED:
            flat[base : base + depth] = stack_e[:depth]
            offsets[a + 1] = base + depth
        else:
            offsets[a + 1] = base
        a += 1
        if flag == ABORTED or flag == EXHAUSTED:
            break
    for b in range(a, n_ants):  # never started
        flags[b] = ABORTED
        steps_out[b] = 0
        offsets[b + 1] = offsets[a]
    return a, total


@dataclass
class _TimedBuffers:
    """Work arrays of the timed walks, reused from colony to colony."""

    stamp: np.ndarray
    stack_e: np.ndarray
    stack_prev: np.ndarray
    stack_t: np.ndarray
    stack_gap: np.ndarray
    cand_e: np.ndarray
    cand_w: np.ndarray
    cand_n: np.ndarray
    gap: np.ndarray
    near_ids: np.ndarray
    ahead: np.ndarray
    fuzzy_memo: np.ndarray
    flat: np.ndarray
    walk_base: int = 0

    @classmethod
    def allocate(cls, problem: ColonyProblem, n_obstacles: int) -> "_TimedBuffers":
        g = problem.graph
        depth = problem.n_free + 1
        degree = max(int(g.degree.max()) if g.n_nodes else 0, 1)
        return cls(stamp=np.full(g.n_nodes, -1, dtype=np.int32), stack_e=np.zeros(depth, dtype=np.int64),
                   stack_prev=np.zeros(depth, dtype=np.int64), stack_t=np.zeros(depth),
                   stack_gap=np.zeros((depth, n_obstacles)),
                   cand_e=np.zeros(depth * degree, dtype=np.int64), cand_w=np.zeros(depth * degree),
                   cand_n=np.zeros(depth, dtype=np.int64), gap=np.zeros(n_obstacles),
                   near_ids=np.zeros(n_obstacles, dtype=np.int64), ahead=np.zeros((max(n_obstacles, 1), 2, 3)),
                   fuzzy_memo=np.zeros((g.n_edges, 4, 4)),
                   flat=np.zeros(0, dtype=np.int64))


class TimedWalkEngine(WalkEngine):
    """Sends ants that keep time and avoid moving obstacles (see the module docstring).

    Supports the product rule ``τ^α η^β`` on edge trails with roulette
    choice (FGDACO's eq. 10), and ACS's pseudo-random-proportional choice
    (``rules.q0``) and local update (``rules.local_keep``, ``local_add``) on
    each edge taken: ``rules.weight_mul`` must hold the static priorities
    raised to ``beta``. With zero fuzzy inputs (:func:`timed_product_engine`)
    no edge is ever re-weighed, so the weights are the rule's own.

    Parameters
    ----------
    problem : ColonyProblem
        A 2-D scenario, usually ``dynamic``.
    target_in, clear_in : ndarray, shape (N,)
        Per node: normalised distance to the target and to the nearest static obstacle.
    angle_in : ndarray, shape (E,)
        Per edge: normalised angle to be turned.
    sensing_m : float
        Distance (m) that normalises obstacle distances to ``[0, 1]``.
    beta : float
        Exponent on the priority.
    """

    def __init__(self, problem: ColonyProblem, *, target_in: np.ndarray, angle_in: np.ndarray,
                 clear_in: np.ndarray, sensing_m: float, beta: float) -> None:
        super().__init__(problem)
        s = problem.scenario
        g = problem.graph
        self.buffers = _TimedBuffers.allocate(problem, len(s.moving_obstacles))
        self.obstacles, self.route_gap, self.graph_arrays, self.node_xy = problem.memo(
            ("fgdaco_walk", "scenario_tables"), lambda: self._scenario_tables(problem))
        self.length = np.ascontiguousarray(g.length)
        self.target_in = np.ascontiguousarray(target_in, dtype=np.float64)
        self.angle_in = np.ascontiguousarray(angle_in, dtype=np.float64)
        self.clear_in = np.ascontiguousarray(clear_in, dtype=np.float64)
        self.sensing_m = float(sensing_m)
        self.beta = float(beta)
        speed = s.vehicle.cruise_speed
        centres = s.point_of(np.array([problem.start, problem.goal]))
        self.t_head = float(np.linalg.norm(s.start - centres[0])) / speed
        self.head_free = all(ob.min_distance(s.start, centres[0], 0.0, self.t_head) >= ob.radius
                             for ob in s.moving_obstacles)
        tail_time = float(np.linalg.norm(s.goal - centres[1])) / speed
        self.tail = np.array([*centres[1], *s.goal, tail_time])

    @staticmethod
    def _scenario_tables(problem: ColonyProblem) -> tuple:
        """The packed obstacles, each node's :func:`route_clearance`, the int32 graph arrays and the cell centres.

        Kept per scenario. The centres are ``((node % width + 0.5) cell, (node // width + 0.5) cell)``, the
        numbers the walks used to compute per candidate (an integer division each).
        """
        s = problem.scenario
        g = problem.graph
        obstacles = pack_obstacles(s.moving_obstacles)
        node = np.arange(g.n_nodes)
        node_xy = np.stack([(node % g.shape[1] + 0.5) * s.cell_size, (node // g.shape[1] + 0.5) * s.cell_size], axis=1)
        return (obstacles, route_clearance(obstacles, s.point_of(node)),
                (g.indptr, g.indices.astype(np.int32), g.offset_id.astype(np.int32), problem.horizontal_offsets),
                node_xy)

    def walk(self, rules: WalkRules, trail: Pheromone, n_ants: int, seed: int,
             allowance: int = 2**62) -> Walks:
        """Send ``n_ants`` timed ants from the start (see :meth:`WalkEngine.walk`)."""
        p = self.problem
        g = p.graph
        offsets = np.zeros(n_ants + 1, dtype=np.int64)
        flags = np.full(n_ants, STUCK, dtype=np.int8)
        steps = np.zeros(n_ants, dtype=np.int64)
        if not self.head_free:  # the first piece, exact start -> start cell centre, is always hit
            return Walks(np.zeros(0, dtype=np.int64), offsets, flags, steps, n_ants)
        b = self.buffers
        if b.walk_base + n_ants >= 2**31 - 1:  # the int32 walk stamps would overflow: start afresh
            b.stamp[:] = -1
            b.walk_base = 0
        if b.flat.size < n_ants * (p.n_free + 1):  # a walk is a simple path: at most n_free edges
            b.flat = np.zeros(n_ants * (p.n_free + 1), dtype=np.int64)
        _seed(seed)
        ob = self.obstacles
        cp = compiled_priority()
        started, total = _timed_walk(
            *self.graph_arrays, rules.turn, self.length,
            trail.x, trail.scale, trail.lo, trail.hi, rules.tau_exp, rules.weight_mul, self.beta,
            rules.q0, rules.local_keep, rules.local_add, p.start, p.goal, rules.backtrack, rules.max_steps, allowance, n_ants, b.walk_base,
            b.stamp, b.stack_e, b.stack_prev, b.stack_t, b.stack_gap, b.cand_e, b.cand_w, b.cand_n, b.gap, b.near_ids,
            b.ahead,
            b.flat, offsets, flags, steps,
            self.node_xy, p.scenario.vehicle.cruise_speed, self.t_head, self.tail,
            ob.points, ob.cum, ob.count, ob.speed, ob.phase, ob.radius, self.route_gap,
            self.target_in, self.angle_in, self.clear_in, self.sensing_m, b.fuzzy_memo,
            cp.vertices, cp.rules, cp.consequents, cp.area_w, cp.moment_w,
        )
        b.walk_base += n_ants
        self.total_steps += int(total)
        used = int(offsets[-1])
        return Walks(b.flat[:used].copy(), offsets, flags, steps, int(started))


def timed_product_engine(problem: ColonyProblem, beta: float, sensing_m: float = 10.0) -> WalkEngine:
    """The walks of a product-rule colony: timed among moving obstacles, else the shared static engine.

    The timed engine gets zero fuzzy inputs, so an edge's weight is the
    rule's ``τ^α η^β`` (with ACS's ``q0`` and local update when the rules
    set them) and a moving obstacle only forbids the edges it would hit at
    the time the ant drives them. ``sensing_m`` only scales the (unused)
    obstacle input.
    """
    if not problem.scenario.moving_obstacles:
        return WalkEngine(problem)
    g = problem.graph
    zeros_n = np.zeros(g.n_nodes)
    return TimedWalkEngine(problem, target_in=zeros_n, angle_in=np.zeros(g.n_edges), clear_in=zeros_n,
                           sensing_m=sensing_m, beta=beta)
