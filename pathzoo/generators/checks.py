"""Value checks shared by the generators and the scenario-file reader, raising one-line InvalidScenarioError."""

from __future__ import annotations

import math
from typing import Any, Sequence

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["check_number", "check_seed", "check_shape", "relocated"]


def check_number(
    value: Any,
    field: str,
    *,
    source: str | None = None,
    low: float | None = None,
    high: float | None = None,
    low_open: bool = False,
    high_open: bool = False,
    integer: bool = False,
) -> float:
    """Return ``value`` if it is a finite number (an int when ``integer``) inside the bounds.

    Parameters
    ----------
    value : object
        What the caller was given.
    field : str
        Name used in the error message.
    source : str, optional
        File the value came from.
    low, high : float, optional
        Bounds; inclusive unless ``low_open`` / ``high_open``.
    integer : bool
        Require an ``int`` (``bool`` is never a number here).

    Raises
    ------
    InvalidScenarioError
        Naming ``field`` (and ``source``), the allowed range and the value given.
    """
    kinds = (int,) if integer else (int, float)
    what = "an integer" if integer else "a number"
    if isinstance(value, bool) or not isinstance(value, kinds) or not math.isfinite(value):
        raise InvalidScenarioError(f"must be {what}, got {value!r}", source=source, field=field)
    too_low = low is not None and (value <= low if low_open else value < low)
    too_high = high is not None and (value >= high if high_open else value > high)
    if too_low or too_high:
        lo = "-inf" if low is None else f"{low:g}"
        hi = "inf" if high is None else f"{high:g}"
        interval = f"{'(' if low_open or low is None else '['}{lo}, {hi}{')' if high_open or high is None else ']'}"
        raise InvalidScenarioError(f"must be in {interval}, got {value!r}", source=source, field=field)
    return value


def check_seed(seed: Any, field: str = "seed", *, source: str | None = None) -> int:
    """Return ``seed`` if it is a non-negative integer (what :func:`numpy.random.default_rng` accepts)."""
    return int(check_number(seed, field, source=source, low=0, integer=True))


def check_shape(
    shape: Any, field: str = "shape", *, ndims: Sequence[int] = (2,), minimum: int = 1, source: str | None = None
) -> tuple[int, ...]:
    """Return ``shape`` as a tuple of integers >= ``minimum`` with an allowed number of axes."""
    if not isinstance(shape, (list, tuple)) or len(shape) not in ndims:
        allowed = " or ".join(str(n) for n in ndims)
        raise InvalidScenarioError(f"must be a list of {allowed} integers, got {shape!r}", source=source, field=field)
    for n in shape:
        check_number(n, field, source=source, low=minimum, integer=True)
    return tuple(int(n) for n in shape)


def relocated(
    error: InvalidScenarioError, *, source: str | None, field: str | None = None, note: str = ""
) -> InvalidScenarioError:
    """The same complaint placed in ``source`` at ``field`` (default: the error's own field), prefixed by ``note``.

    Lets a reader report an error raised by a checked value or object (which
    knows the field but not the file) at the file and the full field name.
    """
    message = str(error)
    if error.source is not None:
        message = message.removeprefix(f"{error.source}: ")
    if error.field is not None:
        message = message.removeprefix(f"field '{error.field}': ")
    return InvalidScenarioError(f"{note}{message}", source=source, field=field or error.field)
