"""aco.acs: the Ant Colony System of Dorigo and Gambardella (1997) on path-planning graphs.

Mechanism: the pseudo-random-proportional rule (with probability ``q0`` the
ant takes the edge maximising ``τ η^β``, otherwise it draws as in AS) and the
local update ``τ <- (1 - ξ) τ + ξ τ0`` on every edge just crossed (both in
:meth:`AntColonySystem.walk_rules`); after each colony only the global-best
walk is updated, ``τ <- (1 - ρ) τ + ρ / L_gb`` (:meth:`AntColonySystem.update_trail`).
``τ0 = 1 / (n L_nn)`` comes from one greedy walk (:meth:`AntColonySystem.init_state`).
See ``docs/planners/aco.acs.md``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from pathzoo.core.planner import Param
from pathzoo_aco.engine import (
    ColonyProblem,
    ColonyState,
    Pheromone,
    WalkEngine,
    WalkRules,
    Walks,
    colony_params,
    deposit_walks,
)
from pathzoo_aco.timed_colony import TimedProductColony

__all__ = ["AntColonySystem"]


class AntColonySystem(TimedProductColony):
    """Ant Colony System, Dorigo & Gambardella 1997, with its standard parameters."""

    id = "aco.acs"
    version = "1"
    summary = "Ant Colony System (Dorigo & Gambardella 1997): q0 exploitation, local and global-best updates"
    params = {
        **colony_params(n_ants=10, iterations=1000, alpha=1.0, beta=2.0, rho=0.1),
        "q0": Param(0.9, "probability of taking the best edge outright", low=0.0, high=1.0, tune=(0.0, 0.99)),
        "xi": Param(0.1, "local evaporation ξ: τ <- (1-ξ) τ + ξ τ0 on each crossed edge", low=0.0, high=1.0),
    }

    def walk_rules(self, problem: ColonyProblem) -> WalkRules:
        """Product rule with ``q0`` and the local update (``τ0`` is filled in by :meth:`init_state`)."""
        return WalkRules.product(self.alpha, self.heuristic(problem), self.beta, q0=self.q0,
                                 local_keep=1.0 - self.xi, **self.walk_options(problem))

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> ColonyState:
        """Compute ``τ0 = 1 / (n L_nn)`` from one greedy walk and start every trail at it.

        The greedy walk always takes the edge of largest heuristic (``q0 = 1``
        on a uniform trail) and counts as one evaluation; ``n`` is its number
        of edges. If it fails (step cap, unreachable goal), ``τ0 = 1``.
        """
        greedy = replace(rules, q0=1.0, local_keep=1.0, local_add=0.0)
        walk = engine.walk(greedy, Pheromone(trail.x.size, 1.0, on_nodes=trail.on_nodes), 1,
                           int(rng.integers(2**31 - 1)))
        length = float(walk.totals(problem.graph.length)[0])
        tau0 = 1.0 / (len(walk.edges(0)) * length) if np.isfinite(length) else 1.0
        trail.x[:] = tau0
        state = ColonyState(problem, replace(rules, local_add=self.xi * tau0), trail, rng)
        state.evaluations = walk.started
        return state

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Global update on the global-best walk only: ``τ <- (1 - ρ) τ + ρ / L_gb``."""
        if state.best_edges is None:
            return
        edges = state.best_edges
        deposit_walks(state.trail, state.problem.graph.indices, edges, np.array([0, len(edges)]), np.array([0]),
                      self.rho / state.best_cost, keep=1.0 - self.rho)
