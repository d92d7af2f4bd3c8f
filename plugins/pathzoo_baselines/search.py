"""Run-time support shared by the metaheuristics: budgeted evaluation, best-so-far, global RNG seeding, result.

Budgets
-------
- ``iterations``: generations (PSO iterations, GA generations, cuckoo
  generations). Evaluating the initial population is iteration 0.
- ``evaluations``: penalised-cost evaluations of candidates. A batch that
  would overrun the limit is cut: only its first candidates are evaluated,
  the rest get cost ``inf`` and are not counted, so the limit is never
  exceeded.
- ``time_s``: checked between generations, so the limit is overshot by at
  most one generation.
- No limit at all: :data:`DEFAULT_ITERATIONS` generations.

Determinism
-----------
pyswarms draws from ``numpy.random``'s global state and DEAP from Python's
``random`` module. :func:`seeded_global_random` seeds both from the run's
``rng`` for the duration of ``plan()`` and restores them afterwards, so a
seed gives the same path whatever the caller did to the global state
(``tests/baselines/test_determinism.py`` proves it). This is not thread-safe;
the harness runs one ``plan()`` per process at a time.
"""

from __future__ import annotations

import math
import random
from contextlib import contextmanager
from typing import Any, Iterator

import numpy as np

from pathzoo.core import Budget, PlanResult, ProgressCallback, Scenario, Status
from pathzoo_baselines.encodings import Encoding

__all__ = ["DEFAULT_ITERATIONS", "Search", "seeded_global_random"]

DEFAULT_ITERATIONS = 200
"""Generations run when the budget sets no limit at all."""


@contextmanager
def seeded_global_random(rng: np.random.Generator) -> Iterator[None]:
    """Seed ``numpy.random`` and ``random`` from ``rng``; restore their previous states on exit."""
    saved_np, saved_py = np.random.get_state(), random.getstate()
    np.random.seed(int(rng.integers(2**32)))
    random.seed(int(rng.integers(2**63)))
    try:
        yield
    finally:
        np.random.set_state(saved_np)
        random.setstate(saved_py)


class Search:
    """Budget, counters and best-so-far of one metaheuristic run.

    Parameters
    ----------
    scenario : Scenario
        The problem.
    encoding : Encoding
        How candidates become paths and costs.
    budget : Budget
        The run's limits (see the module docstring).
    progress : callable, optional
        The harness's ``progress(iteration, evaluations, best_cost)``.
    """

    def __init__(self, scenario: Scenario, encoding: Encoding, budget: Budget, progress: ProgressCallback | None):
        self.scenario = scenario
        self.encoding = encoding
        self.budget = Budget(iterations=DEFAULT_ITERATIONS) if budget.unlimited else budget
        self.clock = self.budget.start()
        self._progress = progress
        self.iterations = 0
        self.evaluations = 0
        self.best_genes: np.ndarray | None = None
        self.best_cost = math.inf
        self.best_violation = math.inf

    @property
    def remaining_evaluations(self) -> float:
        """Evaluations left (``inf`` without an evaluation limit)."""
        limit = self.budget.evaluations
        return math.inf if limit is None else limit - self.evaluations

    def exhausted(self) -> bool:
        """True once any limit is reached."""
        return self.clock.exhausted(iterations=self.iterations, evaluations=self.evaluations)

    def evaluate(self, genes: np.ndarray) -> np.ndarray:
        """Penalised costs of a batch; candidates beyond the evaluation limit get ``inf``."""
        genes = np.asarray(genes)
        costs = np.full(len(genes), math.inf)
        n = int(min(len(genes), self.remaining_evaluations))
        if n <= 0:
            return costs
        cost, violation = self.encoding.evaluate(genes[:n])
        costs[:n] = cost
        self.evaluations += n
        i = int(np.argmin(cost))
        if cost[i] < self.best_cost:
            self.best_cost = float(cost[i])
            self.best_violation = float(violation[i])
            self.best_genes = genes[i].copy()
        return costs

    def report(self) -> None:
        """Tell the harness the best cost so far (called once per generation, and after initialisation)."""
        if self._progress is not None:
            self._progress(self.iterations, self.evaluations, self.best_cost)

    def next_iteration(self) -> None:
        """Count one generation and report it."""
        self.iterations += 1
        self.report()

    def result(self, extras: dict[str, Any] | None = None) -> PlanResult:
        """The best candidate as a solved path if the validator accepts it, else ``FAILED`` with the reason."""
        info = {"best_cost": self.best_cost, "violation": self.best_violation, **(extras or {})}
        common = dict(iterations=self.iterations, evaluations=self.evaluations, extras=info)
        if self.best_genes is None:
            return PlanResult(Status.FAILED, message="no candidate was evaluated within the budget", **common)
        if self.best_violation > 0:
            return PlanResult(
                Status.FAILED,
                message=f"the best candidate still violates the constraints (violation {self.best_violation:.3g})",
                **common,
            )
        from pathzoo.rules import validate_path  # imports numba: not at registration time

        path = self.encoding.path(self.best_genes)
        verdict = validate_path(self.scenario, path)
        if not verdict:
            message = f"the best candidate is not a valid path: {verdict.reason}"
            return PlanResult(Status.FAILED, message=message, **common)
        return PlanResult(Status.SOLVED, path=path, **common)
