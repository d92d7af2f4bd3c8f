"""aco.mmas: the MAX-MIN Ant System of Stützle and Hoos (2000) on path-planning graphs.

Mechanism (all in :meth:`MaxMinAntSystem.update_trail`): only one ant
deposits per iteration, the iteration-best or, every 25th iteration, the
global-best one (:func:`global_best_due`); every trail stays
within ``[τmin, τmax]`` with ``τmax = 1 / (ρ L_gb)`` and
``τmin = τmax (1 - p_best^(1/n)) / ((avg - 1) p_best^(1/n))``; trails start
above ``τmax`` and are clamped down to it once the first walk is known.
See ``docs/planners/aco.mmas.md``.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

from pathzoo.core.errors import InvalidParameterError
from pathzoo.core.planner import Param
from pathzoo_aco.engine import ColonyProblem, ColonyState, Walks, colony_params, deposit_walks
from pathzoo_aco.timed_colony import TimedProductColony

__all__ = ["MaxMinAntSystem", "global_best_due", "GLOBAL_BEST_PERIOD"]

GLOBAL_BEST_PERIOD = 25
"""Without local search the global-best ant deposits every 25th iteration, the iteration-best otherwise."""

_SCHEDULE = ((25, 25), (75, 5), (125, 3), (250, 2))
"""(last iteration, period of the global-best deposit) of the growing schedule; period 1 after iteration 250."""


def global_best_due(iteration: int, growing: bool = False) -> bool:
    """Whether the global-best ant deposits at this (1-based) iteration.

    Stützle & Hoos's reference implementation (ACOTSP) uses period 25 when ants
    do no local search, and the growing schedule of the FGCS article with it.
    """
    period = GLOBAL_BEST_PERIOD
    if growing:
        period = next((p for last, p in _SCHEDULE if iteration <= last), 1)
    return iteration % period == 0


class MaxMinAntSystem(TimedProductColony):
    """MAX-MIN Ant System, Stützle & Hoos 2000, with its standard parameters."""

    id = "aco.mmas"
    version = "1"
    summary = "MAX-MIN Ant System (Stützle & Hoos 2000): one best ant deposits, trails within [τmin, τmax]"
    params = {
        **colony_params(n_ants=20, iterations=1000, alpha=1.0, beta=2.0, rho=0.02),
        "p_best": Param(0.05, "probability that a converged colony rebuilds the best walk (sets τmin)",
                        low=0.0, high=1.0, low_open=True, high_open=True),
        "best_ant": Param("periodic", "which ant deposits: iteration-best with the global-best every 25th "
                          "iteration, the growing schedule, or always one kind",
                          choices=("periodic", "schedule", "iteration", "global")),
    }

    def _check_params(self, values: Mapping[str, Any]) -> None:
        if values["rho"] == 0.0:
            raise InvalidParameterError(f"{self.id}: parameter 'rho' must be > 0 (τmax = 1/(ρ L)), got 0.0")

    def initial_trail(self, problem: ColonyProblem) -> float:
        """``1 / (ρ L_lb)`` with ``L_lb`` the straight-line start-goal distance: at least any later ``τmax``."""
        return 1.0 / (self.rho * float(problem.goal_distance[problem.start]))

    def trail_limits(self, problem: ColonyProblem, best_edges: np.ndarray, best_length: float) -> tuple[float, float]:
        """``(τmin, τmax)`` from the best walk so far.

        ``n`` is the number of decisions (edges) of the best walk and ``avg``
        the mean number of neighbours of its nodes (the TSP's ``n/2`` has no
        counterpart on a grid); ``τmin`` never exceeds ``τmax``.
        """
        tau_max = 1.0 / (self.rho * best_length)
        g = problem.graph
        n = max(len(best_edges), 1)
        nodes = np.concatenate([[problem.start], g.indices[best_edges[:-1]]])
        avg = max(float(g.degree[nodes].mean()), 2.0)
        root = self.p_best ** (1.0 / n)
        tau_min = tau_max * (1.0 - root) / ((avg - 1.0) * root)
        return min(tau_min, tau_max), tau_max

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Evaporate, reset the bounds from the global best, and let one best ant deposit ``1 / L``."""
        trail = state.trail
        trail.evaporate(self.rho)
        if state.best_edges is None:
            return
        trail.set_bounds(*self.trail_limits(state.problem, state.best_edges, state.best_cost))
        use_global = self.best_ant == "global" or (
            self.best_ant in ("periodic", "schedule") and global_best_due(state.iteration, self.best_ant == "schedule"))
        if use_global or not np.isfinite(costs).any():
            edges, length = state.best_edges, state.best_cost
        else:
            k = int(np.argmin(costs))
            edges, length = walks.edges(k), float(costs[k])
        deposit_walks(trail, state.problem.graph.indices, edges, np.array([0, len(edges)]), np.array([0]),
                      1.0 / length)
