"""Walk outcomes and the compiled walk kernels' states and return codes, shared by every kernel of the engine."""

from __future__ import annotations

__all__ = ["REACHED", "STUCK", "STEP_CAP", "EXHAUSTED", "ABORTED", "OUTRUN", "FRESH", "RUNNING", "DONE",
           "NEED_SPACE"]

REACHED, STUCK, STEP_CAP, EXHAUSTED, ABORTED = 0, 1, 2, 3, 4
"""Walk outcomes: reached the goal; dead end without backtracking; step cap;
backtracked to an empty walk (component exhausted); stopped by the time
budget or never started."""

FRESH, RUNNING, OUTRUN = -2, -1, 5
"""Walk states before an outcome: not started, walking; and the race outcome "another ant reached the goal first"."""

DONE, NEED_SPACE = 0, 1
"""What a kernel returns: every walk has stopped; or a buffer must grow before the kernel is called again."""
