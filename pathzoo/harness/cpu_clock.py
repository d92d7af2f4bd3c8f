"""CPU seconds of a process and its descendants, read from outside them.

The harness charges a run the CPU time of the worker process *and* of every
process it starts (an external planner's command, a solver's helpers), so
``budget.cpu_s`` limits the planner's whole process tree. Everything here
is read from the kernel by the harness; nothing the planner's process
reports is used. :class:`ChargedCpu` is what a run is charged: the larger of
the process tree's and the worker cgroup's usage since the run was handed
over.
"""

from __future__ import annotations

import math
import os
import sys
import time
from typing import Callable

__all__ = ["DESCENDANTS_REFRESH_S", "ProcessTreeCpu", "ChargedCpu", "process_cpu_time"]

_clock = time.perf_counter  # bound at import: a later patch of the time module does not reach the harness
_clock_gettime = getattr(time, "clock_gettime", None)
_LINUX = sys.platform.startswith("linux")
_CPU_CLOCK_OF_PID = _LINUX and _clock_gettime is not None
_TICK = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100

DESCENDANTS_REFRESH_S = 0.25
"""How often the list of live descendants is read again (listing them scans every process)."""


def process_cpu_time(pid: int) -> float:
    """User + system CPU seconds of one process (its threads, not its children), read from outside it (NaN when gone).

    On Linux this reads the process's CPU-time clock (``clock_gettime`` on
    the clock id the kernel derives from a pid, as glibc's
    ``clock_getcpuclockid`` does): about 5 microseconds and nanosecond
    resolution, against 0.3-0.6 ms and 10 ms clock ticks for psutil's
    ``cpu_times``, which is the fallback elsewhere.
    """
    if _CPU_CLOCK_OF_PID:
        try:
            return _clock_gettime((~pid << 3) | 2)  # type: ignore[misc]  # MAKE_PROCESS_CPUCLOCK(pid, CPUCLOCK_SCHED)
        except OSError:  # gone
            return math.nan
    try:
        import psutil

        times = psutil.Process(pid).cpu_times()
        return float(times.user + times.system)
    except Exception:  # noqa: BLE001 - gone, or psutil unavailable
        return math.nan


def _reaped_children_cpu(pid: int) -> float:
    """CPU seconds of the children ``pid`` has waited for (``cutime + cstime``), 0 when unknown."""
    if _LINUX:
        try:
            with open(f"/proc/{pid}/stat", "rb") as f:
                fields = f.read().rsplit(b")", 1)[1].split()
            return (int(fields[13]) + int(fields[14])) / _TICK  # fields 16 and 17 of proc(5)
        except (OSError, IndexError, ValueError):
            return 0.0
    try:
        import psutil

        times = psutil.Process(pid).cpu_times()
        return float(times.children_user + times.children_system)
    except Exception:  # noqa: BLE001 - gone, or psutil unavailable
        return 0.0


def _descendants(pid: int) -> list[int]:
    try:
        import psutil

        return [child.pid for child in psutil.Process(pid).children(recursive=True)]
    except Exception:  # noqa: BLE001 - gone, or psutil unavailable
        return []


class ProcessTreeCpu:
    """CPU seconds of a process and all its descendants, live or reaped.

    :meth:`read` adds the process's own CPU clock, the time of the children
    it has waited for, and the same two figures for each live descendant.
    Listing descendants scans every process (milliseconds), so the list is
    read again at most every :data:`DESCENDANTS_REFRESH_S`; each read still
    reads every listed process's clock afresh. A descendant that ends and is
    reaped between two listings moves from its own clock to its parent's
    reaped-children time, so it is counted once.

    A sandboxed worker's tree is its cgroup (its root joins the group before
    it starts the sandbox, and every process it starts is born in it): with
    ``members``, the group's process list, one small file, is read at every
    read instead of scanning every process of the machine.

    Parameters
    ----------
    pid : int
        The root of the tree (a worker process).
    members : callable, optional
        The processes of the root's cgroup now (:meth:`~pathzoo.harness.cgroup.ProcessGroup.pids`), root included.
    """

    def __init__(self, pid: int, members: Callable[[], list[int]] | None = None) -> None:
        self.pid = pid
        self.members = members
        self.reaped = math.nan
        """Of the last :meth:`read`: the reaped-children time in it (whole clock ticks of each child)."""
        self._children: list[int] = []
        self._listed = -math.inf

    def read(self, *, relist: bool = False) -> float:
        """CPU seconds of the tree so far (NaN when the root is gone); ``relist`` lists the descendants now."""
        now = _clock()
        if self.members is not None:
            self._children = [p for p in self.members() if p != self.pid]
        elif relist or now - self._listed >= DESCENDANTS_REFRESH_S:
            self._children = _descendants(self.pid)
            self._listed = now
        reaped = _reaped_children_cpu(self.pid)
        total = process_cpu_time(self.pid)
        for child in self._children:
            own = process_cpu_time(child)
            if not math.isnan(own):
                total += own
                reaped += _reaped_children_cpu(child)
        self.reaped = reaped
        return total + reaped


class ChargedCpu:
    """The CPU seconds a run is charged: the larger of its process tree's and its cgroup's usage since :meth:`start`.

    The tree (:class:`ProcessTreeCpu`) has nanosecond resolution; the
    cgroup's ``cpuacct.usage`` counts every process that was ever in it,
    whatever it did to leave the tree (a double fork, a reparented daemon).
    Taking the larger of the two differences charges the run for either.

    Parameters
    ----------
    pid : int
        The root of the worker's process tree.
    cgroup : callable, optional
        The cgroup's CPU seconds so far (:meth:`~pathzoo.harness.cgroup.ProcessGroup.cpu_seconds`);
        none for an unsandboxed worker.
    members : callable, optional
        The cgroup's processes now (:meth:`~pathzoo.harness.cgroup.ProcessGroup.pids`), to list the tree
        from (see :class:`ProcessTreeCpu`).
    """

    def __init__(self, pid: int, cgroup: Callable[[], float] | None = None,
                 members: Callable[[], list[int]] | None = None) -> None:
        self.tree = ProcessTreeCpu(pid, members)
        self.cgroup = cgroup
        self._tree0 = self._group0 = self._reaped0 = math.nan

    def start(self, *, relist: bool = True) -> None:
        """Start counting from now (with ``relist``, the descendants are listed afresh: a scan of every process)."""
        self._tree0, self._reaped0, self._group0 = self._read(relist=relist)

    def spent(self, reaped: float = math.nan) -> float:
        """CPU seconds charged since :meth:`start` (NaN before it).

        ``reaped`` is the CPU seconds of a child that a process of the tree
        has reaped since :meth:`start`, as ``wait4`` gave them to its parent:
        exact, where the reaped-children time the tree reads counts whole
        clock ticks of each of user and system time (up to two ticks short).
        The part of it that the tree's reaped-children time gained since
        :meth:`start` misses is added, so the figure can only rise, by at most
        the child's own figure.
        """
        return self._charged(*self._read(), reaped)

    def lap(self, reaped: float = math.nan) -> float:
        """:meth:`spent`, then :meth:`start` from the same reading (the descendants not listed afresh): one reading
        ends a run's charge and starts the next's, so no CPU time falls between the two."""
        now = self._read()
        charged = self._charged(*now, reaped)
        self._tree0, self._reaped0, self._group0 = now
        return charged

    def _read(self, *, relist: bool = False) -> tuple[float, float, float]:
        """The tree's CPU seconds, the reaped-children part of them, and the cgroup's (NaN without one), now."""
        tree = self.tree.read(relist=relist)
        return tree, self.tree.reaped, self.cgroup() if self.cgroup is not None else math.nan

    def _charged(self, tree_now: float, reaped_now: float, group_now: float, reaped: float) -> float:
        """The charge since :meth:`start` at a reading of :meth:`_read` (``reaped``: see :meth:`spent`)."""
        tree = tree_now - self._tree0
        if math.isfinite(reaped):
            tree += max(0.0, reaped - max(0.0, reaped_now - self._reaped0))
        if self.cgroup is None:
            return tree
        group = group_now - self._group0
        return group if math.isnan(tree) else max(tree, group)
