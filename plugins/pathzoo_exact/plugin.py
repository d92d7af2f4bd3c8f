"""The ``exact`` plugin: registers Dijkstra, A*, Theta* and the any-angle optimum through pathzoo's entry points."""

from __future__ import annotations

from typing import Sequence

from pathzoo.core import Planner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners"]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    """The exact reference planners ``exact.dijkstra``, ``exact.astar``, ``exact.thetastar`` and ``exact.anyangle``."""
    from pathzoo_exact.anyangle import AnyAnglePlanner
    from pathzoo_exact.astar import AStarPlanner
    from pathzoo_exact.dijkstra import DijkstraPlanner
    from pathzoo_exact.thetastar import ThetaStarPlanner

    return [DijkstraPlanner, AStarPlanner, ThetaStarPlanner, AnyAnglePlanner]
