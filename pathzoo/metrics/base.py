"""The base of the metrics measured on a validated path: NaN unless the run succeeded."""

from __future__ import annotations

import abc
import math
from typing import TYPE_CHECKING

import numpy as np

from pathzoo.core.metric import Metric

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["PathMetric"]


class PathMetric(Metric, abc.ABC):
    """A metric of the returned path, defined only for successful runs.

    :meth:`compute` returns NaN unless the harness validated a solved path
    (``record.success``); subclasses implement :meth:`measure`.
    """

    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """NaN unless ``record.success``; otherwise :meth:`measure` of the path."""
        if not record.success or record.path is None:
            return math.nan
        return float(self.measure(scenario, np.asarray(record.path, dtype=np.float64), record))

    @abc.abstractmethod
    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """The metric of a validated path (world coordinates, metres)."""
