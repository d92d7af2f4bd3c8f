"""aco.ggaco: gain-based green ACO of Sangeetha & Ravichandran (2024/25), eqs. 11-18.

Mechanism, with the paper's equations:

- **gain** (eqs. 11-14): at the ant's node ``i``, every neighbour ``j`` has
  ``progress = d(j, D) / d(i, D)`` and ``Gain_ij = 1 / (1 + e^(-λ progress))``;
  the gain is *added* to the trail toward the neighbour nearest the
  destination ``D`` (all of them on a tie) and *subtracted* from the other
  trails (eq. 13) before the ant chooses: :meth:`GGACO.gain`;
- **transition** (eq. 15): ``τ^α η^β · n_j / (n_j + 1)``;
- **heuristic** (eqs. 16-17): ``η = 1 / d + v / φ`` with the slope-scaled
  distance ``d``: :meth:`GGACO.heuristic`;
- **deposit** (eq. 18): after evaporation with ``ρ = 0.4`` every ant that
  reached ``D`` lays ``1 / d_ij + 1 / E_ij`` on each edge it crossed:
  :meth:`GGACO.update_trail`.

See ``docs/planners/aco.ggaco.md`` for every interpretation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from pathzoo.core.planner import Param
from pathzoo.grid.graph_cache import release_pages
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
from pathzoo_aco.gant import ENERGY_FLOOR, PHI, green_heuristic

__all__ = ["GGACO", "GgacoState"]


@dataclass
class GgacoState(ColonyState):
    """Colony state plus the lengths, slopes and energies of the latest colony's walked edges.

    The colony's costs (eq. 6) and deposits (eq. 18) both need them.
    """

    geometry_of: Walks | None = None
    geometry: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None


class GGACO(AntColonyPlanner):
    """GGACO (Sangeetha & Ravichandran 2024/25) with ρ = 0.4 and G-Ant's Table 3 for the rest."""

    id = "aco.ggaco"
    version = "1"
    summary = "GGACO (Sangeetha & Ravichandran 2024): sigmoid gain toward the destination, energy deposits"
    kinds = frozenset({"grid2d", "terrain"})
    params = {
        **colony_params(n_ants=20, iterations=1000, alpha=0.4, beta=0.6, rho=0.4),
        "lam": Param(1.0, "λ of the gain sigmoid, 0 <= λ <= 1 (eqs. 12, 14)", low=0.0, high=1.0),
        "phi": PHI,
        "tau_floor": Param(1e-3, "lowest trail value (τ0 = 0 and the subtracted gains would reach 0 or less)",
                           low=0.0, low_open=True),
        "energy_floor_j": ENERGY_FLOOR,
        "objective": Param("energy", "which walk is best: least energy (eq. 6) or length (eq. 5)",
                           choices=("energy", "length")),
        "colony": Param("race", "ants race in lock step until the first reaches D (Algorithm 1), or each "
                        "ant walks to D", choices=("race", "complete")),
    }

    @staticmethod
    def slope_distance(problem: ColonyProblem, edges: slice = slice(None)) -> np.ndarray:
        """Eq. 17: ``d_ij = |V_i V_j| · (1 + |θ_ij|)``, the 3-D edge length scaled by the rise over run."""
        return problem.graph.length[edges] * (1.0 + problem.tangent_of(edges))

    def heuristic(self, problem: ColonyProblem, edges: slice = slice(None)) -> np.ndarray:
        """Eq. 16: ``η_ij = 1 / d_ij + v_ij / φ`` with ``v`` the vehicle's cruise speed."""
        return green_heuristic(self.slope_distance(problem, edges), problem.scenario.vehicle.cruise_speed, self.phi)

    def gain(self, problem: ColonyProblem, nodes: slice = slice(None)) -> np.ndarray:
        """Signed gain per edge (eqs. 11-14): ``+Gain_ij`` toward the neighbour(s) nearest ``D``, else ``-Gain_ij``.

        Distances to ``D`` are 3-D between cell centres; the neighbours are
        the node's graph neighbours (traversable ones). Returns the edges
        leaving ``nodes`` (a range of node ids), in graph order. The
        progress, the exponent and the signs are one compiled pass
        (:func:`_gain_exponent`); the exponential is NumPy's.
        """
        g = problem.graph
        lo, hi, _ = nodes.indices(g.n_nodes)
        exponent, nearest = _gain_exponent(g.indptr, g.indices, problem.goal_distance, lo, hi, -self.lam)
        gain = 1.0 / (1.0 + np.exp(exponent))
        return np.where(nearest, gain, -gain)

    def walk_rules(self, problem: ColonyProblem) -> WalkRules:
        """Eq. 15 with the pre-choice gain of eq. 13; ants race until the first reaches ``D`` (Algorithm 1).

        The product ``η^β · n_j / (n_j + 1)`` and the gains are built block by
        block of nodes (:meth:`ColonyProblem.node_blocks`) straight into the
        single-precision arrays the walks read, as :meth:`WalkRules.product`
        would build them whole, so no graph-sized double-precision temporary
        is needed, and the pages of a memory-mapped graph are let go block by
        block (:func:`pathzoo.grid.graph_cache.release_pages`).
        """
        g = problem.graph
        mul = np.empty(g.n_edges, dtype=np.float32)
        gain = np.empty(g.n_edges, dtype=np.float32)
        for nodes in problem.node_blocks():
            edges = slice(int(g.indptr[nodes.start]), int(g.indptr[nodes.stop]))
            mul[edges] = np.power(self.heuristic(problem, edges), self.beta) * self.neighbour_factor(problem, edges)
            gain[edges] = self.gain(problem, nodes)
            release_pages(g, edges)  # a memory-mapped graph's pages of this block are not read again
        return WalkRules(tau_exp=float(self.alpha), weight_mul=mul, pre_add=gain, race=self.colony == "race",
                         **self.walk_options(problem))

    def initial_trail(self, problem: ColonyProblem) -> float:
        """``τ0 = 0`` (section 3.2.2.2); reads are floored at ``tau_floor``."""
        return 0.0

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> ColonyState:
        """Floor the trail at ``tau_floor``."""
        trail.set_bounds(self.tau_floor)
        return GgacoState(problem, rules, trail, rng)

    @staticmethod
    def walked_geometry(state: GgacoState, walks: Walks) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """3-D lengths, slopes and energies (eq. 6) of the walked edges, computed once per colony.

        Lengths and slopes come from :meth:`ColonyProblem.walk_geometry`.
        """
        if state.geometry_of is not walks:
            length, slope = state.problem.walk_geometry(walks.flat, walks.offsets)
            energy = state.problem.scenario.vehicle.segment_energy(length, slope)
            state.geometry_of, state.geometry = walks, (length, slope, energy)
        assert state.geometry is not None  # set above, or by an earlier call on these walks
        return state.geometry

    @staticmethod
    def edge_energy(problem: ColonyProblem, edges: np.ndarray | slice) -> np.ndarray:
        """Eq. 6's energy (J) of the given edges: ``graph.energy[edges]`` without the graph-sized array."""
        g = problem.graph
        return problem.scenario.vehicle.segment_energy(g.length[edges], g.slope[edges])

    def edge_deposit(self, problem: ColonyProblem, edges: np.ndarray | slice = slice(None)) -> np.ndarray:
        """Eq. 18 per edge: ``1 / d_ij + 1 / E_ij``, for the given edges (all by default)."""
        g = problem.graph
        return self.deposit_of(problem, g.length[edges], g.slope[edges])

    def deposit_of(self, problem: ColonyProblem, length: np.ndarray, slope: np.ndarray,
                   energy: np.ndarray | None = None) -> np.ndarray:
        """Eq. 18 for edges of the given 3-D lengths and slopes (eq. 17's ``d``, eq. 6's ``E``, unless given)."""
        if energy is None:
            energy = problem.scenario.vehicle.segment_energy(length, slope)
        return 1.0 / (length * (1.0 + problem.tangent_from(slope))) + 1.0 / np.maximum(energy, self.energy_floor_j)

    def walk_costs(self, state: ColonyState, walks: Walks) -> np.ndarray:
        """Energy (J, eq. 6) or length (m, eq. 5) of each walk (computed for the walked edges only)."""
        assert isinstance(state, GgacoState)  # made by init_state
        if self.objective == "energy":
            return walks.sums(self.walked_geometry(state, walks)[2])
        return walks.totals(state.problem.graph.length)

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Eqs. 13 and 18: ``τ <- (1 - ρ) τ + Σ_k (1 / d_ij + 1 / E_ij)`` over the edges each successful ant crossed.

        The deposit is computed for the crossed edges only (no per-edge table
        is kept), from their cells (:meth:`ColonyProblem.walk_geometry`).
        """
        assert isinstance(state, GgacoState)  # made by init_state
        state.trail.evaporate(self.rho)
        ok = np.flatnonzero(walks.reached)
        deposit = self.deposit_of(state.problem, *self.walked_geometry(state, walks))
        deposit_walks(state.trail, state.problem.graph.indices, walks.flat, walks.offsets, ok, 0.0,
                      per_step=deposit)


@numba.njit(cache=True)
def _gain_exponent(indptr, indices, dist, lo, hi, minus_lam):
    """Per edge leaving nodes ``lo:hi``: eq. 12's exponent ``-λ progress`` and whether it leads to a nearest neighbour.

    ``progress = d(j, D) / d(i, D)`` (``d(i, D)`` taken as 1 at the
    destination itself, whose edges no ant takes); a neighbour is nearest
    when ``d(j, D)`` is within a relative 1e-12 of the node's least
    (``np.minimum``'s, NaN included).
    """
    first = indptr[lo]
    exponent = np.empty(indptr[hi] - first)
    nearest = np.empty(indptr[hi] - first, dtype=np.bool_)
    for i in range(lo, hi):
        here = dist[i]
        den = here if here > 0.0 else 1.0
        least = np.inf
        for e in range(indptr[i], indptr[i + 1]):
            to = dist[indices[e]]
            exponent[e - first] = minus_lam * (to / den)
            if to < least or math.isnan(to) or e == indptr[i]:
                least = to
        bound = least * (1.0 + 1e-12)
        for e in range(indptr[i], indptr[i + 1]):
            nearest[e - first] = dist[indices[e]] <= bound
    return exponent, nearest
