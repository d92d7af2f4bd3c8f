"""Reading an external planner's answer: one JSON object, checked field by field, never trusted.

Every check failure raises :class:`~pathzoo.core.errors.ExternalPlannerError`
with one line naming the planner, the field and what was wrong, so the run
is stored as a crash with that reason. Values that are well formed but
wrong (a path through a wall, coordinates given as ``null``) pass here and
are judged by the harness like any planner's.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pathzoo.core.errors import ExternalPlannerError
from pathzoo.core.results import PlanResult
from pathzoo.core.status import Status

__all__ = ["Answer", "decode_answer", "read_answer", "ANSWER_KEYS", "MAX_COUNT"]

ANSWER_KEYS = ("status", "path", "times", "iterations", "evaluations", "history", "message")
"""The fields of an answer; only ``status`` is required."""

MAX_COUNT = 2**62
"""Largest iteration or evaluation count accepted."""

_SNIPPET = 60


@dataclass(frozen=True)
class Answer:
    """A checked answer: the planner's result and its progress points ``(iteration, evaluations, best_cost)``."""

    result: PlanResult
    history: tuple[tuple[int, int, float], ...] = ()


def decode_answer(data: bytes, who: str) -> Any:
    """The JSON value of ``data`` (a program's standard output), or a one-line protocol error.

    Raises
    ------
    ExternalPlannerError
        ``data`` is empty, not UTF-8, or not exactly one JSON value.
    """
    text = data.decode("utf-8", "replace").strip()
    if not text:
        raise ExternalPlannerError(f"{who}: wrote nothing on standard output (the answer must be one JSON object)")
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        snippet = json.dumps(text[:_SNIPPET])
        raise ExternalPlannerError(
            f"{who}: standard output is not one JSON object ({exc.msg} at line {exc.lineno} column {exc.colno}); "
            f"it begins {snippet}{'...' if len(text) > _SNIPPET else ''}") from None


def _count(value: Any, name: str, who: str) -> int:
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= MAX_COUNT:
        raise ExternalPlannerError(f"{who}: '{name}' must be an integer in [0, 2**62], got {_show(value)}")
    return value


def _show(value: Any) -> str:
    text = json.dumps(value) if isinstance(value, (int, float, str, bool, type(None))) else type(value).__name__
    return text if len(text) <= _SNIPPET else text[:_SNIPPET] + "..."


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _path(value: Any, dim: int, who: str) -> np.ndarray:
    """The path as an ``(N, dim)`` float array; ``null`` coordinates become NaN (the judge rejects them)."""
    axes = "x, y" if dim == 2 else "x, y, z"
    if not isinstance(value, list):
        raise ExternalPlannerError(f"{who}: 'path' must be a list of points [{axes}], got {_show(value)}")
    if value and all(_number(v) for v in value):
        raise ExternalPlannerError(f"{who}: 'path' must be a list of points [{axes}], got a flat list of "
                                   f"{len(value)} numbers")
    for i, point in enumerate(value):
        if not isinstance(point, list) or len(point) != dim:
            size = f"{len(point)} numbers" if isinstance(point, list) else _show(point)
            hint = " (a matrix of one row per coordinate? give one row per point)" if (
                isinstance(point, list) and len(value) == dim and len(point) != dim) else ""
            raise ExternalPlannerError(
                f"{who}: 'path' point {i} must be [{axes}] ({dim} numbers), got {size}; the path has "
                f"{len(value)} rows{hint}")
        if not all(_number(c) or c is None for c in point):
            raise ExternalPlannerError(f"{who}: 'path' point {i} has a coordinate that is not a number")
    return np.array([[math.nan if c is None else float(c) for c in p] for p in value],
                    dtype=np.float64).reshape(len(value), dim)


def _times(value: Any, n: int, who: str) -> np.ndarray:
    if not isinstance(value, list) or len(value) != n or not all(_number(t) or t is None for t in value):
        raise ExternalPlannerError(f"{who}: 'times' must be a list of {n} numbers (one per path point), "
                                   f"got {_show(value) if not isinstance(value, list) else f'{len(value)} values'}")
    return np.array([math.nan if t is None else float(t) for t in value], dtype=np.float64)


def _history(value: Any, who: str) -> tuple[tuple[int, int, float], ...]:
    if not isinstance(value, list):
        raise ExternalPlannerError(f"{who}: 'history' must be a list of [iteration, evaluations, best_cost]")
    out = []
    for i, point in enumerate(value):
        if not isinstance(point, list) or len(point) != 3:
            raise ExternalPlannerError(f"{who}: 'history' point {i} must be [iteration, evaluations, best_cost], "
                                       f"got {_show(point) if not isinstance(point, list) else f'{len(point)} values'}")
        cost = point[2]
        if not (_number(cost) or cost is None):
            raise ExternalPlannerError(f"{who}: 'history' point {i}: best_cost must be a number or null")
        out.append((_count(point[0], f"history[{i}] iteration", who), _count(point[1], f"history[{i}] evaluations", who),
                    math.inf if cost is None else float(cost)))
    return tuple(out)


def read_answer(data: Any, *, dim: int, who: str) -> Answer:
    """Check a decoded answer and turn it into a :class:`PlanResult` and progress points.

    Parameters
    ----------
    data : object
        The decoded JSON value.
    dim : int
        Coordinates per path point (2, or 3 in air volumes).
    who : str
        The planner's id, for messages.

    Raises
    ------
    ExternalPlannerError
        The answer is not an object, has unknown fields, lacks ``status``,
        or a field has the wrong type or shape.
    """
    if not isinstance(data, dict):
        raise ExternalPlannerError(f"{who}: the answer must be a JSON object, got {_show(data)}")
    unknown = sorted(set(data) - set(ANSWER_KEYS))
    if unknown:
        raise ExternalPlannerError(f"{who}: unknown field(s) {unknown} in the answer; allowed: {', '.join(ANSWER_KEYS)}")
    statuses = [s.value for s in Status]
    if data.get("status") not in statuses:
        raise ExternalPlannerError(f"{who}: 'status' must be one of {', '.join(statuses)}, got "
                                   f"{_show(data.get('status')) if 'status' in data else 'nothing'}")
    path = None if data.get("path") is None else _path(data["path"], dim, who)
    times = None
    if data.get("times") is not None:
        if path is None:
            raise ExternalPlannerError(f"{who}: 'times' given without a path")
        times = _times(data["times"], len(path), who)
    message = data.get("message", "")
    if not isinstance(message, str):
        raise ExternalPlannerError(f"{who}: 'message' must be a string, got {_show(message)}")
    result = PlanResult(
        Status(data["status"]),
        path=path,
        times=times,
        iterations=_count(data.get("iterations", 0), "iterations", who),
        evaluations=_count(data.get("evaluations", 0), "evaluations", who),
        message=message,
    )
    return Answer(result, _history(data.get("history", []), who))
