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
- the hard limit counts from the *first* "started" event of the run, on the
  harness's clock;
- wall and CPU time are measured *inside* the worker process (with clock
  functions bound when pathzoo was imported, so patching ``time`` does not
  change them, but a planner that patches pathzoo itself could). Worker
  events reach the client with a delay of their own, so the harness cannot
  time ``plan()`` from outside as the process executor does: use that one
  when timings must be forgery-proof. CPU time is only meaningful with one
  thread per worker (the local cluster uses ``threads_per_worker=1``);
- the outcome comes back as bytes (:mod:`pathzoo.harness.wire`) and is decoded
  and bounded here, like the process executor's; Dask itself still unpickles
  what its workers send, so a cluster must only run trusted worker processes;
- a worker process in which a planner rebound module attributes
  (:mod:`pathzoo.harness.tamper`) refuses every later task and is restarted
  through its nanny; the refused tasks are submitted again;
- file scenarios are read by path on the workers, so the files must be
  visible to them at the same path; Python scenario objects travel in the task.
"""

from __future__ import annotations

import logging
import math
import os
import threading
import time
from concurrent.futures import CancelledError, Future
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from pathzoo.core.errors import PathzooError
from pathzoo.harness.executors.base import RunExecutor
from pathzoo.harness.tamper import ModuleFingerprint
from pathzoo.harness.wire import decode_outcome, encode_outcome
from pathzoo.harness.worker import SETUP_TIMEOUT_S, RunOutcome, ensure_plugins, execute_task, quiet_registry, utc_now

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = ["DaskExecutor"]

_STARTED_TOPIC = "pathzoo-run-started"
_TICK_S = 0.1
_MAX_ATTEMPTS = 3
_clock = time.perf_counter
_process_state: dict[str, Any] = {}


def _run_on_worker(task: "RunTask", check_tamper: bool) -> bytes:
    """The Dask task: run one task, report "started" and "planning" as worker events, return the encoded outcome.

    The first byte says whether the process is still clean (``D``), was
    tainted by this run (``T``) or had been tainted before, so the task was
    refused (``X``). Worker threads of the harness process (``check_tamper``
    false) share it with the harness, so there is nothing to check.
    """
    from distributed import get_worker

    worker = get_worker()
    if not check_tamper:
        return b"D" + encode_outcome(execute_task(
            task, lambda event: worker.log_event(_STARTED_TOPIC, [task.run_key, event, worker.address])))
    if _process_state.get("tainted"):
        return b"X" + worker.address.encode()
    quiet_registry()  # discovered before the baseline: the registry is not the planner's change
    ensure_plugins(task.plugin_modules)
    fingerprint = _process_state.get("fingerprint") or ModuleFingerprint().update()
    outcome = execute_task(task, lambda event: worker.log_event(_STARTED_TOPIC, [task.run_key, event, worker.address]))
    changed = fingerprint.changed()
    tainted = bool(changed)
    if tainted:
        logging.getLogger("pathzoo.harness").warning("worker %s tainted by run %s: %s", worker.address, task.run_key,
                                                     ", ".join(changed))
    _process_state.update(tainted=tainted, fingerprint=None if tainted else fingerprint.update())
    return (b"T" if tainted else b"D") + encode_outcome(outcome)


_RESENT_START_S = 120.0


def _start_limit(run: "_Run") -> float:
    """How long a run may wait for its start: the setup limit, or less for a run sent again after a worker restart
    (such tasks are sometimes lost by the scheduler, which would otherwise hang the experiment)."""
    return SETUP_TIMEOUT_S if run.attempts == 1 else _RESENT_START_S


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

    isolated = True

    def __init__(self, jobs: int | None = None, *, address: str | None = None, processes: bool = True) -> None:
        try:
            import dask
            from distributed import Client, LocalCluster
        except ImportError:
            raise PathzooError("the 'dask' executor needs dask.distributed: pip install 'pathzoo[dask]'") from None
        self._cluster = None
        if address:
            try:
                self._client = Client(address, timeout="20s")
            except (OSError, ValueError, TypeError) as exc:  # TimeoutError is an OSError
                raise PathzooError(f"cannot connect to the Dask scheduler at {address!r}: "
                                   f"{' '.join(str(exc).split()) or type(exc).__name__}") from None
        else:
            # a run that kills its worker is a crash, not a task to retry elsewhere
            with dask.config.set({"distributed.scheduler.allowed-failures": 0}):
                self._cluster = LocalCluster(
                    n_workers=int(jobs or os.cpu_count() or 1), threads_per_worker=1, processes=processes,
                    dashboard_address=None,
                )
            self._client = Client(self._cluster)
        self.capacity = max(1, sum(self._client.nthreads().values()))
        self.isolated = bool(address) or processes  # worker threads in this process are not isolated
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
        self._send(_Run(task, future, None, _clock()))
        return future

    def _send(self, run: _Run) -> None:
        run.submitted = _clock()
        run.dask_future = self._client.submit(_run_on_worker, run.task, self.isolated, pure=False)
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
        try:
            key, what, worker = event[1]  # (timestamp, [run_key, "started" or "planning", worker address])
        except (TypeError, ValueError):
            return
        with self._lock:
            run = self._runs.get(key)
            if run is None:
                return
            if what == "started" and math.isnan(run.started):
                run.started = _clock()
                run.deadline = run.started + run.task.timeout_s
                run.worker = worker


    def _done(self, key: str, dask_future: Any) -> None:
        with self._lock:
            run = self._runs.get(key)
            if run is None or run.dask_future is not dask_future:  # timed out, shut down, or sent again since
                return
            del self._runs[key]
        try:
            self._resolve(run, key, dask_future)
        except BaseException as exc:  # noqa: BLE001 - a callback that raises would leave the run pending forever
            if not run.future.done():
                run.future.set_result(RunOutcome(key, crash=True, started_at=utc_now(),
                                                 message=f"dask result could not be handled: {exc!r}"))

    def _resolve(self, run: _Run, key: str, dask_future: Any) -> None:
        try:
            data = dask_future.result()
            if not isinstance(data, bytes) or data[:1] not in (b"D", b"T", b"X"):
                raise TypeError(f"the worker returned {type(data).__name__}, not an encoded outcome")
            if data[:1] == b"X" and run.attempts < _MAX_ATTEMPTS:  # a tainted worker refused it: try again
                self._restart(data[1:].decode("utf-8", "replace"))
                run.attempts += 1
                run.started, run.deadline, run.worker = math.nan, math.inf, ""
                self._send(run)
                return
            if data[:1] == b"T":
                self._restart(run.worker)
            outcome = decode_outcome(data[1:], key) if data[:1] != b"X" else RunOutcome(
                key, crash=True, message="refused by tainted workers on every attempt")
            outcome = replace(outcome, started_at=outcome.started_at or utc_now())
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
            now = _clock()
            with self._lock:
                expired = [key for key, run in self._runs.items() if now >= run.deadline]
                runs = [self._runs.pop(key) for key in expired]
                lost = [key for key, run in self._runs.items()
                        if math.isnan(run.started) and now - run.submitted > _start_limit(run)]
                unstarted = [self._runs.pop(key) for key in lost]
            for run in unstarted:  # never reported a start: a lost task must not hang the experiment
                run.future.set_result(RunOutcome(
                    run.task.run_key, crash=True, started_at=utc_now(),
                    message=f"the cluster did not start the run within {_start_limit(run):g} s"))
            for run in runs:
                elapsed = now - run.started
                run.future.set_result(RunOutcome(
                    run.task.run_key, timed_out=True, wall_time_s=elapsed, started_at=utc_now(),
                    message=f"dask task abandoned after {elapsed:.3g} s",
                ))
                threading.Thread(target=self._restart_worker_of, args=(run.dask_future,), daemon=True).start()

    def _restart(self, worker: str) -> None:
        """Restart one worker through its nanny, in the background (best effort)."""
        if not worker:
            return
        with self._lock:
            self._restarted.add(worker)

        def restart() -> None:
            before = _clock()
            try:
                self._client.restart_workers([worker], raise_for_error=False)
            except Exception:  # noqa: BLE001 - a worker that cannot restart keeps refusing runs
                pass
            self._resend_unstarted(before)
        threading.Thread(target=restart, daemon=True).start()

    def _resend_unstarted(self, before: float) -> None:
        """Send again the runs submitted before a worker restart that have not started.

        The scheduler sometimes loses tasks that were queued on a restarted
        worker; waiting for them would hang the experiment. A copy that does
        start after all is ignored when it finishes (only the current Dask
        future of a run counts).
        """
        with self._lock:
            stale = [r for r in self._runs.values()
                     if math.isnan(r.started) and r.submitted <= before and r.attempts < _MAX_ATTEMPTS]
        for run in stale:
            old = run.dask_future
            run.attempts += 1
            self._send(run)
            old.cancel()

    def _restart_worker_of(self, dask_future: Any) -> None:
        """Cancel the task and restart the worker running it, if the cluster allows (best effort)."""
        try:
            processing = self._client.processing()
            workers = [w for w, keys in processing.items() if dask_future.key in keys]
            dask_future.cancel()
            with self._lock:
                self._restarted.update(workers)
            if workers:
                before = _clock()
                self._client.restart_workers(workers, raise_for_error=False)
                self._resend_unstarted(before)
        except Exception:  # restarting is an optimisation; the run is already recorded
            pass
