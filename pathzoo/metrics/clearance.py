"""Metrics of the distance kept from obstacles: smallest and mean clearance along the path."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pathzoo.metrics.base import PathMetric
from pathzoo.metrics.geometry import clearance_samples

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["ClearanceMin", "ClearanceMean"]


class ClearanceMin(PathMetric):
    """Smallest clearance (m) over the path's samples (see :func:`~pathzoo.metrics.geometry.clearance_samples`)."""

    id = "clearance_min"
    unit = "m"
    direction = "max"
    summary = "smallest distance to an obstacle along the path (cell resolution)"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """``min_k clearance(cell(s_k))``."""
        return float(clearance_samples(scenario, path).min())


class ClearanceMean(PathMetric):
    """Mean clearance (m) over samples evenly spaced by arc length."""

    id = "clearance_mean"
    unit = "m"
    direction = "max"
    summary = "mean distance to obstacles along the path (cell resolution)"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """``mean_k clearance(cell(s_k))``."""
        return float(clearance_samples(scenario, path).mean())
