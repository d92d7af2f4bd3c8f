"""What a sandboxed worker may read: the directories of the experiment's scenario files and of its planners' files.

A sandboxed worker sees the directories noted before it started
(``docs/sandbox.md``); a run whose scenario file lies elsewhere goes to a
worker started later (:func:`sees`).
"""

from __future__ import annotations

import os
import threading
from typing import TYPE_CHECKING, Iterable

if TYPE_CHECKING:
    from pathzoo.harness.executors.worker_handle import Worker
    from pathzoo.harness.specs import RunTask

__all__ = ["Visibility", "sees"]


class Visibility:
    """The directories sandboxed workers started from now on can read (thread-safe)."""

    def __init__(self) -> None:
        self._dirs: set[str] = set()
        self._lock = threading.Lock()

    def dirs(self) -> list[str]:
        """The directories noted so far, sorted."""
        with self._lock:
            return sorted(self._dirs)

    def _add(self, dirs: Iterable[str]) -> None:
        with self._lock:
            self._dirs.update(dirs)

    def see_files(self, tasks: "list[RunTask]") -> None:
        """Note the directories of the tasks' scenario files and of the files their planners read (``LazyPlanner.folders``).

        Sandboxed workers started from now on can read them.
        """
        self._add(os.path.dirname(os.path.abspath(t.scenario.location)) for t in tasks
                  if t.scenario.source == "file")
        for planner_id in {t.planner.id for t in tasks}:
            self.see_planner(planner_id)

    def see_planner(self, planner_id: str) -> None:
        """Note the folders the planner reads (``LazyPlanner.folders``), for the sandboxed workers started from now on."""
        from pathzoo.plugins.entries import LazyPlanner
        from pathzoo.plugins.manager import get_registry

        entry = get_registry().planners.get(planner_id)
        if entry is not None and isinstance(entry.provided, LazyPlanner):
            self._add(entry.provided.folders)


def sees(worker: Worker, task: "RunTask") -> bool:
    """Whether the worker can read the task's scenario (a sandboxed one sees the files known when it started)."""
    spec = task.scenario
    return (worker.group is None or spec.source != "file"
            or os.path.dirname(os.path.abspath(spec.location)) in worker.visible)
