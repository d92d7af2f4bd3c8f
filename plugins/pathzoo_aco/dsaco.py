"""aco.dsaco: the dual-strategy ACO of Mai et al. (Intelligence & Robotics, 2023), eqs. 2-3 and 11-23.

Mechanism, with the paper's equations:

- **flight constraints** (eqs. 2-3): a walk longer than ``L_max`` or with a
  straight segment (a run of steps in one direction, the last one excepted)
  shorter than ``L_min`` is infeasible: its fitness is infinite, so it never
  becomes the best walk and never deposits (:meth:`DSACO.infeasible_walks`).
  The paper gives no values; ``l_max = l_min = 0`` switches them off;

- **search heuristic** ``η = S · M · D`` (eqs. 11-13): ``S`` admits a node
  only at least ``h_c`` above the ground under it, ``M = 1 / (1 + h)``
  favours low flight and ``D = 1 / (step + distance to the target)`` pulls
  toward the target (:meth:`DSACO.search_heuristic`);
- **dual transition** (eqs. 14-15): with probability ``q0`` the ant takes the
  heaviest ``τ^α η^β``, otherwise it draws by roulette; ``q0`` falls from
  ``q0_initial`` over the first 70 % of the iterations, then jumps to half of
  it and rises again (:func:`q0_schedule`, :meth:`DSACO.before_iteration`);
- **best-ant update** (eqs. 16-18): all trails evaporate and only the
  iteration's best ant deposits ``Q / ((1 - p) F_now + p F_global)``; trails
  stay in ``[τmin, τmax]`` (:meth:`DSACO.update_trail`);
- **p decay** (eq. 19): ``p`` is multiplied by ``γ_p = 0.9`` every 100
  iterations (:func:`p_schedule`);
- **fitness** (eqs. 20-23): ``f1 D0 + f2 Dh + f3 DT`` -- length, summed
  segment heights and summed turning angles -- is what "best" means
  (:meth:`DSACO.walk_costs`).

:meth:`DSACO.plan` runs the colony in compiled code
(:mod:`pathzoo_aco.dsaco_colony`) with the same results as the generic loop
(``extras["walk_time_s"]`` is the compiled colony's time); a clock limit is
checked between iterations and only stops it.

Lengths and heights are measured in horizontal cells (the paper's
kilometres on its 1 km grid). Table 4: m = 10, n = 500, Q = 100, α = 1,
β = 8, ρ = 0.2, τmax = 0.9, τmin = 0.03, p = 1. See
``docs/planners/aco.dsaco.md`` for every interpretation.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace
from typing import Any, Callable, Mapping

import numba
import numpy as np

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidParameterError
from pathzoo.core.planner import Param, ProgressCallback
from pathzoo.core.results import PlanResult
from pathzoo.core.scenario import Scenario
from pathzoo.core.status import Status
from pathzoo_aco.dsaco_colony import run_colony
from pathzoo_aco.dsaco_tables import ColonyRun, MoveTable
from pathzoo_aco.dsaco_fitness import infeasible_walks, walk_fitness
from pathzoo_aco.engine import (
    AntColonyPlanner,
    ColonyProblem,
    ColonyState,
    Pheromone,
    WalkEngine,
    WalkRules,
    Walks,
    colony_params,
    deposit_walks,
)

__all__ = ["DSACO", "DsacoState", "q0_schedule", "p_schedule"]


def q0_schedule(k: int, k_max: int, q0_initial: float) -> float:
    """Eq. 15: ``q0`` at (0-based) iteration ``k`` of ``k_max``; iterations past ``k_max`` keep its last value.

    ``q0 = (K - k) / K · q0_initial`` for ``k < k0 = 0.7 K``, and
    ``(k - k0) / K · q0_initial + q0_initial / 2`` from ``k0`` on.
    """
    k = min(k, k_max)
    k0 = 0.7 * k_max
    if k < k0:
        return (k_max - k) / k_max * q0_initial
    return (k - k0) / k_max * q0_initial + q0_initial / 2.0


def p_schedule(t: int, p_initial: float, gamma: float, every: int = 100) -> float:
    """Eq. 19: the weight ``p`` used at (1-based) iteration ``t``: ``p_initial · γ^floor((t - 1) / every)``."""
    return p_initial * gamma ** ((t - 1) // every)


def _per_walk(per_position: np.ndarray, walks: Walks) -> np.ndarray:
    """Sum a value given per position of ``walks.flat`` over each walk (``inf`` for walks that failed)."""
    cum = np.concatenate([[0.0], np.cumsum(per_position)])
    return np.where(walks.reached, cum[walks.offsets[1:]] - cum[walks.offsets[:-1]], np.inf)


def _eta(m: np.ndarray, root: np.ndarray, admitted: np.ndarray, length: np.ndarray, cells: float) -> np.ndarray:
    """Eqs. 11-13 for broadcastable node terms ``M``, ``sqrt(1 + d²)``, ``S`` and step lengths (m)."""
    return np.where(admitted, m * (1.0 / (length / cells + root)), 0.0)


_SCHEDULE_CHUNK = 4096
"""Iterations whose seeds and schedules are computed at a time by :meth:`DSACO.plan`."""
_UNCOUNTED = 2**62
"""Iterations scheduled under a clock-only budget: more than any clock allows."""


@numba.njit(cache=True)
def _gather(rows, offset_id, table, length_class, move_factor, refused):
    """Per edge ``e``: ``table[rows[e], length_class[move(e)]]``, or ``refused`` where the move's factor is 0.

    The step rule's factor is 1 or 0, so ``η · 1 = η`` and ``η · 0 = 0``
    exactly: gathering instead of multiplying changes no value.
    """
    out = np.empty(rows.size)
    for e in range(rows.size):
        o = offset_id[e]
        out[e] = table[rows[e], length_class[o]] if move_factor[o] != 0.0 else refused
    return out


@numba.njit(cache=True)
def _move_lengths(offset_id, length, n_moves):
    """Per move the length of its edges, and whether every edge of a move has the same one (one pass over the edges).

    Moves without edges get 0. ``consistent`` is False as soon as an edge's
    length differs from the first of its move (or is NaN), as
    ``np.array_equal(length, step[offset_id])`` would say.
    """
    step = np.zeros(n_moves)
    seen = np.zeros(n_moves, dtype=np.bool_)
    consistent = True
    for e in range(length.size):
        o = offset_id[e]
        if not seen[o]:
            step[o] = length[e]
            seen[o] = True
        if length[e] != step[o]:
            consistent = False
    return step, consistent


@dataclass
class DsacoState(ColonyState):
    """Colony state plus the flight height of every node (in cells) and the turn angle between moves."""

    node_height: np.ndarray | None = None
    turn_angle: np.ndarray | None = None


class DSACO(AntColonyPlanner):
    """DSACO (Mai et al. 2023) with the parameters of its Table 4."""

    id = "aco.dsaco"
    version = "1"
    summary = "DSACO (Mai et al. 2023): S·M·D heuristic, q0 schedule, best-ant fitness update, p decay"
    kinds = frozenset({"air3d", "grid2d"})
    params = {
        **colony_params(n_ants=10, iterations=500, alpha=1.0, beta=8.0, rho=0.2),
        "q": Param(100.0, "pheromone intensity Q (eq. 17)", low=0.0, low_open=True),
        "tau_max": Param(0.9, "upper trail bound τmax (eq. 18); also τ0", low=0.0, low_open=True),
        "tau_min": Param(0.03, "lower trail bound τmin (eq. 18)", low=0.0, low_open=True),
        "p": Param(1.0, "initial weight p of the global best fitness (eq. 17)", low=0.0, high=1.0),
        "gamma_p": Param(0.9, "decay γ_p of p every 100 iterations (eq. 19)", low=0.0, high=1.0),
        "q0_initial": Param(0.9, "q0_initial of the q0 schedule (eq. 15; not given in the paper)", low=0.0, high=1.0),
        "h_c": Param(50.0, "safety height h_c above the ground for S (eq. 11), m", low=0.0),
        "f1": Param(1.0, "weight of the length D0 (eq. 20; not given)", low=0.0),
        "f2": Param(0.1, "weight of the summed segment heights Dh (eq. 20; not given)", low=0.0),
        "f3": Param(1.0, "weight of the summed turning angles DT in radians (eq. 20; not given)", low=0.0),
        "l_max": Param(0.0, "maximum path length L_max in cells (eq. 2; not given; 0 = no limit)", low=0.0),
        "l_min": Param(0.0, "minimum straight-segment length L_min in cells (eq. 3; not given; 0 = no limit)",
                       low=0.0),
        "step_rule": Param("graph", "moves: the scenario's whole neighbourhood graph, or the paper's longitude "
                           "rule (one cell along x toward the target per step)", choices=("graph", "longitude")),
    }

    def _check_params(self, values: Mapping[str, Any]) -> None:
        if values["tau_min"] >= values["tau_max"]:
            raise InvalidParameterError(
                f"{self.id}: parameter 'tau_min' must be < tau_max ({values['tau_max']!r}), got {values['tau_min']!r}")
        if values["f1"] + values["f2"] + values["f3"] == 0.0:
            raise InvalidParameterError(f"{self.id}: parameters 'f1', 'f2', 'f3' must not all be 0 (fitness of eq. 20)")

    # ------------------------------------------------------------- heuristic
    @staticmethod
    def node_height(problem: ColonyProblem) -> np.ndarray:
        """Flight height ``h`` of every node in horizontal cells (0 on flat maps)."""
        return problem.node_xyz[:, 2] / problem.scenario.cell_size

    def search_heuristic(self, problem: ColonyProblem) -> np.ndarray:
        """Eqs. 11-13 per edge ``i -> j``: ``S_j · M_j · D_ij``.

        ``S_j = 1`` when ``j`` is at least ``h_c`` above the ground under it
        (always 1 without a ground model), ``M_j = 1 / (1 + h_j)`` and
        ``D_ij = 1 / (ℓ_ij + sqrt(1 + d_jB²))`` with ``ℓ`` the step and
        ``d_jB`` the straight distance from ``j`` to the target, all in cells.
        """
        return self._per_edge(problem, lambda table: table, 0.0)

    def heuristic_power(self, problem: ColonyProblem) -> np.ndarray:
        """``η^β`` per edge: :meth:`search_heuristic` raised to ``beta``, with ``np.power`` as
        :meth:`WalkRules.product` applies it, but evaluated once per (target node, step length) rather than
        once per edge (the same values: ``η`` depends on nothing else)."""
        return self._per_edge(problem, lambda table: np.power(table, self.beta),
                              float(np.power(np.zeros(1), self.beta)[0]))

    def _per_edge(self, problem: ColonyProblem, of_eta: Callable[[np.ndarray], np.ndarray],
                  refused: float, by_node: bool = True) -> np.ndarray:
        """``of_eta(η)`` per edge, and ``refused`` on the edges the step rule refuses (where ``η = 0``).

        ``η`` is computed per target node and distinct step length when every
        move's edges have one length (grids: always) and ``by_node``, else per
        edge (the same values, checked by the tests).
        """
        s = problem.scenario
        g = problem.graph
        h = self.node_height(problem)
        admitted = np.ones(g.n_nodes, dtype=bool)
        if s.elevation is not None:
            ground = np.broadcast_to(s.elevation, s.shape).reshape(-1)
            admitted = problem.node_xyz[:, 2] >= np.nan_to_num(ground, nan=np.inf) + self.h_c
        m = 1.0 / (1.0 + h)
        root = np.sqrt(1.0 + (problem.goal_distance / s.cell_size) ** 2)
        step, consistent = _move_lengths(g.offset_id, g.length, len(g.offsets))
        if by_node and consistent:
            lengths, length_class = np.unique(step, return_inverse=True)
            table = _eta(m[:, None], root[:, None], admitted[:, None], lengths[None, :], s.cell_size)
            return _gather(g.indices, g.offset_id, of_eta(table), length_class.reshape(-1),
                           self.move_factor(problem), refused)
        j = g.indices
        table = _eta(m[j], root[j], admitted[j], g.length, s.cell_size).reshape(-1, 1)
        return _gather(np.arange(g.n_edges), g.offset_id, of_eta(table), np.zeros(len(g.offsets), dtype=np.int64),
                       self.move_factor(problem), refused)

    def allowed_moves(self, problem: ColonyProblem) -> np.ndarray:
        """1 for the edges the step rule allows, 0 for the others (all 1 under ``step_rule="graph"``)."""
        return self.move_factor(problem)[problem.graph.offset_id]

    def move_factor(self, problem: ColonyProblem) -> np.ndarray:
        """Per move of the neighbourhood: 1 if the step rule allows it, else 0.

        The longitude rule (section 2.1.2) keeps the moves that advance exactly
        one cell along ``x`` toward the target's column, with any lateral and
        vertical step the scenario's graph allows.
        """
        g = problem.graph
        if self.step_rule == "graph":
            return np.ones(len(g.offsets))
        width = g.shape[-1]
        direction = np.sign(problem.goal % width - problem.start % width)
        return ((g.offsets[:, -1] == direction) & (direction != 0)).astype(np.float64)

    def heuristic(self, problem: ColonyProblem) -> np.ndarray:
        """``η = Q_search = S · M · D`` (eqs. 11-13)."""
        return self.search_heuristic(problem)

    def walk_rules(self, problem: ColonyProblem) -> WalkRules:
        """Eq. 14: ``τ^α η^β`` with the deterministic choice of probability ``q0`` (set per iteration)."""
        return WalkRules(tau_exp=float(self.alpha), weight_mul=self.heuristic_power(problem), q0=self.q0_initial,
                         **self.walk_options(problem))

    def before_iteration(self, state: ColonyState) -> WalkRules:
        """Eq. 15: the iteration's ``q0`` (the schedule spans the ``iterations`` parameter)."""
        return replace(state.rules, q0=q0_schedule(state.iteration, self.iterations, self.q0_initial))

    # ------------------------------------------------------------- trail and fitness
    def initial_trail(self, problem: ColonyProblem) -> float:
        """``τ0 = τmax``."""
        return self.tau_max

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> DsacoState:
        """Bound the trail to ``[τmin, τmax]``; precompute node heights and the turn angle between moves.

        The fitness terms are computed along the walks only (O(walk length)
        per iteration, nothing per edge).
        """
        trail.set_bounds(self.tau_min, self.tau_max)
        g = problem.graph
        moves = g.offsets[:, ::-1] * problem.scenario.cell_sizes  # world vectors (x, y[, z])
        unit = moves / np.linalg.norm(moves, axis=1, keepdims=True)
        turn = np.arccos(np.clip(unit @ unit.T, -1.0, 1.0))
        return DsacoState(problem, rules, trail, rng, node_height=self.node_height(problem), turn_angle=turn)

    @staticmethod
    def step_turns(state: ColonyState, walks: Walks) -> np.ndarray:
        """Per position of ``walks.flat``: the angle (radians) between that segment and the walk's previous one."""
        assert isinstance(state, DsacoState) and state.turn_angle is not None
        moves = state.problem.graph.offset_id[walks.flat]
        turns = np.zeros(moves.size)
        if moves.size > 1:
            turns[1:] = state.turn_angle[moves[:-1], moves[1:]]
        turns[walks.offsets[:-1][walks.offsets[:-1] < moves.size]] = 0.0  # no turn into a walk's first segment
        return turns

    def fitness_terms(self, state: ColonyState, walks: Walks) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(D0, Dh, DT)`` of every walk (eqs. 21-23; ``inf`` for walks that failed).

        ``D0`` sums the segment lengths and ``Dh`` the segment heights (mean
        of both ends), in cells; ``DT`` sums the angles (radians) between
        consecutive segments.
        """
        assert isinstance(state, DsacoState) and state.node_height is not None
        g = state.problem.graph
        h = state.node_height
        height = 0.5 * (h[g.sources[walks.flat]] + h[g.indices[walks.flat]])
        return (_per_walk(g.length[walks.flat] / state.problem.scenario.cell_size, walks), _per_walk(height, walks),
                _per_walk(self.step_turns(state, walks), walks))

    def walk_costs(self, state: ColonyState, walks: Walks) -> np.ndarray:
        """Eq. 20: ``Fitness = f1 D0 + f2 Dh + f3 DT`` (one compiled pass over the walks)."""
        assert isinstance(state, DsacoState) and state.node_height is not None and state.turn_angle is not None
        p = state.problem
        costs = walk_fitness(walks.flat, walks.offsets, walks.reached, p.graph.indices, p.graph.offset_id,
                              p.graph.length, state.node_height, state.turn_angle, p.start, p.scenario.cell_size,
                              self.f1, self.f2, self.f3)
        if self.l_max > 0.0 or self.l_min > 0.0:
            costs[self.infeasible_walks(state, walks)] = np.inf
        return costs

    def infeasible_walks(self, state: ColonyState, walks: Walks) -> np.ndarray:
        """Eqs. 2-3 per walk: total length above ``l_max``, or a straight segment other than the last one
        shorter than ``l_min`` (lengths in horizontal cells, like the fitness; a limit of 0 is off).

        A straight segment is a run of consecutive steps with the same move
        (:func:`pathzoo_aco.dsaco_fitness.infeasible_walks`)."""
        g = state.problem.graph
        return infeasible_walks(walks.flat, walks.offsets, walks.reached, g.length, g.offset_id,
                                float(state.problem.scenario.cell_size), self.l_max, self.l_min)

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Eqs. 16-19: evaporate everywhere; the iteration-best ant lays ``Q / ((1-p) F_now + p F_global)``."""
        state.trail.evaporate(self.rho)
        k = int(np.argmin(costs))
        if not math.isfinite(costs[k]):  # no ant reached the target
            return
        p = p_schedule(state.iteration, self.p, self.gamma_p)
        amount = self.q / ((1.0 - p) * float(costs[k]) + p * state.best_cost)
        deposit_walks(state.trail, state.problem.graph.indices, walks.flat, walks.offsets, np.array([k]), amount)

    # ------------------------------------------------------------- the compiled colony
    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        """Run the colony in compiled code (:mod:`pathzoo_aco.dsaco_colony`); results equal the generic loop's.

        The generic :meth:`AntColonyPlanner.plan` runs instead for a turn
        table with factors other than 0 and 1 (none is built today). Without a
        ``progress`` callback or a clock limit the iterations run in one call
        per :data:`_SCHEDULE_CHUNK` of them; otherwise one call per iteration,
        so each report comes when its iteration ends and a clock stop is seen
        before the next one starts.
        """
        self.check_supports(scenario)
        budget = budget.or_default(self.iterations)
        clock = budget.start()
        problem = ColonyProblem.of(scenario)
        rules = problem.memo(self.table_key("walk_rules"), lambda: self.walk_rules(problem))
        if not np.isin(rules.turn, (0.0, 1.0)).all():  # the lists know allowed or not only
            return super().plan(scenario, budget=budget, rng=rng, progress=progress)
        if problem.start == problem.goal:
            return PlanResult(Status.SOLVED, problem.walk_points(np.zeros(0, dtype=np.int64)),
                              message="start and goal share a cell")
        engine = self.walk_engine(problem)
        table = problem.memo(self.table_key("move_table"), lambda: MoveTable.of(engine.adjacency(rules), rules.turn))
        trail = Pheromone(len(table.node), self.initial_trail(problem))  # in the table's storage order
        state = self.init_state(problem, rules, trail, engine, rng)
        assert isinstance(state, DsacoState) and state.node_height is not None and state.turn_angle is not None
        g = problem.graph
        fitness = (g.indices, g.offset_id, g.length, state.node_height, state.turn_angle,
                   float(problem.scenario.cell_size), self.f1, self.f2, self.f3, self.l_max, self.l_min)
        run = ColonyRun.start(g.n_nodes, int(np.diff(table.adj_ptr).max(initial=0)), trail.x, trail.scale)
        arrays = (table, problem.horizontal_offsets, rules.turn, fitness, (trail.x, trail.lo, trail.hi, self.rho),
                  (rules.tau_exp, self.q, problem.start, problem.goal, rules.backtrack, rules.max_steps))
        walk_time = 0.0
        timed = budget.timed
        stopped = False
        total = self.iteration_count(budget)
        for first in range(0, total, _SCHEDULE_CHUNK):  # bounded memory for the schedule of any budget
            ants = self.ants_per_iteration(budget, first, min(total, first + _SCHEDULE_CHUNK))
            rng_state = rng.bit_generator.state
            schedule = (np.array([int(rng.integers(2**31 - 1)) for _ in ants], dtype=np.int64),
                        np.array([q0_schedule(first + k, self.iterations, self.q0_initial) for k in range(len(ants))]),
                        np.array([p_schedule(first + k + 1, self.p, self.gamma_p) for k in range(len(ants))]), ants)
            started = time.perf_counter()
            one_call = progress is None and not timed
            for stop_at in ([first + len(ants)] if one_call else range(first + 1, first + len(ants) + 1)):
                if timed and clock.time_up():
                    stopped = True
                    break
                run_colony(*arrays, schedule, run, first=first, stop_at=stop_at)
                if progress is not None:
                    progress(int(run.counters[0]), int(run.counters[1]), float(run.best_cost[0]))
                if run.counters[4]:
                    break
            walk_time += time.perf_counter() - started
            if run.counters[4] or stopped:  # stopped early: leave the rng as the generic loop would
                rng.bit_generator.state = rng_state
                for _ in range(int(run.counters[0]) - first):
                    rng.integers(2**31 - 1)
                break
        iterations, evaluations = int(run.counters[0]), int(run.counters[1])
        message = "an ant searched the start's whole component: the goal is unreachable" if run.counters[4] else ""
        extras = {"ant_steps": int(run.counters[2]), "walk_time_s": walk_time}
        if not math.isfinite(run.best_cost[0]):
            return PlanResult(Status.FAILED, iterations=iterations, evaluations=evaluations,
                              message=message or "no ant reached the goal within the budget", extras=extras)
        return PlanResult(Status.SOLVED, problem.walk_points(run.best_edges[: run.counters[3]]),
                          iterations=iterations, evaluations=evaluations, message=message, extras=extras)

    def iteration_count(self, budget: Budget) -> int:
        """Iterations the budget's counts allow: its iterations, or as many as its evaluations fill (``n_ants``
        each); without a count (a clock-only budget, which ends the run) :data:`_UNCOUNTED` iterations."""
        counts = [n for n in (budget.iterations,
                              None if budget.evaluations is None else -(-budget.evaluations // self.n_ants))
                  if n is not None]
        return min(counts) if counts else _UNCOUNTED

    def ants_per_iteration(self, budget: Budget, first: int, last: int) -> np.ndarray:
        """Ants of iterations ``first`` to ``last - 1`` (0-based): ``n_ants``, fewer in the iteration where the
        evaluation budget runs out."""
        ants = np.full(last - first, self.n_ants, dtype=np.int64)
        if budget.evaluations is not None:
            ants = np.minimum(ants, budget.evaluations - self.n_ants * np.arange(first, last))
        return ants
