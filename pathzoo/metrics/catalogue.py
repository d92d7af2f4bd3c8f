"""The list of pathzoo's built-in metric classes, in the column order of result tables."""

from __future__ import annotations

from pathzoo.core.metric import Metric
from pathzoo.metrics.clearance import ClearanceMean, ClearanceMin
from pathzoo.metrics.optimality import ArrivalRatio, LengthRatio, LengthRatioAnyAngle, LengthRatioAnyAngleBound
from pathzoo.metrics.outcome import CpuTime, Evaluations, Iterations, PlanningTime, Success
from pathzoo.metrics.path_shape import Length, Smoothness, TurningAngle, Turns
from pathzoo.metrics.travel import Energy, TravelTime

__all__ = ["BUILTIN_METRICS"]

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
