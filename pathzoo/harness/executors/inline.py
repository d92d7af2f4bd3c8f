"""The inline executor: runs execute one after another in this process (for debugging and docs)."""

from __future__ import annotations

from concurrent.futures import Future
from typing import TYPE_CHECKING

from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.worker import execute_task

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask
    from pathzoo.harness.worker import RunOutcome

__all__ = ["InlineExecutor"]


class InlineExecutor(RunExecutor):
    """Run each task at submission, in the calling process.

    There is no isolation: a planner that hangs hangs the experiment, one that
    kills its process kills the harness, and the hard limit can only be applied
    after the fact (a run that returns later than ``timeout_s`` is recorded as
    ``timeout``). Results are identical to the other executors'.
    """

    capacity = 1

    def submit(self, task: "RunTask") -> "Future[RunOutcome]":
        """Run the task now and return a completed future."""
        future: Future[RunOutcome] = Future()
        future.set_running_or_notify_cancel()
        future.set_result(execute_task(task))
        return future
