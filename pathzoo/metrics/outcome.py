"""Metrics of the run itself: success, planning wall and CPU time, iterations and evaluations."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from pathzoo.core.metric import Metric
from pathzoo.core.status import RunStatus

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["Success", "PlanningTime", "CpuTime", "Iterations", "Evaluations", "RETURNED"]

RETURNED: frozenset[RunStatus] = frozenset({RunStatus.SOLVED, RunStatus.INVALID, RunStatus.NO_PATH, RunStatus.FAILED})
"""Statuses of runs whose ``plan()`` returned a result (no crash, no timeout)."""


class Success(Metric):
    """1 when the harness validated a solved path, else 0 (never NaN)."""

    id = "success"
    unit = "1"
    direction = "max"
    summary = "1 if the run gave a valid path, else 0"

    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """``1.0`` if ``record.success`` else ``0.0``."""
        return 1.0 if record.success else 0.0


class PlanningTime(Metric):
    """Wall-clock seconds spent in ``plan()`` by a successful run."""

    id = "planning_time"
    unit = "s"
    direction = "min"
    summary = "wall time of plan() (successful runs)"

    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """``record.wall_time_s``, NaN unless the run succeeded."""
        return float(record.wall_time_s) if record.success else math.nan


class CpuTime(Metric):
    """CPU seconds (all threads of the worker process) spent in ``plan()`` by a successful run."""

    id = "cpu_time"
    unit = "s"
    direction = "min"
    summary = "CPU time of plan() (successful runs)"

    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """``record.cpu_time_s``, NaN unless the run succeeded."""
        return float(record.cpu_time_s) if record.success else math.nan


class Iterations(Metric):
    """Iterations the planner reports, for every run whose ``plan()`` returned (NaN on crash or timeout)."""

    id = "iterations"
    unit = "1"
    direction = "min"
    summary = "planner iterations (every run that returned)"

    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """``record.iterations``; NaN for ``crash`` and ``timeout``."""
        return float(record.iterations) if record.status in RETURNED else math.nan


class Evaluations(Metric):
    """Candidate evaluations the planner reports, for every run whose ``plan()`` returned."""

    id = "evaluations"
    unit = "1"
    direction = "min"
    summary = "planner evaluations (every run that returned)"

    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """``record.evaluations``; NaN for ``crash`` and ``timeout``."""
        return float(record.evaluations) if record.status in RETURNED else math.nan
