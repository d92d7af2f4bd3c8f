"""The ``baselines`` plugin: declares the metaheuristic baselines, pure and hybrid (imported when first built)."""

from __future__ import annotations

from typing import Sequence

from pathzoo.plugins.entries import LazyPlanner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners", "PLANNERS"]

_ALL = frozenset({"grid2d", "terrain", "dynamic", "air3d"})
_GRID_TERRAIN = frozenset({"grid2d", "terrain"})
_EVO = {"deap": "evo"}

PLANNERS: tuple[LazyPlanner, ...] = (
    LazyPlanner("swarm.pso", "Particle swarm optimisation (pyswarms) of K straight-segment waypoints, no graph search",
                "pathzoo_baselines.pso:PsoPlanner", kinds=_ALL, requires={"pyswarms": "evo"}, path_model="anyangle"),
    LazyPlanner("swarm.cuckoo", "Cuckoo search (Yang & Deb) with Mantegna Lévy flights over K straight-segment waypoints",
                "pathzoo_baselines.cuckoo:CuckooPlanner", kinds=_ALL, path_model="anyangle"),
    LazyPlanner("swarm.coa",
                "Cuckoo Optimization Algorithm (Rajabioun 2011; FGDACO's COA) over K straight-segment waypoints",
                "pathzoo_baselines.coa:CoaPlanner", kinds=_ALL, path_model="anyangle"),
    LazyPlanner("evo.ga", "Genetic algorithm (DEAP) over K straight-segment waypoints (or grid moves), no graph search",
                "pathzoo_baselines.ga:GaPlanner", kinds=_ALL, requires=_EVO, path_model="anyangle"),
    LazyPlanner("evo.fuzzy_rate_ga",
                "GA whose crossover/mutation rates a fuzzy controller sets (our design; DEAP + scikit-fuzzy)",
                "pathzoo_baselines.fuzzy_rate_ga:FuzzyRateGaPlanner", kinds=_ALL, requires=_EVO, path_model="anyangle"),
    LazyPlanner("swarm.pso_astar",
                "PSO over K waypoints joined by A* grid routes where a straight segment is blocked",
                "pathzoo_baselines.hybrids:PsoAstarPlanner", kinds=_GRID_TERRAIN, requires={"pyswarms": "evo"},
                hybrid=True, path_model="anyangle"),
    LazyPlanner("swarm.cuckoo_astar",
                "Cuckoo search over K waypoints joined by A* grid routes where a segment is blocked",
                "pathzoo_baselines.hybrids:CuckooAstarPlanner", kinds=_GRID_TERRAIN, hybrid=True,
                path_model="anyangle"),
    LazyPlanner("evo.ga_astar",
                "GA over feasible cell chains whose operators reroute by A* (or A*-routed waypoints)",
                "pathzoo_baselines.hybrids:GaAstarPlanner", kinds=_GRID_TERRAIN, requires=_EVO, hybrid=True),
    LazyPlanner("evo.fuzzy_rate_ga_astar",
                "Fuzzy-rate GA over feasible cell chains whose operators reroute by A*",
                "pathzoo_baselines.hybrids:FuzzyRateGaAstarPlanner", kinds=_GRID_TERRAIN, requires=_EVO, hybrid=True),
)
"""The pure metaheuristics (every kind, no graph search) and their A*-routed hybrids, declared without importing them.

Waypoint planners draw straight segments, so their lengths are compared with the any-angle optimum
(``path_model="anyangle"``); the cell-chain hybrids move between neighbouring cells (``"grid"``)."""


@hookimpl
def pathzoo_register_planners() -> Sequence[LazyPlanner]:
    """The metaheuristic baselines (:data:`PLANNERS`)."""
    return PLANNERS
