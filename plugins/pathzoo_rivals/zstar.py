"""``exact.zstar``: Z*, the constraint-aware energy-optimal search of Ganganath, Cheng and Tse (IEEE TII 2015).

Z* is A* on a grid elevation map whose edge cost is the energy a wheeled
robot spends on the edge and whose heuristic is a lower bound on the energy
left to the goal. Its contribution is the heuristic for goals *above* the
robot's climbing limit ``θ_M``: no straight path can reach such a goal, so
the bound assumes the cheapest zigzag, a path that climbs the height
difference ``Δh`` entirely at ``θ_M``.

Cost of a move of 3-D length ``L`` and slope ``θ`` (robot weight ``W = m g``,
friction coefficient ``μ``)::

    c = W L (μ cos θ + sin θ)   if θ_B < θ <= θ_M,  θ_B = -atan μ (braking angle)
        0                       if θ <= θ_B           (gravity pulls harder than friction)
        ∞                       if θ > θ_M            (the robot cannot climb it)

Heuristic from a node to the goal, with ``D`` the horizontal straight-line
distance, ``Δh`` the height difference and ``θ = atan(Δh / D)``::

    h = 0                                   if θ <= θ_B
        W (μ D + Δh)                        if θ_B < θ <= θ_M   (the straight line's cost)
        W Δh (μ cos θ_M + sin θ_M) / sin θ_M  if θ > θ_M        (zigzag at θ_M)

pathzoo's edge energy (``scenario.graph.energy``, eq. 4 of G-Ant, see
``docs/energy.md``) is this cost with ``μ`` = the vehicle's rolling
resistance ``f``, plus two terms the Z* model does not have: the internal
resistance ``C_I`` (inside the clipped traction term) and the onboard load
``b`` (outside it). :func:`zstar_heuristic` carries both into the bound so
that it stays admissible; with ``C_I = b = 0`` (every pack's default) it is
exactly the paper's heuristic. The derivation is in
``docs/planners/exact.zstar.md``.

The search itself, endpoints, connectors and budgets are the exact family's
(:class:`pathzoo_exact.base.GraphSearchPlanner`). A* with a consistent
heuristic ``h`` expands nodes in the same order as Dijkstra on the *reduced*
costs ``c(u, v) + h(v) - h(u)`` (non-negative by consistency), whose path sums
are the energies minus ``h(start)``; so Z* runs the exact family's numba
kernel with the zero heuristic on reduced costs (:func:`reduced_costs`) and
adds ``h(start)`` back to the goal's cost (only ties may be broken
differently, which never changes the optimal energy).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numba
import numpy as np

from pathzoo.core import Param, PlanResult, ProgressCallback, Scenario
from pathzoo_exact.base import GraphSearchPlanner, PreparedSearch
from pathzoo_exact.answer import Batch, astar_answer
from pathzoo_exact.problem import H_ZERO, grid_dims, search_problem

__all__ = ["ZStarPlanner", "zstar_heuristic", "zstar_edge_cost", "reduced_costs"]

SLOPE_SLACK = 1e-9
"""Relative slack on ``tan θ_M`` in the zigzag bound, so that an edge the graph admits at exactly
``θ_M`` (its slope rounded in floating point) never makes the bound exceed the true cost."""


def zstar_edge_cost(scenario: Scenario, max_climb_rad: float) -> np.ndarray:
    """Edge energies of ``scenario.graph`` (J), ``inf`` on edges steeper uphill than ``max_climb_rad``.

    The energy is :meth:`~pathzoo.core.vehicle.VehicleModel.segment_energy`,
    which is Z*'s ``W L (μ cos θ + sin θ)`` clipped at zero below the braking
    angle when ``C_I = b = 0``.
    """
    graph = scenario.graph
    cost = np.array(graph.energy, dtype=np.float64)
    cost[graph.slope > max_climb_rad] = np.inf
    return cost


def zstar_heuristic(scenario: Scenario, max_climb_rad: float, nodes: np.ndarray | None = None) -> np.ndarray:
    """Z*'s lower bound on the energy from each node's cell centre to the goal cell's centre (J).

    Every node's, or only those of ``nodes`` (the same values, element by element).

    ``H = max(D, Δh / tan θ_M)`` bounds the horizontal distance any feasible
    path drives (a path may climb at most ``tan θ_M`` metres per horizontal
    metre); the bound is ``max(0, W Δh + (f W + C_I) H) + b H / v``. With
    ``C_I = b = 0`` it reduces to the three cases of the module docstring.
    Blocked cells and cells without a height get 0 (they have no edges).
    """
    vehicle = scenario.vehicle
    shape = scenario.shape
    if nodes is None:
        nodes = np.arange(math.prod(shape))
    rows, cols = (np.asarray(axis, dtype=np.float64) for axis in np.unravel_index(nodes, shape))
    goal_r, goal_c = np.unravel_index(scenario.goal_node, shape)
    cs = scenario.cell_size
    horizontal = cs * np.hypot(rows - goal_r, cols - goal_c)
    if scenario.kind == "terrain":
        assert scenario.elevation is not None  # every terrain scenario has one
        z = scenario.elevation.reshape(-1)
        rise = float(z[scenario.goal_node]) - z[nodes]
    else:
        rise = np.zeros_like(horizontal)
    tan_max = math.tan(max_climb_rad) * (1.0 + SLOPE_SLACK) if max_climb_rad < math.pi / 2 else math.inf
    zigzag = np.where(rise > 0.0, rise / tan_max, 0.0)
    travel = np.maximum(horizontal, zigzag)
    w = vehicle.weight_n
    traction = np.maximum(w * rise + (vehicle.rolling_resistance * w + vehicle.internal_resistance_n) * travel, 0.0)
    h = traction + vehicle.onboard_power_w * travel / vehicle.cruise_speed
    return np.where(np.isfinite(h), h, 0.0)


def reduced_costs(scenario: Scenario, cost: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Edge costs ``c(u, v) + h(v) - h(u)``: Dijkstra on them is A* with ``h`` (``inf`` stays ``inf``).

    Consistency makes them non-negative up to rounding (at most about 1e-10
    of the edge costs on the pack's DEMs, see ``tests/rivals/test_zstar.py``).
    One compiled pass over the edges (:func:`_reduce`), without the edge-long
    temporaries of ``cost + h[indices] - h[sources]``, whose values it gives.
    """
    graph = scenario.graph
    return _reduce(graph.indptr, graph.indices, cost, h)


@numba.njit(cache=True)
def _reduce(indptr: np.ndarray, indices: np.ndarray, cost: np.ndarray, h: np.ndarray) -> np.ndarray:
    """``(cost[e] + h[v]) - h[u]`` for every edge ``e = (u, v)`` of the CSR graph ``indptr, indices``."""
    out = np.empty(cost.shape[0])
    for u in range(indptr.shape[0] - 1):
        hu = h[u]
        for e in range(indptr[u], indptr[u + 1]):
            out[e] = cost[e] + h[indices[e]] - hu
    return out


class ZStarPlanner(GraphSearchPlanner):
    """Z* (Ganganath, Cheng and Tse 2015): energy-optimal A* with the zigzag heuristic.

    Parameters
    ----------
    max_climb_deg : float
        The robot's climbing limit ``θ_M`` in degrees; the search uses the
        smaller of this and the scenario vehicle's ``max_climb_deg``.
    """

    id: ClassVar[str] = "exact.zstar"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = ("Z* (Ganganath, Cheng & Tse 2015): energy-optimal A* with a zigzag heuristic above "
                              "the climb limit")
    kinds: ClassVar[frozenset[str]] = frozenset({"terrain", "grid2d"})
    params = {
        "max_climb_deg": Param(90.0, "climbing limit θ_M in degrees (the scenario vehicle's limit applies too)",
                               low=0.0, high=90.0, low_open=True),
    }

    def _cost_kind(self) -> str:
        return "energy"

    def max_climb_rad(self, scenario: Scenario) -> float:
        """``θ_M``: the smaller of the parameter and the vehicle's climb limit, in radians."""
        return math.radians(min(float(self.max_climb_deg), scenario.vehicle.max_climb_deg))

    def _make_batch(self, scenario: Scenario, target: int) -> Batch:
        graph = scenario.graph
        theta_m = self.max_climb_rad(scenario)
        weights = reduced_costs(scenario, zstar_edge_cost(scenario, theta_m), zstar_heuristic(scenario, theta_m))
        dims = grid_dims(graph.shape)
        args = (graph.indptr, graph.indices, weights, *search_problem(target, dims, np.zeros(3), H_ZERO, 0.0))
        return Batch(astar_answer, args, len(graph.offsets))

    def _solved(
        self,
        scenario: Scenario,
        search: PreparedSearch,
        expanded: int,
        graph_cost: float,
        path: np.ndarray,
        progress: ProgressCallback | None,
    ) -> PlanResult:
        """Turn the goal's reduced cost back into energy (add ``h(start)``), then build the result as usual."""
        h = zstar_heuristic(scenario, self.max_climb_rad(scenario), np.array([scenario.start_node]))
        return super()._solved(scenario, search, expanded, graph_cost + float(h[0]), path, progress)
