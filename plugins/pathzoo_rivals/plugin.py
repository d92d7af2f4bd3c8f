"""The ``rivals`` plugin: declares the non-ant rivals of the papers' tables (imported when first built)."""

from __future__ import annotations

from typing import Sequence

from pathzoo.plugins.entries import LazyPlanner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners", "PLANNERS"]

_GRID_TERRAIN = frozenset({"grid2d", "terrain"})

PLANNERS: tuple[LazyPlanner, ...] = (
    LazyPlanner("exact.zstar",
                "Z* (Ganganath, Cheng & Tse 2015): energy-optimal A* with a zigzag heuristic above the climb limit",
                "pathzoo_rivals.zstar:ZStarPlanner", kinds=_GRID_TERRAIN),
    LazyPlanner("swarm.mosfla",
                "MOSFLA after Hidalgo-Paniagua et al. 2015 (reconstructed): shuffled frog-leaping on waypoint "
                "routes, objectives length, safety, smoothness",
                "pathzoo_rivals.mosfla:MosflaPlanner", kinds=_GRID_TERRAIN),
    LazyPlanner("search.movns",
                "MOVNS after Hidalgo-Paniagua et al. 2016 (reconstructed): multi-objective VNS on waypoint routes, "
                "objectives length, safety, smoothness",
                "pathzoo_rivals.movns:MovnsPlanner", kinds=_GRID_TERRAIN),
)
"""``exact.zstar`` and the reconstructions ``swarm.mosfla`` and ``search.movns``, declared without importing them."""


@hookimpl
def pathzoo_register_planners() -> Sequence[LazyPlanner]:
    """The rivals (:data:`PLANNERS`)."""
    return PLANNERS
