"""The three interfaces of pathzoo (Scenario, Planner, Metric) and their data types."""

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

__all__ = [
    "Budget",
    "BudgetClock",
    "HistoryPoint",
    "InvalidExperimentError",
    "InvalidParameterError",
    "InvalidScenarioError",
    "Metric",
    "MovingObstacle",
    "Param",
    "PathzooError",
    "PlanResult",
    "Planner",
    "ProgressCallback",
    "RunRecord",
    "RunStatus",
    "SCENARIO_KINDS",
    "Scenario",
    "ScenarioKind",
    "Status",
    "TerrainRules",
    "UnknownPluginError",
    "UnsupportedScenarioError",
    "VehicleModel",
]
