"""pathzoo's built-in metrics, computed by the harness from each run's path (see ``docs/metrics.md``)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from pathzoo.lazy_names import lazy_getattr

if TYPE_CHECKING:
    from pathzoo.metrics.catalogue import BUILTIN_METRICS
    from pathzoo.metrics.clearance import ClearanceMean, ClearanceMin
    from pathzoo.metrics.optimality import ArrivalRatio, LengthRatio, LengthRatioAnyAngle, LengthRatioAnyAngleBound
    from pathzoo.metrics.outcome import CpuTime, Evaluations, Iterations, PlanningTime, Success
    from pathzoo.metrics.path_shape import Length, Smoothness, TurningAngle, Turns
    from pathzoo.metrics.travel import Energy, TravelTime

_LAZY = {
    "BUILTIN_METRICS": "catalogue",
    "ClearanceMean": "clearance",
    "ClearanceMin": "clearance",
    "ArrivalRatio": "optimality",
    "LengthRatio": "optimality",
    "LengthRatioAnyAngle": "optimality",
    "LengthRatioAnyAngleBound": "optimality",
    "CpuTime": "outcome",
    "Evaluations": "outcome",
    "Iterations": "outcome",
    "PlanningTime": "outcome",
    "Success": "outcome",
    "Length": "path_shape",
    "Smoothness": "path_shape",
    "TurningAngle": "path_shape",
    "Turns": "path_shape",
    "Energy": "travel",
    "TravelTime": "travel",
}
"""Each name's module: the package imports none of them, so a module that needs one metric (the store needs
:mod:`pathzoo.metrics.outcome`) does not load the geometry kernels (numba, scipy) of the others."""

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

__getattr__ = lazy_getattr(__name__, _LAZY)
