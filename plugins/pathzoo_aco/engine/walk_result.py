"""The walks of one colony as the planners read them: every walk's edges, outcome and steps."""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import EXHAUSTED, REACHED
from pathzoo_aco.engine.prefetch import AHEAD, prefetch

__all__ = ["Walks"]


@dataclass(frozen=True, eq=False)
class Walks:
    """The walks of one iteration.

    Attributes
    ----------
    flat : ndarray of int64
        Edge ids of every walk that reached the goal, concatenated.
    offsets : ndarray of int64, shape (n + 1,)
        Walk ``a`` is ``flat[offsets[a]:offsets[a + 1]]`` (empty unless it reached the goal).
    flags : ndarray of int8, shape (n,)
        Outcome per walk (:data:`REACHED`, :data:`STUCK`, :data:`STEP_CAP`, :data:`EXHAUSTED`,
        :data:`ABORTED`, :data:`OUTRUN`).
    steps : ndarray of int64, shape (n,)
        Steps each ant took, backtracking moves included.
    started : int
        Walks actually started (the evaluation count).
    """

    flat: np.ndarray
    offsets: np.ndarray
    flags: np.ndarray
    steps: np.ndarray
    started: int

    @property
    def reached(self) -> np.ndarray:
        """Boolean mask of the walks that reached the goal."""
        return self.flags == REACHED

    @property
    def exhausted(self) -> bool:
        """True when some ant searched the start's whole component without reaching the goal."""
        return bool(np.any(self.flags == EXHAUSTED))

    def edges(self, ant: int) -> np.ndarray:
        """Edge ids of one walk."""
        return self.flat[self.offsets[ant] : self.offsets[ant + 1]]

    def totals(self, per_edge: np.ndarray) -> np.ndarray:
        """Sum of a per-edge quantity over each walk; ``inf`` for walks that did not reach the goal."""
        out = _walk_sums(np.asarray(per_edge, dtype=np.float64), self.flat, self.offsets, True)
        return np.where(self.reached, out, np.inf)

    def sums(self, per_step: np.ndarray) -> np.ndarray:
        """As :meth:`totals`, from values given per entry of :attr:`flat` (computed for the walked edges only)."""
        out = _walk_sums(np.asarray(per_step, dtype=np.float64), self.flat, self.offsets, False)
        return np.where(self.reached, out, np.inf)


@numba.njit(cache=True)
def _walk_sums(values, flat, offsets, by_edge):
    """Per walk, the difference of one running sum over all walks at its two ends.

    The running sum is taken entry by entry in ``flat`` order (of
    ``values[flat[p]]`` when ``by_edge``, else of ``values[p]``), exactly as
    ``np.cumsum`` does, so the results equal ``cum[end] - cum[start]`` of it.
    """
    n = offsets.size - 1
    out = np.empty(n)
    acc = 0.0
    p = 0
    start = 0.0
    last = offsets[n] - 1
    for a in range(n):
        while p < offsets[a]:
            acc += values[flat[p]] if by_edge else values[p]
            p += 1
        start = acc
        while p < offsets[a + 1]:
            if by_edge:  # the walk's edges follow no stride: ask for the value a few edges ahead
                prefetch(values, flat[min(p + AHEAD, last)])
            acc += values[flat[p]] if by_edge else values[p]
            p += 1
        out[a] = acc - start
    return out
