"""The Metric interface: a number the harness computes from a run's path."""

from __future__ import annotations

import abc
from typing import TYPE_CHECKING, ClassVar, Literal

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["Metric"]


class Metric(abc.ABC):
    """Base class of every metric.

    Attributes
    ----------
    id : str
        Column name in result tables, e.g. ``"length"``.
    unit : str
        SI unit (``"m"``, ``"s"``, ``"J"``, ``"rad"``, ``"1"``).
    direction : {"min", "max"}
        Whether smaller or larger is better.
    summary : str
        One line for ``pathzoo list metrics``.
    """

    id: ClassVar[str] = ""
    unit: ClassVar[str] = "1"
    direction: ClassVar[Literal["min", "max"]] = "min"
    summary: ClassVar[str] = ""

    @abc.abstractmethod
    def compute(self, scenario: "Scenario", record: "RunRecord") -> float:
        """Return the metric for one run, or NaN when the run did not succeed."""
