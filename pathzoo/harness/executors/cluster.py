"""The Dask executor: runs go to a ``dask.distributed`` cluster (or a local one), timed outside the planner.

``dask`` is imported only when this executor is built (``pip install
pathzoo[dask]``). Each run is one Dask task, but the planner never runs in
the Dask worker: the task hands the run to a one-worker
:class:`~pathzoo.harness.executors.process.ProcessExecutor` that the Dask
worker thread owns (started on its first task, kept for the next ones), so
the planner runs in a child process of the Dask worker and the Dask worker
supervises it exactly as the process executor does (read that module's
docstring). What this gives:

- wall time is the Dask worker's clock from the child's "planning" message to
  its outcome, CPU time the child's CPU time read from outside it (psutil):
  a planner that patches ``time`` or pathzoo's clocks in its own process
  changes neither. CPU time is meaningful with any number of threads per
  Dask worker, since each thread has its own child;
- the hard limit counts from the child's first "started" message (planner
  built, scenario loaded), so runs waiting in the cluster's queue never time
  out; at the limit the child gets ``SIGKILL`` and the run is ``timeout``:
  no thread keeps running and the Dask worker needs no restart;
- exceptions in ``plan()``, a child that dies (``os._exit``, segfault, out
  of memory) or breaks the protocol, and a child whose planner rebound module
  attributes (:mod:`pathzoo.harness.tamper`) are handled by the process
  executor: ``crash`` outcomes and a fresh child for the next run;
- nothing the planner's process sends is unpickled (:mod:`pathzoo.harness.wire`).
  Dask unpickles what its workers send, but the Dask worker processes now run
  only pathzoo code; the outcome still travels as bytes and is decoded and
  bounded here again;
- a Dask worker *process* that dies is detected by the scheduler, which fails
  the task with ``KilledWorker``: the run is recorded as ``crash``. The local
  cluster sets ``distributed.scheduler.allowed-failures`` to 0 for this; an
  external scheduler retries the task on other workers as often as its own
  setting allows (3 by default) before giving up;
- a Dask task that never starts (lost by the scheduler) is given up after
  :data:`~pathzoo.harness.worker.SETUP_TIMEOUT_S`, and one that never answers
  after that limit plus the run's hard limit plus :data:`ANSWER_GRACE_S`
  (both as ``crash``), so an experiment cannot hang on a broken cluster;
- Dask worker processes must be allowed to have children: Dask starts them as
  *daemonic* processes by default, which :mod:`multiprocessing` forbids to
  fork. The local cluster turns that off while the executor lives
  (``distributed.worker.daemon: False``); for an external cluster start the
  workers with ``DASK_DISTRIBUTED__WORKER__DAEMON=False`` (or ``dask worker
  --no-nanny``), else the executor refuses to start with an error saying so;
- file scenarios are read by path on the workers, so the files must be
  visible to them at the same path; Python scenario objects travel in the task;
- the pool follows the cluster: :attr:`~DaskExecutor.capacity` (and as many
  runs again queued on the scheduler, :attr:`~DaskExecutor.lookahead`) is the
  number of threads of the workers connected now, polled every
  :data:`WORKERS_POLL_S`, and :meth:`~DaskExecutor.capacity_changed` wakes the
  runner when it changes, so a worker that joins late (a SLURM job leaving
  the queue, adaptive scaling) gets runs at once. While no worker is
  connected one run waits on the scheduler and the ``pathzoo.harness``
  logger says, every :data:`WAIT_NOTICE_S`, that the experiment is waiting
  for workers; a run waiting for a free thread (all threads busy, or none)
  is never given up as lost. A worker that joins late as a daemonic process
  is named in a warning and left out of the capacity.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import threading
import time
import logging
import uuid
from concurrent.futures import CancelledError, Future
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from pathzoo.core.errors import PathzooError
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.executors.process import ProcessExecutor
from pathzoo.harness.sandbox import sandbox_problem
from pathzoo.harness.wire import decode_outcome, encode_outcome
from pathzoo.harness.outcome import RunOutcome, utc_now
from pathzoo.harness.worker import SETUP_TIMEOUT_S

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = ["DaskExecutor", "ANSWER_GRACE_S", "WORKERS_POLL_S", "WAIT_NOTICE_S"]

_STARTED_TOPIC = "pathzoo-run-started"
_TICK_S = 0.1
ANSWER_GRACE_S = 120.0
"""Slack beyond the setup and hard limits before the harness gives up on a Dask task that does not answer."""
WORKERS_POLL_S = 0.5
"""How often the executor asks the scheduler which workers are connected."""
WAIT_NOTICE_S = 60.0
"""How often the wait for a first worker is said again."""
log = logging.getLogger("pathzoo.harness")
_clock = time.perf_counter  # bound at import: a later patch of time.perf_counter does not reach the harness

_supervisors: dict[tuple[str, int], ProcessExecutor] = {}
_supervisors_lock = threading.Lock()


def _supervisor(token: str) -> ProcessExecutor:
    """The one-worker process executor of this Dask worker thread for the executor ``token`` (made on first use)."""
    key = (token, threading.get_ident())
    with _supervisors_lock:
        executor = _supervisors.get(key)
        if executor is None:
            executor = _supervisors[key] = ProcessExecutor(1)  # sandboxed where the Dask worker's host can
    return executor


def _close_supervisors(token: str, thread: int | None = None) -> int:
    """Shut down the process executors made for ``token`` in this Dask worker process (one thread's, or all)."""
    with _supervisors_lock:
        keys = [key for key in _supervisors if key[0] == token and thread in (None, key[1])]
        executors = [_supervisors.pop(key) for key in keys]
    for executor in executors:
        executor.shutdown()
    return len(executors)


def _may_fork() -> bool:
    """Whether this (Dask worker) process may start child processes, i.e. is not daemonic."""
    return not multiprocessing.current_process().daemon


def _run_on_worker(task: "RunTask", token: str) -> bytes:
    """The Dask task: report the start, run the task in this thread's supervised child, return the encoded outcome."""
    from distributed import get_worker

    get_worker().log_event(_STARTED_TOPIC, [task.run_key])
    try:
        outcome = _supervisor(token).submit(task).result()
    except BaseException:  # its child could not start and its monitor stopped: the next run gets a fresh one
        _close_supervisors(token, threading.get_ident())
        raise
    return encode_outcome(outcome)


@dataclass
class _Run:
    task: "RunTask"
    future: "Future[RunOutcome]"
    dask_future: Any
    submitted: float
    started: float = math.nan

    @property
    def deadline(self) -> float:
        """When the harness stops waiting: no start within the setup limit, or no answer well past the hard limit."""
        if math.isnan(self.started):
            return self.submitted + SETUP_TIMEOUT_S
        return self.started + SETUP_TIMEOUT_S + self.task.timeout_s + ANSWER_GRACE_S


class DaskExecutor(RunExecutor):
    """Run tasks on a Dask cluster, each planner in a supervised child of its Dask worker (see the module docstring).

    Parameters
    ----------
    jobs : int, optional
        Workers of the local cluster (default ``os.cpu_count()``); ignored with ``address`` or ``cluster``.
    address : str, optional
        Scheduler address such as ``"tcp://10.0.0.5:8786"``; without it (and
        without ``cluster``) a ``LocalCluster`` with one thread per worker is
        started and closed.
    processes : bool
        Local cluster only: Dask workers as processes (True) or as threads in
        this process. Planners run in child processes either way.
    cluster : distributed.deploy.Cluster, optional
        A cluster made by the caller (a dask-jobqueue ``SLURMCluster``, say),
        whose workers may still be starting; the executor connects to it and
        closes it at :meth:`shutdown`.

    Raises
    ------
    PathzooError
        dask is not installed, the scheduler cannot be reached, or its workers
        are daemonic processes (which cannot start the planners' processes).
    """

    isolated = True
    sandbox_problem = ""
    """A local cluster's workers are sandboxed where this host can; each run's outcome says whether it was."""

    def __init__(self, jobs: int | None = None, *, address: str | None = None, processes: bool = True,
                 cluster: Any = None) -> None:
        try:
            import dask
            from distributed import Client, LocalCluster
        except ImportError:
            raise PathzooError("the 'dask' executor needs dask.distributed: pip install 'pathzoo[dask]'") from None
        self._cluster = cluster
        self._config = None
        self._where = address or getattr(cluster, "scheduler_address", "") or "the local cluster"
        if address or cluster is not None:
            try:
                self._client = Client(cluster) if cluster is not None else Client(address, timeout="20s")
            except (OSError, ValueError, TypeError) as exc:  # TimeoutError is an OSError
                raise PathzooError(f"cannot connect to the Dask scheduler at {self._where!r}: "
                                   f"{' '.join(str(exc).split()) or type(exc).__name__}") from None
        else:
            # a run that kills its Dask worker is a crash, not a task to retry elsewhere; workers (and the ones
            # their nannies start again later) must be allowed to start the planners' processes
            self._config = dask.config.set({"distributed.scheduler.allowed-failures": 0,
                                            "distributed.worker.daemon": False})
            self._cluster = LocalCluster(
                n_workers=int(jobs or os.cpu_count() or 1), threads_per_worker=1, processes=processes,
                dashboard_address=":0",  # Dask always serves HTTP; a free port, never a clash on 8787
            )
            self._client = Client(self._cluster)
            self.sandbox_problem = sandbox_problem()
        self._token = uuid.uuid4().hex
        self._lock = threading.Lock()
        self._runs: dict[str, _Run] = {}
        self._closing = threading.Event()
        self._workers: dict[str, int] = {}  # address: threads, of the workers that may run planners
        self._refused: set[str] = set()  # daemonic workers, left out
        self._wake: Future[None] = Future()
        self._waiting_since = math.nan
        try:
            self._follow_workers(refuse=True)
        except BaseException:
            self._client.close()
            raise
        self._client.subscribe_topic(_STARTED_TOPIC, self._on_started)
        self._watchdog = threading.Thread(target=self._watch, name="pathzoo-dask-watchdog", daemon=True)
        self._watchdog.start()

    def _follow_workers(self, refuse: bool = False) -> None:
        """Bring :attr:`capacity` up to date with the workers connected now; check the ones seen first now.

        Daemonic workers raise with ``refuse`` (at the start), else they are
        named in a warning and left out.
        """
        try:
            threads = dict(self._client.nthreads())
        except Exception as exc:  # noqa: BLE001 - any failure to ask is a failure to connect
            if refuse:
                raise PathzooError(f"cannot query the Dask workers at {self._where!r}: "
                                   f"{type(exc).__name__}: {exc}") from None
            return
        new = sorted(set(threads) - set(self._workers) - self._refused)
        if new:
            try:
                allowed = self._client.run(_may_fork, workers=new)
            except Exception as exc:  # noqa: BLE001 - a worker that left meanwhile: asked again next time
                if refuse:
                    raise PathzooError(f"cannot query the Dask workers at {self._where!r}: "
                                       f"{type(exc).__name__}: {exc}") from None
                allowed = {}
            daemonic = sorted(worker for worker, ok in allowed.items() if not ok)
            if daemonic and refuse:
                raise PathzooError(
                    f"the Dask workers {', '.join(daemonic)} at {self._where!r} are daemonic processes and cannot "
                    "start planner processes: start them with DASK_DISTRIBUTED__WORKER__DAEMON=False")
            if daemonic:
                log.warning("pathzoo: Dask worker(s) %s joined as daemonic processes, which cannot start planner "
                            "processes: left out (start them with DASK_DISTRIBUTED__WORKER__DAEMON=False)",
                            ", ".join(daemonic))
            self._refused.update(daemonic)
            self._workers.update({w: threads[w] for w in allowed if allowed[w]})
        for gone in set(self._workers) - set(threads):
            del self._workers[gone]
        capacity = sum(self._workers.values())
        self._notice_wait(capacity)
        capacity = max(1, capacity)  # with no worker, one run waits on the scheduler for the first to come
        if (capacity, capacity) != (self.capacity, self.lookahead):
            self.capacity = self.lookahead = capacity
            wake, self._wake = self._wake, Future()
            wake.set_result(None)

    def _notice_wait(self, threads: int) -> None:
        """Say that the experiment waits for workers (at once, then every :data:`WAIT_NOTICE_S`), and when they come."""
        now = _clock()
        if threads and not math.isnan(self._waiting_since):
            log.warning("pathzoo: %d Dask worker thread(s) connected at %s, running", threads, self._where)
            self._waiting_since = math.nan
        elif not threads and (math.isnan(self._waiting_since) or now - self._waiting_since >= WAIT_NOTICE_S):
            log.warning("pathzoo: no Dask worker is connected to the scheduler at %s: waiting for one (runs start "
                        "when workers join; Ctrl-C stops)", self._where)
            self._waiting_since = now

    def capacity_changed(self) -> "Future[None]":
        """A future that resolves when :attr:`capacity` next changes (a worker joined or left)."""
        return self._wake

    def submit(self, task: "RunTask") -> "Future[RunOutcome]":
        """Submit one run as a Dask task."""
        future: Future[RunOutcome] = Future()
        future.set_running_or_notify_cancel()
        run = _Run(task, future, None, _clock())
        with self._lock:
            self._runs[task.run_key] = run
        run.dask_future = self._client.submit(_run_on_worker, task, self._token, pure=False)
        run.dask_future.add_done_callback(lambda f, key=task.run_key: self._done(key, f))
        return future

    def shutdown(self) -> None:
        """Cancel outstanding tasks, stop the planners' processes, close the client and the cluster it made or was
        given (a second call does nothing)."""
        if self._closing.is_set():
            return
        self._closing.set()
        self._watchdog.join()
        with self._lock:
            runs, self._runs = list(self._runs.values()), {}
        for run in runs:
            run.dask_future.cancel()
            if not run.future.done():
                run.future.cancel()
        try:
            self._client.run(_close_supervisors, self._token)
        except Exception:  # noqa: BLE001 - workers that are gone have no children left to stop
            pass
        self._client.close()
        if self._cluster is not None:
            self._cluster.close()
        if self._config is not None:
            self._config.__exit__(None, None, None)

    # ------------------------------------------------------------- internals
    def _on_started(self, event: Any) -> None:
        try:
            (key,) = event[1]  # (timestamp, [run_key])
        except (TypeError, ValueError):
            return
        with self._lock:
            run = self._runs.get(key)
            if run is not None and math.isnan(run.started):
                run.started = _clock()

    def _done(self, key: str, dask_future: Any) -> None:
        with self._lock:
            run = self._runs.get(key)
            if run is None or run.dask_future is not dask_future:  # given up, or shut down
                return
            del self._runs[key]
        try:
            outcome = self._outcome(key, dask_future)
        except BaseException as exc:  # noqa: BLE001 - a callback that raises would leave the run pending forever
            outcome = RunOutcome(key, crash=True, started_at=utc_now(),
                                 message=f"dask result could not be handled: {exc!r}")
        run.future.set_result(outcome)

    @staticmethod
    def _outcome(key: str, dask_future: Any) -> RunOutcome:
        try:
            data = dask_future.result()
            if not isinstance(data, bytes):
                raise TypeError(f"the worker returned {type(data).__name__}, not an encoded outcome")
            outcome = decode_outcome(data, key)
            return replace(outcome, started_at=outcome.started_at or utc_now())
        except CancelledError:
            return RunOutcome(key, crash=True, message="dask task was cancelled", started_at=utc_now())
        except Exception as exc:  # noqa: BLE001 - KilledWorker, a child that failed to start, a broken connection
            return RunOutcome(key, crash=True, started_at=utc_now(),
                              message=f"dask task failed: {type(exc).__name__}: {exc}")

    def _watch(self) -> None:
        polled = _clock()
        while not self._closing.wait(_TICK_S):
            now = _clock()
            if now - polled >= WORKERS_POLL_S:
                self._follow_workers()
                polled = now
            with self._lock:
                busy = sum(not math.isnan(run.started) for run in self._runs.values())
                if busy >= sum(self._workers.values()):  # no free thread: the runs not started wait for one
                    for run in self._runs.values():
                        if math.isnan(run.started):
                            run.submitted = now
                expired = [key for key, run in self._runs.items() if now >= run.deadline]
                runs = [self._runs.pop(key) for key in expired]
            for run in runs:  # a lost or stuck Dask task must not hang the experiment
                run.dask_future.cancel()
                what = ("the cluster did not start the run" if math.isnan(run.started)
                        else "the Dask task did not answer")
                run.future.set_result(RunOutcome(run.task.run_key, crash=True, started_at=utc_now(),
                                                 message=f"{what} within {now - run.submitted:.3g} s"))
