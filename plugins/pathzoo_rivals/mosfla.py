"""``swarm.mosfla``: multi-objective shuffled frog-leaping on routes, after Hidalgo-Paniagua et al. (EAAI 2015).

Reconstructed from the paper's abstract (shuffled frog-leaping, three
objectives: safety, length, smoothness; NSGA-II as its rival) and the
shuffled frog-leaping algorithm of Eusuff and Lansey (2003):

1. a population of ``n_memeplexes × n_frogs`` frogs (routes) is ordered best
   to worst and dealt into memeplexes like cards (frog ``i`` to memeplex
   ``i mod m``);
2. in each memeplex, ``n_local`` times: the worst frog leaps toward the
   memeplex's best (``X_w + r (X_b - X_w)``); if the new frog is infeasible or
   dominated by the worst, it leaps toward the population's best instead;
   if that fails too, a random frog replaces it;
3. the memeplexes are shuffled back together: one iteration.

"Best" and "worst" are NSGA-II's order (front rank, then crowding distance,
pymoo's, compiled in :mod:`pathzoo_rivals.pareto`), our multi-objective
reading of SFLA's fitness sort. The route encoding, the leap on routes
(:func:`pathzoo_rivals.route_moves.leap`) and the defaults are pathzoo's
(``docs/planners/swarm.mosfla.md``).
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from pathzoo.core import Param
from pathzoo_rivals.pareto import dominates, rank_and_crowding_order
from pathzoo_rivals.route_moves import leap
from pathzoo_rivals.route_search import SELECT, RouteRun, RouteSearchPlanner

__all__ = ["MosflaPlanner"]


class MosflaPlanner(RouteSearchPlanner):
    """MOSFLA reconstruction (see the module docstring and ``docs/planners/swarm.mosfla.md``)."""

    id: ClassVar[str] = "swarm.mosfla"
    version: ClassVar[str] = "2"
    summary: ClassVar[str] = ("MOSFLA after Hidalgo-Paniagua et al. 2015 (reconstructed): shuffled frog-leaping on "
                              "waypoint routes, objectives length, safety, smoothness")
    params = {
        "n_memeplexes": Param(4, "memeplexes m", low=1),
        "n_frogs": Param(5, "frogs per memeplex n (at least 2: a best and a worst)", low=2),
        "n_local": Param(5, "leaps of each memeplex's worst frog between two shuffles", low=1),
        "select": SELECT,
    }

    def search(self, run: RouteRun, rng: np.random.Generator) -> None:
        """Evaluate the first population, then leap and shuffle until the budget is spent."""
        problem = run.problem
        frogs: list[np.ndarray] = []
        scores: list[np.ndarray] = []
        for _ in range(self.n_memeplexes * self.n_frogs):
            route = problem.random_route(rng)
            if route is None:
                return
            f = run.evaluate(route)
            if f is None:
                return
            frogs.append(route)
            scores.append(f)
        while True:
            order = rank_and_crowding_order(np.array(scores))
            global_best = frogs[int(order[0])]
            for j in range(self.n_memeplexes):
                members = [int(i) for i in order[j:: self.n_memeplexes]]
                for _ in range(self.n_local):
                    local = rank_and_crowding_order(np.array([scores[i] for i in members]))
                    best, worst = members[int(local[0])], members[int(local[-1])]
                    replaced = self.leap_or_replace(run, frogs[worst], scores[worst], frogs[best], global_best, rng)
                    if replaced is None:
                        return
                    frogs[worst], scores[worst] = replaced
            if not run.next_iteration():
                return

    def leap_or_replace(self, run: RouteRun, worst: np.ndarray, f_worst: np.ndarray, best: np.ndarray,
                        global_best: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray] | None:
        """SFLA's three tries for the worst frog; ``None`` once the budget is spent."""
        for target in (best, global_best):
            moved = leap(run.problem, worst, target, rng)
            if moved is None:
                continue
            f = run.evaluate(moved)
            if f is None:
                return None
            if not dominates(f_worst, f):
                return moved, f
        route = run.problem.random_route(rng)
        if route is None:
            return None
        f = run.evaluate(route)
        return None if f is None else (route, f)
