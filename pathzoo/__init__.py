"""pathzoo: compare path planners honestly.

The public API is small:

- :func:`load_scenario` and :func:`load_scenarios` give :class:`Scenario` objects;
- :func:`make_planner` builds a registered planner with validated parameters;
- :func:`run` runs planners x scenarios x seeds through the harness;
- :func:`list_plugins` shows what the installed plugins provide.
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Sequence

from pathzoo.lazy_names import lazy_getattr

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
}


@functools.cache
def _installed_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("pathzoo")
    except PackageNotFoundError:  # running from a source tree
        return "0.0.0+unknown"


_public = lazy_getattr(__name__, _WHERE)


def __getattr__(name: str) -> Any:
    """The public classes and ``__version__``, loaded on first use (PEP 562).

    ``import pathzoo`` alone then imports neither numpy nor pluggy nor
    :mod:`importlib.metadata`, so ``pathzoo run`` can start its fork server
    at once (:func:`pathzoo.harness.launch.start_server`).
    """
    return _installed_version() if name == "__version__" else _public(name)


def load_scenario(id_or_path: str | Path) -> Scenario:
    """Load one scenario by registered id or from a file.

    Parameters
    ----------
    id_or_path : str or path
        A registered id such as ``"gant.fig7"`` (see ``pathzoo list
        scenarios``), or a scenario TOML file.

    Raises
    ------
    UnknownPluginError
        No scenario is registered under that id.
    InvalidScenarioError
        The file is malformed; the message names the file and field.
    """
    from pathzoo.core.errors import UnknownPluginError
    from pathzoo.io.paths import looks_like_path

    text = str(id_or_path)
    if isinstance(id_or_path, Path) or looks_like_path(text):
        from pathzoo.io import load_scenario_file

        return load_scenario_file(Path(text))
    from pathzoo.plugins.manager import get_registry

    try:
        entry = get_registry().get("scenarios", text)
    except UnknownPluginError as exc:
        raise UnknownPluginError(f"{exc} (and no file named '{text}' exists)") from None
    return entry.obj.load()


def load_scenarios(path: str | Path) -> list[Scenario]:
    """Load every scenario a file describes.

    A ``.scen`` file gives one scenario per problem line (with its optimal
    length as ``reference_length``); a scenario TOML gives one; a glob pattern
    of registered ids (``"movingai.arena.*"``) gives every match.
    """
    from pathzoo.io.paths import looks_like_path

    text = str(path)
    if isinstance(path, Path) or looks_like_path(text):
        from pathzoo.io import load_scenario_files

        return load_scenario_files(Path(text))
    from pathzoo.plugins.manager import get_registry

    reg = get_registry()
    return [reg.get("scenarios", sid).obj.load() for sid in reg.match("scenarios", text)]


def make_planner(planner_id: str, **params: Any) -> Planner:
    """Build a registered planner; parameters are validated now.

    Raises
    ------
    UnknownPluginError
        No planner is registered under ``planner_id``.
    InvalidParameterError
        A parameter is unknown or out of range.
    """
    from pathzoo.plugins.manager import get_registry

    cls = get_registry().get("planners", planner_id).obj
    return cls(**params)


def list_plugins(kind: str = "planners") -> list[PluginEntry]:
    """Entries of one kind (``planners``, ``scenarios`` or ``metrics``), sorted by id."""
    from pathzoo.plugins.manager import get_registry

    table = get_registry().table(kind)  # type: ignore[arg-type]
    return [table[k] for k in sorted(table)]


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
