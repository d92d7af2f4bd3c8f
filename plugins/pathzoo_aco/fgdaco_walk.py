"""Timed ant walks among moving obstacles: FGDACO's walk engine for ``dynamic`` scenarios.

Among moving obstacles an edge's worth depends on *when* the ant would drive
it. The walks are the timed kernel of the engine's one walk body
(:func:`~pathzoo_aco.engine.walk_kernel.colony_kernel` with ``timed``,
compiled as :func:`~pathzoo_aco.engine.walk_kernel.timed_colony`); this
module gives it its tables. Every ant carries its clock: it leaves
the exact start at ``t = 0``, reaches the start cell's centre after
``|start - centre| / v`` and every further node after the edge's length over
the vehicle's cruise speed ``v``, which is how the harness times the path it
returns (driven without stopping). Backtracking returns the ant to the
node's earlier time, since the returned path is the walk without its dead
ends.

For a candidate edge ``i -> j`` left at ``t_i`` and reached at ``t_j``:

- it is **forbidden** when a moving obstacle's centre comes closer than its
  radius during ``[t_i, t_j]`` (exact, :func:`~pathzoo_aco.fgdaco_moving.obstacle_min_distance`; a quick
  bound skips obstacles that are too far away to matter); an edge into the
  goal also checks the final piece from the goal cell's centre to the exact
  goal;
- otherwise its weight is ``τ^α · priority^β`` where the priority is the
  planner's precomputed static one, unless a moving obstacle at ``t_j`` is
  nearer to ``j`` than every static obstacle: then the fuzzy inference is
  run again with that distance. That is :func:`~pathzoo_aco.fgdaco_fuzzy.priority_one`'s number,
  computed in two exact steps: the rules' ceilings from the edge's fixed
  target and angle inputs (:func:`~pathzoo_aco.fgdaco_fuzzy.rule_ceilings`, once per edge), then the
  firing strengths for the new obstacle input (:func:`~pathzoo_aco.fgdaco_fuzzy.fired_strengths`).
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

from dataclasses import dataclass

import numpy as np

from pathzoo_aco.engine import STUCK, ColonyProblem, Pheromone, WalkEngine, WalkRules, Walks
from pathzoo_aco.engine.walk_kernel import Adjacency
from pathzoo_aco.fgdaco_fuzzy import compiled_priority
from pathzoo_aco.fgdaco_moving import pack_obstacles, route_clearance

__all__ = ["TimedWalkEngine", "timed_product_engine"]


@dataclass
class _TimedBuffers:
    """Work arrays of the timed walks, reused from colony to colony: per depth the clock, the obstacle bounds and
    the number of candidates kept; per obstacle its bound now, the near ones and their arrival positions; per
    edge its fuzzy record."""

    stack_t: np.ndarray
    stack_gap: np.ndarray
    level_n: np.ndarray
    gap: np.ndarray
    near_ids: np.ndarray
    ahead: np.ndarray
    fuzzy_memo: np.ndarray

    @classmethod
    def allocate(cls, problem: ColonyProblem, n_obstacles: int) -> "_TimedBuffers":
        depth = problem.n_free + 1
        return cls(stack_t=np.zeros(depth), stack_gap=np.zeros((depth, n_obstacles)),
                   level_n=np.zeros(depth, dtype=np.int64), gap=np.zeros(n_obstacles),
                   near_ids=np.zeros(n_obstacles, dtype=np.int64), ahead=np.zeros((max(n_obstacles, 1), 2, 3)),
                   fuzzy_memo=np.zeros((problem.graph.n_edges, 4, 4)))


class TimedWalkEngine(WalkEngine):
    """Sends ants that keep time and avoid moving obstacles (see the module docstring).

    The walks are the shared body's timed kernel
    (:func:`~pathzoo_aco.engine.walk_kernel.colony_kernel` with ``timed``):
    ants one after another on the trail as it is at each step, with the
    rules' choice (``rules.q0``) and local update (``rules.local_keep``,
    ``local_add``) on each edge taken; ``rules.weight_mul`` must hold the
    static priorities raised to ``beta`` (FGDACO's eq. 10). With zero fuzzy
    inputs (:func:`timed_product_engine`) no edge is ever re-weighed, so the
    weights are the rule's own.

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
        self.cand_w = np.zeros((problem.n_free + 1) * self.cand_w.size)  # a level of candidates per depth
        buffers = _TimedBuffers.allocate(problem, len(s.moving_obstacles))
        obstacles, route_gap, node_xy = problem.memo(("fgdaco_walk", "obstacle_tables"),
                                                     lambda: self._scenario_tables(problem))
        speed = s.vehicle.cruise_speed
        centres = s.point_of(np.array([problem.start, problem.goal]))
        t_head = float(np.linalg.norm(s.start - centres[0])) / speed
        self.head_free = all(ob.min_distance(s.start, centres[0], 0.0, t_head) >= ob.radius
                             for ob in s.moving_obstacles)
        tail = np.array([*centres[1], *s.goal, float(np.linalg.norm(s.goal - centres[1])) / speed])
        cp = compiled_priority()
        self._timing = (
            np.ascontiguousarray(g.length), float(speed), t_head, tail, node_xy, obstacles.points, obstacles.cum,
            obstacles.count, obstacles.speed, obstacles.phase, obstacles.radius, route_gap, float(sensing_m),
            np.ascontiguousarray(target_in, dtype=np.float64), np.ascontiguousarray(angle_in, dtype=np.float64),
            np.ascontiguousarray(clear_in, dtype=np.float64), float(beta), cp.vertices, cp.rules, cp.consequents,
            cp.area_w, cp.moment_w, buffers.stack_t, buffers.stack_gap, buffers.level_n, buffers.gap,
            buffers.near_ids, buffers.ahead, buffers.fuzzy_memo)
        self._full: tuple = (None, None, None)  # weight_mul, weight_add and the whole graph's lists with them

    @staticmethod
    def _scenario_tables(problem: ColonyProblem) -> tuple:
        """The packed obstacles, each node's :func:`route_clearance` and the cell centres, kept per scenario.

        The centres are ``((node % width + 0.5) cell, (node // width + 0.5) cell)``: read, not computed (an integer
        division each), per candidate.
        """
        s = problem.scenario
        g = problem.graph
        obstacles = pack_obstacles(s.moving_obstacles)
        node = np.arange(g.n_nodes)
        node_xy = np.stack([(node % g.shape[1] + 0.5) * s.cell_size, (node // g.shape[1] + 0.5) * s.cell_size], axis=1)
        return obstacles, route_clearance(obstacles, s.point_of(node)), node_xy

    def adjacency(self, rules: WalkRules) -> Adjacency:
        """Every edge of the graph: the fuzzy priority may give an edge whose ``weight_mul`` is 0 a weight, so none
        is left out (see :meth:`WalkEngine.adjacency`)."""
        mul, add, lists = self._full
        if mul is not rules.weight_mul or add is not rules.weight_add:
            lists = (self.problem.graph.indptr, self.indices, None, self.offset_id, rules.weight_mul, rules.weight_add)
            self._full = (rules.weight_mul, rules.weight_add, lists)
        return lists

    def colony_weights(self, rules: WalkRules, trail: Pheromone) -> None:
        """None: an edge's weight depends on when the ant would drive it, so it is computed at that step."""
        return None

    def timing(self) -> tuple:
        """The clock, obstacle and fuzzy arrays the timed kernel reads, and its buffers."""
        return self._timing

    def walk(self, rules: WalkRules, trail: Pheromone, n_ants: int, seed: int,
             allowance: int = 2**62) -> Walks:
        """Send ``n_ants`` timed ants from the start (see :meth:`WalkEngine.walk`); every ant is :data:`STUCK`
        when a moving obstacle hits the first piece, exact start to the start cell's centre."""
        if not self.head_free:
            return Walks(np.zeros(0, dtype=np.int64), np.zeros(n_ants + 1, dtype=np.int64),
                         np.full(n_ants, STUCK, dtype=np.int8), np.zeros(n_ants, dtype=np.int64), n_ants)
        if rules.race or rules.pre_add.size:
            raise ValueError("timed ants walk one after another, without pre-choice additions")
        return super().walk(rules, trail, n_ants, seed, allowance)


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
