"""Walk outcomes and the compiled walk kernels' states and return codes, shared by every kernel of the engine."""

from __future__ import annotations

import numba

__all__ = ["REACHED", "STUCK", "STEP_CAP", "EXHAUSTED", "ABORTED", "OUTRUN", "FRESH", "RUNNING", "DONE",
           "NEED_SPACE", "stop_before_step"]

REACHED, STUCK, STEP_CAP, EXHAUSTED, ABORTED = 0, 1, 2, 3, 4
"""Walk outcomes: reached the goal; dead end without backtracking; step cap;
backtracked to an empty walk (component exhausted); stopped by the time
budget or never started."""

FRESH, RUNNING, OUTRUN = -2, -1, 5
"""Walk states before an outcome: not started, walking; and the race outcome "another ant reached the goal first"."""

DONE, NEED_SPACE = 0, 1
"""What a kernel returns: every walk has stopped; or a buffer must grow before the kernel is called again."""


@numba.njit(cache=True, inline="always")
def stop_before_step(node: int, goal: int, steps: int, max_steps: int, total: int, allowance: int) -> int:
    """The outcome of a walk at ``node`` after ``steps`` steps (``total`` in the call), or RUNNING if it steps on.

    At the goal it has REACHED it; at its step cap it stops with STEP_CAP;
    once the call's steps reach ``allowance`` it is ABORTED. Every kernel
    asks this before each step. It takes numbers only, so numba inlines it
    with no reference counts.
    """
    if node == goal:
        return REACHED
    if steps >= max_steps:
        return STEP_CAP
    if total >= allowance:
        return ABORTED
    return RUNNING
