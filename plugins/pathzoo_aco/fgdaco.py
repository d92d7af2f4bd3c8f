"""aco.fgdaco: fuzzy gain-based dynamic ACO of Sangeetha et al. (Symmetry, 2021), eqs. 1-15.

Mechanism, with the paper's equations:

- **fuzzy priority** (eqs. 1-2, 11-13, Tables 3-4): a Mamdani inference
  turns three normalised inputs of a candidate node ``j`` -- its distance to
  the target, the heading change to reach it, its distance to the nearest
  obstacle -- into
  its priority, the heuristic ``η`` of eq. 10 (:mod:`pathzoo_aco.fgdaco_fuzzy`,
  :meth:`FGDACO.fuzzy_inputs`);
- **transition** (eq. 10): ``τ_ij^α η_j^β`` by roulette over the nodes not in
  the ant's tabu list;
- **moving obstacles**: on ``dynamic`` scenarios each ant keeps time at the
  vehicle's cruise speed, never takes an edge a moving obstacle would hit
  while it is driven, and feeds the obstacle's distance at its arrival time
  into the fuzzy inference (:mod:`pathzoo_aco.fgdaco_walk`);
- **update** (eq. 9): ``τ <- (1 - ρ) τ + Σ_k Δτ^k ± Gain``, with
  ``Δτ_ij = 1 / d_ij + d_io`` on every edge of every ant that reached the
  target (eq. 15) and, for every node ``i`` such an ant left, the sigmoid
  gain of eq. 14 added to the edge toward the neighbour nearest the target
  (farthest from obstacles on a tie) and subtracted from ``i``'s other edges
  (:meth:`FGDACO.update_trail`, :meth:`FGDACO.signed_gain`).

Table 6: α = β = ρ = 0.5, 20 ants, 100 iterations. See
``docs/planners/aco.fgdaco.md`` for every interpretation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

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
from pathzoo_aco.fgdaco_fuzzy import fuzzy_priority

__all__ = ["FGDACO", "FgdacoState", "FuzzyInputs"]


@dataclass(frozen=True)
class FuzzyInputs:
    """The normalised inputs of the fuzzy inference, static part.

    Attributes
    ----------
    target : ndarray, shape (N,)
        Per node: straight-line distance to the goal over the start's, clipped to 1.
    angle : ndarray, shape (E,)
        Per edge ``i -> j``: angle between the move and the bearing from ``i``
        to the goal, over π.
    obstacle : ndarray, shape (N,)
        Per node: distance to the nearest static obstacle (``scenario.clearance``)
        over the sensing range, clipped to 1.
    """

    target: np.ndarray
    angle: np.ndarray
    obstacle: np.ndarray


@dataclass
class FgdacoState(ColonyState):
    """Colony state plus the per-edge deposit of eq. 15 and the signed gain of eq. 14 (both static).

    ``left`` is :func:`_add_gains`' scratch space (per node, how many walks left it).
    """

    deposit: np.ndarray | None = None
    gain: np.ndarray | None = None
    left: np.ndarray | None = None


@numba.njit(cache=True)
def _add_gains(x, scale, lo, hi, indptr, indices, flat, offsets, ants, start, gain, left):
    """Add ``gain[e]`` to every edge ``e`` leaving each node the walks ``ants`` left, once per walk that left it.

    Each update is the clamped read-modify-write of :func:`~pathzoo_aco.engine.deposit_walks`:
    ``x[e] = clip(clip(scale x[e]) + gain[e]) / scale``. Walks are simple paths, so an edge gets one
    update per walk that left its node, and every update of an edge is the same function of its
    value: applying them edge by edge (``left[i]`` times for node ``i``) rather than walk by walk
    gives the same numbers with one pass over the touched nodes.

    When ``scale`` is a power of two (``ρ = 0.5``), dividing by it equals multiplying by its inverse,
    and reading a stored value back (``scale (t / scale)``) gives ``t`` itself, exactly, as long as
    ``t / scale`` is a finite normal number: an edge's value then stays in a register for its
    ``left[i]`` updates and is stored once. An edge resting on the floor ``lo`` that loses (``gain[e]
    <= 0``) stays there and is not written (its stored value may lie below the floor: reads clamp,
    so its true value is ``lo`` either way). ``left`` (one int32 per node, all zero) is scratch space
    and is left zero.
    """
    for i in range(ants.size):
        a = ants[i]
        node = start
        for p in range(offsets[a], offsets[a + 1]):
            left[node] += 1
            node = indices[flat[p]]
    inverse = 1.0 / scale
    exact_inverse = math.frexp(scale)[0] == 0.5
    in_register = exact_inverse and lo * inverse >= 2.2250738585072014e-308  # every stored t / scale is normal
    for node in range(left.size):
        m = left[node]
        if m == 0:
            continue
        left[node] = 0
        for e in range(indptr[node], indptr[node + 1]):
            g = gain[e]
            t = min(max(scale * x[e], lo), hi)
            if g <= 0.0 and t <= lo:
                continue
            if in_register and (t + m * max(g, 0.0)) * inverse < 1e300:  # a bound on every value t takes
                for _ in range(m):
                    t = min(max(t + g, lo), hi)
                x[e] = t * inverse
            else:
                for _ in range(m):
                    t = min(max(min(max(scale * x[e], lo), hi) + g, lo), hi)
                    x[e] = t * inverse if exact_inverse else t / scale


class FGDACO(AntColonyPlanner):
    """FGDACO (Sangeetha et al. 2021) with the parameters of its Table 6."""

    id = "aco.fgdaco"
    version = "1"
    summary = "FGDACO (Sangeetha et al. 2021): fuzzy node priority, sigmoid gain, timed walks among moving obstacles"
    kinds = frozenset({"dynamic", "grid2d"})
    params = {
        **colony_params(n_ants=20, iterations=100, alpha=0.5, beta=0.5, rho=0.5),
        "lam": Param(1.0, "λ of the gain sigmoid, 0 <= λ <= 1 (eq. 14)", low=0.0, high=1.0),
        "sensing_m": Param(10.0, "distance that normalises obstacle distances to [0, 1], m", low=0.0, low_open=True),
        "tau_floor": Param(1e-3, "lowest trail value (τ0 = 0 and the subtracted gains would reach 0 or less)",
                           low=0.0, low_open=True),
    }

    # ------------------------------------------------------------- inputs
    def fuzzy_inputs(self, problem: ColonyProblem) -> FuzzyInputs:
        """Normalised target distance (per node), angle to be turned (per edge), static obstacle distance (per node).

        Computed once per scenario and configuration (:meth:`ColonyProblem.memo`).
        """
        return problem.memo(self.table_key("fuzzy_inputs"), lambda: self._fuzzy_inputs(problem))

    def _fuzzy_inputs(self, problem: ColonyProblem) -> FuzzyInputs:
        s = problem.scenario
        g = problem.graph
        xy = problem.node_xyz[:, :2]
        to_goal = problem.goal_distance
        target = np.minimum(to_goal / max(float(to_goal[problem.start]), 1e-12), 1.0)
        move = xy[g.indices] - xy[problem.sources]
        bearing = xy[problem.goal] - xy[problem.sources]
        # |move| |bearing|, as np.linalg.norm(., axis=1) computes them (square, add, sqrt) without its slow reduction
        norm = np.sqrt(move[:, 0] * move[:, 0] + move[:, 1] * move[:, 1]) * np.sqrt(
            bearing[:, 0] * bearing[:, 0] + bearing[:, 1] * bearing[:, 1])
        with np.errstate(invalid="ignore", divide="ignore"):
            cos = np.where(norm > 0, np.einsum("ij,ij->i", move, bearing) / norm, 1.0)
        angle = np.arccos(np.clip(cos, -1.0, 1.0)) / np.pi
        obstacle = np.minimum(s.clearance.ravel() / self.sensing_m, 1.0)
        return FuzzyInputs(target, angle, obstacle)

    def heuristic(self, problem: ColonyProblem) -> np.ndarray:
        """``η_ij``: the fuzzy priority of node ``j`` reached by the move ``i -> j`` (eqs. 10-13, static obstacles)."""
        inp = self.fuzzy_inputs(problem)
        return fuzzy_priority(inp.target, inp.angle, inp.obstacle, nodes=problem.graph.indices)

    def walk_rules(self, problem: ColonyProblem) -> WalkRules:
        """Eq. 10: ``τ^α η^β`` with roulette choice."""
        return WalkRules.product(self.alpha, self.heuristic(problem), self.beta, **self.walk_options(problem))

    def walk_engine(self, problem: ColonyProblem) -> WalkEngine:
        """Timed walks (:class:`~pathzoo_aco.fgdaco_walk.TimedWalkEngine`) when the scenario has moving obstacles."""
        if not problem.scenario.moving_obstacles:
            return WalkEngine(problem)
        from pathzoo_aco.fgdaco_walk import TimedWalkEngine

        inp = self.fuzzy_inputs(problem)
        return TimedWalkEngine(problem, target_in=inp.target, angle_in=inp.angle, clear_in=inp.obstacle,
                               sensing_m=self.sensing_m, beta=self.beta)

    # ------------------------------------------------------------- trail
    def signed_gain(self, problem: ColonyProblem, inputs: FuzzyInputs) -> np.ndarray:
        """Eq. 14 per edge ``i -> j``: ``+Gain_ij`` toward ``i``'s best neighbour, ``-Gain_ij`` toward the others.

        ``Gain_ij = 1 / (1 + exp(-λ progress))`` with
        ``progress = (δ_j + d_io) / δ_i``, ``δ`` the normalised distance to the
        target and ``d_io`` the normalised obstacle distance of ``i``. The
        best neighbour has the least ``δ_j``, and among equals the largest
        obstacle distance (all of them if still tied).
        """
        g = problem.graph
        src = problem.sources
        delta_j = inputs.target[g.indices]
        delta_i = inputs.target[src]
        with np.errstate(divide="ignore", invalid="ignore"):
            progress = np.where(delta_i > 0.0, (delta_j + inputs.obstacle[src]) / delta_i, np.inf)
        gain = 1.0 / (1.0 + np.exp(-self.lam * progress))
        rows = g.indptr[:-1][g.degree > 0]
        nearest = np.full(g.n_nodes, np.inf)
        nearest[g.degree > 0] = np.minimum.reduceat(delta_j, rows) if rows.size else nearest[:0]
        closest = delta_j <= nearest[src] + 1e-12
        clear_j = np.where(closest, inputs.obstacle[g.indices], -np.inf)
        widest = np.full(g.n_nodes, -np.inf)
        widest[g.degree > 0] = np.maximum.reduceat(clear_j, rows) if rows.size else widest[:0]
        best = closest & (clear_j >= widest[src] - 1e-12)
        return np.where(best, gain, -gain)

    def initial_trail(self, problem: ColonyProblem) -> float:
        """``τ0 = 0`` (section 3.4.2); reads are floored at ``tau_floor``."""
        return 0.0

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> FgdacoState:
        """Floor the trail and compute eq. 15's ``1 / d_ij + d_io`` and eq. 14's signed gain per edge."""
        trail.set_bounds(self.tau_floor)
        inputs = self.fuzzy_inputs(problem)
        deposit, gain = problem.memo(self.table_key("deposit_gain"), lambda: (
            1.0 / problem.graph.length + inputs.obstacle[problem.sources], self.signed_gain(problem, inputs)))
        return FgdacoState(problem, rules, trail, rng, deposit=deposit, gain=gain,
                           left=np.zeros(problem.graph.n_nodes, dtype=np.int32))

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Eq. 9: evaporate, add eq. 15's deposits along every successful walk, then the signed gains of its nodes."""
        assert isinstance(state, FgdacoState) and state.deposit is not None and state.gain is not None
        assert state.left is not None
        g = state.problem.graph
        state.trail.evaporate(self.rho)
        ok = np.flatnonzero(walks.reached)
        if ok.size == 0:
            return
        deposit_walks(state.trail, g.indices, walks.flat, walks.offsets, ok, 0.0, per_edge=state.deposit)
        t = state.trail
        _add_gains(t.x, t.scale, t.lo, t.hi, g.indptr, g.indices, walks.flat, walks.offsets, ok,
                   state.problem.start, state.gain, state.left)
