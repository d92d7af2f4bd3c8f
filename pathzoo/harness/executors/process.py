"""The process executor: a pool of long-lived worker processes that are killed and replaced when needed.

Each worker is a :mod:`multiprocessing` process with its own pipe. A monitor
thread in the harness process hands tasks to idle workers and waits on the
pipes and on the process sentinels at the same time. Workers run planner
code, so nothing they send is unpickled: they send short tagged byte strings
(read with a size limit) and the outcome in the format of
:mod:`pathzoo.harness.wire`:

- ``R`` (ready) once started, ``I`` (idle) after each run when the process
  is still clean, ``T`` (tainted) when the run rebound module attributes
  (:mod:`pathzoo.harness.tamper`) or the warm-up left planner code running
  (:class:`~pathzoo.harness.zygote.Residue`): that worker is retired and a
  fresh one started, so no planner's patch reaches another run;
- a new worker is first sent a :class:`~pathzoo.harness.zygote.WarmUp`
  (the configuration and the scenario kind, nothing of any run): ``U``
  once it has built the planner (the warm-up has the run's hard limit
  ``timeout_s`` from there), ``W`` when its warm-up is done: the worker's
  CPU is charged to its runs from then on, and the run is sent;
- ``S`` (started: scenario loaded and its graph built): the hard limit
  ``timeout_s`` counts from the *first* ``S``; later ones are ignored. The
  setup before it has its own limit,
  :data:`~pathzoo.harness.worker.SETUP_TIMEOUT_S`, and is recorded as ``crash``;
- ``P`` (hand-over, just before the worker forks the run's child): the wall
  clock starts;
- ``D`` + the child's CPU seconds (``wait4``) + the outcome, sent once the
  child has exited and been reaped: the run ends. Wall time is the
  harness's ``time.perf_counter`` from ``P`` to ``D``; CPU time is the
  larger of the worker's process tree and cgroup
  (:class:`~pathzoo.harness.cpu_clock.ChargedCpu`: for a sandboxed worker,
  the tree under its ``bwrap`` process) from the end of the previous run
  (or ``W``) to ``D``, and of the child's figure from ``D`` (which can only
  raise it), all read from the kernel, so a planner cannot change its own
  timings (``docs/sandbox.md``, "What a run is charged"). While a run with
  a clock limit plans, the monitor reads these clocks (for ``cpu_s``: see
  :data:`CLOCK_POLL_S`) and sets the worker's shared stop byte
  (:class:`~pathzoo.harness.clock_stop.SharedClockStop`) when a limit is
  spent; the run is stored with the stop the harness set (``stopped_by``),
  whatever the planner did with the byte. A ``D`` before ``P`` (a failed
  setup) is a ``crash`` whatever it says; any other frame while a run is
  out (a repeated one, or one the planner's warm-up wrote on the control
  socket) is ignored;
- a worker past its hard limit gets ``SIGKILL`` (``Process.kill``), the run
  resolves as ``timed_out`` and a fresh worker replaces it; one that dies
  (``os._exit``, segfault, out of memory) gives a ``crash`` with the exit code
  or signal; one that sends anything else, or more than
  :data:`~pathzoo.harness.wire.MAX_OUTCOME_BYTES`, is killed and its run is a ``crash``.

Each worker runs one planner configuration (planner id, parameter hash
and scenario kind, :func:`configuration`) for as many runs as the experiment has of it;
a queued run goes to an idle worker of its configuration, else to a new
worker, so no interpreter state (a recursion limit, a replaced cached
scenario) passes from one planner to another. At most ``jobs`` workers have
a run at once, but up to :attr:`~ProcessExecutor.kept_workers` (twice as
many) stay alive, idle ones waiting for their configuration's next run, and
no configuration gets more workers than ``jobs``: a sweep that alternates
configurations keeps its workers instead of starting one per switch. Only
when that many are alive is an idle worker that no queued run can use
retired to make room.

Where the system allows (:func:`~pathzoo.harness.sandbox.sandbox_problem`),
workers are sandboxed: each is spawned through bubblewrap in a cgroup of its
own (:mod:`pathzoo.harness.sandbox`, :mod:`pathzoo.harness.cgroup`, and
``docs/sandbox.md``). When a sandboxed worker reports idle, its cgroup must
hold only the processes it held when it became ready; anything else (a
child, a daemon) gets the whole cgroup killed and the worker replaced, and a
killed or timed-out worker's cgroup is emptied the same way.

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

A scenario object (:meth:`~pathzoo.harness.specs.ScenarioSpec.of_object`)
is sent to each worker once; later tasks on it refer to it by digest
(:func:`~pathzoo.harness.scenario_cache.keep_payload`).

Unsandboxed workers all start when the executor is built (sandboxed ones when
a run of their configuration is queued, or earlier for a planner named to
:meth:`ProcessExecutor.start_worker`), and the runner keeps one run per
worker queued here (:attr:`lookahead`), so a worker goes from one run to
the next without waiting for the harness. The very first run goes alone,
though: the other workers get nothing, and no other sandboxed worker starts,
until it starts planning or ends, so that its setup (interpreter, plugins,
planner class, scenario, warm-up) shares the cores with the judge's start
only, and the first result comes sooner.
"""

from __future__ import annotations

import itertools
import math
import os
import shutil
import signal
import struct
import threading
import time
import tempfile
from collections import Counter, deque
from concurrent.futures import Future
from dataclasses import dataclass, field, replace
from pathlib import Path
from multiprocessing.connection import Connection
from typing import TYPE_CHECKING, Any, Callable

from pathzoo.core.errors import PathzooError
from pathzoo.core.budget import StopReason
from pathzoo.harness.clock_stop import SharedClockStop
from pathzoo.harness.cpu_clock import ChargedCpu, process_cpu_time
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.cgroup import ProcessGroup
from pathzoo.harness.poller import Poller
from pathzoo.harness.launch import (NoMainContext, SandboxedProcess, default_start_method, die_with_harness,
                                    harness_alive, start_server)
from pathzoo.harness.sandbox import SandboxLimits, SandboxUnavailableError, sandbox_problem, sandboxed_command, \
    worker_numba_cache
from pathzoo.harness.specs import HeldScenarios
from pathzoo.harness.tamper import ModuleFingerprint
from pathzoo.harness.wire import MAX_OUTCOME_BYTES, decode_outcome
from pathzoo.harness.outcome import RunOutcome, utc_now
from pathzoo.harness.scenario_cache import keep_payload
from pathzoo.harness.worker import SETUP_TIMEOUT_S
from pathzoo.harness.zygote import WarmUp, Zygote, drop_resource_tracker, refuse_audit_hooks, undumpable

if TYPE_CHECKING:
    from multiprocessing.process import BaseProcess

    from pathzoo.harness.specs import RunTask

__all__ = ["ProcessExecutor", "WorkerStartError", "default_start_method", "process_cpu_time", "configuration",
           "MAX_START_FAILURES"]

_WORKER_SERIALS = itertools.count(1)
"""Numbers of the sandboxed workers of this process, over all its executors (their cgroups' names)."""

_clock = time.perf_counter  # bound at import: a later patch of time.perf_counter does not reach the harness


class WorkerStartError(PathzooError, RuntimeError):
    """A worker process died before it was ready: the harness cannot run anything."""


MAX_START_FAILURES = 3
"""Workers in a row that die before they are ready, after which the executor gives up (:class:`WorkerStartError`)."""

CLOCK_POLL_S = 0.01
"""How often, at most, the monitor reads the CPU time of a run with a ``cpu_s`` limit while it plans.

Far from the limit it reads it less often: a process tree cannot use more
than one CPU second per core in a wall second, so the next reading is due
when the CPU seconds left, spread over every core, could be spent."""

_CORES = os.cpu_count() or 1

_EVENTS = {"warming": b"U", "started": b"S", "planning": b"P"}

_CPU = struct.Struct("<d")
"""The child's CPU seconds at the head of a ``D`` message, as the zygote's ``wait4`` read them from the kernel."""


def _worker_main(conn: Connection, alive: Connection, stop_flag: Any, sandboxed: bool = False) -> None:
    """Loop of one worker process (a :class:`~pathzoo.harness.zygote.Zygote`): receive a task, run it in a fresh
    child, send the outcome and whether the process is clean."""
    die_with_harness(alive)
    drop_resource_tracker()
    refuse_audit_hooks()
    undumpable()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sandboxed:  # spawned, not forked from the server that has done this already
        import pathzoo.harness.executors.warmup  # noqa: F401
    fingerprint = ModuleFingerprint().update()
    zygote = Zygote(SharedClockStop(stop_flag))
    conn.send_bytes(b"R")
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        if isinstance(task, WarmUp):
            zygote.warm_up(task, _reporter(conn))
            fingerprint.update().changed()  # the modules the warm-up loaded, and the quick check armed, uncharged:
            # checked after a run, only what that run moved is examined, and the outcome goes out sooner
            conn.send_bytes(b"W")
            continue
        keep_payload(task.scenario)  # the executor counts it as held from now on
        try:
            data, child_cpu = zygote.run(task, _reporter(conn))
        except (EOFError, OSError):
            return
        changed = fingerprint.changed() + zygote.residue  # the outcome and the verdict on the process go out together
        try:
            conn.send_bytes(b"D" + _CPU.pack(child_cpu) + data)
        except (EOFError, OSError):
            return
        if changed:
            conn.send_bytes(b"T" + ", ".join(changed).encode("utf-8", "replace")[:1000])
            return
        fingerprint.update()
        conn.send_bytes(b"I")


def _reporter(conn: Connection) -> "Callable[[str], None]":
    """The ``report`` callback of :meth:`~pathzoo.harness.zygote.Zygote.run`: send the event."""

    def report(event: str) -> None:
        conn.send_bytes(_EVENTS[event])

    return report


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


def _written(sentinel: int) -> bool:
    """Whether a readable exit pipe holds data (written by planner code in the worker) rather than its end of file."""
    try:
        return bool(os.read(sentinel, 64))
    except OSError:
        return False


@dataclass
class _Worker:
    process: "BaseProcess"
    conn: Connection
    stop: SharedClockStop
    cpu: ChargedCpu
    idle: bool = False
    was_ready: bool = False
    started_once: bool = False
    task: "RunTask | None" = None
    future: "Future[RunOutcome] | None" = None
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

    @property
    def listening(self) -> bool:
        return self.task is not None or not self.idle

    def finish(self, outcome: RunOutcome) -> None:
        assert self.future is not None
        if not self.future.done():
            self.future.set_result(outcome)
        self.task, self.future, self.deadline = None, None, math.inf


def configuration(task: "RunTask") -> tuple[str, str, str]:
    """The planner configuration of a task, ``(planner id, parameter hash, scenario kind)``: a worker process runs one
    only, warmed up on synthetic scenarios of that kind (:class:`~pathzoo.harness.zygote.WarmUp`)."""
    return task.planner.id, task.params_hash, task.scenario.kind


def _any_configuration(planner_id: str) -> tuple[str, str, str]:
    """The configuration of a worker started early for a planner (:meth:`ProcessExecutor.start_worker`): its first
    run, whatever its parameters, fixes the configuration."""
    return planner_id, "", ""


class ProcessExecutor(RunExecutor):
    """A pool of ``jobs`` long-lived worker processes, each for one planner configuration (see the module docstring).

    Parameters
    ----------
    jobs : int, optional
        Number of workers (default: ``os.cpu_count()``).
    start_method : str, optional
        ``"forkserver"`` or ``"spawn"`` (default :func:`default_start_method`)
        for unsandboxed workers; sandboxed ones are always spawned.
    sandbox : bool, optional
        ``None`` (default): sandbox the workers where the system can
        (:func:`~pathzoo.harness.sandbox.sandbox_problem`), else run them
        unsandboxed; ``True``: raise :class:`SandboxUnavailableError` where
        it cannot; ``False``: never.
    limits : SandboxLimits, optional
        Memory, task and scratch limits of each sandboxed worker.

    Attributes
    ----------
    sandboxed : bool
        Whether the workers run sandboxed.
    sandbox_problem : str
        Why they do not (``""`` when they do).
    """

    isolated = True

    def __init__(self, jobs: int | None = None, *, start_method: str | None = None, sandbox: bool | None = None,
                 limits: SandboxLimits | None = None) -> None:
        self.capacity = int(jobs or os.cpu_count() or 1)
        self.sandbox_problem = "switched off (sandbox=False)" if sandbox is False else sandbox_problem()
        if sandbox and self.sandbox_problem:
            raise SandboxUnavailableError(f"planner processes cannot be sandboxed here: {self.sandbox_problem}")
        self.sandboxed = sandbox is not False and not self.sandbox_problem
        self.limits = limits or SandboxLimits()
        self._ctx: Any = NoMainContext(start_method or default_start_method())
        if not self.sandboxed:
            start_server(start_method)  # from this thread, not the monitor: the server dies with its starting thread
        self._scratch_root = tempfile.mkdtemp(prefix="pathzoo-sandbox-") if self.sandboxed else ""
        self._readable_dirs: set[str] = set()
        self._start_failures = 0
        self._lock = threading.Lock()
        self._pending: deque[tuple[RunTask, Future[RunOutcome]]] = deque()
        self._early: list[str] = []  # planner ids of start_worker, for the monitor to start
        self._workers: list[_Worker] = []
        self._first_alone = self.capacity > 1  # see _dispatch
        self._closing = False
        self._wake_r, self._wake_w = self._ctx.Pipe(duplex=False)
        self._poller = Poller()  # the monitor's: one poll object for all its waits
        self.lookahead = self.capacity
        self.kept_workers = 2 * self.capacity
        """Worker processes kept, idle ones included: at most :attr:`capacity` run at once, and an idle worker of
        another configuration waits for its next run instead of being replaced at every switch of configuration."""
        self._thread = threading.Thread(target=self._monitor, name="pathzoo-process-executor", daemon=True)
        self._thread.start()

    # ------------------------------------------------------------ interface
    def submit(self, task: "RunTask") -> "Future[RunOutcome]":
        """Queue a run for the next idle worker of its configuration."""
        future: Future[RunOutcome] = Future()
        with self._lock:
            if self._closing:
                raise RuntimeError("executor is shut down")
            self._pending.append((task, future))
        self._wake_w.send(None)
        return future

    def start_worker(self, planner_id: str) -> None:
        """Start a sandboxed worker for ``planner_id`` now, before its configuration is known.

        Call it while the experiment is still being read (its planners
        described, :mod:`~pathzoo.harness.planner_info`): the worker's
        interpreter starts meanwhile, and the first queued run of that
        planner, whatever its parameters, takes it (it then runs that
        configuration only). Nothing when the workers are not sandboxed
        (they all start with the executor) or the pool is full.
        """
        if not self.sandboxed:
            return
        with self._lock:
            self._early.append(planner_id)
        self._wake_w.send(None)

    def prepare(self, tasks: "list[RunTask]") -> None:
        """Note where the experiment's scenario files are (a sandboxed worker sees only those directories)."""
        with self._lock:
            self._see_files(tasks)

    def shutdown(self) -> None:
        """Stop the monitor, ask idle workers to exit, kill busy ones, cancel queued runs."""
        with self._lock:
            if self._closing:
                return
            self._closing = True
        self._wake_w.send(None)
        self._thread.join()
        for worker in self._workers:
            if worker.task is not None or not worker.idle:
                self._kill_tree(worker)
            elif worker.process.is_alive():
                try:
                    worker.conn.send(None)
                except OSError:
                    pass
        deadline = time.monotonic() + 2.0
        for worker in self._workers:
            worker.process.join(max(0.0, deadline - time.monotonic()))
            self._release(worker)
            if worker.future is not None:
                worker.future.cancel()
        self._workers.clear()
        for _, future in self._pending:
            future.cancel()
        self._pending.clear()
        self._wake_r.close()
        self._wake_w.close()
        if self._scratch_root:
            shutil.rmtree(self._scratch_root, ignore_errors=True)

    # ------------------------------------------------------------- internals
    def _spawn(self, config: "tuple[str, str, str] | None") -> _Worker:
        """A new worker, for ``config`` (sandboxed: in its own cgroup and bubblewrap sandbox)."""
        parent, child = self._ctx.Pipe(duplex=True)
        group, scratch, visible = None, "", frozenset(self._visible_dirs())
        flag = self._ctx.RawArray("b", 1)
        if self.sandboxed:
            assert config is not None
            serial = next(_WORKER_SERIALS)  # of this process: two executors here never share a cgroup
            group = ProcessGroup(f"w{serial}", memory_bytes=self.limits.memory_bytes,
                                 max_tasks=self.limits.max_tasks)
            scratch = os.path.join(self._scratch_root, f"w{serial}")
            process: Any = SandboxedProcess(target=_worker_main, args=(child, harness_alive(), flag, True),
                                            name="pathzoo-worker")
            process.sandbox_prefix = sandboxed_command(
                (), procs_files=group.procs_files, scratch=Path(scratch), numba_cache=worker_numba_cache(config[0]),
                readable=visible, scratch_bytes=self.limits.scratch_bytes)
        else:
            process = self._ctx.Process(target=_worker_main, args=(child, harness_alive(), flag),
                                        name="pathzoo-worker")
        try:
            process.start()
        except BaseException:
            if group is not None:
                group.remove()
            raise
        child.close()
        cpu = (ChargedCpu(process.pid or 0) if group is None
               else ChargedCpu(process.pid or 0, group.cpu_seconds, members=group.pids))  # its tree is its cgroup
        worker = _Worker(process, parent, SharedClockStop(flag), cpu, config=config,
                         group=group, scratch=scratch, visible=visible)
        self._workers.append(worker)
        return worker

    def _visible_dirs(self) -> list[str]:
        with self._lock:
            return sorted(self._readable_dirs)

    def _kill_tree(self, worker: _Worker) -> None:
        """``SIGKILL`` the worker and, when sandboxed, every process of its cgroup."""
        if worker.group is not None:
            worker.group.kill()
        if worker.process.is_alive():
            worker.process.kill()

    def _release(self, worker: _Worker) -> None:
        """Kill what is left of a worker, reap it, remove its cgroup and scratch directory, close its pipe."""
        self._kill_tree(worker)
        worker.process.join()
        if worker.group is not None:
            worker.group.remove()
        if worker.scratch:
            shutil.rmtree(worker.scratch, ignore_errors=True)
        worker.conn.close()

    def _retire(self, worker: _Worker) -> None:
        self._release(worker)
        self._workers.remove(worker)

    def _see_files(self, tasks: "list[RunTask]") -> None:
        """Note the directories of the tasks' scenario files and of the files their planners read (``LazyPlanner.folders``).

        Sandboxed workers started from now on can read them.
        """
        self._readable_dirs.update(os.path.dirname(os.path.abspath(t.scenario.location)) for t in tasks
                                   if t.scenario.source == "file")
        for planner_id in {t.planner.id for t in tasks}:
            self._see_planner(planner_id)

    def _see_planner(self, planner_id: str) -> None:
        """Note the folders the planner reads (``LazyPlanner.folders``), for the sandboxed workers started from now on."""
        from pathzoo.plugins.entries import LazyPlanner
        from pathzoo.plugins.manager import get_registry

        entry = get_registry().planners.get(planner_id)
        if entry is not None and isinstance(entry.provided, LazyPlanner):
            self._readable_dirs.update(entry.provided.folders)

    def _start_workers(self) -> None:
        """Start the workers asked for by :meth:`start_worker`, then those for the queued runs that no idle or starting
        worker of their configuration will take; only the first queued run's until it plans (see :meth:`_dispatch`)."""
        with self._lock:
            early, self._early = self._early, []
            queued = [task for task, _ in self._pending]
        for planner_id in early:
            if len(self._workers) < self.capacity and not self._closing:
                with self._lock:
                    self._see_planner(planner_id)
                self._spawn(_any_configuration(planner_id))
        if self._first_alone and any(w.task is not None for w in self._workers):
            return
        starting = Counter(w.config for w in self._workers if not w.was_ready)
        wanted = {configuration(task) for task in queued}
        wanted |= {_any_configuration(config[0]) for config in wanted}
        for task in queued[:1] if self._first_alone else queued:
            config = configuration(task)
            if starting[config] > 0:
                starting[config] -= 1
                continue
            if starting[_any_configuration(config[0])] > 0:  # started early for this planner: it takes this one
                starting[_any_configuration(config[0])] -= 1
                continue
            if starting[None] > 0 and not self.sandboxed:
                starting[None] -= 1
                continue
            if sum(w.config in (config, _any_configuration(config[0])) and self._sees(w, task)
                   for w in self._workers) >= self.capacity:
                continue  # as many of its configuration as can run at once: one of them takes it
            if len(self._workers) >= self.kept_workers:  # retire an idle worker that no queued run can use
                spare = next((w for w in self._workers if w.idle and w.task is None and w.config not in wanted), None)
                if spare is None:
                    return
                self._retire(spare)
            with self._lock:
                self._see_files([task])
            self._spawn(config)

    def _sees(self, worker: _Worker, task: "RunTask") -> bool:
        """Whether the worker can read the task's scenario (a sandboxed one sees the files known when it started)."""
        spec = task.scenario
        return (worker.group is None or spec.source != "file"
                or os.path.dirname(os.path.abspath(spec.location)) in worker.visible)

    def _take(self) -> "tuple[_Worker, RunTask, Future[RunOutcome]] | None":
        """The first queued run with an idle worker of its configuration (or, unsandboxed, one not yet used), while
        fewer than :attr:`capacity` workers have a run."""
        with self._lock:
            if sum(w.task is not None for w in self._workers) >= self.capacity:
                return None
            for i, (task, future) in enumerate(self._pending):
                config = configuration(task)
                worker = next((w for w in self._workers if w.idle and w.task is None
                               and w.config in (config, _any_configuration(config[0])) and self._sees(w, task)), None)
                if worker is None and not self.sandboxed:
                    worker = next((w for w in self._workers if w.idle and w.task is None and w.config is None), None)
                if worker is not None:
                    del self._pending[i]
                    worker.config = config
                    return worker, task, future
        return None

    def _dispatch(self) -> None:
        if self._first_alone and any(w.task is not None for w in self._workers):
            return  # the first run's setup shares the cores with the judge's only, until it plans or ends
        while True:
            taken = self._take()
            if taken is None:
                if sum(w.task is not None for w in self._workers) < self.capacity:
                    self._start_workers()
                return
            worker, task, future = taken
            if not future.set_running_or_notify_cancel():
                continue
            worker.task, worker.future, worker.idle, worker.started_once = task, future, False, False
            worker.sent_at, worker.started_at = _clock(), utc_now()
            worker.plan_t0 = worker.plan_t1 = math.nan
            worker.stopped_by = None
            worker.stop.clear()  # the worker is idle: it reads the byte only once it plans this task
            worker.deadline = worker.sent_at + max(task.timeout_s, SETUP_TIMEOUT_S)
            worker.in_setup = True
            self._send(worker, task, future)

    def _send(self, worker: _Worker, task: "RunTask", future: "Future[RunOutcome]") -> None:
        """Send the task to its worker, or first the order to warm up (a new worker; the task follows its ``W``)."""
        try:
            if worker.warm:
                worker.conn.send(worker.held.outgoing(task))
                worker.held.sent(task)
            else:
                worker.conn.send(WarmUp.of(task))
        except (OSError, EOFError):  # the idle worker had died: retry the task on a fresh one
            worker.task, worker.future = None, None
            self._retire(worker)
            with self._lock:
                self._pending.appendleft((task, future))
        except Exception as exc:  # the task did not pickle
            self._finish(worker, RunOutcome(task.run_key, crash=True, message=f"task could not be sent: {exc!r}",
                                            started_at=worker.started_at))
            worker.idle = True

    def _finish(self, worker: _Worker, outcome: RunOutcome) -> None:
        self._first_alone = False
        if worker.group is not None and worker.group.out_of_memory() and outcome.crash:
            outcome = replace(outcome, message=f"{outcome.message} (out of memory: over the sandbox's limit of "
                                               f"{self.limits.memory_bytes / 2**20:.0f} MiB)")
        worker.finish(replace(outcome, sandboxed=worker.group is not None))

    @staticmethod
    def _cpu_since(worker: _Worker) -> float:
        """CPU seconds charged to the current run (NaN before the worker's warm-up ended)."""
        return worker.cpu.spent() if worker.warm else math.nan

    def _timed(self, worker: _Worker, outcome: RunOutcome, child_cpu: float) -> RunOutcome:
        """The outcome with the harness's own times (``P`` to ``D``) and stop; a ``D`` before ``P`` is a failed setup,
        whatever it says.

        The CPU charged is the larger of the worker's tree and cgroup (read here),
        the tree's reaped child counted at the child's own figure, which the
        zygote read from the kernel when it reaped it (microseconds, where the
        tree has the reaped child's time in clock ticks only,
        :meth:`~pathzoo.harness.cpu_clock.ChargedCpu.spent`): a figure from the
        worker can raise the charge, never lower it."""
        assert worker.task is not None
        if math.isnan(worker.plan_t0):
            return RunOutcome(worker.task.run_key, crash=True, message=outcome.message, started_at=worker.started_at)
        worker.plan_t1 = _clock()
        cpu = worker.cpu.spent(reaped=child_cpu)
        worker.cpu.start(relist=False)  # what the worker spends until its next run's end is charged to that run;
        # its child is reaped by now, and a new one is listed within DESCENDANTS_REFRESH_S (the cgroup counts it)
        stopped_by = worker.stopped_by or worker.task.budget.count_reached(outcome.iterations, outcome.evaluations)
        return replace(outcome, wall_time_s=worker.plan_t1 - worker.plan_t0, cpu_time_s=cpu,
                       stopped_by=stopped_by or "none", started_at=worker.started_at)

    def _planning(self, worker: _Worker) -> bool:
        """True while the worker's run plans under a clock limit that the harness has not stopped yet."""
        return (worker.task is not None and worker.task.budget.timed and worker.stopped_by is None
                and not math.isnan(worker.plan_t0) and math.isnan(worker.plan_t1))

    def _watch_clocks(self, now: float) -> float:
        """Set the stop of each planning run whose clock limit is spent; return when to look again."""
        nearest = math.inf
        for worker in self._workers:
            if not self._planning(worker):
                continue
            assert worker.task is not None
            budget = worker.task.budget
            cpu_left = math.inf if budget.cpu_s is None else budget.cpu_s - worker.cpu.spent()
            if cpu_left <= 0.0:
                worker.stopped_by = "cpu_time"
            elif budget.time_s is not None and now - worker.plan_t0 >= budget.time_s:
                worker.stopped_by = "wall_time"
            if worker.stopped_by is not None:
                worker.stop.set(worker.stopped_by)
                continue
            if budget.cpu_s is not None:  # a process tree uses at most one CPU second per core and wall second
                nearest = min(nearest, now + max(CLOCK_POLL_S, cpu_left / _CORES))
            if budget.time_s is not None:
                nearest = min(nearest, worker.plan_t0 + budget.time_s)
        return nearest

    def _violation(self, worker: _Worker, what: str) -> None:
        if worker.task is not None:
            self._finish(worker, RunOutcome(worker.task.run_key, crash=True, started_at=worker.started_at,
                                            message=f"the worker broke the protocol ({what}) and was killed"))
        self._retire(worker)

    def _left_behind(self, worker: _Worker) -> bool:
        """Whether the worker's cgroup holds a process that was not there when it became ready (a planner's child)."""
        return worker.group is not None and not set(worker.group.pids()) <= worker.baseline

    def _receive(self, worker: _Worker) -> None:
        while worker.listening and worker.conn.poll():
            try:
                message = worker.conn.recv_bytes(MAX_OUTCOME_BYTES + 1)
            except (EOFError, OSError) as exc:
                if isinstance(exc, OSError) and worker.process.is_alive():  # over the size limit
                    self._violation(worker, "a message over the size limit")
                return  # else the sentinel reports the death
            tag, body = message[:1], message[1:]
            if tag == b"R" and not worker.was_ready:
                worker.idle = worker.was_ready = True
                self._start_failures = 0
                if worker.group is not None:
                    worker.baseline = frozenset(worker.group.pids())
            elif tag == b"I" and worker.task is None:
                worker.idle, worker.deadline = True, math.inf
                if self._left_behind(worker):  # nothing of a run outlives it: the whole tree goes
                    self._retire(worker)
                    return
            elif tag == b"T" and worker.task is None:
                self._retire(worker)  # a planner patched modules in it: never reuse it
                return
            elif tag == b"S" and worker.task is not None and not worker.started_once:
                worker.started_once, worker.in_setup = True, False
                worker.sent_at = _clock()
                worker.deadline = worker.sent_at + worker.task.timeout_s
            elif tag == b"U" and worker.task is not None and not worker.warm and worker.in_setup:
                worker.in_setup, worker.sent_at = False, _clock()  # the warm-up has the run's hard limit
                worker.deadline = worker.sent_at + worker.task.timeout_s
            elif tag == b"W" and worker.task is not None and not worker.warm and worker.future is not None:
                if worker.group is not None:  # processes the warm-up left behind: none outlives it
                    worker.group.kill(spare=worker.baseline)
                worker.warm, worker.in_setup, worker.sent_at = True, True, _clock()
                worker.deadline = worker.sent_at + max(worker.task.timeout_s, SETUP_TIMEOUT_S)
                worker.cpu.start()
                self._send(worker, worker.task, worker.future)
            elif tag == b"P" and worker.task is not None and worker.started_once and math.isnan(worker.plan_t0):
                worker.plan_t0 = _clock()
                self._first_alone = False
            elif tag == b"D" and worker.task is not None and worker.warm and len(body) >= _CPU.size:
                (child_cpu,) = _CPU.unpack(body[:_CPU.size])
                self._finish(worker, self._timed(worker, decode_outcome(body[_CPU.size:], worker.task.run_key),
                                                 child_cpu))
            elif worker.task is not None:
                continue  # a repeated announcement, or one out of turn (planner code can write frames during its
                # warm-up): it changes nothing, the clocks run from the warm-up's end to the outcome whatever it says
            else:
                self._violation(worker, f"unexpected message {bytes(message[:8])!r}")
                return

    def _died(self, worker: _Worker) -> None:
        worker.process.join()
        if worker.task is not None:
            elapsed = _clock() - worker.sent_at
            cpu = self._cpu_since(worker)
            how = describe_exit(worker.process.exitcode, sandboxed=worker.group is not None)
            self._finish(worker, RunOutcome(
                worker.task.run_key, crash=True, wall_time_s=elapsed, cpu_time_s=cpu, started_at=worker.started_at,
                message=f"worker process died ({how}) after {elapsed:.3g} s",
            ))
        elif not worker.was_ready:
            self._start_failures += 1
            if self._start_failures >= MAX_START_FAILURES:
                raise WorkerStartError(f"{self._start_failures} pathzoo worker processes failed to start (the last: "
                                       f"{describe_exit(worker.process.exitcode)})")
        self._retire(worker)

    def _kill(self, worker: _Worker) -> None:
        assert worker.task is not None
        elapsed = _clock() - worker.sent_at
        cpu = self._cpu_since(worker)
        self._kill_tree(worker)
        if worker.in_setup:  # not the planner's time: its plan() never started
            outcome = RunOutcome(worker.task.run_key, crash=True, started_at=worker.started_at,
                                 message=f"run setup (planner, scenario and its graph) took over {elapsed:.3g} s")
        else:
            outcome = RunOutcome(worker.task.run_key, timed_out=True, wall_time_s=elapsed, cpu_time_s=cpu,
                                 started_at=worker.started_at, message=f"worker killed after {elapsed:.3g} s")
        self._finish(worker, outcome)
        self._retire(worker)

    def _monitor(self) -> None:
        try:
            if not self.sandboxed:  # all at once: they start while the first task is prepared
                while len(self._workers) < self.capacity:
                    self._spawn(None)
            while True:
                with self._lock:
                    if self._closing:
                        return
                self._dispatch()
                listening = [w for w in self._workers if w.listening]
                nearest = min(min((w.deadline for w in listening), default=math.inf), self._watch_clocks(_clock()))
                timeout = None if math.isinf(nearest) else max(0.0, nearest - _clock())
                ready = set(self._poller.wait(
                    [self._wake_r, *(w.conn for w in listening), *(w.process.sentinel for w in self._workers)], timeout
                ))
                if self._wake_r in ready:
                    while self._wake_r.poll():
                        self._wake_r.recv()
                for worker in listening:
                    if worker.conn in ready and worker in self._workers:
                        self._receive(worker)
                for worker in list(self._workers):
                    if worker.process.sentinel in ready and worker in self._workers:
                        self._receive(worker)  # a result sent just before exiting still counts
                        if worker in self._workers and _written(worker.process.sentinel):
                            self._violation(worker, "it wrote to its exit pipe")  # planner code wrote there
                        elif worker in self._workers:
                            self._died(worker)
                now = _clock()
                for worker in list(self._workers):
                    if worker.task is not None and now >= worker.deadline:
                        self._kill(worker)
        except BaseException as exc:  # never leave the runner waiting on futures forever
            for worker in self._workers:
                if worker.future is not None and not worker.future.done():
                    worker.future.set_exception(exc)
            with self._lock:
                for _, future in self._pending:
                    if not future.cancelled() and future.set_running_or_notify_cancel():
                        future.set_exception(exc)
                self._pending.clear()
            raise
