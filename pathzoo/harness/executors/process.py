"""The process executor: a pool of long-lived worker processes that are killed and replaced when needed.

Each worker is a :mod:`multiprocessing` process with its own pipe. A monitor
thread in the harness process hands tasks to idle workers and waits on the
pipes and on the process sentinels at the same time. Workers run planner
code, so nothing they send is unpickled: they send short tagged byte strings
(read with a size limit) and the outcome in the format of
:mod:`pathzoo.harness.wire`. The frames, and the clocks they start and stop,
are listed in :mod:`~pathzoo.harness.executors.worker_loop`. A worker past
its hard limit gets ``SIGKILL`` (``Process.kill``): the run resolves as
``timed_out`` and a fresh worker replaces it; one that dies (``os._exit``,
segfault, out of memory) gives a ``crash`` with the exit code or signal; one
that sends anything else, or more than
:data:`~pathzoo.harness.wire.MAX_OUTCOME_BYTES`, is killed and its run is a
``crash``.

Each worker runs one planner configuration (planner id, parameter hash and
scenario kind, :func:`~pathzoo.harness.executors.worker_handle.configuration`)
for as many runs as the experiment has of it;
a queued run goes to an idle worker of its configuration, else to a new
worker, so no interpreter state (a recursion limit, a replaced cached
scenario) passes from one planner to another. At most ``jobs`` workers have
a run at once, but up to :attr:`~ProcessExecutor.kept_workers` (twice as
many) stay alive, idle ones waiting for their configuration's next run: a
sweep that alternates configurations keeps its workers instead of starting
one per switch. No configuration gets more workers than ``jobs``, and one
that has a worker gets another only when its share of the slots, by the work
it has left, says so (:mod:`~pathzoo.harness.executors.slot_shares`), or
when a slot its share keeps for other configurations has stayed free for a
worker start's worth of time while its runs wait, and they would still give
each of its workers over a start's worth of work: the runner hands over runs
a few at a time, in the experiment's order, so a paper's table of 20 seeds
per pair shows the pool one configuration for minutes. Only when that many
are alive is an idle worker that no queued run can use retired to make room.

When a sandboxed worker reports idle, its cgroup must hold only the
processes it held when it became ready; anything else (a child, a daemon)
gets the whole cgroup killed and the worker replaced, and a killed or
timed-out worker's cgroup is emptied the same way.

How a worker starts and stops is in
:mod:`~pathzoo.harness.executors.worker_handle`, the loop it runs in
:mod:`~pathzoo.harness.executors.worker_loop`, the clocks and stops of its
runs in :mod:`~pathzoo.harness.executors.run_clocks`, and what a sandboxed
one may read in :mod:`~pathzoo.harness.executors.visibility`.

A scenario object (:meth:`~pathzoo.harness.specs.ScenarioSpec.of_object`)
is sent to each worker once; later tasks on it refer to it by digest
(:func:`~pathzoo.harness.scenario_cache.keep_payload`).

Unsandboxed workers all start when the executor is built (sandboxed ones when
a run of their configuration is queued and a slot is free, counting workers
still starting as taking a slot, or earlier for a planner named to
:meth:`ProcessExecutor.start_worker`), and the runner keeps one run per
worker queued here (:attr:`lookahead`), so a worker goes from one run to the
next without waiting for the harness. The very first run goes alone: the workers of the first configurations
start together, but no worker other than the first run's gets a run until that run plans or ends, so that its
warm-up and setup share the cores with no other run's.
"""

from __future__ import annotations

import contextlib
import math
import os
import shutil
import tempfile
import threading
import time
from collections import Counter, deque
from concurrent.futures import Future
from dataclasses import replace
from typing import TYPE_CHECKING, Any, Hashable

from pathzoo.core.errors import PathzooError
from pathzoo.harness.cpu_clock import process_cpu_time
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.executors.run_clocks import cpu_since, timed, watch_clocks
from pathzoo.harness.executors.slot_shares import SlotShares
from pathzoo.harness.executors.visibility import Visibility, sees
from pathzoo.harness.executors.worker_handle import (Worker, any_configuration, configuration, describe_exit,
                                                     launch_worker, wrote_to_exit_pipe)
from pathzoo.harness.executors.worker_loop import CPU_FRAME, GO
from pathzoo.harness.launch import NoMainContext, default_start_method, start_server
from pathzoo.harness.outcome import RunOutcome, utc_now
from pathzoo.harness.poller import Poller
from pathzoo.harness.sandbox import SandboxLimits, SandboxUnavailableError, sandbox_problem
from pathzoo.harness.wire import MAX_OUTCOME_BYTES, decode_outcome
from pathzoo.harness.worker import SETUP_TIMEOUT_S
from pathzoo.harness.zygote import WarmUp

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = ["ProcessExecutor", "WorkerStartError", "default_start_method", "process_cpu_time", "MAX_START_FAILURES"]

_clock = time.perf_counter  # bound at import: a later patch of time.perf_counter does not reach the harness


class WorkerStartError(PathzooError, RuntimeError):
    """A worker process died before it was ready: the harness cannot run anything."""


MAX_START_FAILURES = 3
"""Workers in a row that die before they are ready, after which the executor gives up (:class:`WorkerStartError`)."""


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
        self._visibility = Visibility()
        self._start_failures = 0
        self._lock = threading.Lock()
        self._pending: deque[tuple[RunTask, Future[RunOutcome]]] = deque()
        self._ended: list[tuple[Future[RunOutcome], RunOutcome]] = []  # resolved by _resolve, after the dispatch
        self._early: list[str] = []  # planner ids of start_worker, for the monitor to start
        self._workers: list[Worker] = []
        self._first_alone = self.capacity > 1  # see _dispatch
        self._slot_idle_since = math.nan  # since when a slot is free while runs wait for a worker (_start_workers)
        self._closing = False
        self._wake_r, self._wake_w = self._ctx.Pipe(duplex=False)
        self._poller = Poller()  # the monitor's: one poll object for all its waits
        self.lookahead = self.capacity
        self.kept_workers = 2 * self.capacity
        """Worker processes kept, idle ones included: at most :attr:`capacity` run at once, and an idle worker of
        another configuration waits for its next run instead of being replaced at every switch of configuration."""
        self._shares = SlotShares(self.capacity)
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

    def lane(self, task: "RunTask") -> Hashable:
        """The task's configuration (:func:`~pathzoo.harness.executors.worker_handle.configuration`): a worker runs
        one."""
        return configuration(task)

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
        """Note where the experiment's scenario files are (a sandboxed worker sees only those directories) and how
        many runs each configuration has (:class:`~pathzoo.harness.executors.slot_shares.SlotShares`)."""
        self._visibility.see_files(tasks)
        self._shares.expect(tasks)

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
                worker.kill_tree()
            elif worker.process.is_alive():
                with contextlib.suppress(OSError):
                    worker.conn.send(None)
        deadline = time.monotonic() + 2.0
        for worker in self._workers:
            worker.process.join(max(0.0, deadline - time.monotonic()))
            worker.release()
            for future in worker.futures():
                future.cancel()
        self._workers.clear()
        for _, future in self._pending:
            future.cancel()
        self._pending.clear()
        self._wake_r.close()
        self._wake_w.close()
        if self._scratch_root:
            shutil.rmtree(self._scratch_root, ignore_errors=True)

    # ------------------------------------------------------------- internals
    def _spawn(self, config: "tuple[str, str, str] | None") -> Worker:
        """A new worker, for ``config`` (:func:`~pathzoo.harness.executors.worker_handle.launch_worker`)."""
        worker = launch_worker(self._ctx, config, sandboxed=self.sandboxed, limits=self.limits,
                               scratch_root=self._scratch_root, dirs=self._visibility.dirs())
        worker.launched_at = _clock()
        self._workers.append(worker)
        return worker

    def _retire(self, worker: Worker) -> None:
        """Stop a worker; its run sent ahead, and its current run if not yet let go (``G``), wait for another."""
        again = [worker.ahead] if worker.ahead is not None else []
        if worker.task is not None and not worker.cleared:
            assert worker.future is not None
            again.insert(0, (worker.task, worker.future))
            worker.task, worker.future = None, None
        worker.ahead = None
        worker.release()
        self._workers.remove(worker)
        with self._lock:
            self._pending.extendleft(reversed(again))

    def _start_workers(self) -> None:
        """Start the workers asked for by :meth:`start_worker`, then those for the queued runs that no idle or starting
        worker of their configuration will take."""
        with self._lock:
            early, self._early = self._early, []
            queued = [task for task, _ in self._pending]
        for planner_id in early:
            if len(self._workers) < self.capacity and not self._closing:
                self._visibility.see_planner(planner_id)
                self._spawn(any_configuration(planner_id))
        refused: "tuple[RunTask, tuple[str, str, str]] | None" = None  # the first run its share kept from a worker
        starting = Counter(w.config for w in self._workers if not w.was_ready)
        taken = sum(w.listening for w in self._workers)  # a slot is taken by a run, or a start or end on its way
        wanted = {configuration(task) for task in queued}
        wanted |= {any_configuration(config[0]) for config in wanted}
        for task in queued:
            config = configuration(task)
            if starting[config] > 0:
                starting[config] -= 1
                continue
            if starting[any_configuration(config[0])] > 0:  # started early for this planner: it takes this one
                starting[any_configuration(config[0])] -= 1
                continue
            if starting[None] > 0 and not self.sandboxed:
                starting[None] -= 1
                continue
            alive = sum(w.config in (config, any_configuration(config[0])) and sees(w, task) for w in self._workers)
            if alive >= self.capacity:
                continue  # one of its workers takes it: another could not run
            if not self._shares.worth_another(config, alive):
                if refused is None and self._shares.pays_for_a_start(config, alive):
                    refused = (task, config)  # refused for its share only: it may take a slot that idles
                continue  # one of its workers takes it: another would cost more than it saves, unless a slot idles
            if taken >= self.capacity or not self._spawn_for(task, config, wanted):
                refused = None
                break
            taken += 1
        if refused is None or taken >= self.capacity:
            self._slot_idle_since = math.nan
        elif math.isnan(self._slot_idle_since):
            self._slot_idle_since = _clock()
        elif _clock() >= self._idle_slot_due():  # idle for a start's worth: a start costs less than idling on
            self._slot_idle_since = math.nan if self._spawn_for(*refused, wanted) else _clock()

    def _spawn_for(self, task: "RunTask", config: "tuple[str, str, str]", wanted: "set[Any]") -> bool:
        """Start a worker for ``task``'s configuration, first retiring an idle one that no queued run (of the
        configurations ``wanted``) can use when :attr:`kept_workers` are alive; False when none can be retired."""
        if len(self._workers) >= self.kept_workers:
            spare = next((w for w in self._workers if w.idle and w.task is None and w.config not in wanted), None)
            if spare is None:
                return False
            self._retire(spare)
        self._visibility.see_files([task])
        self._spawn(config)
        return True

    def _idle_slot_due(self) -> float:
        """When a slot left free by the shares is given to a waiting run (:meth:`_start_workers`); inf if none is."""
        return self._slot_idle_since + self._shares.start_seconds if math.isfinite(self._slot_idle_since) else math.inf

    def _take(self) -> "tuple[Worker, RunTask, Future[RunOutcome]] | None":
        """The first queued run with an idle worker of its configuration (or, unsandboxed, one not yet used), while
        fewer than :attr:`capacity` workers have a run."""
        with self._lock:
            if sum(w.task is not None for w in self._workers) >= self.capacity:
                return None
            for i, (task, future) in enumerate(self._pending):
                worker = next((w for w in self._workers if w.idle and w.task is None and _fits(w, task)), None)
                if worker is None and not self.sandboxed:
                    worker = next((w for w in self._workers if w.idle and w.task is None and w.config is None), None)
                if worker is not None:
                    del self._pending[i]
                    worker.config = configuration(task)
                    self._shares.taken(worker.config)
                    return worker, task, future
        return None

    def _dispatch(self) -> None:
        # no other worker gets a run until the first run plans or ends: its setup shares the cores with no other run's
        while not (self._first_alone and any(w.task is not None for w in self._workers)):
            taken = self._take()
            if taken is None:
                break
            worker, task, future = taken
            if not future.set_running_or_notify_cancel():
                continue
            self._assign(worker, task, future)
            self._send(worker, task, future)
        if sum(w.task is not None for w in self._workers) < self.capacity:
            self._start_workers()
        else:
            self._slot_idle_since = math.nan

    def _assign(self, worker: Worker, task: "RunTask", future: "Future[RunOutcome]") -> None:
        """Make ``task`` the worker's current run, in setup from now."""
        worker.task, worker.future, worker.idle, worker.started_once = task, future, False, False
        worker.sent_at, worker.started_at = _clock(), utc_now()
        worker.taken_at = worker.sent_at if worker.warm else math.nan  # a new worker's warm-up is not a run's
        worker.plan_t0 = worker.plan_t1 = math.nan
        worker.stopped_by = None
        worker.stop.clear()  # no child of the worker's plans now: the next reads the byte only once it plans this task
        worker.deadline = worker.sent_at + max(task.timeout_s, SETUP_TIMEOUT_S)
        worker.in_setup = True

    def _take_ahead(self) -> "tuple[Worker, RunTask, Future[RunOutcome]] | None":
        """The first queued run of a busy warm worker's configuration, for a worker whose current run is let go
        and that has none sent ahead."""
        with self._lock:
            for worker in self._workers:
                if worker.task is None or not worker.cleared or worker.ahead is not None or not worker.warm:
                    continue
                for i, (task, future) in enumerate(self._pending):
                    if _fits(worker, task):
                        del self._pending[i]
                        self._shares.taken(configuration(task))
                        return worker, task, future
        return None

    def _send_ahead(self) -> None:
        """Send each busy worker its next run of the same configuration, queued in its pipe behind its current run:
        the worker sets it up as soon as it has sent its outcome, and plans it once told ``G``
        (:meth:`_clear`)."""
        while (taken := self._take_ahead()) is not None:
            worker, task, future = taken
            try:
                _write_task(worker, task)
            except (OSError, EOFError):  # the worker died: its sentinel says so, and the run waits for another
                with self._lock:
                    self._pending.appendleft((task, future))
                return
            except Exception as exc:  # the task did not pickle
                if future.set_running_or_notify_cancel():
                    self._ended.append((future, RunOutcome(task.run_key, crash=True, started_at=utc_now(),
                                                           message=f"task could not be sent: {exc!r}")))
                continue
            worker.ahead = (task, future)

    def _promote(self, worker: Worker) -> None:
        """The run sent ahead becomes the current one (in setup), waiting for ``G``."""
        if worker.ahead is None:
            return
        (task, future), worker.ahead = worker.ahead, None
        self._assign(worker, task, future)
        worker.cleared = False

    def _clear(self, worker: Worker) -> None:
        """Let the worker's current run hand over (``G``): its last run left nothing behind."""
        assert worker.future is not None
        if not worker.future.set_running_or_notify_cancel():  # cancelled: the executor is shutting down
            self._retire(worker)
            return
        worker.cleared = True
        try:
            worker.conn.send_bytes(GO)
        except (OSError, EOFError):  # the worker died: its sentinel says so
            pass

    def _send(self, worker: Worker, task: "RunTask", future: "Future[RunOutcome]") -> None:
        """Send the task to its worker, or first the order to warm up (a new worker; the task follows its ``W``)."""
        try:
            if worker.warm:
                _write_task(worker, task)
                worker.cleared = True
                worker.conn.send_bytes(GO)  # idle, so its last run left nothing behind (checked at its I)
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

    def _finish(self, worker: Worker, outcome: RunOutcome) -> None:
        self._first_alone = False
        if worker.config is not None:
            self._shares.ran(worker.config, _clock() - worker.taken_at)
        if worker.group is not None and worker.group.out_of_memory() and outcome.crash:
            outcome = replace(outcome, message=f"{outcome.message} (out of memory: over the sandbox's limit of "
                                               f"{self.limits.memory_bytes / 2**20:.0f} MiB)")
        self._ended.append((worker.end_run(), replace(outcome, sandboxed=worker.group is not None)))

    def _resolve(self) -> None:
        """Resolve the futures of the runs that ended. The monitor calls it once it has given the workers that ended
        them their next runs: the runner's thread, woken by a future, would otherwise hold the interpreter while an
        idle worker waits for its next run."""
        ended, self._ended = self._ended, []
        for future, outcome in ended:
            if not future.done():
                future.set_result(outcome)

    def _violation(self, worker: Worker, what: str) -> None:
        if worker.task is not None:
            self._finish(worker, RunOutcome(worker.task.run_key, crash=True, started_at=worker.started_at,
                                            message=f"the worker broke the protocol ({what}) and was killed"))
        self._retire(worker)

    def _left_behind(self, worker: Worker) -> bool:
        """Whether the worker's cgroup holds a process that was not there when it became ready (a planner's child)."""
        return worker.group is not None and not set(worker.group.pids()) <= worker.baseline

    def _receive(self, worker: Worker) -> None:
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
            elif tag == b"I" and not worker.cleared:  # the run sent ahead is set up meanwhile, and waits for G
                if self._left_behind(worker):  # the whole tree goes, and the run sent ahead waits for another
                    self._retire(worker)
                    return
                self._clear(worker)
            elif tag == b"T" and (worker.task is None or not worker.cleared):
                self._retire(worker)  # a planner patched modules in it: never reuse it (a run sent ahead waits for
                # another worker)
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
                self._shares.started(worker.sent_at - worker.launched_at)
                worker.deadline = worker.sent_at + max(worker.task.timeout_s, SETUP_TIMEOUT_S)
                worker.cpu.start()
                self._send(worker, worker.task, worker.future)
            elif tag == b"P" and worker.task is not None and worker.started_once and math.isnan(worker.plan_t0):
                worker.plan_t0 = _clock()
                self._first_alone = False
            elif tag == b"D" and worker.task is not None and worker.warm and len(body) >= CPU_FRAME.size:
                (child_cpu,) = CPU_FRAME.unpack(body[:CPU_FRAME.size])
                self._finish(worker, timed(worker, decode_outcome(body[CPU_FRAME.size:], worker.task.run_key),
                                                 child_cpu))
                self._promote(worker)
            elif worker.task is not None:
                continue  # a repeated announcement, or one out of turn (planner code can write frames during its
                # warm-up): it changes nothing, the clocks run from the warm-up's end to the outcome whatever it says
            else:
                self._violation(worker, f"unexpected message {bytes(message[:8])!r}")
                return

    def _died(self, worker: Worker) -> None:
        worker.process.join()
        if worker.task is not None:
            elapsed = _clock() - worker.sent_at
            cpu = cpu_since(worker)
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

    def _kill(self, worker: Worker) -> None:
        assert worker.task is not None
        elapsed = _clock() - worker.sent_at
        cpu = cpu_since(worker)
        worker.kill_tree()
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
                        self._resolve()
                        return
                self._dispatch()
                self._send_ahead()
                self._resolve()
                listening = [w for w in self._workers if w.listening]
                nearest = min(min((w.deadline for w in listening), default=math.inf),
                              watch_clocks(self._workers, _clock()), self._idle_slot_due())
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
                        if worker in self._workers and wrote_to_exit_pipe(worker.process.sentinel):
                            self._violation(worker, "it wrote to its exit pipe")  # planner code wrote there
                        elif worker in self._workers:
                            self._died(worker)
                now = _clock()
                for worker in list(self._workers):
                    if worker.task is not None and now >= worker.deadline:
                        self._kill(worker)
        except BaseException as exc:  # never leave the runner waiting on futures forever
            self._resolve()
            for worker in self._workers:
                for future in worker.futures():
                    if not future.done():
                        future.set_exception(exc)
            with self._lock:
                for _, future in self._pending:
                    if not future.cancelled() and future.set_running_or_notify_cancel():
                        future.set_exception(exc)
                self._pending.clear()
            raise


def _fits(worker: Worker, task: "RunTask") -> bool:
    """Whether ``worker`` runs ``task``'s configuration (or was started early for its planner) and can read its
    scenario."""
    config = configuration(task)
    return worker.config in (config, any_configuration(config[0])) and sees(worker, task)


def _write_task(worker: Worker, task: "RunTask") -> None:
    """Send ``task`` down the worker's pipe (a scenario it holds goes by reference)."""
    worker.conn.send(worker.held.outgoing(task))
    worker.held.sent(task)
