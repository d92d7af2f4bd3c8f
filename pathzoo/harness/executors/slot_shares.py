"""How many of a worker pool's slots each planner configuration is worth, so a sweep starts as few workers as it needs.

A sandboxed worker costs about a CPU second to start (an interpreter, numba,
the planner's kernels, a warm-up), as much as tens of short runs. The
process executor starts a second worker for a configuration that already
has one only when :meth:`SlotShares.worth_another` says so: when the
configuration's share of the slots, by the work it has left, is larger than
the workers it has, and each of them would still have more than a start's
worth of runs to do. Two configurations with hundreds of runs each on two
slots then get one worker each, instead of two each taking turns.

Work is runs left times the configuration's mean time per run, measured in
the harness from the hand-over of a run to a warm worker to its outcome; the
start cost is measured from a worker's launch to its warm-up's end. Neither
is read from a worker: the numbers only decide when processes start, never
what a run is charged.
"""

from __future__ import annotations

import math
from collections import Counter
from typing import TYPE_CHECKING

from pathzoo.harness.executors.worker_handle import configuration

if TYPE_CHECKING:
    from collections.abc import Iterable

    from pathzoo.harness.specs import RunTask

__all__ = ["SlotShares", "DEFAULT_START_S"]

Config = tuple[str, str, str]

DEFAULT_START_S = 1.0
"""Seconds a worker start is taken to cost until one has been measured."""


class SlotShares:
    """Runs left and measured times per configuration, and the slots each is worth.

    Parameters
    ----------
    capacity : int
        Runs the pool runs at once.
    """

    def __init__(self, capacity: int) -> None:
        self.capacity = capacity
        self.left: Counter[Config] = Counter()
        self._run_s: dict[Config, tuple[int, float]] = {}  # runs timed, their total seconds
        self._all_s: tuple[int, float] = (0, 0.0)  # the same over every configuration
        self._start_s: tuple[int, float] = (0, 0.0)

    def expect(self, tasks: "Iterable[RunTask]") -> None:
        """Count the runs the pool is going to be given."""
        self.left.update(configuration(task) for task in tasks)

    def taken(self, config: Config) -> None:
        """A run of ``config`` went to a worker."""
        if self.left[config] > 0:
            self.left[config] -= 1

    def ran(self, config: Config, seconds: float) -> None:
        """A warm worker of ``config`` took ``seconds`` from a run's hand-over to its outcome."""
        if math.isfinite(seconds):
            n, total = self._run_s.get(config, (0, 0.0))
            self._run_s[config] = (n + 1, total + seconds)
            n, total = self._all_s
            self._all_s = (n + 1, total + seconds)

    def started(self, seconds: float) -> None:
        """A worker took ``seconds`` from its launch to the end of its warm-up."""
        n, total = self._start_s
        self._start_s = (n + 1, total + seconds)

    def run_seconds(self, config: Config) -> float:
        """Mean seconds per run of ``config``; the mean over all configurations until it has one; 1 before any."""
        n, total = self._run_s.get(config) or self._all_s
        return total / n if n else 1.0

    @property
    def start_seconds(self) -> float:
        """Mean seconds a worker start has taken (:data:`DEFAULT_START_S` before one is measured)."""
        n, total = self._start_s
        return total / n if n else DEFAULT_START_S

    def shares(self) -> dict[Config, int]:
        """Slots per configuration with runs left: one each to the configurations with the most work, as far as
        the slots go, then each further slot to the one with the most work per slot (the D'Hondt rule)."""
        work = {c: n * self.run_seconds(c) for c, n in self.left.items() if n > 0}
        order = sorted(work, key=lambda c: (-work[c], c))
        shares = dict.fromkeys(order[:self.capacity], 1)
        for _ in range(self.capacity - len(shares) if shares else 0):
            best = max(shares, key=lambda c: (work[c] / (shares[c] + 1), c))
            shares[best] += 1
        return shares

    def worth_another(self, config: Config, alive: int) -> bool:
        """Whether ``config``, with ``alive`` workers (starting ones included), should get one more.

        Always when it has none. Otherwise only when its share of the slots
        is larger than ``alive`` and, with one more worker, each would still
        have over a start's worth of its runs left. A configuration whose
        runs were never announced (:meth:`expect`) gets one when asked.
        """
        if alive == 0 or config not in self.left:
            return True
        return self.shares().get(config, 0) > alive and self.pays_for_a_start(config, alive)

    def pays_for_a_start(self, config: Config, alive: int) -> bool:
        """Whether, with one more worker than its ``alive`` ones, each worker of ``config`` would still have over a
        start's worth of its runs left (its share of the slots aside)."""
        return self.left[config] * self.run_seconds(config) / (alive + 1) > self.start_seconds
