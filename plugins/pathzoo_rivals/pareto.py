"""Pareto bookkeeping of the multi-objective rivals: dominance, an archive of non-dominated routes and NSGA-II order.

Non-dominated sorting and crowding distances are compiled here (numba) and
give pymoo's values to the last bit
(:class:`~pymoo.util.nds.non_dominated_sorting.NonDominatedSorting`: fronts
of the Pareto ranks, members in index order;
:func:`~pymoo.operators.survival.rank_and_crowding.metrics.calc_crowding_distance`:
per objective, the gaps to the neighbours in a stable sort over the
objective's range, ``0`` where the range is ``0``, boundary points ``inf``,
the objectives summed in order as NumPy's reduction of a row does), which ``tests/rivals/test_pareto.py`` checks against pymoo. A
frog-leaping run sorts a memeplex before each of its leaps, tens of thousands
of small sets, where pymoo's per-call overhead was most of the time.
"""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["dominates", "rank_and_crowding_order", "crowding_distances", "ParetoArchive"]


def dominates(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether objective vector ``a`` Pareto-dominates ``b`` (all minimised)."""
    return bool(np.all(a <= b) and np.any(a < b))


@numba.njit(cache=True)
def _dominates(objectives: np.ndarray, a: int, b: int) -> bool:
    """Whether row ``a`` of ``objectives`` Pareto-dominates row ``b``."""
    better = False
    for c in range(objectives.shape[1]):
        if objectives[a, c] > objectives[b, c]:
            return False
        if objectives[a, c] < objectives[b, c]:
            better = True
    return better


@numba.njit(cache=True)
def _crowding_of(objectives: np.ndarray, members: np.ndarray, out: np.ndarray) -> None:
    """``out[members]`` = the crowding distances of the rows ``members`` (one front, in this order)."""
    k, m = len(members), objectives.shape[1]
    if k <= 2:
        for i in range(k):
            out[members[i]] = np.inf
        return
    parts = np.zeros((k, m))
    column = np.empty(k)
    for c in range(m):
        for i in range(k):
            column[i] = objectives[members[i], c]
        order = np.argsort(column, kind="mergesort")
        norm = column[order[k - 1]] - column[order[0]]
        for p in range(k):
            last = column[order[p]] - column[order[p - 1]] if p > 0 else np.inf
            after = column[order[p + 1]] - column[order[p]] if p < k - 1 else np.inf
            last = last / norm if norm != 0.0 else 0.0
            after = after / norm if norm != 0.0 else 0.0
            parts[order[p], c] = last + after
    for i in range(k):
        total = parts[i, 0]
        for c in range(1, m):
            total += parts[i, c]
        out[members[i]] = total / m


@numba.njit(cache=True)
def _nsga2_order(objectives: np.ndarray) -> np.ndarray:
    """Indices in NSGA-II's order (see :func:`rank_and_crowding_order`)."""
    n = objectives.shape[0]
    rank = np.full(n, -1, dtype=np.int64)
    crowd = np.empty(n)
    members = np.empty(n, dtype=np.int64)
    r, done = 0, 0
    while done < n:
        k = 0
        for i in range(n):
            if rank[i] != -1:
                continue
            free = True
            for j in range(n):
                if rank[j] == -1 and j != i and _dominates(objectives, j, i):
                    free = False
                    break
            if free:
                members[k] = i
                k += 1
        for t in range(k):
            rank[members[t]] = r
        _crowding_of(objectives, members[:k], crowd)
        done += k
        r += 1
    order = np.arange(n)
    for i in range(1, n):  # stable insertion sort: rank ascending, then crowding descending
        v = order[i]
        j = i - 1
        while j >= 0 and (rank[order[j]] > rank[v] or (rank[order[j]] == rank[v] and crowd[order[j]] < crowd[v])):
            order[j + 1] = order[j]
            j -= 1
        order[j + 1] = v
    return order


def crowding_distances(front: np.ndarray) -> np.ndarray:
    """Crowding distances of one front (pymoo's); fronts of one or two points are all boundary (``inf``)."""
    front = np.ascontiguousarray(front, dtype=np.float64)
    out = np.empty(len(front))
    _crowding_of(front, np.arange(len(front)), out)
    return out


def rank_and_crowding_order(objectives: np.ndarray) -> np.ndarray:
    """Indices from best to worst in NSGA-II's order: front rank ascending, then crowding distance descending.

    Ties keep the input order (stable sort), so the order is deterministic.
    """
    return _nsga2_order(np.ascontiguousarray(objectives, dtype=np.float64))


class ParetoArchive:
    """The non-dominated routes seen so far, at most ``capacity`` of them (crowding truncation keeps the extremes).

    Parameters
    ----------
    capacity : int
        Largest number of routes kept.
    """

    def __init__(self, capacity: int) -> None:
        self.capacity = capacity
        self.routes: list[np.ndarray] = []
        self.objectives = np.empty((0, 0))

    def __len__(self) -> int:
        return len(self.routes)

    def add(self, route: np.ndarray, f: np.ndarray) -> bool:
        """Offer a route; returns whether it entered (no member dominates or equals it).

        Members it dominates leave. When the archive overflows, the member
        with the smallest crowding distance leaves (the first one on a tie).
        """
        f = np.asarray(f, dtype=np.float64)
        if len(self.routes):
            F = self.objectives
            if np.any(np.all(F <= f, axis=1)):
                return False
            stay = ~(np.all(f <= F, axis=1) & np.any(f < F, axis=1))
            self.routes = [r for r, s in zip(self.routes, stay) if s]
            self.objectives = np.vstack([F[stay], f])
        else:
            self.objectives = f[None, :]
        self.routes.append(route)
        if len(self.routes) > self.capacity:
            drop = int(np.argmin(crowding_distances(self.objectives)))
            del self.routes[drop]
            self.objectives = np.delete(self.objectives, drop, axis=0)
        return True
