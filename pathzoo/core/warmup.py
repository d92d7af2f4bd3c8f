"""Untimed warm-up calls that move JIT compilation out of measured planning time."""

from __future__ import annotations

import threading

import numpy as np

from pathzoo.core.budget import Budget
from pathzoo.core.planner import Planner
from pathzoo.core.scenario import Scenario
from pathzoo.core.tiny_scenarios import check_scenario

__all__ = ["warm_up", "is_warm", "WARM_UP_BUDGET"]

WARM_UP_BUDGET = Budget(iterations=2)
"""Budget of a warm-up call: enough to reach every compiled kernel, too little to matter.

Two iterations, and no other limit: an evaluation cap stops a one-pass
search (an exact planner's) before it reaches the goal and the kernels that
build the path, and a clock limit would stop a warm-up during its first,
slow compilation, before the search loop; either left those kernels to be
compiled in the first measured run. The hard limit of the run still applies."""

_warmed: set[tuple[type, str]] = set()
_lock = threading.Lock()


def is_warm(planner: Planner, kind: str) -> bool:
    """Whether :func:`warm_up` has run for this planner class and scenario kind in this process."""
    with _lock:
        return (type(planner), kind) in _warmed


def warm_up(planner: Planner, kind: str, budget: Budget = WARM_UP_BUDGET, *, on: Scenario | None = None) -> None:
    """Plan once, ignoring the outcome: once per planner class and scenario kind in this process, or on ``on``.

    Numba compiles (or loads from its cache) on first call, which can take
    seconds. Both the harness and the conformance kit call this before they
    start a clock, so the first run in a worker is not charged for it and a
    run cut short by the clock does not give a different answer. The call uses
    the tiny scenario of ``kind`` (:mod:`pathzoo.core.tiny_scenarios`), or ``on`` when given
    (every time: the caller decides how often), and its own random
    generator, so it cannot influence the measured run. Errors are ignored:
    the measured call that follows makes the same mistakes and is judged.

    Numba compiles one specialisation per combination of argument types, and
    a kernel's types can follow the scenario (read-only arrays, index
    widths, optional tables present or not), so the harness warms up on a
    twin of the run's own scenario (``on``); the kit's tiny scenarios do not
    reach every specialisation.
    """
    if on is None:
        key = (type(planner), kind)
        with _lock:
            if key in _warmed:
                return
            _warmed.add(key)
    try:
        scenario = check_scenario(kind) if on is None else on
        planner.plan(scenario, budget=budget, rng=np.random.default_rng(0), progress=None)
    except Exception:  # noqa: BLE001 - see docstring
        return
