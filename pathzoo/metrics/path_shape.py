"""Metrics of the path's shape: length, turns, total turning angle and smoothness."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pathzoo.metrics.base import PathMetric
from pathzoo.metrics.geometry import TURN_EPS_RAD, driven_pieces, turn_angles

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["Length", "Turns", "TurningAngle", "Smoothness"]


class Length(PathMetric):
    """Length of the path in metres: 3-D over the DEM on terrain, 3-D in air, planar otherwise."""

    id = "length"
    unit = "m"
    direction = "min"
    summary = "path length (3-D on terrain and in air)"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """Sum of :func:`~pathzoo.metrics.geometry.driven_pieces` lengths."""
        return float(driven_pieces(scenario, path)[0].sum())


class Turns(PathMetric):
    """Number of waypoints where the heading changes by more than 1e-6 rad."""

    id = "turns"
    unit = "1"
    direction = "min"
    summary = "number of heading changes"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """Count of :func:`~pathzoo.metrics.geometry.turn_angles` above :data:`TURN_EPS_RAD`."""
        return float(np.count_nonzero(turn_angles(path) > TURN_EPS_RAD))


class TurningAngle(PathMetric):
    """Sum of the absolute heading changes along the path, radians."""

    id = "turning_angle"
    unit = "rad"
    direction = "min"
    summary = "total heading change"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """``Σ |Δψ_i|`` over the waypoints."""
        return float(turn_angles(path).sum())


class Smoothness(PathMetric):
    """Total heading change per metre driven, rad/m (0 for a straight path; smaller is smoother)."""

    id = "smoothness"
    unit = "rad/m"
    direction = "min"
    summary = "heading change per metre (turning_angle / length)"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """``Σ |Δψ_i| / L``; 0 for a path of zero length."""
        length = float(driven_pieces(scenario, path)[0].sum())
        return float(turn_angles(path).sum()) / length if length > 0 else 0.0
