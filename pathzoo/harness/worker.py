"""The worker side of a run: rebuild planner and scenario, run ``plan()``, report what came back.

:func:`execute_task` runs in whatever process the executor chose. It never
raises (``SystemExit`` and every other ``BaseException`` from the planner,
its warm-up or its message's ``__str__`` included): anything that goes wrong
gives an outcome with ``crash`` set. It does not judge the result either;
the harness does (:mod:`pathzoo.harness.judge`), in a judge process where no
planner code ever ran, on a scenario that process loaded itself.

Scenarios are loaded once per process, sealed, and checked after each run
(:mod:`pathzoo.harness.scenario_cache`); each configuration is warmed up
once per scenario before its first measured run
(:mod:`pathzoo.harness.worker_warmup`); what a run gives back is a
:class:`~pathzoo.harness.outcome.RunOutcome`.
Monkeypatching is caught by :mod:`pathzoo.harness.tamper` and makes the
executor replace the worker.

The planning clocks start just before the planner is built (its
constructor is planning work) and end when ``plan()`` returns, before the
scenario's check and any other harness work (``docs/timing.md``). The times
measured here (``time.perf_counter`` and ``time.process_time`` inside the
planner's process) are only a fallback: the process and Dask executors time
runs with their own clocks, outside this process. A budget with a clock
limit gets a clock stop (:mod:`pathzoo.harness.clock_stop`): the executor's
shared one, or one read in this process.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from pathzoo.core.budget import ClockStop
from pathzoo.core.results import PlanResult
from pathzoo.core.status import Status
from pathzoo.harness.bounds import bound_outcome
from pathzoo.harness.clock_stop import InProcessClockStop
from pathzoo.harness.history import HistoryRecorder
from pathzoo.harness.outcome import RunOutcome, as_array, describe_exception, message_text, utc_now
from pathzoo.harness.plugin_loading import ensure_plugins
from pathzoo.harness.provenance import provenance, reset_peak_rss, versions_of
from pathzoo.harness.scenario_cache import evict, load_cached
from pathzoo.harness.worker_warmup import warm_up_for

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask

__all__ = ["execute_task", "stopped_by_of", "Report", "SETUP_TIMEOUT_S"]

SETUP_TIMEOUT_S = 900.0
"""Limit on a run's setup in a worker (plugins, planner, scenario, shared geometry), before ``plan()``."""

_clock = time.perf_counter  # bound at import, so a planner that patches the time module changes no timing
_cpu = time.process_time


Report = Callable[[str], None]
"""Callback through which :func:`execute_task` announces ``"started"`` (setup done), ``"planning"`` and ``"planned"``."""


def execute_task(task: "RunTask", report: Report | None = None, *, interruptible: bool = False,
                 stop: ClockStop | None = None) -> RunOutcome:
    """Run one task in this process and report what happened; never raises.

    Parameters
    ----------
    task : RunTask
        The run.
    report : callable, optional
        Called with ``"started"`` once the planner and scenario are ready (the
        hard limit starts there, before the warm-up), with ``"planning"`` just
        before the measured planner is built (the planning clocks start
        there) and with ``"planned"`` as soon as ``plan()`` returns (they end
        there). It may block until the executor has read its clocks.
    interruptible : bool
        Let ``KeyboardInterrupt`` through (the inline executor, where Ctrl-C is
        the user's); otherwise it is a crash like any other exception.
    stop : ClockStop, optional
        The executor's clock stop for a budget with a clock limit (default:
        an :class:`~pathzoo.harness.clock_stop.InProcessClockStop`).
    """
    try:
        return bound_outcome(_execute(task, report or (lambda event: None), stop))
    except KeyboardInterrupt:
        if interruptible:
            raise
        return RunOutcome(task.run_key, crash=True, message="KeyboardInterrupt raised in the run")
    except BaseException as exc:  # noqa: BLE001 - whatever a planner raises, the run is an outcome
        return RunOutcome(task.run_key, crash=True, message=message_text(describe_exception(exc)))


def stopped_by_of(task: "RunTask", stop: ClockStop | None, result: Any) -> str:
    """The clock stop reported to the planner, else the count limit its result reached, else ``"none"``."""
    clock = None if stop is None else stop.reason()
    if clock is not None:
        return clock
    if isinstance(result, PlanResult):
        try:
            return task.budget.count_reached(int(result.iterations), int(result.evaluations)) or "none"
        except BaseException:  # noqa: BLE001 - counts of any type; bound_outcome reports them
            return "none"
    return "none"


def _execute(task: "RunTask", report: Report, stop: ClockStop | None) -> RunOutcome:
    started_at = utc_now()
    try:
        ensure_plugins(task.plugin_modules)
        planner = task.build_planner()  # for the version check and the warm-up; the measured run builds its own
        if planner.version != task.planner_version:
            raise RuntimeError(
                f"{task.planner.id} is version {planner.version} in this worker, {task.planner_version} in the harness"
            )
        scenario, sealed = load_cached(task.scenario)
        versions = versions_of(task)
    except Exception as exc:
        return RunOutcome(task.run_key, message="run setup failed: " + describe_exception(exc), crash=True,
                          started_at=started_at)
    rng = np.random.default_rng(task.seed)
    recorder = HistoryRecorder()
    report("started")
    crash: BaseException | None = None
    result: Any = None
    t0 = c0 = math.nan
    budget = task.budget
    try:
        # inside the hard limit (a hanging planner still times out), outside planning time
        warm_up_for(task, planner)
        reset_peak_rss()
        report("planning")
        recorder.t0 = t0 = _clock()
        c0 = _cpu()
        if budget.timed:
            stop = stop if stop is not None else InProcessClockStop(budget)
            budget = replace(budget, stop=stop)
        planner = task.build_planner()  # measured and limited: work done in a constructor is planning work
        result = planner.plan(scenario, budget=budget, rng=rng, progress=recorder)
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # noqa: BLE001 - SystemExit included
        crash = exc
    wall = _clock() - t0  # NaN when plan() never started
    cpu = _cpu() - c0
    if not math.isnan(t0):
        report("planned")
    stopped_by = stopped_by_of(task, budget.stop, result)
    versions = provenance(versions)
    modified = not sealed.intact()
    if modified:
        evict(task.scenario)
    common: dict[str, Any] = dict(
        wall_time_s=wall, cpu_time_s=cpu, stopped_by=stopped_by, history=recorder.history(), scenario_modified=modified,
        versions=versions, started_at=started_at,
    )
    if crash is not None:
        return RunOutcome(task.run_key, message=message_text(describe_exception(crash)), crash=True, **common)
    if not isinstance(result, PlanResult) or not isinstance(result.status, Status):
        what = type(result).__name__ if not isinstance(result, PlanResult) else f"status {type(result.status)}"
        return RunOutcome(task.run_key, message=f"plan() returned {what}, not a PlanResult with a Status", crash=True,
                          **common)
    path, path_error = as_array(result.path)
    times, times_error = as_array(result.times)
    return RunOutcome(
        task.run_key,
        status=result.status,
        path=path,
        times=times,
        path_error=path_error or (f"times {times_error}" if times_error else ""),
        iterations=result.iterations,
        evaluations=result.evaluations,
        message=message_text(result.message),
        **common,
    )
