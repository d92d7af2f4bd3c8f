"""The clock stops the harness attaches to a run's budget (:class:`pathzoo.core.budget.ClockStop`).

A planner learns that a clock limit is spent only through its budget's
clock (:meth:`~pathzoo.core.budget.BudgetClock.exhausted`), which reads the
stop attached here. Two kinds:

- :class:`SharedClockStop`: one byte shared between the harness and a
  worker process. The harness measures the run's CPU time (the worker's
  process tree, :mod:`pathzoo.harness.cpu_clock`) and wall time from
  outside and sets the byte when a limit is spent; the worker only reads
  it. The harness keeps its own record of what it set, so a planner that
  writes the byte changes only its own stopping, never what is stored.
- :class:`InProcessClockStop`: the run's clocks read in the planner's own
  process (``time.process_time``, ``time.perf_counter``), for the executors
  that run planners where the harness cannot watch them from outside
  (``inline``, Dask).

Both are sticky: once a limit is reported, it is reported on every later call.
"""

from __future__ import annotations

import math
import time
from typing import Any

from pathzoo.core.budget import Budget, StopReason

__all__ = ["InProcessClockStop", "SharedClockStop"]

_CODES: dict[int, StopReason] = {1: "cpu_time", 2: "wall_time"}
_REASONS = {reason: code for code, reason in _CODES.items()}


class SharedClockStop:
    """A stop byte in shared memory: the harness sets it, the planner's budget clock reads it.

    Parameters
    ----------
    flag : ctypes array of one signed byte
        Shared memory, e.g. ``multiprocessing.get_context().RawArray("b", 1)``
        made by the harness and passed to the worker when it starts.
    """

    def __init__(self, flag: Any) -> None:
        self.flag = flag

    def reason(self) -> StopReason | None:
        """The limit the harness reported spent, or None."""
        return _CODES.get(self.flag[0])

    def set(self, reason: StopReason) -> None:
        """Report ``reason`` (``"cpu_time"`` or ``"wall_time"``) to the planner (harness side)."""
        self.flag[0] = _REASONS[reason]

    def clear(self) -> None:
        """Reset before the next run is sent (harness side, while the worker is idle)."""
        self.flag[0] = 0


class InProcessClockStop:
    """The clock limits of ``budget``, read in this process from its creation on.

    Parameters
    ----------
    budget : Budget
        The run's budget (its ``cpu_s`` and ``time_s``).
    """

    def __init__(self, budget: Budget) -> None:
        self.cpu_s = math.inf if budget.cpu_s is None else budget.cpu_s
        self.time_s = math.inf if budget.time_s is None else budget.time_s
        self.t0 = time.perf_counter()
        self.c0 = time.process_time()
        self.raised: StopReason | None = None

    def reason(self) -> StopReason | None:
        """``"cpu_time"`` or ``"wall_time"`` once that limit is spent (the first one stays), else None."""
        if self.raised is None:
            if time.process_time() - self.c0 >= self.cpu_s:
                self.raised = "cpu_time"
            elif time.perf_counter() - self.t0 >= self.time_s:
                self.raised = "wall_time"
        return self.raised
