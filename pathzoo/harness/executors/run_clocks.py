"""Clock enforcement of the process executor: the harness's own times of a run, and its clock stops.

Wall time is the harness's ``time.perf_counter`` from a run's ``P`` to its
``D`` frame; CPU time is what the worker's process tree and cgroup are
charged (:class:`~pathzoo.harness.cpu_clock.ChargedCpu`). While a run with a
clock limit plans, the monitor reads these clocks (:func:`watch_clocks`) and
sets the worker's shared stop byte when a limit is spent; the run is stored
with the stop the harness set (``docs/timing.md``).
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import replace
from typing import TYPE_CHECKING, Iterable

from pathzoo.harness.outcome import RunOutcome

if TYPE_CHECKING:
    from pathzoo.harness.executors.worker_handle import Worker

__all__ = ["CLOCK_POLL_S", "cpu_since", "timed", "planning", "watch_clocks"]

_clock = time.perf_counter  # bound at import: a later patch of time.perf_counter does not reach the harness

CLOCK_POLL_S = 0.01
"""How often, at most, the monitor reads the CPU time of a run with a ``cpu_s`` limit while it plans.

Far from the limit it reads it less often: a process tree cannot use more
than one CPU second per core in a wall second, so the next reading is due
when the CPU seconds left, spread over every core, could be spent."""

_CORES = os.cpu_count() or 1


def cpu_since(worker: Worker) -> float:
    """CPU seconds charged to the current run (NaN before the worker's warm-up ended)."""
    return worker.cpu.spent() if worker.warm else math.nan


def timed(worker: Worker, outcome: RunOutcome, child_cpu: float) -> RunOutcome:
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
    cpu = worker.cpu.lap(reaped=child_cpu)  # what the worker spends until its next run's end is charged to that
    # run; its child is reaped by now, and a new one is listed within DESCENDANTS_REFRESH_S (the cgroup counts it)
    stopped_by = worker.stopped_by or worker.task.budget.count_reached(outcome.iterations, outcome.evaluations)
    return replace(outcome, wall_time_s=worker.plan_t1 - worker.plan_t0, cpu_time_s=cpu,
                   stopped_by=stopped_by or "none", started_at=worker.started_at)


def planning(worker: Worker) -> bool:
    """True while the worker's run plans under a clock limit that the harness has not stopped yet."""
    return (worker.task is not None and worker.task.budget.timed and worker.stopped_by is None
            and not math.isnan(worker.plan_t0) and math.isnan(worker.plan_t1))


def watch_clocks(workers: "Iterable[Worker]", now: float) -> float:
    """Set the stop of each planning run whose clock limit is spent; return when to look again."""
    nearest = math.inf
    for worker in workers:
        if not planning(worker):
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
