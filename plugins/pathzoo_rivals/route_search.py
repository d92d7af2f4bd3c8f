"""The common ``plan()`` of the multi-objective route rivals: budget counting, archive, incumbent and result.

A subclass implements :meth:`RouteSearchPlanner.search`, which draws routes,
evaluates them through :meth:`RouteRun.evaluate` and ends each iteration with
:meth:`RouteRun.next_iteration`; it stops as soon as either says the budget is
spent. The run keeps

- the Pareto archive of the routes evaluated (objectives of
  :mod:`pathzoo_rivals.routes`), reported in ``extras["front"]``;
- the *incumbent*: the evaluated route that is best by the selection rule
  (``select``: least energy, the harness's energy metric, or least 3-D
  length), which ``plan()`` returns. Because it is the best of every route
  evaluated, the reported cost never increases.

A budget without any limit runs :data:`DEFAULT_ITERATIONS` iterations; a
clock-only budget runs until the clock (:meth:`Budget.or_default`).
"""

from __future__ import annotations

import abc
import math
from typing import Any, ClassVar

import numpy as np

from pathzoo.core import Budget, Param, Planner, PlanResult, ProgressCallback, Scenario, Status
from pathzoo.core.budget import BudgetClock
from pathzoo.rules import segment_problem
from pathzoo_rivals.pareto import ParetoArchive
from pathzoo_rivals.routes import OBJECTIVES, RouteProblem

__all__ = ["DEFAULT_ITERATIONS", "RouteRun", "RouteSearchPlanner", "SELECT"]

SELECT = Param("energy", "which route of the search is returned: least energy (harness metric) or least 3-D length",
               choices=("energy", "length"))

DEFAULT_ITERATIONS = 50
"""Iterations run when the budget sets no limit at all (about 2 CPU s on ``ggaco.hugo``)."""


class RouteRun:
    """Counters, archive and incumbent of one ``plan()`` call.

    Parameters
    ----------
    problem : RouteProblem
        The routes' scenario.
    budget : Budget
        The call's budget.
    progress : callable, optional
        Called with ``(iteration, evaluations, best_cost)`` when the incumbent improves.
    rule : {"energy", "length"}
        Selection rule of the incumbent.
    archive_size : int
        Capacity of the Pareto archive.
    """

    def __init__(self, problem: RouteProblem, budget: Budget, progress: ProgressCallback | None, rule: str,
                 archive_size: int) -> None:
        self.problem = problem
        self.clock: BudgetClock = budget.or_default(DEFAULT_ITERATIONS).start()
        self.progress = progress
        self.rule = rule
        self.archive = ParetoArchive(archive_size)
        self.iterations = 0
        self.evaluations = 0
        self.best: np.ndarray | None = None
        self.best_cost = math.inf

    def exhausted(self) -> bool:
        """Whether the budget (iterations, evaluations or time) is spent."""
        return self.clock.exhausted(iterations=self.iterations, evaluations=self.evaluations)

    def evaluate(self, route: np.ndarray) -> np.ndarray | None:
        """Objectives of a feasible route, archived and offered as incumbent; ``None`` once the budget is spent."""
        if self.exhausted():
            return None
        self.evaluations += 1
        f, cost = self.problem.measure(route, self.rule)
        self.archive.add(route, f)
        if cost < self.best_cost:
            self.best, self.best_cost = route, cost
            if self.progress is not None:
                self.progress(self.iterations, self.evaluations, cost)
        return f

    def next_iteration(self) -> bool:
        """Count one finished iteration; returns whether another may start."""
        self.iterations += 1
        return not self.exhausted()

    def result(self) -> PlanResult:
        """The incumbent as a world path (endpoint connectors checked), with the front in ``extras``."""
        counts: dict[str, Any] = {"iterations": self.iterations, "evaluations": self.evaluations}
        if self.best is None:
            return PlanResult(Status.FAILED, message="the budget ran out before a feasible route was evaluated",
                              **counts)
        scenario = self.problem.scenario
        path = self.problem.world_path(self.best)
        for p0, p1 in ((path[0], path[1]), (path[-2], path[-1])):
            problem = segment_problem(scenario, p0, p1)
            if problem is not None:
                return PlanResult(Status.FAILED, message=f"endpoint connector not allowed: {problem}", **counts)
        extras: dict[str, Any] = {
            "select": self.rule,
            "best_cost": self.best_cost,
            "objectives": list(OBJECTIVES),
            "front": self.archive.objectives.tolist(),
        }
        return PlanResult(Status.SOLVED, path=path, extras=extras, **counts)


class RouteSearchPlanner(Planner, abc.ABC):
    """Base of the multi-objective route rivals (``grid2d`` and ``terrain``)."""

    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d", "terrain"})
    archive_size: ClassVar[int] = 50
    """Capacity of the Pareto archive reported in ``extras["front"]``."""

    @abc.abstractmethod
    def search(self, run: RouteRun, rng: np.random.Generator) -> None:
        """Evaluate routes through ``run`` until it reports the budget spent."""

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Search routes on ``scenario``; see the module docstring."""
        self.check_supports(scenario)
        problem = RouteProblem(scenario)
        if not problem.reachable():
            return PlanResult(Status.NO_PATH, message="the goal cell is not reachable from the start cell")
        run = RouteRun(problem, budget, progress, self.select, self.archive_size)
        if problem.start == problem.goal:
            run.evaluate(np.array([problem.start], dtype=np.int64))  # one cell: the only route is to stay in it
        else:
            self.search(run, rng)
        return run.result()
