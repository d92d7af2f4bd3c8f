"""aco.as: the Ant System of Dorigo, Maniezzo and Colorni (1996), ant-cycle version, on path-planning graphs.

Mechanism (all in :meth:`AntSystem.update_trail`): every ant walks by the
random-proportional rule ``p_ij ∝ τ_ij^α η_ij^β`` over its allowed
neighbours; after the colony, every trail evaporates, ``τ <- (1 - ρ) τ``, and
every ant ``k`` that reached the goal lays ``Q / L_k`` on each edge of its
walk. See ``docs/planners/aco.as.md``.
"""

from __future__ import annotations

import numpy as np

from pathzoo.core.planner import Param
from pathzoo_aco.engine import ColonyProblem, ColonyState, Walks, colony_params, deposit_walks
from pathzoo_aco.timed_colony import TimedProductColony

__all__ = ["AntSystem"]


class AntSystem(TimedProductColony):
    """Ant System (ant-cycle), Dorigo, Maniezzo & Colorni 1996, with its standard parameters."""

    id = "aco.as"
    version = "1"
    summary = "Ant System (Dorigo et al. 1996): every ant deposits Q/L on its walk"
    params = {
        **colony_params(n_ants=20, iterations=1000, alpha=1.0, beta=5.0, rho=0.5),
        "q": Param(100.0, "deposit constant Q (Δτ = Q / L_k)", low=0.0, low_open=True),
        "tau0": Param(1e-6, "initial trail c on every edge", low=0.0, low_open=True),
    }

    def initial_trail(self, problem: ColonyProblem) -> float:
        """The small constant ``c`` of the paper."""
        return self.tau0

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """``τ <- (1 - ρ) τ + Σ_k Q / L_k`` over the edges of each successful walk ``k``."""
        state.trail.evaporate(self.rho)
        ok = np.flatnonzero(walks.reached)
        deposit_walks(state.trail, state.problem.graph.indices, walks.flat, walks.offsets, ok, self.q / costs[ok])
