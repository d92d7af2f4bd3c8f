"""``exact.lazytheta3d``: Lazy Theta* in air volumes (Nash, Koenig & Tovey 2010); a short any-angle path, not the optimum.

The search is :func:`pathzoo.grid.lazy_theta3d.lazy_theta_path`; this planner
returns its path once the judge's rule accepts it (the search ignores the
turn limit, so a path that breaks it is a failure with the judge's reason).
Its length is the reference ``length_ratio_anyangle_bound`` divides by.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from pathzoo.core import Budget, Planner, PlanResult, ProgressCallback, Scenario, Status
from pathzoo.grid.lazy_theta3d import lazy_theta_path
from pathzoo.grid.paths import path_pieces
from pathzoo.rules import validate_path

__all__ = ["LazyTheta3dPlanner"]


class LazyTheta3dPlanner(Planner):
    """Lazy Theta* on the air graph with the judge's segment rule as line of sight (no parameters)."""

    id: ClassVar[str] = "exact.lazytheta3d"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = ("Lazy Theta* in air volumes (Nash et al. 2010): a short any-angle path whose length "
                              "bounds the any-angle optimum from above")
    kinds: ClassVar[frozenset[str]] = frozenset({"air3d"})

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """One search (one iteration); the budget's clock is not looked at (the search takes milliseconds)."""
        self.check_supports(scenario)
        path = lazy_theta_path(scenario)
        if path is None:
            return PlanResult(Status.NO_PATH, iterations=1,
                              message="the goal voxel is not reachable from the start voxel in the air graph")
        check = validate_path(scenario, path)
        if not check:
            return PlanResult(Status.FAILED, iterations=1, message=f"the Lazy Theta* path breaks a rule: {check.reason}")
        length = float(path_pieces(scenario, path)[0].sum())
        if progress is not None:
            progress(1, 1, length)
        return PlanResult(Status.SOLVED, path=path, iterations=1, evaluations=1,
                          extras={"cost": "length", "best_cost": length})
