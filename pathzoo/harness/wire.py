"""The outcome of a run as plain bytes (JSON and float64 buffers), so the parent never unpickles what a worker sends.

A worker process runs planner code, so anything it sends is untrusted:
unpickling it could run arbitrary code in the judge's process. The process
executor therefore receives only short tagged byte strings (see
:mod:`pathzoo.harness.executors.process`), and the outcome travels as::

    4-byte little-endian header length | JSON header | path bytes | times bytes | history bytes

The header holds the scalar fields and the shapes of the three arrays
(float64, C order; the history is ``(n, 4)``: iteration, evaluations, best
cost, time). :func:`decode_outcome` checks every field's type and the total
size, and the result still goes through
:func:`~pathzoo.harness.bounds.bound_outcome`.
"""

from __future__ import annotations

import json
import struct
from typing import Any

import numpy as np

from pathzoo.core.results import HistoryPoint
from pathzoo.core.status import Status
from pathzoo.harness.bounds import MAX_HISTORY_POINTS, MAX_PATH_POINTS, bound_outcome
from pathzoo.harness.outcome import RunOutcome

__all__ = ["encode_outcome", "decode_outcome", "MAX_OUTCOME_BYTES", "WireError"]

MAX_OUTCOME_BYTES = 8 * 3 * MAX_PATH_POINTS + 8 * MAX_PATH_POINTS + 32 * MAX_HISTORY_POINTS + (1 << 20)
"""Largest encoded outcome accepted (a maximal 3-D path with times and a full history, plus 1 MiB of header)."""

_BOOLS = ("crash", "scenario_modified", "tainted", "sandboxed")
_TEXTS = ("path_error", "message", "started_at", "bounds_error", "stopped_by")
_FLOATS = ("wall_time_s", "cpu_time_s")


class WireError(ValueError):
    """Bytes from a worker that are not an encoded outcome."""


def _shape(arr: np.ndarray | None) -> list[int] | None:
    return None if arr is None else list(arr.shape)


def encode_outcome(outcome: RunOutcome) -> bytes:
    """Encode a (bounded) outcome; see the module docstring."""
    history = np.array([(p.iteration, p.evaluations, p.best_cost, p.time_s) for p in outcome.history],
                       dtype=np.float64).reshape(-1, 4)
    header: dict[str, Any] = {
        "run_key": outcome.run_key,
        "status": None if outcome.status is None else outcome.status.value,
        "iterations": outcome.iterations,
        "evaluations": outcome.evaluations,
        "versions": dict(outcome.versions),
        "path": _shape(outcome.path),
        "times": _shape(outcome.times),
        "history": list(history.shape),
    }
    header.update({name: getattr(outcome, name) for name in (*_BOOLS, *_TEXTS)})
    header.update({name: float(getattr(outcome, name)) for name in _FLOATS})
    head = json.dumps(header, allow_nan=True).encode()
    parts = [struct.pack("<I", len(head)), head]
    for arr in (outcome.path, outcome.times, history):
        if arr is not None:
            parts.append(np.ascontiguousarray(arr, dtype=np.float64).tobytes())
    return b"".join(parts)


def _array(data: memoryview, offset: int, shape: Any, ndim: int) -> tuple[np.ndarray | None, int]:
    if shape is None:
        return None, offset
    if (not isinstance(shape, list) or len(shape) != ndim
            or not all(type(n) is int and 0 <= n <= 4 * MAX_PATH_POINTS for n in shape)):
        raise WireError(f"bad array shape {shape!r}")
    size = 8 * int(np.prod(shape))
    if offset + size > len(data):
        raise WireError("truncated array")
    return np.frombuffer(data[offset:offset + size], dtype=np.float64).reshape(shape).copy(), offset + size


def _decode(data: bytes) -> RunOutcome:
    if len(data) < 4:
        raise WireError("too short")
    view = memoryview(data)
    (n,) = struct.unpack("<I", view[:4])
    try:
        header = json.loads(bytes(view[4:4 + n]).decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise WireError(f"bad header ({exc})") from None
    if not isinstance(header, dict):
        raise WireError("header is not an object")
    path, offset = _array(view, 4 + n, header.get("path"), 2)
    times, offset = _array(view, offset, header.get("times"), 1)
    hist, offset = _array(view, offset, header.get("history"), 2)
    if offset != len(data):
        raise WireError("trailing bytes")
    status = header.get("status")
    kwargs: dict[str, Any] = {
        "status": None if status is None else Status(status),
        "path": path,
        "times": times,
        "iterations": header.get("iterations"),
        "evaluations": header.get("evaluations"),
        "versions": header.get("versions") if isinstance(header.get("versions"), dict) else {},
        "history": () if hist is None else tuple(
            HistoryPoint(int(min(max(i, 0), 2**62)) if i == i else 0,
                         int(min(max(e, 0), 2**62)) if e == e else 0, float(c), float(t))
            for i, e, c, t in hist.reshape(-1, 4).tolist()
        ),
    }
    for name in _BOOLS:
        kwargs[name] = header.get(name) is True
    for name in _TEXTS:
        kwargs[name] = header.get(name) if isinstance(header.get(name), str) else ""
    for name in _FLOATS:
        value = header.get(name)
        kwargs[name] = float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else float("nan")
    return RunOutcome(str(header.get("run_key", "")), **kwargs)


def decode_outcome(data: bytes, run_key: str) -> RunOutcome:
    """Decode and bound what a worker sent for ``run_key``; unreadable bytes give a ``crash`` outcome."""
    if len(data) > MAX_OUTCOME_BYTES:
        return RunOutcome(run_key, crash=True, message=f"the worker sent {len(data)} bytes, over the limit")
    try:
        outcome = _decode(data)
    except (WireError, ValueError, TypeError, OverflowError, struct.error) as exc:
        return RunOutcome(run_key, crash=True, message=f"the worker sent an unreadable outcome: {exc}")
    if outcome.run_key != run_key:
        return RunOutcome(run_key, crash=True, message="the worker sent the outcome of another run")
    return bound_outcome(outcome)
