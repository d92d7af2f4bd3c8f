"""The three interfaces of pathzoo (Scenario, Planner, Metric) and their data types.

The names below are imported from their modules on first use (PEP 562), so
that importing one light module of this package (``pathzoo.core.errors``,
say, as the command line does) does not import numpy.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pathzoo.lazy_names import lazy_getattr

if TYPE_CHECKING:
    from pathzoo.core.budget import Budget, BudgetClock
    from pathzoo.core.errors import (
        InvalidExperimentError,
        InvalidParameterError,
        InvalidScenarioError,
        PathzooError,
        UnknownPluginError,
        UnsupportedScenarioError,
    )
    from pathzoo.core.metric import Metric
    from pathzoo.core.moving import MovingObstacle
    from pathzoo.core.planner import Param, Planner, ProgressCallback
    from pathzoo.core.results import HistoryPoint, PlanResult, RunRecord
    from pathzoo.core.rules import TerrainRules
    from pathzoo.core.scenario import SCENARIO_KINDS, Scenario, ScenarioKind
    from pathzoo.core.status import RunStatus, Status
    from pathzoo.core.vehicle import VehicleModel

_WHERE = {
    "Budget": "budget",
    "BudgetClock": "budget",
    "HistoryPoint": "results",
    "InvalidExperimentError": "errors",
    "InvalidParameterError": "errors",
    "InvalidScenarioError": "errors",
    "Metric": "metric",
    "MovingObstacle": "moving",
    "Param": "planner",
    "PathzooError": "errors",
    "PlanResult": "results",
    "Planner": "planner",
    "ProgressCallback": "planner",
    "RunRecord": "results",
    "RunStatus": "status",
    "SCENARIO_KINDS": "scenario",
    "Scenario": "scenario",
    "ScenarioKind": "scenario",
    "Status": "status",
    "TerrainRules": "rules",
    "UnknownPluginError": "errors",
    "UnsupportedScenarioError": "errors",
    "VehicleModel": "vehicle",
}

__all__ = sorted(_WHERE)


__getattr__ = lazy_getattr(__name__, _WHERE)
