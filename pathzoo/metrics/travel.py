"""Metrics of driving the path: travel time and energy (G-Ant eq. 4 plus the turn model)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pathzoo.metrics.base import PathMetric
from pathzoo.metrics.geometry import travel_time_energy

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["TravelTime", "Energy"]


class TravelTime(PathMetric):
    """Time to drive the path, seconds (cruise speed plus turn slow-downs, or the path's own times)."""

    id = "travel_time"
    unit = "s"
    direction = "min"
    summary = "time to drive the path, turns included"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """See :func:`~pathzoo.metrics.geometry.travel_time_energy`."""
        return travel_time_energy(scenario, path, record.times)[0]


class Energy(PathMetric):
    """Energy to drive the path, joules (eq. 4 of G-Ant per piece plus turn penalties)."""

    id = "energy"
    unit = "J"
    direction = "min"
    summary = "energy to drive the path (G-Ant eq. 4, turns included)"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """See :func:`~pathzoo.metrics.geometry.travel_time_energy` and ``docs/energy.md``."""
        return travel_time_energy(scenario, path, record.times)[1]
