"""Time left in an experiment, from the mean run time of each planner so far.

Planners differ by orders of magnitude in run time, so a progress bar's
overall rate swings with whichever planner happened to finish last. Here the
runs still to do are costed planner by planner instead.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from dataclasses import dataclass, field
from typing import Iterable

__all__ = ["RunTimes", "eta_seconds"]


@dataclass
class RunTimes:
    """Finished run durations per planner label: total seconds and count."""

    total_s: dict[str, float] = field(default_factory=lambda: defaultdict(float))
    count: Counter[str] = field(default_factory=Counter)

    def add(self, planner: str, seconds: float) -> None:
        """Record one finished run of ``planner`` that took ``seconds``."""
        self.total_s[planner] += max(float(seconds), 0.0)
        self.count[planner] += 1


def eta_seconds(remaining: Iterable[str], times: RunTimes, parallel: int = 1) -> float | None:
    """Estimated seconds until the runs ``remaining`` (one planner label per run) are done.

    Each remaining run costs the mean duration of its planner's finished runs,
    or the mean over all finished runs when its planner has none yet; the sum
    is divided by ``parallel``, the number of runs executing at once.

    Returns
    -------
    float or None
        None before any run has finished (nothing to estimate from).
    """
    n_done = sum(times.count.values())
    if n_done == 0:
        return None
    overall = sum(times.total_s.values()) / n_done
    left = Counter(remaining)
    total = sum(n * (times.total_s[p] / times.count[p] if times.count[p] else overall) for p, n in left.items())
    return total / max(int(parallel), 1)
