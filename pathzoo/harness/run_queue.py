"""The runs the runner has yet to submit: in their order, or the next one of a given lane.

The runner submits runs in the experiment's order (pilot first,
:func:`~pathzoo.harness.eta.pilot_first`), a few ahead of the workers
(:attr:`~pathzoo.harness.executors.base.RunExecutor.lookahead`). When runs of
several configurations alternate in that order and one configuration's runs
are faster, the runs queued ahead end up all of the slower one: the faster
configuration's worker then waits for the harness after every run. So the
runner also takes, out of order, the next run of a lane
(:meth:`~pathzoo.harness.executors.base.RunExecutor.lane`) that has a run
executing and none queued. Which run executes when changes nothing stored:
every run's result depends on its task only.
"""

from __future__ import annotations

from collections import deque
from typing import Callable, Generic, Hashable, Sequence, TypeVar

__all__ = ["RunQueue"]

T = TypeVar("T")


class RunQueue(Generic[T]):
    """Items taken in order (:meth:`next`) or the first not yet taken of a lane (:meth:`next_of`), each once.

    Parameters
    ----------
    items : sequence
        The items, in their order.
    lane : callable
        The lane of an item (any hashable value).
    """

    def __init__(self, items: Sequence[T], lane: Callable[[T], Hashable]) -> None:
        self._items = list(items)
        self._taken = bytearray(len(self._items))
        self._at = 0
        self._lanes: dict[Hashable, deque[int]] = {}
        for i, item in enumerate(self._items):
            self._lanes.setdefault(lane(item), deque()).append(i)

    def _take(self, i: int) -> T:
        self._taken[i] = 1
        return self._items[i]

    def next(self) -> T | None:
        """The first item not yet taken; None when every item is."""
        while self._at < len(self._items) and self._taken[self._at]:
            self._at += 1
        return self._take(self._at) if self._at < len(self._items) else None

    def next_of(self, lane: Hashable) -> T | None:
        """The first item of ``lane`` not yet taken; None when there is none."""
        indices = self._lanes.get(lane)
        while indices and self._taken[indices[0]]:
            indices.popleft()
        return self._take(indices.popleft()) if indices else None
