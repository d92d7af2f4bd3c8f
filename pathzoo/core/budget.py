"""Planning budgets: iterations, evaluations, CPU time and wall time, and which one ended a run.

The count limits (``iterations``, ``evaluations``) decide a result: a run
they end gives the same path on every machine. The clock limits (``cpu_s``,
``time_s``) only stop a search; a run they end depends on the machine, and
the harness stores it so (``stopped_by``, see ``docs/timing.md``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Any, Literal, Mapping, Protocol

from pathzoo.core.errors import InvalidParameterError

__all__ = ["Budget", "BudgetClock", "ClockStop", "StopReason", "STOP_REASONS", "CLOCK_STOPS"]

StopReason = Literal["iterations", "evaluations", "cpu_time", "wall_time", "none"]
"""Which limit ended a run; ``"none"``: the planner finished by itself (converged, exact search done)."""

STOP_REASONS: tuple[StopReason, ...] = ("iterations", "evaluations", "cpu_time", "wall_time", "none")
CLOCK_STOPS: tuple[StopReason, ...] = ("cpu_time", "wall_time")
"""Stop reasons that make a result depend on the machine and its load."""

_KEYS = ("iterations", "evaluations", "cpu_s", "time_s")


class ClockStop(Protocol):
    """Tells a running planner that a clock limit is spent; the harness attaches one to each run's budget.

    The harness measures the clocks outside the planner's process and sets
    the stop; :meth:`BudgetClock.exhausted` reads it, so the planner itself
    never reads a clock to decide anything.
    """

    def reason(self) -> StopReason | None:
        """``"cpu_time"`` or ``"wall_time"`` once that limit is spent, else None."""


def _check_seconds(name: str, value: Any) -> None:
    if value is not None and (
        isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0
    ):
        raise InvalidParameterError(f"budget.{name} must be a positive number of seconds, got {value!r}")


@dataclass(frozen=True)
class Budget:
    """Limits a planner must respect; ``None`` means unlimited.

    A planner stops as soon as *any* limit is reached. Exact planners, which
    finish in one pass, only honour the clock limits.

    Parameters
    ----------
    iterations : int, optional
        Maximum number of planner iterations (ACO/PSO/GA generations, ...).
    evaluations : int, optional
        Maximum number of candidate evaluations (ant walks, particle or
        individual cost evaluations, ...).
    time_s : float, optional
        Maximum planning wall time in seconds (a stop only).
    cpu_s : float, optional
        Maximum planning CPU seconds of the planner's process and its
        children, measured by the harness outside that process (a stop only).
    stop : ClockStop, optional
        Set by the harness: the clock limits are then read from it alone.
        Not part of the budget's value (equality, :meth:`to_dict`).
    """

    iterations: int | None = None
    evaluations: int | None = None
    time_s: float | None = None
    cpu_s: float | None = None
    stop: ClockStop | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        for name in ("iterations", "evaluations"):
            value = getattr(self, name)
            if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
                raise InvalidParameterError(f"budget.{name} must be a positive integer, got {value!r}")
        _check_seconds("time_s", self.time_s)
        _check_seconds("cpu_s", self.cpu_s)

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], *, where: str = "budget") -> "Budget":
        """Build a budget from a mapping such as a TOML table.

        Raises
        ------
        InvalidParameterError
            On unknown keys or bad values.
        """
        unknown = set(data) - set(_KEYS)
        if unknown:
            raise InvalidParameterError(f"{where}: unknown key(s) {sorted(unknown)}; allowed: {', '.join(_KEYS)}")
        return cls(**dict(data))

    def to_dict(self) -> dict[str, Any]:
        """Return the limits as a plain dict (``None`` for unlimited; ``cpu_s`` only when set)."""
        out = {"iterations": self.iterations, "evaluations": self.evaluations, "time_s": self.time_s}
        if self.cpu_s is not None:  # left out otherwise, so budgets stored before it existed compare equal
            out["cpu_s"] = self.cpu_s
        return out

    @property
    def unlimited(self) -> bool:
        """True when no limit at all is set."""
        return not self.counted and not self.timed

    @property
    def counted(self) -> bool:
        """True when an iteration or evaluation limit is set (a limit that gives the same result anywhere)."""
        return self.iterations is not None or self.evaluations is not None

    @property
    def timed(self) -> bool:
        """True when a clock limit (``cpu_s`` or ``time_s``) is set."""
        return self.time_s is not None or self.cpu_s is not None

    def or_default(self, iterations: int | None = None, *, evaluations: int | None = None) -> "Budget":
        """The budget a planner runs: this one, or its own count (``iterations`` or ``evaluations``) when no limit is set.

        The one budget rule of every family (``docs/timing.md``): a count
        (``iterations`` or ``evaluations``) ends the run by that count; a
        clock-only budget lets an anytime planner search until the clock; a
        budget without any limit means the planner's own default count. A
        safety limit (the harness's ``timeout_s``) is never part of a budget.

        Examples
        --------
        >>> Budget().or_default(100)
        Budget(iterations=100, evaluations=None, time_s=None, cpu_s=None)
        >>> Budget(cpu_s=2.0).or_default(100).iterations is None
        True
        >>> Budget().or_default(evaluations=5000).evaluations
        5000
        """
        return replace(self, iterations=iterations, evaluations=evaluations) if self.unlimited else self

    def count_reached(self, iterations: int, evaluations: int) -> StopReason | None:
        """``"iterations"`` or ``"evaluations"`` when these counts reach that limit, else None."""
        if self.iterations is not None and iterations >= self.iterations:
            return "iterations"
        if self.evaluations is not None and evaluations >= self.evaluations:
            return "evaluations"
        return None

    def start(self) -> "BudgetClock":
        """Start the clock for one ``plan()`` call."""
        return BudgetClock(self)


@dataclass
class BudgetClock:
    """Tracks consumption of a :class:`Budget` during one ``plan()`` call.

    Under the harness the budget carries a :class:`ClockStop` and the clock
    limits are read from it only. Without one (a planner called directly)
    the clock measures them itself: wall time with ``time.perf_counter`` and
    CPU time with ``time.process_time`` (this process only), from
    :meth:`Budget.start`.

    Examples
    --------
    >>> clock = Budget(iterations=3).start()
    >>> while not clock.exhausted(iterations=i, evaluations=0): ...  # doctest: +SKIP
    """

    budget: Budget
    started: float = field(default_factory=time.perf_counter)
    started_cpu: float = field(default_factory=time.process_time)
    stopped_by: StopReason | None = None
    """The first limit :meth:`exhausted` reported (None until then)."""

    @property
    def elapsed(self) -> float:
        """Wall seconds since the clock started (for reports only: a planner decides nothing from it)."""
        return time.perf_counter() - self.started

    @property
    def remaining_time(self) -> float:
        """Wall seconds left (``inf`` when there is no wall limit; for reports only, like :attr:`elapsed`)."""
        if self.budget.time_s is None:
            return math.inf
        return max(0.0, self.budget.time_s - self.elapsed)

    def time_up(self) -> StopReason | None:
        """``"cpu_time"`` or ``"wall_time"`` once a clock limit is spent, else None."""
        b = self.budget
        if b.stop is not None:
            return b.stop.reason()
        if b.cpu_s is not None and time.process_time() - self.started_cpu >= b.cpu_s:
            return "cpu_time"
        if b.time_s is not None and self.elapsed >= b.time_s:
            return "wall_time"
        return None

    def limit_reached(self, *, iterations: int = 0, evaluations: int = 0) -> StopReason | None:
        """The limit reached by the given counts or by a clock, else None; the first one is kept in :attr:`stopped_by`."""
        reason = self.budget.count_reached(iterations, evaluations) or self.time_up()
        if reason is not None and self.stopped_by is None:
            self.stopped_by = reason
        return reason

    def exhausted(self, *, iterations: int = 0, evaluations: int = 0) -> bool:
        """True once any limit is reached by the given counts or by a clock."""
        return self.limit_reached(iterations=iterations, evaluations=evaluations) is not None
