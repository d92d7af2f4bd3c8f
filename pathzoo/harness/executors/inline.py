"""The inline executor: runs execute one after another in this process (for debugging and docs only).

Nothing is isolated here: the planner runs in the harness's own process, so
it could patch the harness itself. The verdict is still given by the judge
process (:mod:`pathzoo.harness.judge_worker`) on its own scenario, and wall
and CPU times are read with clock functions bound when this module was
imported (the clock limits are read in this process too,
:class:`~pathzoo.harness.clock_stop.InProcessClockStop`), but every run is stored with ``isolated = False`` and shown so by
the leaderboard and the report. Use ``process`` or ``dask`` for results.
"""

from __future__ import annotations

import math
import time
from concurrent.futures import Future
from dataclasses import replace
from typing import TYPE_CHECKING

from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.worker import execute_task

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask
    from pathzoo.harness.outcome import RunOutcome

__all__ = ["InlineExecutor"]

_clock = time.perf_counter
_cpu = time.process_time


class InlineExecutor(RunExecutor):
    """Run each task at submission, in the calling process (not isolated; see the module docstring).

    A planner that hangs hangs the experiment, one that kills its process
    kills the harness, and the hard limit can only be applied after the fact
    (a run that returns later than ``timeout_s`` is recorded as ``timeout``).
    Its results are otherwise identical to the other executors'.
    """

    capacity = 1
    isolated = False
    sandbox_problem = "the inline executor runs planners in the harness's own process"

    def submit(self, task: "RunTask") -> "Future[RunOutcome]":
        """Run the task now and return a completed future."""
        future: Future[RunOutcome] = Future()
        future.set_running_or_notify_cancel()
        marks = {"planning": (math.nan, math.nan), "planned": (math.nan, math.nan)}

        def report(event: str) -> None:
            if event in marks and math.isnan(marks[event][0]):
                marks[event] = (_clock(), _cpu())

        outcome = execute_task(task, report, interruptible=True)
        (t0, c0), (t1, c1) = marks["planning"], marks["planned"]
        future.set_result(replace(outcome, wall_time_s=t1 - t0, cpu_time_s=c1 - c0))
        return future
