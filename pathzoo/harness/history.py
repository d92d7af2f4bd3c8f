"""The progress history of a run: the ``progress`` callback a planner gets, timed by the harness."""

from __future__ import annotations

import math
import time

from pathzoo.core.results import HistoryPoint

__all__ = ["HistoryRecorder"]

_clock = time.perf_counter  # bound at import, so a planner that patches the time module changes no timing


def _same_cost(a: float, b: float) -> bool:
    return a == b or (math.isnan(a) and math.isnan(b))


class HistoryRecorder:
    """The ``progress`` callback given to planners; the harness adds the time.

    A point is kept on the first report, whenever ``best_cost`` changes, and
    for the last report (unless it repeats the last kept one's counts).
    Reading the curve as "the best cost of the last kept point at or before
    this iteration" gives back exactly what the planner reported, while
    reports that change nothing cost no storage.
    """

    def __init__(self) -> None:
        self.t0 = _clock()
        self.points: list[HistoryPoint] = []
        self._last: HistoryPoint | None = None

    def __call__(self, iteration: int, evaluations: int, best_cost: float) -> None:
        point = HistoryPoint(int(iteration), int(evaluations), float(best_cost), _clock() - self.t0)
        last = self._last
        if last is None or not _same_cost(point.best_cost, last.best_cost):
            self.points.append(point)
        self._last = point

    def history(self) -> tuple[HistoryPoint, ...]:
        """The kept points, the last report included."""
        last = self._last
        if last is not None and (last.iteration, last.evaluations) != (self.points[-1].iteration,
                                                                       self.points[-1].evaluations):
            return (*self.points, last)
        return tuple(self.points)
