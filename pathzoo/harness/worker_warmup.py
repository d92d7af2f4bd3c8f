"""A planner's warm-up in a worker: once per configuration and scenario, on a twin of the run's scenario."""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from pathzoo.harness.scenario_cache import cache_lock, load_warm, lru
from pathzoo.harness.sealed import seal

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.harness.specs import RunTask, ScenarioSpec

__all__ = ["warm_up_for"]

_twins: "OrderedDict[tuple[str, str, str, str], Scenario]" = OrderedDict()
_warmed_for: set[tuple[str, str, tuple[str, str, str, str]]] = set()
_TWINS = 2
"""Warm-up twins of scenarios kept per process."""


def _twin(spec: "ScenarioSpec") -> "Scenario":
    """A second copy of a scenario, loaded and sealed as the runs' copy is (same types and flags), for warm-ups only."""
    def make() -> "Scenario":
        scenario = load_warm(spec)
        seal(scenario)  # the twin's arrays go where the run's do: numba meets the same array types
        return scenario

    return lru(_twins, spec.cache_key, _TWINS, make)


def warm_up_for(task: "RunTask", planner: Any) -> None:
    """Warm ``planner`` up on a twin of the task's scenario, once per configuration and scenario in this process.

    The twin is loaded the way the measured run's scenario is, so the warm-up
    meets the same argument types and compiles every numba specialisation
    the run needs (:func:`pathzoo.core.warmup.warm_up`); being another
    object, it keeps whatever the planner caches on a scenario away from
    the measured runs. Errors are left to the measured run.

    The warm-up has the run's own wall limit when the run has one (a
    program planner, :mod:`pathzoo.plugins.external`, sets its deadline from
    it, and under the inline executor nothing else would stop a program
    that never answers); otherwise only the count limit of
    :data:`~pathzoo.core.warmup.WARM_UP_BUDGET`.
    """
    from pathzoo.core.warmup import WARM_UP_BUDGET, warm_up  # not at the top: imported before numba is needed

    key = (task.planner.id, task.params_hash, task.scenario.cache_key)
    with cache_lock:
        if key in _warmed_for:
            return
        _warmed_for.add(key)
    budget = WARM_UP_BUDGET if task.budget.time_s is None else replace(WARM_UP_BUDGET, time_s=task.budget.time_s)
    warm_up(planner, task.scenario.kind, budget, on=_twin(task.scenario))
