"""Pareto bookkeeping of the multi-objective rivals: dominance, an archive of non-dominated routes and NSGA-II order.

Non-dominated sorting and crowding distances are pymoo's
(:class:`~pymoo.util.nds.non_dominated_sorting.NonDominatedSorting`,
:func:`~pymoo.operators.survival.rank_and_crowding.metrics.calc_crowding_distance`),
imported when first used so that listing plugins does not load pymoo (an
optional dependency, extra ``evo``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["dominates", "rank_and_crowding_order", "ParetoArchive"]


def dominates(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether objective vector ``a`` Pareto-dominates ``b`` (all minimised)."""
    return bool(np.all(a <= b) and np.any(a < b))


def _crowding(front: np.ndarray) -> np.ndarray:
    """Crowding distances of one front; fronts of one or two points are all boundary (``inf``)."""
    if len(front) <= 2:
        return np.full(len(front), np.inf)
    from pymoo.operators.survival.rank_and_crowding.metrics import calc_crowding_distance

    return calc_crowding_distance(front)


def rank_and_crowding_order(objectives: np.ndarray) -> np.ndarray:
    """Indices from best to worst in NSGA-II's order: front rank ascending, then crowding distance descending.

    Ties keep the input order (stable sort), so the order is deterministic.
    """
    from pymoo.util.nds.non_dominated_sorting import NonDominatedSorting

    objectives = np.asarray(objectives, dtype=np.float64)
    fronts = NonDominatedSorting().do(objectives)
    rank = np.empty(len(objectives), dtype=np.int64)
    crowd = np.empty(len(objectives))
    for r, members in enumerate(fronts):
        rank[members] = r
        crowd[members] = _crowding(objectives[members])
    return np.lexsort((np.arange(len(objectives)), -crowd, rank))


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
            drop = int(np.argmin(_crowding(self.objectives)))
            del self.routes[drop]
            self.objectives = np.delete(self.objectives, drop, axis=0)
        return True
