"""The ``baselines`` plugin: declares the metaheuristic baselines (imported when first built)."""

from __future__ import annotations

from typing import Sequence

from pathzoo.plugins.entries import LazyPlanner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners", "PLANNERS"]

_GRID_TERRAIN = frozenset({"grid2d", "terrain"})

PLANNERS: tuple[LazyPlanner, ...] = (
    LazyPlanner("swarm.pso", "Particle swarm optimisation (pyswarms) of K waypoints, decoded into a feasible path",
                "pathzoo_baselines.pso:PsoPlanner", kinds=_GRID_TERRAIN, requires={"pyswarms": "evo"}),
    LazyPlanner("swarm.cuckoo",
                "Cuckoo search with Mantegna Lévy flights over K waypoints, decoded into a feasible path",
                "pathzoo_baselines.cuckoo:CuckooPlanner", kinds=_GRID_TERRAIN),
    LazyPlanner("evo.ga",
                "Genetic algorithm (DEAP) over feasible variable-length cell paths (or waypoint/move encodings)",
                "pathzoo_baselines.ga:GaPlanner", kinds=_GRID_TERRAIN, requires={"deap": "evo"}),
    LazyPlanner("evo.fuzzy_ga", "GA whose crossover/mutation rates a fuzzy controller sets (DEAP + scikit-fuzzy)",
                "pathzoo_baselines.fuzzy_ga:FuzzyGaPlanner", kinds=_GRID_TERRAIN, requires={"deap": "evo"}),
)
"""``swarm.pso``, ``swarm.cuckoo``, ``evo.ga`` and ``evo.fuzzy_ga``, declared without importing them."""


@hookimpl
def pathzoo_register_planners() -> Sequence[LazyPlanner]:
    """The metaheuristic baselines (:data:`PLANNERS`)."""
    return PLANNERS
