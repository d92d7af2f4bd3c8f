"""aco.iaca: the improved ant colony algorithm for off-road paths of Wang et al. (2018), eqs. 13-21.

Mechanism, with the paper's equations:

- **grid pheromone**: the trail lives on cells, ``ph(i', j')``, not on edges;
- **tabu tables** (section 2): a move is NO GO when its slope leaves
  ``[-60°, 30°]`` (``G ∈ [-√3, √3/3]``) or when the target cell's soil is too
  weak, ``RCI <= VCI`` (:meth:`IACA.slope_tabu`, :meth:`IACA.soil_tabu`);
- **probability** (eqs. 13-14): roulette over ``ph^α H^β`` with
  ``H = J · gridW / (ΔD + Q)`` on GO moves and 0 on NO GO ones; ``gridW`` is
  the slope weight of Table 1 (``slopeW``) of the move (:meth:`IACA.heuristic`);
- **local update** (eq. 15): ``ph <- (1 - decr) ph`` on every cell an ant enters;
- **elite global update** (eqs. 16-17): on the cells of the iteration's
  shortest path, ``ph <- (1 - rou) ph + rou · K / min length``
  (:meth:`IACA.update_trail`);
- **clamps** (eq. 18): every value stays in ``[ph_min, ph_max]``;
- **distance** (eq. 21): a path's length is ``Σ l_k / slopeW_k``, with ``l_k``
  the Euclidean distance between terrain points in cells (:meth:`IACA.walk_costs`);
- ants that get stuck are dropped (eq. 20: only paths that end at the
  target count).

Section 4.1: ph0 = 0.4, α = 3, β = 4, J = 200, decr = 0.1, rou = 0.4,
K = 500, m = 40, NCmax = 100, ph_min = 0.001, ph_max = 0.8. See
``docs/planners/aco.iaca.md`` for every interpretation.
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

__all__ = ["IACA", "IacaState"]


@dataclass
class IacaState(ColonyState):
    """Colony state plus eq. 21's distance ``l / slopeW`` per edge."""

    edge_distance: np.ndarray | None = None


class IACA(AntColonyPlanner):
    """IACA (Wang et al. 2018) with the parameters of its section 4.1."""

    id = "aco.iaca"
    version = "1"
    summary = "IACA (Wang et al. 2018): grid pheromone, slope/soil tabu tables, slopeW heuristic and distance"
    kinds = frozenset({"terrain", "grid2d"})
    pheromone_on = "nodes"
    params = {
        **colony_params(n_ants=40, iterations=100, alpha=3.0, beta=4.0, rho=0.4, dead_end="die"),
        "j": Param(200.0, "coefficient J of gridW in H (eq. 14)", low=0.0, low_open=True),
        "decr": Param(0.1, "local volatility decr (eq. 15)", low=0.0, high=1.0),
        "k": Param(500.0, "constant K of the elite deposit K / min length (eq. 17)", low=0.0, low_open=True),
        "ph0": Param(0.4, "initial grid pheromone", low=0.0, low_open=True),
        "ph_min": Param(0.001, "lower pheromone bound (eq. 18)", low=0.0, low_open=True),
        "ph_max": Param(0.8, "upper pheromone bound (eq. 18)", low=0.0, low_open=True),
        "climb_deg": Param(30.0, "steepest GO climb of the slope tabu table (atan(√3/3))", low=0.0, high=90.0),
        "descent_deg": Param(60.0, "steepest GO descent of the slope tabu table (atan(√3))", low=0.0, high=90.0),
    }

    def _check_params(self, values: Mapping[str, Any]) -> None:
        if values["ph_min"] >= values["ph_max"]:
            raise InvalidParameterError(
                f"{self.id}: parameter 'ph_min' must be < ph_max ({values['ph_max']!r}), got {values['ph_min']!r}")

    # ------------------------------------------------------------- tables
    def slope_tabu(self, problem: ColonyProblem) -> np.ndarray:
        """Per edge: 1 when the move's slope is GO (``-descent_deg <= θ <= climb_deg``), else 0."""
        deg = np.degrees(problem.graph.slope)
        return ((deg <= self.climb_deg) & (deg >= -self.descent_deg)).astype(np.float64)

    @staticmethod
    def soil_tabu(problem: ColonyProblem) -> np.ndarray:
        """Per node: 1 when the soil carries the vehicle (``RCI > VCI``, all 1 without soil data), else 0."""
        rules = problem.scenario.rules
        if rules.soil_strength is None or rules.min_soil_strength is None:
            return np.ones(problem.n_nodes)
        return (np.asarray(rules.soil_strength, dtype=np.float64).ravel() > rules.min_soil_strength).astype(np.float64)

    @staticmethod
    def grid_weight(problem: ColonyProblem) -> np.ndarray:
        """Per edge: ``gridW = slopeW`` of the move's signed slope (Table 1; 1 without a table)."""
        return problem.scenario.rules.slope_weight(np.degrees(problem.graph.slope))

    @staticmethod
    def step(problem: ColonyProblem) -> np.ndarray:
        """Per edge: the Euclidean (3-D) distance between the two grid centres, in cells."""
        return problem.graph.length / problem.scenario.cell_size

    # ------------------------------------------------------------- choice
    def heuristic(self, problem: ColonyProblem) -> np.ndarray:
        """Eq. 14 per edge ``i -> j``: ``J · gridW / (ΔD + Q_j)`` on GO moves, 0 on NO GO ones.

        ``ΔD`` is the edge's Euclidean length and ``Q_j`` the straight distance
        from ``j`` to the target, both 3-D and in cells.
        """
        g = problem.graph
        to_goal = problem.goal_distance[g.indices] / problem.scenario.cell_size
        go = self.slope_tabu(problem) * self.soil_tabu(problem)[g.indices]
        return go * self.j * self.grid_weight(problem) / (self.step(problem) + to_goal)

    def walk_rules(self, problem: ColonyProblem) -> WalkRules:
        """Eqs. 13 and 15: ``ph^α H^β`` by roulette, and ``ph <- (1 - decr) ph`` on each entered cell."""
        return WalkRules.product(self.alpha, self.heuristic(problem), self.beta, local_keep=1.0 - self.decr,
                                 **self.walk_options(problem))

    # ------------------------------------------------------------- trail
    def initial_trail(self, problem: ColonyProblem) -> float:
        """``ph0`` on every cell."""
        return self.ph0

    def edge_distance(self, problem: ColonyProblem) -> np.ndarray:
        """Eq. 21 per edge: ``l / slopeW`` in cells (``inf`` where ``slopeW = 0``; ants never take those moves)."""
        weight = self.grid_weight(problem)
        with np.errstate(divide="ignore"):
            return np.where(weight > 0.0, self.step(problem) / weight, np.inf)

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> IacaState:
        """Eq. 18: clamp the trail to ``[ph_min, ph_max]``; precompute eq. 21's distance per edge."""
        trail.set_bounds(self.ph_min, self.ph_max)
        return IacaState(problem, rules, trail, rng, edge_distance=self.edge_distance(problem))

    def walk_costs(self, state: ColonyState, walks: Walks) -> np.ndarray:
        """Eq. 21: ``Dist = Σ l_k / slopeW_k`` in cells."""
        assert isinstance(state, IacaState) and state.edge_distance is not None
        return walks.totals(state.edge_distance)

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Eqs. 16-17 on the cells of the iteration's shortest path: ``ph <- (1 - rou) ph + rou · K / Dist_min``."""
        if not np.isfinite(costs).any():
            return
        k = int(np.argmin(costs))
        edges = walks.edges(k)
        deposit_walks(state.trail, state.problem.graph.indices, edges, np.array([0, len(edges)]), np.array([0]),
                      self.rho * self.k / float(costs[k]), keep=1.0 - self.rho)
