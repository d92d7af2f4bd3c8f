"""Rerunning a paper's comparison through the harness: which planners can run, the experiments, labelled runs.

Runs are labelled by the paper's planner keys, so two configurations of one
planner (or one paper's parameters against another's) stay apart without
help from the harness.
"""

from __future__ import annotations

import fnmatch
import importlib
import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

import numpy as np
import pandas as pd

from pathzoo.analysis.reproduction.paper_data import PaperData, PaperPlanner
from pathzoo.core.errors import InvalidExperimentError, InvalidParameterError, PathzooError

if TYPE_CHECKING:
    from pathzoo.harness.sandbox import SandboxLimits

__all__ = [
    "NOT_AVAILABLE",
    "RerunOptions",
    "planner_status",
    "selected_scenarios",
    "build_experiments",
    "planner_groups",
    "paper_budget",
    "experiment_name",
    "label_runs",
    "add_derived",
    "run_labelled",
    "run_paper",
]

NOT_AVAILABLE = "not available (not reconstructed)"
"""What the table shows for a planner id that is not registered."""


def planner_status(planner: PaperPlanner) -> str:
    """``""`` when the planner can run with the paper's parameters, else why not (shown in the table)."""
    from pathzoo.harness.specs import PlannerSpec
    from pathzoo.plugins.manager import get_registry

    if planner.id not in get_registry().planners:
        return NOT_AVAILABLE
    try:
        PlannerSpec.of((planner.id, dict(planner.params)))
    except PathzooError as exc:
        return f"not run: parameters rejected ({exc})"
    return ""


def selected_scenarios(paper: PaperData, pattern: str | None) -> dict[str, str]:
    """The paper's scenarios (key -> scenario id) whose id matches the glob ``pattern`` (all if ``None``)."""
    chosen = {k: v for k, v in paper.scenarios.items() if pattern is None or fnmatch.fnmatchcase(v, pattern)}
    if not chosen:
        raise InvalidParameterError(f"no scenario of paper '{paper.name}' matches '{pattern}'")
    return chosen


def build_experiments(
    paper: PaperData,
    *,
    seeds: int | None = None,
    iterations: int | None = None,
    scenarios: str | None = None,
    db: str | Path | None = None,
) -> list["Any"]:
    """The :class:`~pathzoo.harness.experiment.Experiment` (s) that rerun the paper's table.

    Only available planners take part; planners that run a scenario variant
    (:attr:`PaperPlanner.variant`) form their own experiment, so nobody runs
    scenarios it does not need. ``seeds`` defaults to the paper's run count;
    ``iterations`` replaces the budget's iteration limit and caps every
    planner's ``iterations`` parameter (for quick checks); ``scenarios`` is a
    glob on the paper's scenario ids. The experiment names record the seed
    count and any iteration override, so runs with other settings are kept
    apart in one database.
    """
    from pathzoo.core.budget import Budget
    from pathzoo.harness.experiment import Experiment

    groups = planner_groups(paper, iterations)
    n = seeds if seeds is not None else paper.runs
    name = experiment_name(paper, n, iterations)
    ids = list(selected_scenarios(paper, scenarios).values())
    return [
        Experiment.build(planners=specs, scenarios=[sid + variant for sid in ids], seeds=n,
                         budget=Budget(**paper_budget(paper, iterations)), name=name + variant.replace("_", "."), db=db)
        for variant, specs in sorted(groups.items())
    ]


def planner_groups(paper: PaperData, iterations: int | None = None,
                   keys: Callable[[PaperPlanner], bool] = lambda p: True) -> dict[str, list[tuple[str, dict[str, Any]]]]:
    """The available planners (of those ``keys`` accepts) as ``(id, params)`` per scenario variant.

    ``iterations`` caps every planner's ``iterations`` parameter (see :func:`build_experiments`).

    Raises
    ------
    InvalidExperimentError
        When none of the paper's planners is available.
    """
    groups: dict[str, list[tuple[str, dict[str, Any]]]] = {}
    for p in paper.planners:
        if planner_status(p) or not keys(p):
            continue
        params = dict(p.params)
        if iterations is not None and "iterations" in _param_names(p.id):
            params["iterations"] = min(int(params.get("iterations", iterations)), iterations)
        groups.setdefault(p.variant, []).append((p.id, params))
    if not groups:
        raise InvalidExperimentError(f"paper '{paper.name}': none of its planners is available")
    return groups


def paper_budget(paper: PaperData, iterations: int | None = None) -> dict[str, Any]:
    """The paper's budget as keyword arguments of :class:`~pathzoo.core.budget.Budget`, ``iterations`` replacing its count."""
    budget = dict(paper.budget)
    if iterations is not None:
        budget["iterations"] = iterations
    return budget


def experiment_name(paper: PaperData, seeds: int, iterations: int | None = None) -> str:
    """The name of a rerun's experiment: the paper, the seed count and any iteration override."""
    return f"reproduce.{paper.name}.s{seeds}" + (f".i{iterations}" if iterations is not None else "")


def _param_names(planner_id: str) -> set[str]:
    from pathzoo.harness.planner_info import info_of

    return set(info_of(planner_id, {}).declared)


def label_runs(paper: PaperData, runs: pd.DataFrame, experiment: Any) -> pd.DataFrame:
    """Runs labelled by the paper's planner key (one configuration per key), variants under the paper's scenario id."""
    by_spec = {}
    for spec in experiment.planners:
        for p in paper.planners:
            if p.id == spec.id and not planner_status(p):
                by_spec[(spec.id, spec.params_hash)] = p
    out = runs.copy()
    chosen = [by_spec.get((pid, h)) for pid, h in zip(runs["planner"], runs["params_hash"])]
    out["planner"] = [p.key if p else pid for p, pid in zip(chosen, runs["planner"])]
    out["scenario"] = [sid[: len(sid) - len(p.variant)] if p and p.variant and sid.endswith(p.variant) else sid
                       for p, sid in zip(chosen, runs["scenario"])]
    out["params_hash"] = "paper"
    out["label"] = out["planner"]  # the configuration name the analysis shows (pathzoo.analysis.frame.config_labels)
    return out


def add_derived(paper: PaperData, runs: pd.DataFrame, db: str | Path, experiment: str) -> pd.DataFrame:
    """Columns for the paper's derived metrics, computed from each stored path."""
    from pathzoo.plugins.lookup import load_scenario
    from pathzoo.harness.store import read_path

    derived = [m for m in paper.metrics if m.derived]
    if not derived:
        return runs
    out = runs.copy()
    scenarios = {sid: load_scenario(sid) for sid in out["scenario"].unique()}
    for m in derived:
        module, _, func = str(m.derived).partition(":")
        fn: Callable[[Any, np.ndarray], float] = getattr(importlib.import_module(module), func)
        values = []
        for key, sid in zip(out["run_key"], out["scenario"]):
            path = read_path(db, experiment, key)[0]
            values.append(float(fn(scenarios[sid], path)) if path is not None and len(path) else math.nan)
        out[m.id] = values
    return out


@dataclass(frozen=True)
class RerunOptions:
    """How a paper's comparison is rerun, by :func:`run_paper` and the equal-evaluation rerun.

    Attributes
    ----------
    db : path
        The results database; a rerun resumes the runs it holds.
    seeds, iterations, scenarios
        Runs per planner and scenario (default: the paper's run count), a cap
        on the iterations, a glob on the paper's scenario ids: see
        :func:`build_experiments`.
    jobs, executor, progress
        Passed to :func:`~pathzoo.harness.runner.run_experiment`.
    sandbox_limits : SandboxLimits, optional
        The limits of each sandboxed worker; by default the paper's
        ``sandbox_memory_gib`` where it sets one, else the sandbox's own.
    """

    db: str | Path
    seeds: int | None = None
    iterations: int | None = None
    scenarios: str | None = None
    jobs: int | None = None
    executor: str = "process"
    progress: bool = True
    sandbox_limits: "SandboxLimits | None" = None


def run_labelled(paper: PaperData, experiment: Any, options: RerunOptions) -> pd.DataFrame:
    """Run (or resume) one experiment of a rerun; its runs with the derived metrics, labelled (:func:`label_runs`)."""
    from pathzoo.harness.runner import run_experiment

    limits = options.sandbox_limits
    if limits is None and paper.sandbox_memory_gib is not None:
        from pathzoo.harness.sandbox import SandboxLimits

        limits = SandboxLimits.with_memory_gib(paper.sandbox_memory_gib)
    runs = run_experiment(experiment, db=options.db, jobs=options.jobs, executor=options.executor,
                          progress=options.progress, sandbox_limits=limits)
    return label_runs(paper, add_derived(paper, runs, options.db, experiment.name), experiment)


def run_paper(paper: PaperData, options: RerunOptions) -> tuple[pd.DataFrame, list[str]]:
    """Run (or resume) the paper's comparison; return the labelled runs and the experiments' names."""
    experiments = build_experiments(paper, seeds=options.seeds, iterations=options.iterations,
                                    scenarios=options.scenarios, db=options.db)
    return pd.concat([run_labelled(paper, exp, options) for exp in experiments], ignore_index=True), \
        [exp.name for exp in experiments]
