"""Limits on every value a planner chooses, applied before anything reaches the judge or the store.

A planner controls its ``PlanResult`` (status, path, times, counts, message)
and its progress reports, and, from inside its worker process, everything
that process sends back. :func:`bound_outcome` turns whatever came back into
an outcome the parent can judge and store without overflowing, running out
of memory or failing on bad text:

- ``iterations``/``evaluations`` must be integers in ``[0, MAX_COUNT]``;
  otherwise the run is judged ``invalid`` with the reason (``bounds_error``);
- a path of more than :data:`MAX_PATH_POINTS` points, or not of shape
  ``(N, 2)``/``(N, 3)``, and times that are not one value per point, are not
  kept: the path error says why, and a ``SOLVED`` claim becomes ``invalid``;
- the message is cut to :data:`MAX_MESSAGE_CHARS` characters and made valid
  UTF-8 (a lone surrogate would make SQLite fail);
- the history keeps at most :data:`MAX_HISTORY_POINTS` points (the first
  ones and the last), counts clipped to ``[0, MAX_COUNT]``, times and costs
  as floats;
- timings that are not finite and non-negative become NaN;
- the versions mapping keeps at most 16 short string entries.

``PlanResult.extras`` never leaves the worker, so it needs no limit.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from pathzoo.core.budget import STOP_REASONS
from pathzoo.core.results import HistoryPoint
from pathzoo.core.status import Status

if TYPE_CHECKING:
    from pathzoo.harness.outcome import RunOutcome

__all__ = [
    "MAX_COUNT",
    "MAX_PATH_POINTS",
    "MAX_MESSAGE_CHARS",
    "MAX_HISTORY_POINTS",
    "bound_outcome",
    "bound_text",
    "bound_time",
]

MAX_COUNT = 2**62
"""Largest iteration or evaluation count accepted (fits SQLite's 64-bit integers)."""

MAX_PATH_POINTS = 1_000_000
"""Largest path (points) the harness judges and stores."""

MAX_MESSAGE_CHARS = 4_000
"""Longest planner message kept (crash descriptions included)."""

MAX_HISTORY_POINTS = 100_000
"""Most progress points kept per run."""

_MAX_VERSIONS = 16
_MAX_VERSION_CHARS = 100


def bound_text(value: Any, limit: int = MAX_MESSAGE_CHARS) -> str:
    """``value`` as valid UTF-8 text of at most ``limit`` characters (never raises)."""
    try:
        text = value if type(value) is str else ""
    except BaseException:  # noqa: BLE001 - a hostile __class__ property
        text = ""
    text = text.encode("utf-8", "replace").decode("utf-8", "replace")
    if len(text) > limit:
        text = text[:limit] + f" ... [{len(text) - limit} more characters cut]"
    return text


def bound_time(value: Any) -> float:
    """A finite, non-negative duration in seconds, else NaN."""
    try:
        seconds = float(value)
    except (TypeError, ValueError, OverflowError):
        return math.nan
    return seconds if math.isfinite(seconds) and seconds >= 0 else math.nan


def _count(value: Any, name: str) -> tuple[int, str]:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        return 0, f"{name} is not an integer ({type(value).__name__})"
    number = int(value)
    if not 0 <= number <= MAX_COUNT:
        return 0, f"{name} = {number:.6g} is outside [0, 2**62]"
    return number, ""


def _path(path: Any, times: Any) -> tuple[np.ndarray | None, np.ndarray | None, str]:
    if path is None:
        return None, None, ""
    if not isinstance(path, np.ndarray) or path.dtype != np.float64:
        return None, None, "path is not a float64 array"
    if path.ndim != 2 or path.shape[1] not in (2, 3):
        return None, None, f"path has shape {path.shape}, not (N, 2) or (N, 3)"
    if path.shape[0] > MAX_PATH_POINTS:
        return None, None, f"path has {path.shape[0]} points, more than the limit of {MAX_PATH_POINTS}"
    if times is None:
        return path, None, ""
    if not isinstance(times, np.ndarray) or times.dtype != np.float64 or times.shape != (path.shape[0],):
        return None, None, "times are not one float64 value per path point"
    return path, times, ""


def _history(points: Any) -> tuple[HistoryPoint, ...]:
    if not isinstance(points, tuple):
        return ()
    if len(points) > MAX_HISTORY_POINTS:
        points = (*points[: MAX_HISTORY_POINTS - 1], points[-1])
    out = []
    for p in points:
        if not isinstance(p, HistoryPoint):
            continue
        iteration = min(max(int(p.iteration), 0), MAX_COUNT) if isinstance(p.iteration, int) else 0
        evaluations = min(max(int(p.evaluations), 0), MAX_COUNT) if isinstance(p.evaluations, int) else 0
        out.append(HistoryPoint(iteration, evaluations, float(p.best_cost), bound_time(p.time_s)))
    return tuple(out)


def bound_outcome(outcome: "RunOutcome") -> "RunOutcome":
    """The outcome with every planner-chosen value within the limits of the module docstring."""
    status = outcome.status if isinstance(outcome.status, Status) else None
    iterations, bad_iterations = _count(outcome.iterations, "iterations")
    evaluations, bad_evaluations = _count(outcome.evaluations, "evaluations")
    path, times, path_error = _path(outcome.path, outcome.times)
    versions = outcome.versions if isinstance(outcome.versions, dict) else {}
    versions = {
        bound_text(k, _MAX_VERSION_CHARS): bound_text(v, _MAX_VERSION_CHARS)
        for k, v in list(versions.items())[:_MAX_VERSIONS]
    }
    return replace(
        outcome,
        status=status,
        path=path,
        times=times,
        path_error=bound_text(outcome.path_error) or path_error,
        iterations=iterations,
        evaluations=evaluations,
        message=bound_text(outcome.message),
        wall_time_s=bound_time(outcome.wall_time_s),
        cpu_time_s=bound_time(outcome.cpu_time_s),
        stopped_by=outcome.stopped_by if outcome.stopped_by in STOP_REASONS else "none",
        history=_history(outcome.history),
        versions=versions,
        bounds_error=bound_text(outcome.bounds_error) or bad_iterations or bad_evaluations,
    )
