"""pathzoo's built-in metrics, computed by the harness from each run's path (see ``docs/metrics.md``)."""

from __future__ import annotations

from pathzoo.core.metric import Metric
from pathzoo.metrics.clearance import ClearanceMean, ClearanceMin
from pathzoo.metrics.optimality import ArrivalRatio, LengthRatio, LengthRatioAnyAngle, LengthRatioAnyAngleBound
from pathzoo.metrics.outcome import CpuTime, Evaluations, Iterations, PlanningTime, Success
from pathzoo.metrics.path_shape import Length, Smoothness, TurningAngle, Turns
from pathzoo.metrics.travel import Energy, TravelTime

__all__ = [
    "ArrivalRatio",
    "BUILTIN_METRICS",
    "ClearanceMean",
    "ClearanceMin",
    "CpuTime",
    "Energy",
    "Evaluations",
    "Iterations",
    "Length",
    "LengthRatio",
    "LengthRatioAnyAngle",
    "LengthRatioAnyAngleBound",
    "PlanningTime",
    "Smoothness",
    "Success",
    "TravelTime",
    "TurningAngle",
    "Turns",
]

BUILTIN_METRICS: list[type[Metric]] = [
    Success,
    Length,
    LengthRatio,
    LengthRatioAnyAngle,
    LengthRatioAnyAngleBound,
    ArrivalRatio,
    PlanningTime,
    CpuTime,
    TravelTime,
    Energy,
    Turns,
    TurningAngle,
    Smoothness,
    ClearanceMin,
    ClearanceMean,
    Iterations,
    Evaluations,
]
"""Every built-in metric class, in the column order of result tables."""
