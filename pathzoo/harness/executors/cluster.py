"""The Dask executor: runs go to a ``dask.distributed`` cluster (or a local one).

``dask`` is imported only when this executor is built (``pip install
pathzoo[dask]``). Each run is one task calling
:func:`~pathzoo.harness.worker.execute_task` on a Dask worker, which loads
plugins and scenarios itself (cached per worker process) and returns the
outcome; the harness judges and stores it as with the other executors.

What it can and cannot guarantee:

- exceptions in ``plan()`` are caught in the task and recorded as ``crash``;
- a worker *process* that dies is detected by the scheduler, which fails the
  task with ``KilledWorker``: the run is recorded as ``crash``. The local
  cluster sets ``distributed.scheduler.allowed-failures`` to 0 for this; an
  external scheduler retries the task on other workers as often as its own
  setting allows (3 by default) before giving up;
- the hard limit counts from the moment ``plan()`` starts (the task reports it
  with a worker event), so runs waiting in the cluster's queue never time out;
- a thread cannot be killed: at the hard limit the run is recorded as
  ``timeout`` and its task cancelled, and the harness asks the scheduler to
  restart the worker that runs it (best effort: this needs a nanny, i.e. a
  worker started by ``dask worker`` or a ``LocalCluster(processes=True)``).
  Without a restart the thread keeps running until ``plan()`` returns, and
  that worker has one thread less meanwhile. Runs that die with such a
  restarted worker, or with a worker killed by another run before they
  started, are submitted again (up to 3 attempts), not recorded as crashes;
- CPU time is process CPU time of the worker, so it is only meaningful with
  one thread per worker (the local cluster uses ``threads_per_worker=1``);
- file scenarios are read by path on the workers, so the files must be
  visible to them at the same path; Python scenario objects travel in the task.
"""

from __future__ import annotations

import math
import os
import threading
import time
from concurrent.futures import CancelledError, Future
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from pathzoo.core.errors import PathzooError
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.worker import RunOutcome, execute_task, utc_now

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = ["DaskExecutor"]

_STARTED_TOPIC = "pathzoo-run-started"
_TICK_S = 0.1
_MAX_ATTEMPTS = 3


def _run_on_worker(task: "RunTask") -> RunOutcome:
    """The Dask task: run one task and report the start of ``plan()`` as a worker event."""
    from distributed import get_worker

    worker = get_worker()
    return execute_task(task, on_started=lambda: worker.log_event(_STARTED_TOPIC, [task.run_key, worker.address]))


@dataclass
class _Run:
    task: "RunTask"
    future: "Future[RunOutcome]"
    dask_future: Any
    submitted: float
    started: float = math.nan
    deadline: float = math.inf
    worker: str = ""
    attempts: int = 1


class DaskExecutor(RunExecutor):
    """Run tasks on a Dask cluster (see the module docstring for its guarantees).

    Parameters
    ----------
    jobs : int, optional
        Workers of the local cluster (default ``os.cpu_count()``); ignored with ``address``.
    address : str, optional
        Scheduler address such as ``"tcp://10.0.0.5:8786"``; without it a
        ``LocalCluster`` with one thread per worker is started and closed.
    processes : bool
        Local cluster only: worker processes (True) or threads in this process.
    """

    def __init__(self, jobs: int | None = None, *, address: str | None = None, processes: bool = True) -> None:
        try:
            import dask
            from distributed import Client, LocalCluster
        except ImportError:
            raise PathzooError("the 'dask' executor needs dask.distributed: pip install 'pathzoo[dask]'") from None
        self._cluster = None
        if address:
            self._client = Client(address)
        else:
            # a run that kills its worker is a crash, not a task to retry elsewhere
            with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
                self._cluster = LocalCluster(
                    n_workers=int(jobs or os.cpu_count() or 1), threads_per_worker=1, processes=processes,
                    dashboard_address=None,
                )
            self._client = Client(self._cluster)
        self.capacity = max(1, sum(self._client.nthreads().values()))
        self._lock = threading.Lock()
        self._runs: dict[str, _Run] = {}
        self._restarted: set[str] = set()
        self._closing = threading.Event()
        self._client.subscribe_topic(_STARTED_TOPIC, self._on_started)
        self._watchdog = threading.Thread(target=self._watch, name="pathzoo-dask-watchdog", daemon=True)
        self._watchdog.start()

    def submit(self, task: "RunTask") -> "Future[RunOutcome]":
        """Submit one run as a Dask task."""
        future: Future[RunOutcome] = Future()
        future.set_running_or_notify_cancel()
        self._send(_Run(task, future, None, time.perf_counter()))
        return future

    def _send(self, run: _Run) -> None:
        run.dask_future = self._client.submit(_run_on_worker, run.task, pure=False)
        with self._lock:
            self._runs[run.task.run_key] = run
        run.dask_future.add_done_callback(lambda f, key=run.task.run_key: self._done(key, f))

    def shutdown(self) -> None:
        """Cancel outstanding tasks and close the client (and the local cluster)."""
        self._closing.set()
        self._watchdog.join()
        with self._lock:
            runs, self._runs = list(self._runs.values()), {}
        for run in runs:
            run.dask_future.cancel()
        self._client.close()
        if self._cluster is not None:
            self._cluster.close()

    # ------------------------------------------------------------- internals
    def _on_started(self, event: Any) -> None:
        key, worker = event[1]  # (timestamp, [run_key, worker address])
        with self._lock:
            run = self._runs.get(key)
            if run is not None:
                run.started = time.perf_counter()
                run.deadline = run.started + run.task.timeout_s
                run.worker = worker

    def _done(self, key: str, dask_future: Any) -> None:
        with self._lock:
            run = self._runs.pop(key, None)
        if run is None:  # already timed out, or shut down
            return
        try:
            outcome = dask_future.result()
        except CancelledError:
            outcome = RunOutcome(key, crash=True, message="dask task was cancelled", started_at=utc_now())
        except Exception as exc:
            with self._lock:
                innocent = not run.worker or run.worker in self._restarted
            if type(exc).__name__ == "KilledWorker" and innocent and run.attempts < _MAX_ATTEMPTS:
                # its worker died under another run (or was restarted by us) before or while it ran: run it again
                run.attempts += 1
                run.started, run.deadline, run.worker = math.nan, math.inf, ""
                self._send(run)
                return
            outcome = RunOutcome(key, crash=True, started_at=utc_now(),
                                 message=f"dask task failed: {type(exc).__name__}: {exc}")
        run.future.set_result(outcome)

    def _watch(self) -> None:
        while not self._closing.wait(_TICK_S):
            now = time.perf_counter()
            with self._lock:
                expired = [key for key, run in self._runs.items() if now >= run.deadline]
                runs = [self._runs.pop(key) for key in expired]
            for run in runs:
                elapsed = now - run.started
                run.future.set_result(RunOutcome(
                    run.task.run_key, timed_out=True, wall_time_s=elapsed, started_at=utc_now(),
                    message=f"dask task abandoned after {elapsed:.3g} s",
                ))
                threading.Thread(target=self._restart_worker_of, args=(run.dask_future,), daemon=True).start()

    def _restart_worker_of(self, dask_future: Any) -> None:
        """Cancel the task and restart the worker running it, if the cluster allows (best effort)."""
        try:
            processing = self._client.processing()
            workers = [w for w, keys in processing.items() if dask_future.key in keys]
            dask_future.cancel()
            with self._lock:
                self._restarted.update(workers)
            if workers:
                self._client.restart_workers(workers, raise_for_error=False)
        except Exception:  # restarting is an optimisation; the run is already recorded
            pass
