"""The process executor: a pool of long-lived worker processes that are killed and replaced when needed.

Each worker is a :mod:`multiprocessing` process with its own pipe. A monitor
thread in the harness process hands tasks to idle workers and waits on the
pipes and on the process sentinels at the same time, so it notices at once

- a result (``("done", outcome)``): the future resolves;
- the start of ``plan()`` (``("started",)``, sent once the planner is built
  and the scenario is loaded and its graph built): the hard limit
  ``timeout_s`` counts from here. The setup before it has its own limit,
  :data:`~pathzoo.harness.worker.SETUP_TIMEOUT_S` (a huge map can take a
  while to load); a setup past it is recorded as ``crash``;
- a worker past its hard limit: it gets ``SIGKILL`` (``Process.kill``), the
  run resolves as ``timed_out`` and a fresh worker replaces it;
- a worker that died (``os._exit``, segfault, ``SIGKILL`` from outside, out
  of memory): the run resolves as ``crash`` with the exit code or signal, and
  a fresh worker replaces it.

Workers start with the ``forkserver`` method where available (``spawn``
elsewhere): replacing a killed worker then costs a fork, not a new
interpreter, and no state of the harness process leaks into workers. Workers
ignore ``SIGINT``; Ctrl-C reaches the harness, which kills them on shutdown.
"""

from __future__ import annotations

import math
import multiprocessing as mp
import os
import signal
import threading
import time
from collections import deque
from concurrent.futures import Future
from dataclasses import dataclass
from multiprocessing.connection import Connection, wait
from typing import TYPE_CHECKING, Any

from pathzoo.core.errors import PathzooError
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.worker import SETUP_TIMEOUT_S, RunOutcome, execute_task, utc_now

if TYPE_CHECKING:
    from multiprocessing.process import BaseProcess

    from pathzoo.harness.specs import RunTask

__all__ = ["ProcessExecutor", "WorkerStartError", "default_start_method"]

_PRELOAD = ["pathzoo.harness.executors.warmup"]


class WorkerStartError(PathzooError, RuntimeError):
    """A worker process died before it was ready: the harness cannot run anything."""


def default_start_method() -> str:
    """``forkserver`` where the platform has it, else ``spawn``."""
    return "forkserver" if "forkserver" in mp.get_all_start_methods() else "spawn"


def _worker_main(conn: Connection) -> None:
    """Loop of one worker process: receive a task, run it, send the outcome; ``None`` stops."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    conn.send(("ready",))
    while True:
        try:
            task = conn.recv()
        except (EOFError, OSError):
            return
        if task is None:
            return
        outcome = execute_task(task, on_started=lambda: conn.send(("started",)))
        try:
            conn.send(("done", outcome))
        except (EOFError, OSError):
            return
        except Exception as exc:  # the outcome did not pickle
            conn.send(("done", RunOutcome(task.run_key, crash=True, message=f"outcome could not be sent back: {exc!r}",
                                          started_at=outcome.started_at)))


def describe_exit(exitcode: int | None) -> str:
    """``"exit code 3"`` or ``"signal 9 (SIGKILL)"``."""
    if exitcode is None:
        return "unknown exit status"
    if exitcode < 0:
        try:
            return f"signal {-exitcode} ({signal.Signals(-exitcode).name})"
        except ValueError:
            return f"signal {-exitcode}"
    return f"exit code {exitcode}"


@dataclass
class _Worker:
    process: "BaseProcess"
    conn: Connection
    ready: bool = False
    task: "RunTask | None" = None
    future: "Future[RunOutcome] | None" = None
    sent_at: float = math.nan
    started_at: str = ""
    deadline: float = math.inf
    in_setup: bool = False

    def finish(self, outcome: RunOutcome) -> None:
        assert self.future is not None
        if not self.future.done():
            self.future.set_result(outcome)
        self.task, self.future, self.deadline = None, None, math.inf


class ProcessExecutor(RunExecutor):
    """A pool of ``jobs`` long-lived worker processes (see the module docstring).

    Parameters
    ----------
    jobs : int, optional
        Number of workers (default: ``os.cpu_count()``).
    start_method : str, optional
        :mod:`multiprocessing` start method (default :func:`default_start_method`).
    """

    def __init__(self, jobs: int | None = None, *, start_method: str | None = None) -> None:
        self.capacity = int(jobs or os.cpu_count() or 1)
        self._ctx: Any = mp.get_context(start_method or default_start_method())
        if self._ctx.get_start_method() == "forkserver":
            self._ctx.set_forkserver_preload(_PRELOAD)
        self._lock = threading.Lock()
        self._pending: deque[tuple[RunTask, Future[RunOutcome]]] = deque()
        self._workers: list[_Worker] = []
        self._closing = False
        self._wake_r, self._wake_w = self._ctx.Pipe(duplex=False)
        self._thread = threading.Thread(target=self._monitor, name="pathzoo-process-executor", daemon=True)
        self._thread.start()

    # ------------------------------------------------------------ interface
    def submit(self, task: "RunTask") -> "Future[RunOutcome]":
        """Queue a run for the next idle worker."""
        future: Future[RunOutcome] = Future()
        with self._lock:
            if self._closing:
                raise RuntimeError("executor is shut down")
            self._pending.append((task, future))
        self._wake_w.send(None)
        return future

    def shutdown(self) -> None:
        """Stop the monitor, ask idle workers to exit, kill busy ones, cancel queued runs."""
        with self._lock:
            if self._closing:
                return
            self._closing = True
        self._wake_w.send(None)
        self._thread.join()
        for worker in self._workers:
            if worker.task is not None:
                worker.process.kill()
            elif worker.process.is_alive():
                try:
                    worker.conn.send(None)
                except OSError:
                    pass
        deadline = time.monotonic() + 2.0
        for worker in self._workers:
            worker.process.join(max(0.0, deadline - time.monotonic()))
            if worker.process.is_alive():
                worker.process.kill()
                worker.process.join()
            worker.conn.close()
            if worker.future is not None:
                worker.future.cancel()
        self._workers.clear()
        for _, future in self._pending:
            future.cancel()
        self._pending.clear()
        self._wake_r.close()
        self._wake_w.close()

    # ------------------------------------------------------------- internals
    def _spawn(self) -> _Worker:
        parent, child = self._ctx.Pipe(duplex=True)
        process = self._ctx.Process(target=_worker_main, args=(child,), name="pathzoo-worker")
        process.start()
        child.close()
        worker = _Worker(process, parent)
        self._workers.append(worker)
        return worker

    def _retire(self, worker: _Worker) -> None:
        if worker.process.is_alive():
            worker.process.kill()
        worker.process.join()
        worker.conn.close()
        self._workers.remove(worker)

    def _dispatch(self) -> None:
        while True:
            with self._lock:
                if not self._pending:
                    return
                idle = next((w for w in self._workers if w.ready and w.task is None), None)
                if idle is not None:
                    task, future = self._pending.popleft()
            if idle is None:  # start the missing workers; they say when they are ready
                while len(self._workers) < self.capacity:
                    self._spawn()
                return
            if not future.set_running_or_notify_cancel():
                continue
            worker = idle
            worker.task, worker.future = task, future
            worker.sent_at, worker.started_at = time.perf_counter(), utc_now()
            worker.deadline = worker.sent_at + max(task.timeout_s, SETUP_TIMEOUT_S)
            worker.in_setup = True
            try:
                worker.conn.send(task)
            except (OSError, EOFError):  # the idle worker had died: retry the task on a fresh one
                worker.task, worker.future = None, None
                self._retire(worker)
                with self._lock:
                    self._pending.appendleft((task, future))
            except Exception as exc:  # the task did not pickle
                worker.finish(RunOutcome(task.run_key, crash=True, message=f"task could not be sent: {exc!r}",
                                         started_at=worker.started_at))

    def _receive(self, worker: _Worker) -> None:
        while (worker.task is not None or not worker.ready) and worker.conn.poll():
            try:
                message = worker.conn.recv()
            except (EOFError, OSError):
                return  # the sentinel reports the death
            if message[0] == "ready":
                worker.ready = True
            elif message[0] == "started" and worker.task is not None:
                worker.sent_at = time.perf_counter()
                worker.deadline = worker.sent_at + worker.task.timeout_s
                worker.in_setup = False
            else:
                worker.finish(message[1])

    def _died(self, worker: _Worker) -> None:
        worker.process.join()
        if not worker.ready:
            raise WorkerStartError(
                f"a pathzoo worker process failed to start ({describe_exit(worker.process.exitcode)}); "
                "a script that calls pathzoo.run must do so under `if __name__ == \"__main__\":` "
                "(workers import the main module), or use executor='inline'"
            )
        if worker.task is not None:
            elapsed = time.perf_counter() - worker.sent_at
            worker.finish(RunOutcome(
                worker.task.run_key, crash=True, wall_time_s=elapsed, started_at=worker.started_at,
                message=f"worker process died ({describe_exit(worker.process.exitcode)}) after {elapsed:.3g} s",
            ))
        self._retire(worker)

    def _kill(self, worker: _Worker) -> None:
        assert worker.task is not None
        elapsed = time.perf_counter() - worker.sent_at
        worker.process.kill()
        if worker.in_setup:  # not the planner's time: its plan() never started
            outcome = RunOutcome(worker.task.run_key, crash=True, started_at=worker.started_at,
                                 message=f"run setup (planner, scenario and its graph) took over {elapsed:.3g} s")
        else:
            outcome = RunOutcome(worker.task.run_key, timed_out=True, wall_time_s=elapsed,
                                 started_at=worker.started_at, message=f"worker killed after {elapsed:.3g} s")
        worker.finish(outcome)
        self._retire(worker)

    def _monitor(self) -> None:
        try:
            while True:
                with self._lock:
                    if self._closing:
                        return
                self._dispatch()
                listening = [w for w in self._workers if w.task is not None or not w.ready]
                nearest = min((w.deadline for w in listening), default=math.inf)
                timeout = None if math.isinf(nearest) else max(0.0, nearest - time.perf_counter())
                ready = set(wait(
                    [self._wake_r, *(w.conn for w in listening), *(w.process.sentinel for w in self._workers)], timeout
                ))
                if self._wake_r in ready:
                    while self._wake_r.poll():
                        self._wake_r.recv()
                for worker in listening:
                    if worker.conn in ready:
                        self._receive(worker)
                for worker in list(self._workers):
                    if worker.process.sentinel in ready:
                        self._receive(worker)  # a result sent just before exiting still counts
                        self._died(worker)
                now = time.perf_counter()
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
