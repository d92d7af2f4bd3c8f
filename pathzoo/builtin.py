"""The ``core`` plugin: pathzoo's own metrics, declared like any third-party plugin's and imported when first used."""

from __future__ import annotations

from typing import Sequence

from pathzoo.plugins.entries import LazyMetric
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_metrics", "METRICS"]

METRICS: tuple[LazyMetric, ...] = (
    LazyMetric("success", "1 if the run gave a valid path, else 0", "pathzoo.metrics.outcome:Success",
               unit="1", direction="max"),
    LazyMetric("length", "path length (3-D on terrain and in air)", "pathzoo.metrics.path_shape:Length",
               unit="m", direction="min"),
    LazyMetric("length_ratio", "length / exact graph optimum (any-angle paths may be < 1)",
               "pathzoo.metrics.optimality:LengthRatio", unit="1", direction="min"),
    LazyMetric("length_ratio_anyangle", "length / exact any-angle optimum (grid2d up to 4096x4096; never below 1)",
               "pathzoo.metrics.optimality:LengthRatioAnyAngle", unit="1", direction="min"),
    LazyMetric("length_ratio_anyangle_bound",
               "length / Lazy Theta* length (air3d; an upper bound on the any-angle optimum, may be < 1)",
               "pathzoo.metrics.optimality:LengthRatioAnyAngleBound", unit="1", direction="min"),
    LazyMetric("arrival_ratio", "arrival time / earliest arrival of SIPP (dynamic; grid paths never below 1)",
               "pathzoo.metrics.optimality:ArrivalRatio", unit="1", direction="min"),
    LazyMetric("planning_time", "wall time of plan() (successful runs)", "pathzoo.metrics.outcome:PlanningTime",
               unit="s", direction="min"),
    LazyMetric("cpu_time", "CPU time of plan() (successful runs)", "pathzoo.metrics.outcome:CpuTime",
               unit="s", direction="min"),
    LazyMetric("travel_time", "time to drive the path, turns included", "pathzoo.metrics.travel:TravelTime",
               unit="s", direction="min"),
    LazyMetric("energy", "energy to drive the path (G-Ant eq. 4, turns included)", "pathzoo.metrics.travel:Energy",
               unit="J", direction="min"),
    LazyMetric("turns", "number of heading changes", "pathzoo.metrics.path_shape:Turns", unit="1", direction="min"),
    LazyMetric("turning_angle", "total heading change", "pathzoo.metrics.path_shape:TurningAngle",
               unit="rad", direction="min"),
    LazyMetric("smoothness", "heading change per metre (turning_angle / length)",
               "pathzoo.metrics.path_shape:Smoothness", unit="rad/m", direction="min"),
    LazyMetric("clearance_min", "smallest distance to an obstacle along the path (cell resolution)",
               "pathzoo.metrics.clearance:ClearanceMin", unit="m", direction="max"),
    LazyMetric("clearance_mean", "mean distance to obstacles along the path (cell resolution)",
               "pathzoo.metrics.clearance:ClearanceMean", unit="m", direction="max"),
    LazyMetric("iterations", "planner iterations (every run that returned)", "pathzoo.metrics.outcome:Iterations",
               unit="1", direction="min"),
    LazyMetric("evaluations", "planner evaluations (every run that returned)", "pathzoo.metrics.outcome:Evaluations",
               unit="1", direction="min"),
)
"""Every built-in metric (``pathzoo.metrics.BUILTIN_METRICS``, same order: the column order of result tables)."""


@hookimpl
def pathzoo_register_metrics() -> Sequence[LazyMetric]:
    """Every built-in metric (see ``docs/metrics.md``), declared without importing it (:data:`METRICS`)."""
    return METRICS
