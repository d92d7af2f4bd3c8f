"""The ``exact`` plugin: declares Dijkstra, A*, Theta*, the any-angle optimum, 3-D Lazy Theta* and SIPP (imported when first built)."""

from __future__ import annotations

from typing import Sequence

from pathzoo.plugins.entries import LazyPlanner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners", "PLANNERS"]

_GRID_TERRAIN_AIR = frozenset({"air3d", "grid2d", "terrain"})

PLANNERS: tuple[LazyPlanner, ...] = (
    LazyPlanner("exact.dijkstra", "Dijkstra on the 8-connected (air: max_step) cell graph; optimal length or energy",
                "pathzoo_exact.dijkstra:DijkstraPlanner", kinds=_GRID_TERRAIN_AIR),
    LazyPlanner("exact.astar", "A* on the 8-connected (air: max_step) cell graph; optimal length or energy",
                "pathzoo_exact.astar:AStarPlanner", kinds=_GRID_TERRAIN_AIR),
    LazyPlanner("exact.thetastar", "Theta* any-angle search (Nash et al. 2007); never longer than the grid optimum",
                "pathzoo_exact.thetastar:ThetaStarPlanner", kinds=frozenset({"grid2d"}), path_model="anyangle"),
    LazyPlanner("exact.anyangle",
                "exact any-angle optimum (Polyanya on a rectangle mesh), pushed 1e-6 cells off obstacles",
                "pathzoo_exact.anyangle:AnyAnglePlanner", kinds=frozenset({"grid2d"}), path_model="anyangle"),
    LazyPlanner("exact.lazytheta3d", "Lazy Theta* in air volumes (Nash et al. 2010): a short any-angle path whose "
                "length bounds the any-angle optimum from above",
                "pathzoo_exact.lazytheta3d:LazyTheta3dPlanner", kinds=frozenset({"air3d"}), path_model="anyangle"),
    LazyPlanner("exact.sipp", "SIPP (Phillips & Likhachev 2011): earliest arrival on the 8-connected graph "
                "among the moving obstacles, waiting allowed",
                "pathzoo_exact.sipp:SippPlanner", kinds=frozenset({"dynamic"}), path_model="timed"),
)
"""The exact reference planners, declared without importing them."""


@hookimpl
def pathzoo_register_planners() -> Sequence[LazyPlanner]:
    """``exact.dijkstra``, ``exact.astar``, ``exact.thetastar``, ``exact.anyangle``, ``exact.lazytheta3d`` and ``exact.sipp`` (:data:`PLANNERS`)."""
    return PLANNERS
