"""``exact.astar``: A* on the scenario's neighbourhood graph, optimal for length or energy.

Heuristics (all admissible and consistent, so closing nodes on first
expansion is exact):

- ``grid2d`` and ``terrain``: the octile distance between the cells, in
  metres (``cell_size * (max(dx, dy) + (√2 - 1) min(dx, dy))``). It is the
  exact 8-connected distance on an empty flat grid, and a terrain edge's 3-D
  length is at least its horizontal length.
- ``air3d``: the 3-D Euclidean distance between the voxel centres; every edge
  is a straight segment between centres, so the triangle inequality gives
  consistency.
- ``cost="energy"``: the same distance times ``e_min``, the smallest energy
  per metre of 3-D length over all edges of the graph. Every edge costs at
  least ``e_min`` times its length, which is at least its horizontal (or
  Euclidean) length, so the scaled heuristic stays consistent. With no
  onboard load, steep descents cost zero traction energy, ``e_min`` is 0 and
  A* degrades gracefully to Dijkstra.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from pathzoo.core import Param, Scenario
from pathzoo.core.object_memo import ObjectMemo
from pathzoo.grid.graph import GridGraph
from pathzoo_exact.base import GraphSearchPlanner
from pathzoo_exact.answer import Batch, astar_answer, astar_moves_answer
from pathzoo_exact.problem import H_EUCLID, H_OCTILE, grid_dims, search_problem
from pathzoo_exact.moves import move_table

__all__ = ["AStarPlanner", "least_energy_per_metre"]

_E_MIN: "ObjectMemo[GridGraph, float]" = ObjectMemo()


def least_energy_per_metre(graph: GridGraph) -> float:
    """``e_min``: the smallest ``energy / length`` over the edges of ``graph`` (0 without edges).

    Computed on the first call for a graph (a pass over every edge, about
    10 ms on a 500 x 500 terrain) and kept while the graph lives.
    """
    return _E_MIN.value(graph, lambda: float(np.min(graph.energy / graph.length)) if graph.n_edges else 0.0)


class AStarPlanner(GraphSearchPlanner):
    """A* with an admissible, consistent heuristic (see the module docstring).

    Parameters
    ----------
    cost : {"length", "energy"}
        Edge cost minimised: ``scenario.graph.length`` (metres) or
        ``scenario.graph.energy`` (joules, eq. 4 of G-Ant per edge).
    """

    id: ClassVar[str] = "exact.astar"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = "A* on the 8-connected (air: max_step) cell graph; optimal length or energy"
    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d", "terrain", "air3d"})
    params = {
        "cost": Param("length", "edge cost minimised: 3-D length (m) or energy (J, G-Ant eq. 4)", choices=("length", "energy")),
    }

    def _cost_kind(self) -> str:
        return self.cost

    def _heuristic(self, scenario: Scenario) -> tuple[int, float]:
        """Heuristic mode and scale: octile (ground) or Euclidean (air) metres, times ``e_min`` for energy."""
        mode = H_EUCLID if scenario.kind == "air3d" else H_OCTILE
        if self.cost == "length":
            return mode, 1.0
        return mode, least_energy_per_metre(scenario.graph)

    def _make_batch(self, scenario: Scenario, target: int) -> Batch:
        """The move-table kernel when every move has one cost (flat grids), else the CSR kernel; both give the same result."""
        graph = scenario.graph
        dims = grid_dims(graph.shape)
        sizes = scenario.cell_sizes
        steps = np.array([sizes[0], sizes[1], sizes[2] if len(sizes) == 3 else 0.0])
        mode, scale = self._heuristic(scenario)
        problem = search_problem(target, dims, steps, mode, scale)
        table = move_table(graph, self.cost)
        if table is not None:
            moves = (table.mask, table.shift, table.weight, table.cell)
            return Batch(astar_moves_answer, (*moves, *problem), table.n_moves)
        csr = (graph.indptr, graph.indices, graph.weights(self.cost))
        return Batch(astar_answer, (*csr, *problem), len(graph.offsets))
