"""The harness's verdict on one run: final status, validity and every metric.

Rules, applied in order:

1. the run hit its hard limit (killed by the executor, or measured over it) -> ``timeout``;
2. ``plan()`` raised, returned something else than a PlanResult, the run
   could not be set up, or the worker process died -> ``crash``;
3. the planner modified or replaced any part of the scenario, or a value it
   chose is out of bounds (:mod:`pathzoo.harness.bounds`) -> ``invalid``;
4. the planner says ``SOLVED``: the path must pass
   :func:`~pathzoo.rules.validate_path` -> ``solved``, else ``invalid``
   with the validator's reason;
5. the planner says ``NO_PATH``: if the reference path of
   :func:`~pathzoo.grid.reference.reference_path` exists *and* passes the
   validator, the claim is false -> ``invalid`` ("claimed no path but one
   exists"); otherwise ``no_path``;
6. the planner says ``FAILED`` -> ``failed``.

A run that cannot be judged (judging over its time limit, or raising) is
stored by :func:`~pathzoo.harness.run_record.unjudged` as ``invalid`` with the reason
(:mod:`pathzoo.harness.judge_worker`).

Then every metric is computed from the stored path and the scenario; a metric
that raises gives NaN and a warning, never a lost run.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace
from typing import TYPE_CHECKING, Sequence

from pathzoo.core.results import RunRecord
from pathzoo.core.status import RunStatus, Status
from pathzoo.grid.reference import reference_path
from pathzoo.rules import validate_path
from pathzoo.harness.run_record import run_record

if TYPE_CHECKING:
    from pathzoo.core.metric import Metric
    from pathzoo.core.scenario import Scenario
    from pathzoo.harness.specs import RunTask
    from pathzoo.harness.outcome import RunOutcome

__all__ = ["judge", "verdict"]


def verdict(task: "RunTask", outcome: "RunOutcome", scenario: "Scenario") -> tuple[RunStatus, bool, str, str]:
    """``(status, valid, invalid_reason, message)`` of a run; see the module docstring."""
    if outcome.timed_out or outcome.wall_time_s > task.timeout_s:
        note = f"stopped at the hard limit of {task.timeout_s:g} s"
        return RunStatus.TIMEOUT, False, "", note if not outcome.message else f"{note}; {outcome.message}"
    if outcome.crash:
        return RunStatus.CRASH, False, "", outcome.message
    if outcome.scenario_modified:
        return RunStatus.INVALID, False, "planner modified or replaced part of the scenario", outcome.message
    if outcome.bounds_error:
        return RunStatus.INVALID, False, f"out of bounds: {outcome.bounds_error}", outcome.message
    if outcome.status is Status.SOLVED:
        if outcome.path is None:
            reason = f"claimed solved but the path is {outcome.path_error or 'missing'}"
            return RunStatus.INVALID, False, reason, outcome.message
        if outcome.path_error:
            return RunStatus.INVALID, False, f"claimed solved but the {outcome.path_error}", outcome.message
        check = validate_path(scenario, outcome.path, outcome.times)
        if check:
            return RunStatus.SOLVED, True, "", outcome.message
        return RunStatus.INVALID, False, check.reason, outcome.message
    if outcome.status is Status.NO_PATH:
        ref = reference_path(scenario)
        if ref is not None and validate_path(scenario, ref.path):
            reason = f"claimed no path but one exists (the reference path of {ref.length:.6g} m is valid)"
            return RunStatus.INVALID, False, reason, outcome.message
        return RunStatus.NO_PATH, False, "", outcome.message
    return RunStatus.FAILED, False, "", outcome.message


def judge(task: "RunTask", outcome: "RunOutcome", scenario: "Scenario", metrics: Sequence["Metric"], *,
          isolated: bool = True) -> RunRecord:
    """Build the :class:`RunRecord` of a run: verdict, then every metric.

    Parameters
    ----------
    task : RunTask
        What was run.
    outcome : RunOutcome
        What came back from the worker (or the executor, for kills), bounded.
    scenario : Scenario
        The judge's own copy of the scenario.
    metrics : sequence of Metric
        Every metric to compute.
    isolated : bool
        Whether the planner ran in a process of its own (stored with the run).
    """
    status, valid, reason, message = verdict(task, outcome, scenario)
    record = run_record(task, outcome, status, valid, reason, message, isolated)
    values: dict[str, float] = {}
    for metric in metrics:
        try:
            values[metric.id] = float(metric.compute(scenario, record))
        except Exception as exc:  # a broken metric plugin must not lose the run
            warnings.warn(f"metric '{metric.id}' failed on run {task.run_key}: {type(exc).__name__}: {exc}",
                          RuntimeWarning, stacklevel=2)
            values[metric.id] = math.nan
    return replace(record, metrics=values)
