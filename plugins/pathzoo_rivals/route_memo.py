"""Values of a route kept per route: a converging search evaluates and leaps from the same routes again and again.

A frog population converges (a random frog string-pulled through the same
corners as an earlier one, a leap that lands on its target), so on GGACO's
maps about half of a ``swarm.mosfla`` run's evaluations are of a route
evaluated before, and every leap reads the polylines of two frogs that leapt
before. A route's objectives, selection criterion and polyline are pure
functions of its waypoint cells on one scenario
(:meth:`pathzoo_rivals.routes.RouteProblem.measure`,
:meth:`~pathzoo_rivals.routes.RouteProblem.polyline`), so :class:`RouteMemo`
keeps them keyed by the route's bytes and gives the same values, to the last
bit, without computing them again. What a method counts is unchanged: a route
answered from the memo is still one evaluation of the method
(:meth:`pathzoo_rivals.route_search.RouteRun.evaluate` counts it).
"""

from __future__ import annotations

from typing import Generic, TypeVar

import numpy as np

__all__ = ["RouteMemo", "MEMO_BYTES", "ENTRY_BYTES"]

MEMO_BYTES = 1 << 25
"""Most bytes a :class:`RouteMemo` holds (32 MiB), each route counted as its key, the arrays of its value and
:data:`ENTRY_BYTES`; the memo starts again when full."""

ENTRY_BYTES = 320
"""What a kept route costs besides the bytes of its key and of its value's arrays: array and tuple headers, the
dictionary slot (an upper bound of CPython's sizes)."""

V = TypeVar("V", bound=tuple)


class RouteMemo(Generic[V]):
    """Values (tuples) of routes kept per route (waypoint cells), at most ``capacity`` bytes.

    Values are returned as kept: callers must not modify their arrays.

    Parameters
    ----------
    capacity : int
        Most bytes held (see :data:`MEMO_BYTES`) before the memo starts again.
    """

    def __init__(self, capacity: int = MEMO_BYTES) -> None:
        self.capacity = capacity
        self.kept: dict[bytes, V] = {}
        self.bytes = 0

    def get(self, route: np.ndarray) -> V | None:
        """The kept value of ``route``, ``None`` if not kept."""
        return self.kept.get(np.asarray(route, dtype=np.int64).tobytes())

    def keep(self, route: np.ndarray, value: V) -> None:
        """Keep the value of ``route``; a full memo starts again first."""
        key = np.asarray(route, dtype=np.int64).tobytes()
        size = len(key) + ENTRY_BYTES + sum(v.nbytes for v in value if isinstance(v, np.ndarray))
        if self.bytes + size > self.capacity:
            self.kept.clear()
            self.bytes = 0
        self.kept[key] = value
        self.bytes += size
