"""Values computed once per live object and dropped with it (scenarios, graphs).

Scenarios and their graphs are frozen, so anything derived from one alone
(a reference path, a planner's per-graph table, where a search starts) can be
computed on first use and kept while the object lives. :class:`ObjectMemo`
keeps such values in a weak-keyed map beside the object, so nothing is added
to the object itself and a value goes when its object does.
"""

from __future__ import annotations

import threading
import weakref
from typing import Callable, TypeVar

__all__ = ["ObjectMemo"]

K = TypeVar("K")
V = TypeVar("V")


class ObjectMemo(weakref.WeakKeyDictionary[K, V]):
    """A weak-keyed map whose :meth:`value` computes an object's value on first use (thread-safe).

    A value must not refer to its object, or the object never goes.
    """

    def __init__(self) -> None:
        super().__init__()
        self._lock = threading.Lock()

    def value(self, obj: K, compute: Callable[[], V]) -> V:
        """The value kept for ``obj``, or ``compute()``, kept for it from now on.

        ``compute`` runs outside the lock, so a slow computation never blocks
        other objects; two threads asking for the same new object may both
        compute it, and the first value stored is the one every caller gets.
        """
        with self._lock:
            if obj in self:
                return self[obj]
        computed = compute()
        with self._lock:
            return self.setdefault(obj, computed)
