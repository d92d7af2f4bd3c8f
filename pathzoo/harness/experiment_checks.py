"""The checks of an experiment's values: seeds, budget counts, the hard limit, the name, the seed, the job count.

Each raises :class:`~pathzoo.core.errors.InvalidExperimentError` with a
one-line message naming the value.
"""

from __future__ import annotations

import math
from typing import Any, Iterable

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidExperimentError

__all__ = ["MAX_RUNS", "MAX_SEEDS", "MAX_INT", "resolve_seeds", "check_budget", "check_timeout", "check_name",
           "check_seed", "check_jobs"]


MAX_RUNS = 2_000_000
"""Most runs per experiment (planner x scenario pairs x seeds)."""

MAX_SEEDS = 100_000
"""Most seeds per experiment (a larger count is almost surely a typo, and would exhaust memory)."""

MAX_INT = 2**63 - 1
"""Largest seed, seed index or budget count: the database stores them as signed 64-bit integers."""


def resolve_seeds(seeds: int | Iterable[int]) -> tuple[int, ...]:
    """The seed indices of ``seeds``: a count (``0..n-1``) or distinct indices in ``[0, 2**63-1]``."""
    if isinstance(seeds, bool):
        raise InvalidExperimentError(f"seeds must be a count or a list of seed indices, got {seeds!r}")
    if isinstance(seeds, int):
        if not 1 <= seeds <= MAX_SEEDS:
            raise InvalidExperimentError(f"seeds must be between 1 and {MAX_SEEDS}, got {seeds}")
        return tuple(range(seeds))
    if isinstance(seeds, (str, bytes)):
        raise InvalidExperimentError(f"seeds must be a count or a list of seed indices, got {seeds!r}")
    try:
        out = tuple(seeds)
    except TypeError:
        raise InvalidExperimentError(f"seeds must be a count or a list of seed indices, got {seeds!r}") from None
    if not out or any(isinstance(s, bool) or not isinstance(s, int) or not 0 <= s <= MAX_INT for s in out):
        raise InvalidExperimentError(
            f"seed indices must be a non-empty list of integers in [0, 2**63-1], got {_short(list(out))}"
        )
    if len(out) > MAX_SEEDS:
        raise InvalidExperimentError(f"at most {MAX_SEEDS} seed indices, got {len(out)}")
    if len(set(out)) != len(out):
        raise InvalidExperimentError(f"seed indices must be distinct, got {list(out)!r}")
    return out


def _short(value: Any, limit: int = 80) -> str:
    """``repr(value)`` cut to ``limit`` characters, so an error message stays one short line."""
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def check_budget(budget: Budget) -> Budget:
    """``budget`` if its counts fit the database's 64-bit integers.

    Raises
    ------
    InvalidExperimentError
        Naming the count that is too large.
    """
    for name in ("iterations", "evaluations"):
        value = getattr(budget, name)
        if value is not None and value > MAX_INT:
            raise InvalidExperimentError(f"budget.{name} must be at most 2**63-1, got {_short(value)}")
    return budget


def check_timeout(value: Any) -> float:
    """``value`` as seconds if it is a positive finite number (the hard limit ``timeout_s``)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise InvalidExperimentError(f"timeout_s must be a positive number of seconds, got {value!r}")
    return float(value)


def check_name(value: Any) -> str:
    """``value`` if it is a non-empty string (an experiment's name)."""
    if not isinstance(value, str) or not value.strip():
        raise InvalidExperimentError(f"name must be a non-empty string, got {value!r}")
    return value


def check_seed(value: Any) -> int:
    """``value`` if it is a 64-bit integer (the experiment seed)."""
    if isinstance(value, bool) or not isinstance(value, int) or not -MAX_INT - 1 <= value <= MAX_INT:
        raise InvalidExperimentError(f"seed must be a 64-bit integer, got {_short(value)}")
    return value


def check_jobs(value: Any) -> int | None:
    """``value`` if it is None or a positive integer (a worker count)."""
    if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
        raise InvalidExperimentError(f"jobs must be a positive integer, got {value!r}")
    return value
