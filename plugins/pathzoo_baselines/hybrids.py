"""The A*-routed hybrids: each metaheuristic with a decoder that routes between its points by grid A*.

A hybrid is a different planner from its pure parent, with its own id
(``swarm.pso_astar``, ``swarm.cuckoo_astar``, ``evo.ga_astar``,
``evo.fuzzy_rate_ga_astar``) and ``hybrid = True``, so that a leaderboard can
never credit an exact search's work to the metaheuristic around it:

- ``routed``: K free points; consecutive points are joined by a straight
  segment when it is clear, otherwise by the shortest grid route between
  them (:mod:`pathzoo_baselines.routed`);
- ``cells`` (the GAs only): a variable-length chain of cells whose
  initialisation, crossover repair and mutation are A* routes
  (:mod:`pathzoo_baselines.cellpath`).

Everything else (operators, budgets, seeding) is the parent's. The routes
follow the static 2-D neighbourhood graph, so the hybrids support ``grid2d``
and ``terrain`` only.
"""

from __future__ import annotations

from typing import ClassVar, Mapping

from pathzoo.core import Param
from pathzoo_baselines.cuckoo import CuckooPlanner
from pathzoo_baselines.fuzzy_rate_ga import FuzzyRateGaPlanner
from pathzoo_baselines.ga import CELLS_PARAMS, GaPlanner
from pathzoo_baselines.params import HYBRID_ENCODINGS, HYBRID_KINDS, hybrid_encoding
from pathzoo_baselines.pso import PsoPlanner

__all__ = ["PsoAstarPlanner", "CuckooAstarPlanner", "GaAstarPlanner", "FuzzyRateGaAstarPlanner"]

_ROUTED_WAYPOINTS = Param(8, "K, the number of intermediate waypoints the A*-routed decoder joins", low=1, high=256)
_ROUTED_ONLY = {"encoding": hybrid_encoding("routed", ("routed",)), "waypoints": _ROUTED_WAYPOINTS}
_GA_HYBRID = {"encoding": hybrid_encoding("cells", HYBRID_ENCODINGS), "waypoints": _ROUTED_WAYPOINTS, **CELLS_PARAMS}


class PsoAstarPlanner(PsoPlanner):
    """``swarm.pso`` over the A*-routed waypoint decoder (hybrid, label ``pso+astar``)."""

    id: ClassVar[str] = "swarm.pso_astar"
    version: ClassVar[str] = "2"
    summary: ClassVar[str] = "PSO over K waypoints joined by A* grid routes where a straight segment is blocked"
    kinds: ClassVar[frozenset[str]] = HYBRID_KINDS
    hybrid: ClassVar[bool] = True
    params: ClassVar[Mapping[str, Param]] = {**PsoPlanner.params, **_ROUTED_ONLY}


class CuckooAstarPlanner(CuckooPlanner):
    """``swarm.cuckoo`` over the A*-routed waypoint decoder (hybrid, label ``cuckoo+astar``)."""

    id: ClassVar[str] = "swarm.cuckoo_astar"
    version: ClassVar[str] = "2"
    summary: ClassVar[str] = "Cuckoo search over K waypoints joined by A* grid routes where a segment is blocked"
    kinds: ClassVar[frozenset[str]] = HYBRID_KINDS
    hybrid: ClassVar[bool] = True
    params: ClassVar[Mapping[str, Param]] = {**CuckooPlanner.params, **_ROUTED_ONLY}


class GaAstarPlanner(GaPlanner):
    """``evo.ga`` over A*-routed cell chains or waypoints (hybrid, label ``ga+astar``)."""

    id: ClassVar[str] = "evo.ga_astar"
    version: ClassVar[str] = "2"
    summary: ClassVar[str] = "GA over feasible cell chains whose operators reroute by A* (or A*-routed waypoints)"
    kinds: ClassVar[frozenset[str]] = HYBRID_KINDS
    hybrid: ClassVar[bool] = True
    params: ClassVar[Mapping[str, Param]] = {**GaPlanner.params, **_GA_HYBRID}


class FuzzyRateGaAstarPlanner(FuzzyRateGaPlanner):
    """``evo.fuzzy_rate_ga`` over A*-routed cell chains or waypoints (hybrid, label ``fuzzy_rate_ga+astar``)."""

    id: ClassVar[str] = "evo.fuzzy_rate_ga_astar"
    version: ClassVar[str] = "2"
    summary: ClassVar[str] = "Fuzzy-rate GA over feasible cell chains whose operators reroute by A*"
    kinds: ClassVar[frozenset[str]] = HYBRID_KINDS
    hybrid: ClassVar[bool] = True
    params: ClassVar[Mapping[str, Param]] = {**FuzzyRateGaPlanner.params, **_GA_HYBRID}
