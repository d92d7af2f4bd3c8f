"""Planning budgets: iterations, evaluations and wall time."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Mapping

from pathzoo.core.errors import InvalidParameterError

__all__ = ["Budget", "BudgetClock"]


@dataclass(frozen=True)
class Budget:
    """Limits a planner must respect; ``None`` means unlimited.

    A planner stops as soon as *any* limit is reached. Exact planners, which
    finish in one pass, only honour ``time_s``.

    Parameters
    ----------
    iterations : int, optional
        Maximum number of planner iterations (ACO/PSO/GA generations, ...).
    evaluations : int, optional
        Maximum number of candidate evaluations (ant walks, particle or
        individual cost evaluations, ...).
    time_s : float, optional
        Maximum planning wall time in seconds.
    """

    iterations: int | None = None
    evaluations: int | None = None
    time_s: float | None = None

    def __post_init__(self) -> None:
        for name in ("iterations", "evaluations"):
            value = getattr(self, name)
            if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
                raise InvalidParameterError(f"budget.{name} must be a positive integer, got {value!r}")
        if self.time_s is not None and (
            isinstance(self.time_s, bool)
            or not isinstance(self.time_s, (int, float))
            or not math.isfinite(self.time_s)
            or self.time_s <= 0
        ):
            raise InvalidParameterError(f"budget.time_s must be a positive number of seconds, got {self.time_s!r}")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], *, where: str = "budget") -> "Budget":
        """Build a budget from a mapping such as a TOML table.

        Raises
        ------
        InvalidParameterError
            On unknown keys or bad values.
        """
        unknown = set(data) - {"iterations", "evaluations", "time_s"}
        if unknown:
            raise InvalidParameterError(
                f"{where}: unknown key(s) {sorted(unknown)}; allowed: iterations, evaluations, time_s"
            )
        return cls(**dict(data))

    def to_dict(self) -> dict[str, Any]:
        """Return the limits as a plain dict (``None`` for unlimited)."""
        return {"iterations": self.iterations, "evaluations": self.evaluations, "time_s": self.time_s}

    @property
    def unlimited(self) -> bool:
        """True when no limit at all is set."""
        return self.iterations is None and self.evaluations is None and self.time_s is None

    def start(self) -> "BudgetClock":
        """Start the clock for one ``plan()`` call."""
        return BudgetClock(self)


@dataclass
class BudgetClock:
    """Tracks consumption of a :class:`Budget` during one ``plan()`` call.

    Examples
    --------
    >>> clock = Budget(iterations=3).start()
    >>> while not clock.exhausted(iterations=i, evaluations=0): ...  # doctest: +SKIP
    """

    budget: Budget
    started: float = field(default_factory=time.perf_counter)

    @property
    def elapsed(self) -> float:
        """Seconds since the clock started."""
        return time.perf_counter() - self.started

    @property
    def remaining_time(self) -> float:
        """Seconds left (``inf`` when there is no time limit)."""
        if self.budget.time_s is None:
            return math.inf
        return max(0.0, self.budget.time_s - self.elapsed)

    def exhausted(self, *, iterations: int = 0, evaluations: int = 0) -> bool:
        """True once any limit is reached by the given counts or by the clock."""
        b = self.budget
        if b.iterations is not None and iterations >= b.iterations:
            return True
        if b.evaluations is not None and evaluations >= b.evaluations:
            return True
        return b.time_s is not None and self.elapsed >= b.time_s
