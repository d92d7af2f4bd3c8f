# mypy: disable-error-code="empty-body"
# (a hook specification is a signature and a docstring; the plugins implement the bodies)
"""All pluggy hook specifications of pathzoo, in one place.

A plugin is a module (or object) exposed under the entry-point group of its
kind (:data:`pathzoo.plugins.manager.KIND_GROUPS`): ``pathzoo.planners``,
``pathzoo.scenarios`` or ``pathzoo.metrics``. It implements any of these hooks
with ``@pathzoo.hookimpl``::

    [project.entry-points."pathzoo.planners"]
    greedy = "pathzoo_greedy.plugin"

A module may implement only the registration hook of its group (the others are
ignored, so that the judge never imports planner code).

Registration hooks return classes or entries; data hooks return files a
plugin ships for pathzoo to read (the papers' tables); observer hooks are
told about harness events and return nothing.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Mapping, Sequence

import pluggy

if TYPE_CHECKING:
    from pathzoo.core.metric import Metric
    from pathzoo.core.planner import Planner
    from pathzoo.core.results import RunRecord
    from pathzoo.plugins.entries import LazyMetric, LazyPlanner, ScenarioEntry

__all__ = ["hookspec", "hookimpl", "PROJECT"]

PROJECT = "pathzoo"
hookspec = pluggy.HookspecMarker(PROJECT)
hookimpl = pluggy.HookimplMarker(PROJECT)


@hookspec
def pathzoo_register_planners() -> Sequence[type["Planner"] | "LazyPlanner"]:
    """Return the planners this plugin provides: classes, or lazy declarations that import them when built."""


@hookspec
def pathzoo_register_scenarios() -> Sequence["ScenarioEntry"]:
    """Return the scenarios this plugin provides, as lazily loaded entries."""


@hookspec
def pathzoo_register_metrics() -> Sequence[type["Metric"] | "LazyMetric"]:
    """Return the metrics this plugin provides: classes, or lazy declarations that import them when used."""


@hookspec
def pathzoo_paper_tables() -> Mapping[str, Path]:
    """Return the papers' comparison tables this plugin ships: paper name to its TOML data file.

    ``pathzoo reproduce <paper>`` reruns the table (the file's format is in
    :mod:`pathzoo.analysis.reproduction`). The first plugin registered that
    names a paper provides it.
    """


@hookspec
def pathzoo_run_started(run_key: str, planner_id: str, scenario_id: str, seed: int) -> None:
    """Observer: a run is about to start (called in the harness process)."""


@hookspec
def pathzoo_run_finished(record: "RunRecord") -> None:
    """Observer: a run has been validated, measured and stored."""


@hookspec
def pathzoo_experiment_finished(experiment: str, db: str, n_runs: int) -> None:
    """Observer: every run of an experiment is stored."""
