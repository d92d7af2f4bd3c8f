"""The record of one run as the harness stores it, from the task, the worker's outcome and a verdict.

Kept apart from :mod:`pathzoo.harness.judge`, which needs the validator and the reference optima: the harness's
own process builds records of runs that could not be judged (:func:`unjudged`) without loading them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from pathzoo.core.results import RunRecord
from pathzoo.core.status import RunStatus
from pathzoo.metrics.outcome import RETURNED

if TYPE_CHECKING:
    from pathzoo.harness.specs import RunTask
    from pathzoo.harness.outcome import RunOutcome

__all__ = ["run_record", "unjudged"]


def run_record(task: "RunTask", outcome: "RunOutcome", status: RunStatus, valid: bool, reason: str, message: str,
               isolated: bool) -> RunRecord:
    """The :class:`RunRecord` of a run with the harness's verdict (no metrics yet); the run's values only where it returned."""
    returned = status in RETURNED
    return RunRecord(
        run_key=task.run_key,
        experiment=task.experiment,
        planner_id=task.planner.id,
        planner_version=task.planner_version,
        params=dict(task.planner.params),
        params_hash=task.params_hash,
        scenario_id=task.scenario.id,
        seed_index=task.seed_index,
        seed=task.seed,
        status=status,
        valid=valid,
        invalid_reason=reason,
        message=message,
        wall_time_s=float(outcome.wall_time_s),
        cpu_time_s=float(outcome.cpu_time_s),
        stopped_by=outcome.stopped_by if returned else "wall_time" if status is RunStatus.TIMEOUT else "none",
        iterations=outcome.iterations if returned else 0,
        evaluations=outcome.evaluations if returned else 0,
        path=outcome.path if returned else None,
        times=outcome.times if returned else None,
        history=outcome.history,
        metrics={},
        versions=dict(outcome.versions),
        started_at=outcome.started_at,
        isolated=isolated,
        sandboxed=outcome.sandboxed,
    )


def unjudged(task: "RunTask", outcome: "RunOutcome", reason: str, *, isolated: bool = True) -> RunRecord:
    """The record of a run that could not be judged: ``invalid`` with ``reason``, no metrics."""
    return run_record(task, outcome, RunStatus.INVALID, False, reason, outcome.message, isolated)
