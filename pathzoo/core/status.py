"""Outcome codes for a planner's answer and for a harness run."""

from __future__ import annotations

from enum import Enum

__all__ = ["Status", "RunStatus"]


class Status(str, Enum):
    """What a planner says about its own attempt.

    Attributes
    ----------
    SOLVED
        The planner returns a path it believes connects start and goal.
    NO_PATH
        The planner proved that the goal is unreachable (exact planners only).
    FAILED
        The budget ran out (or the search got stuck) before a path was found.
    """

    SOLVED = "solved"
    NO_PATH = "no_path"
    FAILED = "failed"


class RunStatus(str, Enum):
    """What the harness records for one run after judging it.

    ``SOLVED`` is only ever recorded when the harness itself validated the path.
    """

    SOLVED = "solved"
    NO_PATH = "no_path"
    FAILED = "failed"
    INVALID = "invalid"
    CRASH = "crash"
    TIMEOUT = "timeout"
