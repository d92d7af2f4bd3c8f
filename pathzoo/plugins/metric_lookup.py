"""A metric by id: its unit and whether smaller or larger is better, for every column analysis may rank.

A registered metric's unit and direction are read from the registry
(``pathzoo list metrics``) as the plugins declare them, so a look-up imports
no metric code. The harness's own numeric columns and the columns analysis
derives are known here too. Nothing here needs pandas or numpy, so
``pathzoo run`` checks ``--metric`` without loading them; the analysis uses
the same look-up (:mod:`pathzoo.analysis.frame`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from pathzoo.core.errors import InvalidParameterError, UnknownPluginError
from pathzoo.core.suggest import did_you_mean
from pathzoo.plugins.manager import get_registry

__all__ = ["Direction", "MetricInfo", "RUN_COLUMNS", "DERIVED_COLUMNS", "metric_info"]

Direction = Literal["min", "max"]


@dataclass(frozen=True)
class MetricInfo:
    """What analysis needs to know about a metric column.

    Attributes
    ----------
    id : str
        Column name in the runs frame.
    unit : str
        SI unit, ``"1"`` for dimensionless.
    direction : {"min", "max"}
        Whether smaller or larger is better.
    """

    id: str
    unit: str
    direction: Direction

    @property
    def label(self) -> str:
        """``"length [m]"``, or the bare id for dimensionless metrics."""
        return self.id if self.unit in ("", "1") else f"{self.id} [{self.unit}]"

    @property
    def better(self) -> str:
        """``"lower is better"`` or ``"higher is better"``."""
        return "lower is better" if self.direction == "min" else "higher is better"


RUN_COLUMNS: dict[str, MetricInfo] = {
    "wall_time_s": MetricInfo("wall_time_s", "s", "min"),
    "cpu_time_s": MetricInfo("cpu_time_s", "s", "min"),
    "iterations": MetricInfo("iterations", "1", "min"),
    "evaluations": MetricInfo("evaluations", "1", "min"),
}
"""Numeric harness columns that may be ranked like metrics (all minimised)."""

DERIVED_COLUMNS: dict[str, MetricInfo] = {
    "model_ratio": MetricInfo("model_ratio", "1", "min"),
}
"""Columns analysis adds to the runs frame and ranks like metrics (:mod:`pathzoo.analysis.path_models`)."""

def metric_info(metric: str, direction: Direction | None = None, unit: str | None = None) -> MetricInfo:
    """Look up a metric's unit and direction.

    Parameters
    ----------
    metric : str
        Metric id (a registered metric, or one of :data:`RUN_COLUMNS`).
    direction : {"min", "max"}, optional
        Override (needed for columns that are not registered metrics).
    unit : str, optional
        Override of the unit.

    Raises
    ------
    UnknownPluginError
        The metric is not registered and no ``direction`` was given.
    InvalidParameterError
        ``direction`` is not ``"min"`` or ``"max"``.
    """
    if direction is not None and direction not in ("min", "max"):
        raise InvalidParameterError(f"direction must be 'min' or 'max', got {direction!r}")
    known = RUN_COLUMNS.get(metric) or DERIVED_COLUMNS.get(metric)
    if known is None and (direction is None or unit is None):
        entry = get_registry().metrics.get(metric)
        if entry is not None:  # as declared: a lazily declared metric's module (numba kernels) stays unloaded
            known = MetricInfo(metric, str(entry.declared("unit")), entry.declared("direction"))
    if known is None and direction is None:
        hint = did_you_mean(metric, [*get_registry().metrics, *RUN_COLUMNS])
        raise UnknownPluginError(
            f"unknown metric '{metric}'{hint} (see 'pathzoo list metrics'; from Python, another column is ranked "
            "when given direction='min' or 'max')"
        )
    return MetricInfo(
        metric,
        unit if unit is not None else (known.unit if known else "1"),
        direction if direction is not None else known.direction,  # type: ignore[union-attr]
    )
