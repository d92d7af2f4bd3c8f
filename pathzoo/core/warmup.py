"""Untimed warm-up calls that move JIT compilation out of measured planning time."""

from __future__ import annotations

import threading

import numpy as np

from pathzoo.core.budget import Budget
from pathzoo.core.planner import Planner
from pathzoo.core.tiny_scenarios import check_scenario

__all__ = ["warm_up", "is_warm", "WARM_UP_BUDGET"]

WARM_UP_BUDGET = Budget(iterations=2, evaluations=200, time_s=2.0)
"""Budget of a warm-up call: enough to reach every compiled kernel, too little to matter."""

_warmed: set[tuple[type, str]] = set()
_lock = threading.Lock()


def is_warm(planner: Planner, kind: str) -> bool:
    """Whether :func:`warm_up` has run for this planner class and scenario kind in this process."""
    with _lock:
        return (type(planner), kind) in _warmed


def warm_up(planner: Planner, kind: str, budget: Budget = WARM_UP_BUDGET) -> None:
    """Plan once per planner class and scenario kind in this process, ignoring the outcome.

    Numba compiles (or loads from its cache) on first call, which can take
    seconds. Both the harness and the conformance kit call this before they
    start a clock, so the first run in a worker is not charged for it and a
    run cut short by the clock does not give a different answer. The call uses
    the tiny scenario of ``kind`` (:mod:`pathzoo.core.tiny_scenarios`) and its own random
    generator, so it cannot influence the measured run. Errors are ignored:
    the measured call that follows makes the same mistakes and is judged.
    """
    key = (type(planner), kind)
    with _lock:
        if key in _warmed:
            return
        _warmed.add(key)
    try:
        scenario = check_scenario(kind)
        planner.plan(scenario, budget=budget, rng=np.random.default_rng(0), progress=None)
    except Exception:  # noqa: BLE001 - see docstring
        return
