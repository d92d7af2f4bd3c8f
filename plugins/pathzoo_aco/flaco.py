"""aco.flaco: fuzzy-logic ant colony optimisation after Song et al. (IEEE Access 2020), rebuilt from its abstract.

What the abstract states, and where it sits here:

- **rank-based ant system** (Bullnheimer, Hartl & Strauss 1999): after each
  colony every trail evaporates, ``τ <- (1 - ρ) τ``; the ``w - 1`` best ants
  of the colony lay ``(w - μ) Q / L_μ`` (rank ``μ = 1 .. w-1``) and the
  best-so-far walk lays ``w Q / L*`` (:meth:`FLACO.update_trail`,
  :func:`rank_deposits`);
- **fuzzy logic for dynamic factors, giving a virtual path length**: each
  edge ``i -> j`` counts ``ℓ_ij (1 + κ c_j)`` with ``c_j`` the fuzzy
  impedance of ``j`` (:mod:`pathzoo_aco.flaco_fuzzy`, pathzoo's own rule
  base); ants are ranked by this virtual length and the heuristic is
  ``η_ij = 1 / (ℓ'_ij + d(j, goal))`` (:meth:`FLACO.virtual_lengths`).

On ``dynamic`` scenarios ants keep time and never take an edge a moving
obstacle would hit while it is driven (the timed walks of
:class:`pathzoo_aco.fgdaco_walk.TimedWalkEngine`, used with static weights
only). See ``docs/planners/aco.flaco.md`` for what is reconstructed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from pathzoo.core.errors import InvalidParameterError
from pathzoo.core.planner import Param
from pathzoo_aco.engine import (
    AntColonyPlanner,
    ColonyProblem,
    ColonyState,
    Pheromone,
    WalkEngine,
    WalkRules,
    Walks,
    colony_params,
    deposit_walks,
)
from pathzoo_aco.flaco_fuzzy import impedance, traffic_share

__all__ = ["FLACO", "FlacoState", "rank_deposits"]


def rank_deposits(costs: np.ndarray, reached: np.ndarray, w: int, q: float) -> tuple[np.ndarray, np.ndarray]:
    """The ranked ants of one colony and their deposits ``(w - μ) q / L_μ`` for ranks μ from 1 to w - 1.

    Parameters
    ----------
    costs : ndarray, shape (m,)
        Virtual length of each walk.
    reached : ndarray of bool, shape (m,)
        Which walks reached the goal (only they are ranked).
    w : int
        Rank-based weight (number of elitist ants, best-so-far included).
    q : float
        Deposit constant.

    Returns
    -------
    ants, amounts : ndarray
        Indices of the ranked ants, best first (at most ``w - 1``; ties keep
        the ant order), and what each lays on every edge of its walk.
    """
    ok = np.flatnonzero(reached)
    ranked = ok[np.argsort(costs[ok], kind="stable")][: max(w - 1, 0)]
    mu = np.arange(1, ranked.size + 1)
    return ranked, (w - mu) * q / costs[ranked]


@dataclass
class FlacoState(ColonyState):
    """Colony state plus the per-edge virtual length ``ℓ'``."""

    virtual: np.ndarray | None = None


class FLACO(AntColonyPlanner):
    """FLACO after Song and co-authors (2020): rank-based ant system on fuzzy virtual lengths.

    See the module docstring and ``docs/planners/aco.flaco.md``.
    """

    id = "aco.flaco"
    version = "1"
    summary = ("FLACO after Song et al. 2020 (abstract only): rank-based ant system on a fuzzy virtual length; "
               "the fuzzy rule base is pathzoo's")
    kinds = frozenset({"dynamic", "grid2d"})
    params = {
        **colony_params(n_ants=20, iterations=100, alpha=1.0, beta=2.0, rho=0.1),
        "w": Param(6, "rank-based weight w: the w-1 best ants and the best-so-far deposit", low=1),
        "q": Param(1.0, "deposit constant Q", low=0.0, low_open=True),
        "kappa": Param(1.0, "weight κ of the fuzzy impedance in the virtual length ℓ (1 + κ c)", low=0.0),
        "sensing_m": Param(10.0, "distance that normalises obstacle distances to [0, 1], m", low=0.0,
                           low_open=True),
    }

    def _check_params(self, values: Mapping[str, Any]) -> None:
        if values["rho"] == 0.0:
            raise InvalidParameterError(f"{self.id}: parameter 'rho' must be > 0 (τ0 = ... / (ρ L)), got 0.0")

    # ------------------------------------------------------------- lengths
    def node_impedance(self, problem: ColonyProblem) -> np.ndarray:
        """Fuzzy impedance ``c_j`` per node from moving-obstacle traffic and static clearance."""
        s = problem.scenario
        clearance = np.minimum(s.clearance.ravel() / self.sensing_m, 1.0)
        traffic = traffic_share(problem.node_xyz[:, :2], s.moving_obstacles, self.sensing_m)
        return impedance(traffic, clearance)

    def virtual_lengths(self, problem: ColonyProblem) -> np.ndarray:
        """Per edge ``i -> j``: ``ℓ_ij (1 + κ c_j)``."""
        g = problem.graph
        return g.length * (1.0 + self.kappa * self.node_impedance(problem)[g.indices])

    def heuristic(self, problem: ColonyProblem) -> np.ndarray:
        """``η_ij = 1 / (ℓ'_ij + d(j, goal))``: the engine's path-planning heuristic on virtual lengths."""
        return 1.0 / (self.virtual_lengths(problem) + problem.goal_distance[problem.graph.indices])

    def walk_engine(self, problem: ColonyProblem) -> WalkEngine:
        """Timed walks that refuse edges a moving obstacle would hit, when the scenario has moving obstacles.

        The timed engine re-weighs an edge only when a moving obstacle is
        nearer to its head than the static clearance it is given; with a
        clearance of 0 everywhere that never happens, so the weights stay
        ``τ^α η^β`` with FLACO's own ``η``.
        """
        from pathzoo_aco.fgdaco_walk import timed_product_engine

        return timed_product_engine(problem, self.beta, self.sensing_m)

    # ------------------------------------------------------------- trail
    def initial_trail(self, problem: ColonyProblem) -> float:
        """``τ0 = w (w - 1) / (2 ρ L)``, ``L`` the straight start-goal distance (ASrank's rule, L_nn replaced).

        With ``w = 1`` (no ranked ants) the numerator is taken as 1 so that trails start above 0.
        """
        length = max(float(problem.goal_distance[problem.start]), 1e-12)
        return max(self.w * (self.w - 1), 1) / (2.0 * self.rho * length)

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> FlacoState:
        """Keep the virtual lengths for ranking the walks."""
        return FlacoState(problem, rules, trail, rng, virtual=self.virtual_lengths(problem))

    def walk_costs(self, state: ColonyState, walks: Walks) -> np.ndarray:
        """Virtual length of each walk (``inf`` if it failed)."""
        assert isinstance(state, FlacoState) and state.virtual is not None
        return walks.totals(state.virtual)

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Evaporate; the ``w - 1`` best ants lay ``(w - μ) Q / L_μ``, the best-so-far walk ``w Q / L*``."""
        indices = state.problem.graph.indices
        state.trail.evaporate(self.rho)
        ants, amounts = rank_deposits(costs, walks.reached, self.w, self.q)
        if ants.size:
            deposit_walks(state.trail, indices, walks.flat, walks.offsets, ants, amounts)
        if state.best_edges is not None:
            edges = state.best_edges
            deposit_walks(state.trail, indices, edges, np.array([0, len(edges)]), np.array([0]),
                          self.w * self.q / state.best_cost)
