"""The executor interface: submit run tasks, get futures of their outcomes (concurrent.futures style)."""

from __future__ import annotations

import abc
from concurrent.futures import Future
from typing import TYPE_CHECKING, Hashable

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask
    from pathzoo.harness.outcome import RunOutcome

__all__ = ["RunExecutor"]


class RunExecutor(abc.ABC):
    """Where runs execute.

    :meth:`submit` returns a :class:`concurrent.futures.Future` that always
    resolves to a :class:`~pathzoo.harness.outcome.RunOutcome`: planner
    exceptions, hard-limit kills and dead workers are outcomes (``crash``,
    ``timed_out``), not future exceptions. The runner keeps at most
    :attr:`capacity` + :attr:`lookahead` runs in flight, so a run starts soon after it is submitted.
    Use executors as context managers; :meth:`shutdown` stops every worker.
    """

    capacity: int = 1
    """How many runs execute at the same time."""

    lookahead: int = 0
    """How many runs beyond :attr:`capacity` the runner may queue here, so a worker that finishes a run finds its
    next one waiting instead of waiting for the harness to judge and store the last one."""

    isolated: bool = False
    """Whether every run executes in a process of its own that no other planner's code can have changed
    (stored with each run; an executor that does not say so is taken as not isolated)."""

    sandbox_problem: str = "this executor runs no planner in an OS sandbox"
    """Why this executor's runs are not sandboxed (``""`` when they are, or when each run's outcome says it:
    ``RunOutcome.sandboxed`` is the truth stored with every run; see ``docs/sandbox.md``)."""

    @abc.abstractmethod
    def submit(self, task: "RunTask") -> "Future[RunOutcome]":
        """Schedule one run."""

    def lane(self, task: "RunTask") -> Hashable:
        """The lane of a run, where runs of one lane go to the same workers; None (the default) for an executor
        without lanes.

        The runner keeps a run queued for every lane that has one executing
        (:mod:`pathzoo.harness.run_queue`), so the worker of a lane whose runs
        are fast does not wait for the harness while the runs queued ahead
        are another lane's.
        """
        return None

    def capacity_changed(self) -> "Future[None] | None":
        """A future that resolves when :attr:`capacity` or :attr:`lookahead` next changes, so the runner submits
        more runs at once; None (the default) for an executor whose capacity never changes."""
        return None

    def prepare(self, tasks: "list[RunTask]") -> None:
        """Hear of the runs about to be submitted, e.g. to warm the workers up (default: nothing)."""

    def shutdown(self) -> None:
        """Stop the workers; runs still in flight are abandoned (their futures cancelled)."""

    def __enter__(self) -> "RunExecutor":
        return self

    def __exit__(self, *exc: object) -> None:
        self.shutdown()
