"""Metrics of the run itself: success, planning wall and CPU time, iterations and evaluations."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, ClassVar

from pathzoo.core.metric import Metric
from pathzoo.core.status import RunStatus

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["Success", "RecordValue", "PlanningTime", "CpuTime", "Iterations", "Evaluations", "RETURNED"]

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


class RecordValue(Metric):
    """A number the harness measured or the planner counted, read from the run record.

    Subclasses name the :class:`~pathzoo.core.results.RunRecord` attribute.
    The value is NaN unless the run succeeded, or, with ``every_return``,
    unless ``plan()`` returned at all (no crash, no timeout).
    """

    attribute: ClassVar[str] = ""
    every_return: ClassVar[bool] = False

    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """``record.<attribute>`` or NaN (see the class docstring)."""
        defined = record.status in RETURNED if self.every_return else record.success
        return float(getattr(record, self.attribute)) if defined else math.nan


class PlanningTime(RecordValue):
    """Wall-clock seconds spent in ``plan()`` by a successful run."""

    id = "planning_time"
    unit = "s"
    direction = "min"
    summary = "wall time of plan() (successful runs)"
    attribute = "wall_time_s"


class CpuTime(RecordValue):
    """CPU seconds (all threads of the worker process) spent in ``plan()`` by a successful run."""

    id = "cpu_time"
    unit = "s"
    direction = "min"
    summary = "CPU time of plan() (successful runs)"
    attribute = "cpu_time_s"


class Iterations(RecordValue):
    """Iterations the planner reports, for every run whose ``plan()`` returned (NaN on crash or timeout)."""

    id = "iterations"
    unit = "1"
    direction = "min"
    summary = "planner iterations (every run that returned)"
    attribute = "iterations"
    every_return = True


class Evaluations(RecordValue):
    """Candidate evaluations the planner reports, for every run whose ``plan()`` returned."""

    id = "evaluations"
    unit = "1"
    direction = "min"
    summary = "planner evaluations (every run that returned)"
    attribute = "evaluations"
    every_return = True
