"""Worker processes of the process executor started and stopped: a handle per worker, its configuration, its end.

A worker runs one planner configuration (:func:`configuration`). Where the
system allows (:func:`~pathzoo.harness.sandbox.sandbox_problem`), workers
are sandboxed: each is spawned through bubblewrap in a cgroup of its own
(:mod:`pathzoo.harness.sandbox`, :mod:`pathzoo.harness.cgroup`,
``docs/sandbox.md``), and stopping one kills its whole cgroup
(:meth:`Worker.kill_tree`) and removes what it leaves (:meth:`Worker.release`).

Unsandboxed workers start with the ``forkserver`` method where available (``spawn``
elsewhere), without the main module: the preparation data that would make
them re-import ``__main__`` is left out (:class:`~pathzoo.harness.launch.NoMainContext`), so a
script without an ``if __name__ == "__main__":`` guard (or ``python - <
script.py``) works; planner classes defined in ``__main__`` travel by value
(:attr:`~pathzoo.harness.specs.RunTask.planner_class`). Replacing a worker
costs a fork of the server, which has numba and pathzoo's shared code loaded
(:mod:`~pathzoo.harness.executors.warmup`); each worker discovers the plugins
and imports the planner classes it runs itself, since the judge is forked
from the same server and must never inherit planner code.
Workers ignore ``SIGINT``; Ctrl-C reaches the harness, which kills them on shutdown,
and they die with the harness however it ends (:func:`~pathzoo.harness.launch.die_with_harness`).
"""

from __future__ import annotations

import itertools
import math
import os
import shutil
import signal
from concurrent.futures import Future
from dataclasses import dataclass, field
from multiprocessing.connection import Connection
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pathzoo.core.budget import StopReason
from pathzoo.harness.cgroup import ProcessGroup
from pathzoo.harness.clock_stop import SharedClockStop
from pathzoo.harness.cpu_clock import ChargedCpu
from pathzoo.harness.executors.worker_loop import worker_main
from pathzoo.harness.launch import SandboxedProcess, harness_alive
from pathzoo.harness.outcome import RunOutcome
from pathzoo.harness.sandbox import SandboxLimits, sandboxed_command, worker_numba_cache
from pathzoo.harness.specs import HeldScenarios

if TYPE_CHECKING:
    from multiprocessing.process import BaseProcess

    from pathzoo.harness.specs import RunTask

__all__ = ["Worker", "launch_worker", "describe_exit", "wrote_to_exit_pipe", "configuration", "any_configuration"]

_WORKER_SERIALS = itertools.count(1)
"""Numbers of the sandboxed workers of this process, over all its executors (their cgroups' names)."""


def describe_exit(exitcode: int | None, *, sandboxed: bool = False) -> str:
    """``"exit code 3"`` or ``"signal 9 (SIGKILL)"``.

    ``bwrap`` exits with 128 + the signal that killed the sandboxed process,
    so for a sandboxed worker codes 129-192 are read as that signal.
    """
    if exitcode is None:
        return "unknown exit status"
    if sandboxed and 128 < exitcode <= 128 + 64:
        exitcode = 128 - exitcode
    if exitcode < 0:
        try:
            return f"signal {-exitcode} ({signal.Signals(-exitcode).name})"
        except ValueError:
            return f"signal {-exitcode}"
    return f"exit code {exitcode}"


def wrote_to_exit_pipe(sentinel: int) -> bool:
    """Whether a readable exit pipe holds data (written by planner code in the worker) rather than its end of file."""
    try:
        return bool(os.read(sentinel, 64))
    except OSError:
        return False


@dataclass
class Worker:
    """The harness's handle on one worker process: its pipe, clocks, current run and cgroup."""

    process: "BaseProcess"
    conn: Connection
    stop: SharedClockStop
    cpu: ChargedCpu
    idle: bool = False
    was_ready: bool = False
    started_once: bool = False
    task: "RunTask | None" = None
    future: "Future[RunOutcome] | None" = None
    cleared: bool = True
    """The harness has let the current run hand over (``G``); a run sent ahead waits for it after its setup."""
    ahead: "tuple[RunTask, Future[RunOutcome]] | None" = None
    """The run sent ahead, queued in the worker's pipe behind its current one."""
    sent_at: float = math.nan
    started_at: str = ""
    deadline: float = math.inf
    in_setup: bool = False
    plan_t0: float = math.nan
    plan_t1: float = math.nan
    stopped_by: StopReason | None = None
    """The clock stop the harness set for the current run."""
    held: HeldScenarios = field(default_factory=HeldScenarios)
    config: "tuple[str, str, str] | None" = None
    warm: bool = False
    """The worker has reported its warm-up done (``W``): its CPU is charged to its runs from then on."""
    group: ProcessGroup | None = None
    scratch: str = ""
    baseline: frozenset[int] = frozenset()
    visible: frozenset[str] = frozenset()
    launched_at: float = math.nan
    """When the harness launched it (``time.perf_counter``)."""
    taken_at: float = math.nan
    """When its current run was handed to it, warm (NaN for a run that waits for the warm-up)."""

    @property
    def listening(self) -> bool:
        return self.task is not None or not self.idle

    def end_run(self) -> "Future[RunOutcome]":
        """Forget the current run; return its future, for the caller to resolve."""
        future = self.future
        assert future is not None
        self.task, self.future, self.deadline = None, None, math.inf
        return future

    def futures(self) -> "list[Future[RunOutcome]]":
        """The futures of the runs the worker holds: its current one and the one sent ahead."""
        return [f for f in (self.future, self.ahead[1] if self.ahead is not None else None) if f is not None]

    def kill_tree(self) -> None:
        """``SIGKILL`` the worker and, when sandboxed, every process of its cgroup."""
        if self.group is not None:
            self.group.kill()
        if self.process.is_alive():
            self.process.kill()

    def release(self) -> None:
        """Kill what is left of a worker, reap it, remove its cgroup and scratch directory, close its pipe."""
        self.kill_tree()
        self.process.join()
        if self.group is not None:
            self.group.remove()
        if self.scratch:
            shutil.rmtree(self.scratch, ignore_errors=True)
        self.conn.close()


def configuration(task: "RunTask") -> tuple[str, str, str]:
    """The planner configuration of a task, ``(planner id, parameter hash, scenario kind)``: a worker process runs one
    only, warmed up on synthetic scenarios of that kind (:class:`~pathzoo.harness.zygote.WarmUp`)."""
    return task.planner.id, task.params_hash, task.scenario.kind


def any_configuration(planner_id: str) -> tuple[str, str, str]:
    """The configuration of a worker started early for a planner (:meth:`ProcessExecutor.start_worker`): its first
    run, whatever its parameters, fixes the configuration."""
    return planner_id, "", ""


def launch_worker(ctx: Any, config: "tuple[str, str, str] | None", *, sandboxed: bool, limits: SandboxLimits,
                  scratch_root: str, dirs: "list[str]") -> Worker:
    """Start a worker process for ``config`` (sandboxed: in its own cgroup and bubblewrap sandbox under
    ``scratch_root``, reading ``dirs`` besides the system's files)."""
    parent, child = ctx.Pipe(duplex=True)
    group, scratch, visible = None, "", frozenset(dirs)
    flag = ctx.RawArray("b", 1)
    if sandboxed:
        assert config is not None
        serial = next(_WORKER_SERIALS)  # of this process: two executors here never share a cgroup
        group = ProcessGroup(f"w{serial}", memory_bytes=limits.memory_bytes, max_tasks=limits.max_tasks)
        scratch = os.path.join(scratch_root, f"w{serial}")
        process: Any = SandboxedProcess(target=worker_main, args=(child, harness_alive(), flag, True),
                                        name="pathzoo-worker")
        process.sandbox_prefix = sandboxed_command(
            (), procs_files=group.procs_files, scratch=Path(scratch), numba_cache=worker_numba_cache(config[0]),
            readable=visible, scratch_bytes=limits.scratch_bytes)
    else:
        process = ctx.Process(target=worker_main, args=(child, harness_alive(), flag), name="pathzoo-worker")
    try:
        process.start()
    except BaseException:
        if group is not None:
            group.remove()
        raise
    child.close()
    cpu = (ChargedCpu(process.pid or 0) if group is None
           else ChargedCpu(process.pid or 0, group.cpu_seconds, members=group.pids))  # its tree is its cgroup
    return Worker(process, parent, SharedClockStop(flag), cpu, config=config, group=group, scratch=scratch,
                  visible=visible)
