"""What one run gave back before the harness judges it: :class:`RunOutcome`, and the planner's values made safe for it.

The helpers here turn whatever a planner returned or raised into an
outcome's fields without running more of its code than needed: a path as a
float array, a message as bounded text (a ``__str__`` that fails or exits
gives a note instead), an exception as its type, message and the last lines
of its traceback.
"""

from __future__ import annotations

import math
import traceback
from dataclasses import dataclass, field
from datetime import datetime, timezone
from typing import Any

import numpy as np

from pathzoo.core.errors import ExternalPlannerError
from pathzoo.core.results import HistoryPoint
from pathzoo.core.status import Status
from pathzoo.harness.bounds import bound_text

__all__ = ["RunOutcome", "TRACEBACK_LINES", "utc_now", "describe_exception", "as_array", "message_text"]

TRACEBACK_LINES = 12
"""Lines of traceback kept in a crash message."""


@dataclass(frozen=True)
class RunOutcome:
    """What happened in one run, before the harness judges it.

    Attributes
    ----------
    run_key : str
        The task's key.
    status : Status, optional
        The planner's own status; ``None`` when it did not return a PlanResult.
    path, times : ndarray, optional
        Copies of what the planner returned, as float64 when convertible.
    path_error : str
        Why the path could not be converted to a float array ("" if it could).
    iterations, evaluations : int
        The planner's counts.
    message : str
        The planner's message, or the crash description.
    wall_time_s, cpu_time_s : float
        Wall and CPU time of building the planner and its ``plan()`` call.
    stopped_by : str
        The limit that ended the run (:data:`pathzoo.core.budget.STOP_REASONS`);
        the process executor decides the clock stops itself.
    sandboxed : bool
        The planner ran in an OS sandbox (:mod:`pathzoo.harness.sandbox`); set
        by the executor that supervised it, never by the planner's process.
    history : tuple of HistoryPoint
        Progress reports, timed by the harness (see :class:`HistoryRecorder`).
    crash : bool
        ``plan()`` raised, returned something else than a PlanResult, the setup
        failed or the worker process died.
    timed_out : bool
        The executor stopped the run at its hard limit.
    scenario_modified : bool
        The planner rebound, replaced or changed part of the scenario
        (:meth:`~pathzoo.harness.sealed.ScenarioSeal.intact`).
    versions : dict
        Versions of pathzoo, Python, numpy, the planner's distribution and the
        libraries loaded in the worker, with the CPU, core count and the run's
        peak RSS in MiB (:mod:`pathzoo.harness.provenance`).
    started_at : str
        UTC ISO time the run started.
    tainted : bool
        The planner rebound module attributes in its process
        (:mod:`pathzoo.harness.tamper`); the executor must not reuse that process.
    bounds_error : str
        Why a planner-chosen value is out of bounds (:mod:`pathzoo.harness.bounds`);
        the run is judged ``invalid`` with this reason.
    """

    run_key: str
    status: Status | None = None
    path: np.ndarray | None = None
    times: np.ndarray | None = None
    path_error: str = ""
    iterations: int = 0
    evaluations: int = 0
    message: str = ""
    wall_time_s: float = math.nan
    cpu_time_s: float = math.nan
    stopped_by: str = "none"
    sandboxed: bool = False
    history: tuple[HistoryPoint, ...] = ()
    crash: bool = False
    timed_out: bool = False
    scenario_modified: bool = False
    versions: dict[str, str] = field(default_factory=dict)
    started_at: str = ""
    tainted: bool = False
    bounds_error: str = ""


def utc_now() -> str:
    """The current UTC time in ISO format, to the millisecond."""
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def describe_exception(exc: BaseException) -> str:
    """``"Type: message"`` plus the last lines of the traceback.

    An :class:`~pathzoo.core.errors.ExternalPlannerError` is its own
    report (one line naming the planner and the cause, then the program's
    standard error): the bridge's traceback would add nothing.
    """
    if isinstance(exc, ExternalPlannerError):
        return str(exc)
    head = f"{type(exc).__name__}: {exc}".splitlines()[0] if str(exc) else type(exc).__name__
    tail = traceback.format_exception(type(exc), exc, exc.__traceback__)
    lines = "".join(tail).rstrip().splitlines()[-TRACEBACK_LINES:]
    return head + "\n" + "\n".join(lines)


def as_array(value: Any) -> tuple[np.ndarray | None, str]:
    """``value`` as a float64 array and ``""``; ``None`` and why not when it is not numeric (``None`` for ``None``)."""
    if value is None:
        return None, ""
    try:
        return np.array(value, dtype=np.float64), ""
    except Exception as exc:  # noqa: BLE001 - any object a planner returns
        return None, f"not a numeric array ({type(exc).__name__}: {exc})"


def message_text(value: Any) -> str:
    """The planner's message as text; a ``__str__`` that fails or exits gives a note instead."""
    try:
        return bound_text(str(value))
    except BaseException as exc:  # noqa: BLE001 - SystemExit from a hostile __str__ included
        return f"(message could not be converted to text: {type(exc).__name__})"
