"""pathzoo: compare path planners honestly.

The public API is small:

- :func:`load_scenario` and :func:`load_scenarios` give :class:`Scenario` objects;
- :func:`make_planner` builds a registered planner with validated parameters;
- :func:`run` runs planners x scenarios x seeds through the harness;
- :func:`list_plugins` shows what the installed plugins provide.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Sequence

from pathzoo.lazy_names import lazy_getattr
from pathzoo.version import installed_version

if TYPE_CHECKING:
    import pandas as pd

    from pathzoo.core import (
        Budget,
        InvalidExperimentError,
        InvalidParameterError,
        InvalidScenarioError,
        Metric,
        MovingObstacle,
        Param,
        PathzooError,
        Planner,
        PlanResult,
        RunRecord,
        RunStatus,
        Scenario,
        Status,
        TerrainRules,
        UnknownPluginError,
        UnsupportedScenarioError,
        VehicleModel,
    )
    from pathzoo.plugins.entries import LazyMetric, LazyPlanner, PluginEntry, ScenarioEntry
    from pathzoo.plugins.hookspecs import hookimpl
    from pathzoo.plugins.lookup import list_plugins, load_scenario, load_scenarios, make_planner

__all__ = [
    "Budget",
    "InvalidExperimentError",
    "InvalidParameterError",
    "InvalidScenarioError",
    "LazyMetric",
    "LazyPlanner",
    "Metric",
    "MovingObstacle",
    "Param",
    "PathzooError",
    "PlanResult",
    "Planner",
    "PluginEntry",
    "RunRecord",
    "RunStatus",
    "Scenario",
    "ScenarioEntry",
    "Status",
    "TerrainRules",
    "UnknownPluginError",
    "UnsupportedScenarioError",
    "VehicleModel",
    "hookimpl",
    "list_plugins",
    "load_scenario",
    "load_scenarios",
    "make_planner",
    "run",
    "__version__",
]

_WHERE = {
    **{name: "pathzoo.core" for name in ("Budget", "InvalidExperimentError", "InvalidParameterError",
                                         "InvalidScenarioError", "Metric", "MovingObstacle", "Param", "PathzooError",
                                         "PlanResult", "Planner", "RunRecord", "RunStatus", "Scenario", "Status",
                                         "TerrainRules", "UnknownPluginError", "UnsupportedScenarioError",
                                         "VehicleModel")},
    **{name: "pathzoo.plugins.entries" for name in ("LazyMetric", "LazyPlanner", "PluginEntry", "ScenarioEntry")},
    "hookimpl": "pathzoo.plugins.hookspecs",
    **{name: "pathzoo.plugins.lookup" for name in ("list_plugins", "load_scenario", "load_scenarios", "make_planner")},
}


_public = lazy_getattr(__name__, _WHERE)


def __getattr__(name: str) -> Any:
    """The public classes and ``__version__``, loaded on first use (PEP 562).

    ``import pathzoo`` alone then imports neither numpy nor pluggy nor
    :mod:`importlib.metadata`, so ``pathzoo run`` can start its fork server
    at once (:func:`pathzoo.harness.launch.start_server`).
    """
    return installed_version() if name == "__version__" else _public(name)


def run(
    planners: Sequence[str | Planner | tuple[str, dict[str, Any]] | tuple[str, dict[str, Any], str]],
    scenarios: Sequence[str | Scenario],
    *,
    seeds: int | Iterable[int] = 5,
    db: str | Path = "pathzoo-results.sqlite",
    jobs: int | None = None,
    budget: Budget | None = None,
    timeout_s: float | None = None,
    experiment: str = "default",
    seed: int = 0,
    executor: str = "process",
    progress: bool = True,
    retry: Sequence[str] = (),
) -> "pd.DataFrame":
    """Run planners x scenarios x seeds, validate every path, store and return the runs.

    Parameters
    ----------
    planners : sequence
        Planner ids, ``(id, params)`` pairs, ``(id, params, label)`` triples
        (the label names the configuration in tables and plots; without it
        the name is ``id(param=value, ...)`` for the non-default parameters),
        ``pathzoo.harness.PlannerSpec`` objects, or planner instances.
    scenarios : sequence
        Scenario ids, glob patterns of ids, file paths, or Scenario objects.
    seeds : int or iterable of int
        Number of seeds (indices ``0..n-1``) or explicit seed indices.
    db : path
        SQLite file; runs already stored for this experiment are skipped.
    jobs : int, optional
        Worker processes (default: number of CPUs).
    budget : Budget, optional
        Per-run planning budget (default: 10 s of planning time).
    timeout_s : float, optional
        Hard per-run wall-clock limit after which the worker is killed
        (default: budget time + 30 s).
    experiment : str
        Experiment name, part of every run key.
    seed : int
        Experiment seed from which each run's seed is derived.
    executor : {"process", "dask", "inline"}
        Where runs execute. ``inline`` runs in this process (no isolation;
        its runs are stored with ``isolated = False``). A script needs no
        ``if __name__ == "__main__":`` guard: workers never import it.
    progress : bool
        Show a progress bar.
    retry : sequence of str
        Statuses of stored runs to run again (e.g. ``("crash", "timeout")``).

    Returns
    -------
    pandas.DataFrame
        One row per requested run (planners x scenarios x seeds), metrics as
        columns; other runs stored under the same experiment name are left out.
    """
    from pathzoo.harness.experiment import Experiment
    from pathzoo.harness.runner import run_experiment

    exp = Experiment.build(
        planners=planners,
        scenarios=scenarios,
        seeds=seeds,
        budget=budget,
        timeout_s=timeout_s,
        name=experiment,
        seed=seed,
    )
    return run_experiment(exp, db=db, jobs=jobs, executor=executor, progress=progress, retry=tuple(retry))
