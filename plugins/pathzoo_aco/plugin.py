"""The ``aco`` plugin: declares the ant-colony planners built on the shared engine (imported when first built)."""

from __future__ import annotations

from typing import Sequence

from pathzoo.plugins.entries import LazyPlanner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners", "PLANNERS"]

_GRID_TERRAIN_AIR = frozenset({"air3d", "grid2d", "terrain"})
_GRID_TERRAIN_AIR_DYNAMIC = frozenset({"air3d", "dynamic", "grid2d", "terrain"})
_GRID_TERRAIN = frozenset({"grid2d", "terrain"})
_GRID_DYNAMIC = frozenset({"dynamic", "grid2d"})

PLANNERS: tuple[LazyPlanner, ...] = (
    LazyPlanner("aco.as", "Ant System (Dorigo et al. 1996): every ant deposits Q/L on its walk",
                "pathzoo_aco.ant_system:AntSystem", kinds=_GRID_TERRAIN_AIR_DYNAMIC),
    LazyPlanner("aco.mmas",
                "MAX-MIN Ant System (Stützle & Hoos 2000): one best ant deposits, trails within [τmin, τmax]",
                "pathzoo_aco.mmas:MaxMinAntSystem", kinds=_GRID_TERRAIN_AIR_DYNAMIC),
    LazyPlanner("aco.acs",
                "Ant Colony System (Dorigo & Gambardella 1997): q0 exploitation, local and global-best updates",
                "pathzoo_aco.acs:AntColonySystem", kinds=_GRID_TERRAIN_AIR_DYNAMIC),
    LazyPlanner("aco.ggaco",
                "GGACO (Sangeetha & Ravichandran 2024): sigmoid gain toward the destination, energy deposits",
                "pathzoo_aco.ggaco:GGACO", kinds=_GRID_TERRAIN),
    LazyPlanner("aco.gant",
                "G-Ant (Jabbarpour et al. 2017): additive rule, travel-time and predicted-energy deposits",
                "pathzoo_aco.gant:GreenAnt", kinds=_GRID_TERRAIN),
    LazyPlanner("aco.fgdaco",
                "FGDACO (Sangeetha et al. 2021): fuzzy node priority, sigmoid gain, timed walks among moving "
                "obstacles",
                "pathzoo_aco.fgdaco:FGDACO", kinds=_GRID_DYNAMIC),
    LazyPlanner("aco.dsaco",
                "DSACO (Mai et al. 2023): S·M·D heuristic, q0 schedule, best-ant fitness update, p decay",
                "pathzoo_aco.dsaco:DSACO", kinds=frozenset({"air3d", "grid2d"})),
    LazyPlanner("aco.iaca",
                "IACA (Wang et al. 2018): grid pheromone, slope/soil tabu tables, slopeW heuristic and distance",
                "pathzoo_aco.iaca:IACA", kinds=_GRID_TERRAIN),
    LazyPlanner("aco.flaco",
                "FLACO after Song et al. 2020 (abstract only): rank-based ant system on a fuzzy virtual length; "
                "the fuzzy rule base is pathzoo's",
                "pathzoo_aco.flaco:FLACO", kinds=_GRID_DYNAMIC),
    LazyPlanner("aco.aco_astar",
                "ACO-A* (Yu et al. 2018) on one-target missions: the ACO layer only orders targets, so this is "
                "its A* leg (3-D length, admissible heuristic)",
                "pathzoo_aco.aco_astar:AcoAStar", kinds=_GRID_TERRAIN_AIR),
)
"""Every ant-colony planner of this family, declared without importing it."""


@hookimpl
def pathzoo_register_planners() -> Sequence[LazyPlanner]:
    """Every ant-colony planner of this family (:data:`PLANNERS`)."""
    return PLANNERS
