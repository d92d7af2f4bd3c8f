"""The base class of every ant-colony planner: the iteration loop, budgets, progress and the answer.

A variant is a subclass that sets its paper's parameters and overrides a few
hooks (see ``docs/aco-engine.md``):

- :meth:`AntColonyPlanner.heuristic`: the per-edge heuristic ``η``;
- :meth:`AntColonyPlanner.walk_rules`: how ants weigh edges (product or sum
  rule, neighbour factor, ``q0``, local update, pre-choice additions);
- :meth:`AntColonyPlanner.initial_trail`: ``τ0``;
- :meth:`AntColonyPlanner.init_state`: extra per-run state (a subclass of
  :class:`ColonyState`);
- :meth:`AntColonyPlanner.before_iteration`: per-iteration schedules;
- :meth:`AntColonyPlanner.walk_costs`: what "best" means;
- :meth:`AntColonyPlanner.update_trail`: the pheromone update (required);
- :meth:`AntColonyPlanner.walk_engine`: the engine that sends the ants;
- :meth:`AntColonyPlanner.result_extras`: extra numbers for the answer.

The loop: while the budget lasts, send ``n_ants`` ants (fewer in the last
iteration if the evaluation budget says so), keep the best walk so far, let
the variant update the trail, and report ``progress(iteration, evaluations,
best_cost)`` with the best-so-far cost. One evaluation is one ant walk; one
iteration is one colony cycle. The budget follows the one rule of every
family (:meth:`Budget.or_default`, ``docs/timing.md``): a count ends the
run; a clock-only budget (``cpu_s``, ``time_s``) runs colonies until the
clock, which is checked between colonies; a budget without any limit runs
the ``iterations`` parameter (the paper's count). A run that a count ends is
the same on any machine and load.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from pathzoo.core.budget import Budget
from pathzoo.core.planner import Param, Planner, ProgressCallback
from pathzoo.core.results import PlanResult
from pathzoo.core.scenario import Scenario
from pathzoo.core.status import Status
from pathzoo.grid.graph_cache import release_pages
from pathzoo_aco.engine.pheromone import Pheromone
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.rules import WalkRules
from pathzoo_aco.engine.walk import WalkEngine
from pathzoo_aco.engine.walk_result import Walks

__all__ = ["AntColonyPlanner", "ColonyState", "colony_params"]

def colony_params(*, n_ants: int, iterations: int, alpha: float, beta: float, rho: float,
                  dead_end: str = "backtrack") -> dict[str, Param]:
    """The parameters every colony has, with a variant's defaults.

    Parameters
    ----------
    n_ants, iterations, alpha, beta, rho : number
        Defaults of the colony size, iteration count (used when the budget
        sets no limit at all), trail weight, heuristic weight and evaporation rate.
    dead_end : {"backtrack", "die"}
        Default dead-end handling.
    """
    return {
        "n_ants": Param(n_ants, "ants per iteration (m); at most 10,000, as every ant's walk is held in memory",
                        low=1, high=10_000, tune=(5, 100), tune_log=True),
        "iterations": Param(iterations, "iterations run when the budget sets no limit at all", low=1),
        "alpha": Param(alpha, "weight of the pheromone trail (α)", low=0.0, tune=(0.0, 5.0)),
        "beta": Param(beta, "weight of the heuristic (β)", low=0.0, tune=(0.0, 10.0)),
        "rho": Param(rho, "evaporation rate (ρ)", low=0.0, high=1.0, high_open=True, tune=(0.01, 0.9)),
        "dead_end": Param(dead_end, "at a dead end: step back along the walk, or drop the ant",
                          choices=("backtrack", "die")),
        "max_steps": Param(0, "steps after which an ant is dropped; 0 = twice the free cells (never binds "
                           "when backtracking)", low=0),
    }


@dataclass
class ColonyState:
    """Everything one ``plan()`` call changes; variants may subclass it.

    Attributes
    ----------
    problem : ColonyProblem
        The scenario's graph view.
    rules : WalkRules
        The rules built by :meth:`AntColonyPlanner.walk_rules`.
    trail : Pheromone
        The pheromone trail.
    rng : numpy.random.Generator
        The run's only source of randomness.
    iteration : int
        Colonies completed so far.
    evaluations : int
        Walks started so far.
    best_cost : float
        Cost of the best walk so far (``inf`` before the first success).
    best_edges : ndarray or None
        Edge ids of the best walk so far.
    """

    problem: ColonyProblem
    rules: WalkRules
    trail: Pheromone
    rng: np.random.Generator
    iteration: int = 0
    evaluations: int = 0
    best_cost: float = math.inf
    best_edges: np.ndarray | None = None


class AntColonyPlanner(Planner):
    """Base class of the ant-colony planners; see the module docstring for the hooks."""

    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d", "terrain", "air3d"})
    pheromone_on: ClassVar[str] = "edges"
    """``"edges"`` (``τ_ij``) or ``"nodes"`` (``τ_j``, as IACA's grid pheromone)."""

    # ------------------------------------------------------------------ hooks
    def heuristic(self, problem: ColonyProblem) -> np.ndarray:
        """Per-edge heuristic ``η`` (default: ``1 / (ℓ_ij + d(j, goal))``, the path-planning form)."""
        g = problem.graph
        return 1.0 / (g.length + problem.goal_distance[g.indices])

    def walk_rules(self, problem: ColonyProblem) -> WalkRules:
        """Walk rules; default: the product rule ``τ^α η^β`` with the dead-end and turn rules."""
        return WalkRules.product(self.alpha, self.heuristic(problem), self.beta, **self.walk_options(problem))

    def initial_trail(self, problem: ColonyProblem) -> float | np.ndarray:
        """Initial trail ``τ0`` (default: 1)."""
        return 1.0

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> ColonyState:
        """Build the run's state; override to return a subclass with extra fields.

        ``engine`` may be used for preliminary walks (ACS's greedy walk); add
        them to ``evaluations`` of the returned state.
        """
        return ColonyState(problem, rules, trail, rng)

    def before_iteration(self, state: ColonyState) -> WalkRules:
        """Rules for the coming iteration (default: unchanged). DSACO's ``q0`` schedule goes here."""
        return state.rules

    def walk_costs(self, state: ColonyState, walks: Walks) -> np.ndarray:
        """Cost of each walk, ``inf`` if it failed (default: length in metres)."""
        return walks.totals(state.problem.graph.length)

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Update ``state.trail`` after a colony (evaporation and deposits). Every variant defines it."""
        raise NotImplementedError(f"{type(self).__name__} must define update_trail")

    def walk_engine(self, problem: ColonyProblem) -> WalkEngine:
        """The engine that sends the ants (default: :class:`WalkEngine`; FGDACO's timed walks override it)."""
        return WalkEngine(problem)

    def result_extras(self, state: ColonyState) -> dict[str, Any]:
        """JSON-serialisable extras for the answer (default: none)."""
        return {}

    # ------------------------------------------------------------- helpers
    def table_key(self, name: str) -> tuple:
        """Key of a per-scenario table that depends on this planner's class and parameters only.

        :meth:`plan` keeps :meth:`walk_rules` under ``table_key("walk_rules")``
        in :meth:`ColonyProblem.memo`, so a variant's heuristic, gains and
        turn tables are computed once per scenario and configuration; hooks
        may keep their own tables the same way. A variant whose rules depend
        on anything else must not be cached this way.
        """
        return (type(self), self.version, repr(sorted(self.get_params().items())), name)  # repr: any value type

    def walk_options(self, problem: ColonyProblem) -> dict[str, Any]:
        """Keyword arguments for :class:`WalkRules` from the common parameters and the vehicle's turn limit."""
        cap = self.max_steps or 2 * problem.n_free + 2
        return {"backtrack": self.dead_end == "backtrack", "max_steps": int(cap), "turn": problem.turn_table}

    @staticmethod
    def neighbour_factor(problem: ColonyProblem, edges: slice = slice(None)) -> np.ndarray:
        """Per edge ``i -> j`` (of ``edges``): ``n_j / (n_j + 1)`` with ``n_j`` the number of neighbours of ``j``."""
        g = problem.graph
        n = g.degree[g.indices[edges]].astype(np.float64)
        return n / (n + 1.0)

    # ---------------------------------------------------------------- plan
    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        """Run the colony; see the module docstring."""
        self.check_supports(scenario)
        budget = budget.or_default(self.iterations)
        clock = budget.start()
        problem = ColonyProblem.of(scenario)
        if problem.start == problem.goal:
            return PlanResult(Status.SOLVED, problem.walk_points(np.zeros(0, dtype=np.int64)),
                              message="start and goal share a cell")
        rules = problem.memo(self.table_key("walk_rules"), lambda: self.walk_rules(problem))
        trail = Pheromone(problem.graph.n_nodes if self.pheromone_on == "nodes" else problem.graph.n_edges,
                          self.initial_trail(problem), on_nodes=self.pheromone_on == "nodes")
        engine = self.walk_engine(problem)
        state = self.init_state(problem, rules, trail, engine, rng)
        release_pages(problem.graph)  # set-up read the whole graph; the walks read little of it (docs/graph-cache.md)
        walk_time = 0.0
        message = ""
        while not clock.exhausted(iterations=state.iteration, evaluations=state.evaluations):
            n = self.n_ants
            if budget.evaluations is not None:
                n = min(n, budget.evaluations - state.evaluations)
            rules = self.before_iteration(state)
            t0 = time.perf_counter()
            walks = engine.walk(rules, state.trail, n, int(state.rng.integers(2**31 - 1)))
            walk_time += time.perf_counter() - t0
            state.iteration += 1
            state.evaluations += walks.started
            costs = self.walk_costs(state, walks)
            if walks.started and np.isfinite(costs).any():
                k = int(np.argmin(costs))
                if costs[k] < state.best_cost:
                    state.best_cost = float(costs[k])
                    state.best_edges = walks.edges(k).copy()
            self.update_trail(state, walks, costs)
            if progress is not None:
                progress(state.iteration, state.evaluations, state.best_cost)
            if walks.exhausted and rules.turn.size == 0:
                message = "an ant searched the start's whole component: the goal is unreachable"
                break
        extras = {"ant_steps": engine.total_steps, "walk_time_s": walk_time, **self.result_extras(state)}
        if state.best_edges is None:
            return PlanResult(Status.FAILED, iterations=state.iteration, evaluations=state.evaluations,
                              message=message or "no ant reached the goal within the budget", extras=extras)
        return PlanResult(Status.SOLVED, problem.walk_points(state.best_edges), iterations=state.iteration,
                          evaluations=state.evaluations, message=message, extras=extras)
