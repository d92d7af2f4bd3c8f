"""``exact.thetastar``: any-angle Theta* (Nash, Daniel, Koenig and Felner, AAAI 2007) on 2-D grids.

Theta* is A* on the 8-connected cell graph with one change: when a successor
``s'`` of the expanded node ``s`` can see ``parent(s)``, it is linked to
``parent(s)`` directly ("path 2", cost ``g(parent(s)) + |parent(s) s'|``);
otherwise it is linked to ``s`` as in A* ("path 1"). The heuristic is the
straight-line distance to the goal.

Interpretations:

- Vertices are cell *centres* (the paper uses cell corners); the successors
  of a node are its edges in ``scenario.graph``, so the first move obeys the
  same no-corner-cutting rule as every other planner.
- Line of sight is :func:`pathzoo.grid.segments.segment_blocked_2d`, the
  closed-cell rule the validator applies, so every returned segment validates.
- Path 2 is tried whenever the line of sight exists, as in the paper. By the
  triangle inequality it is never longer than path 1, so every relaxation is
  at least as good as A*'s; with the consistent straight-line heuristic this
  gives ``g(s) <=`` the 8-connected optimum for every expanded node, hence a
  returned length no longer than the grid optimum (not the true any-angle
  optimum, which Theta* does not guarantee).
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from pathzoo.core import Scenario
from pathzoo_exact.base import GraphSearchPlanner
from pathzoo_exact.answer import Batch, thetastar_answer
from pathzoo_exact.problem import H_EUCLID, search_problem

__all__ = ["ThetaStarPlanner"]


class ThetaStarPlanner(GraphSearchPlanner):
    """Any-angle Theta* on occupancy grids; minimises Euclidean path length.

    No hyperparameters. The path's waypoints are cell centres (plus the exact
    start and goal), joined by straight segments that touch no blocked cell.
    """

    id: ClassVar[str] = "exact.thetastar"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = "Theta* any-angle search (Nash et al. 2007); never longer than the grid optimum"
    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d"})

    def _make_batch(self, scenario: Scenario, target: int) -> Batch:
        graph = scenario.graph
        dims = np.array((1, *graph.shape), dtype=np.int64)
        steps = np.array([scenario.cell_size, scenario.cell_size, 0.0])
        problem = search_problem(target, dims, steps, H_EUCLID, 1.0)
        args = (graph.indptr, graph.indices, graph.length, scenario.blocked, *problem)
        return Batch(thetastar_answer, args, len(graph.offsets))
