"""``exact.dijkstra``: Dijkstra's algorithm on the scenario's neighbourhood graph.

It is the A* search of :mod:`pathzoo_exact.astar` with the zero heuristic,
run by the same numba kernel, and stops as soon as the goal cell is expanded.
"""

from __future__ import annotations

from typing import ClassVar

from pathzoo.core import Scenario
from pathzoo_exact.astar import AStarPlanner
from pathzoo_exact.problem import H_ZERO

__all__ = ["DijkstraPlanner"]


class DijkstraPlanner(AStarPlanner):
    """Dijkstra's algorithm: A* with ``h = 0``.

    Parameters
    ----------
    cost : {"length", "energy"}
        Edge cost minimised: ``scenario.graph.length`` (metres) or
        ``scenario.graph.energy`` (joules, eq. 4 of G-Ant per edge).
    """

    id: ClassVar[str] = "exact.dijkstra"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = "Dijkstra on the 8-connected (air: max_step) cell graph; optimal length or energy"

    def _heuristic(self, scenario: Scenario) -> tuple[int, float]:
        return H_ZERO, 0.0
