"""``search.movns``: multi-objective variable neighbourhood search on routes, after Hidalgo-Paniagua et al. (ESWA 2016).

Reconstructed from the paper's abstract (VNS, three objectives: safety,
length, smoothness) and the generic multi-objective VNS scheme of Duarte et
al. (J. Glob. Optim. 2015): pick an archive member, shake it in the ``k``-th
neighbourhood, improve it by a dominance-based descent, and go back to
``k = 1`` when the result enters the Pareto archive, else try ``k + 1``.
The route encoding, the neighbourhoods and every default are pathzoo's
(``docs/planners/search.movns.md``).

Neighbourhood ``N_k`` (``k = 1..k_max``): ``k`` successive random moves, each
a relocation or an insertion within ``k`` cells, or a removal
(:mod:`pathzoo_rivals.route_moves`), so every shaken route stays feasible.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from pathzoo.core import Param
from pathzoo_rivals.pareto import dominates
from pathzoo_rivals.route_moves import insert, relocate, remove
from pathzoo_rivals.route_search import SELECT, RouteRun, RouteSearchPlanner
from pathzoo_rivals.routes import RouteProblem

__all__ = ["MovnsPlanner", "shake"]


def shake(problem: RouteProblem, route: np.ndarray, k: int, rng: np.random.Generator) -> np.ndarray | None:
    """A random route of ``N_k(route)``: ``k`` random feasible moves of radius ``k``; ``None`` if a move found none."""
    out = route
    for _ in range(k):
        kind = int(rng.integers(3))
        if kind == 0:
            moved = relocate(problem, out, rng, k)
        elif kind == 1:
            moved = insert(problem, out, rng, k)
        else:
            moved = remove(problem, out, rng)
        if moved is None:
            return None
        out = moved
    return out


class MovnsPlanner(RouteSearchPlanner):
    """MOVNS reconstruction (see the module docstring and ``docs/planners/search.movns.md``)."""

    id: ClassVar[str] = "search.movns"
    version: ClassVar[str] = "2"
    summary: ClassVar[str] = ("MOVNS after Hidalgo-Paniagua et al. 2016 (reconstructed): multi-objective VNS on "
                              "waypoint routes, objectives length, safety, smoothness")
    params = {
        "n_initial": Param(10, "random routes that seed the Pareto archive", low=1),
        "k_max": Param(3, "number of neighbourhoods N_1..N_k_max", low=1),
        "descent_tries": Param(10, "moves tried by the dominance descent after each shake", low=0),
        "select": SELECT,
    }

    def descend(self, run: RouteRun, route: np.ndarray, f: np.ndarray, rng: np.random.Generator
                ) -> tuple[np.ndarray, np.ndarray] | None:
        """Dominance descent: try removals and radius-1 relocations, keep a move whose route dominates."""
        for _ in range(self.descent_tries):
            moved = remove(run.problem, route, rng) if rng.uniform() < 0.5 else relocate(run.problem, route, rng, 1)
            if moved is None:
                continue
            g = run.evaluate(moved)
            if g is None:
                return None
            if dominates(g, f):
                route, f = moved, g
        return route, f

    def search(self, run: RouteRun, rng: np.random.Generator) -> None:
        """Seed the archive with random routes, then run MO-VNS rounds until the budget is spent."""
        problem = run.problem
        for _ in range(self.n_initial):
            route = problem.random_route(rng)
            if route is None or run.evaluate(route) is None:
                break
        while len(run.archive) and not run.exhausted():
            current = run.archive.routes[int(rng.integers(len(run.archive)))]
            k = 1
            while k <= self.k_max:
                shaken = shake(problem, current, k, rng)
                if shaken is None:
                    k += 1
                    continue
                f = run.evaluate(shaken)
                if f is None:
                    return
                improved = self.descend(run, shaken, f, rng)
                if improved is None:
                    return
                route, f = improved
                if any(r is route for r in run.archive.routes):
                    current, k = route, 1
                else:
                    k += 1
            if not run.next_iteration():
                return
