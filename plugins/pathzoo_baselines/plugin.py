"""The ``baselines`` plugin: registers the metaheuristic baselines through pathzoo's entry points."""

from __future__ import annotations

from typing import Sequence

from pathzoo.core import Planner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners"]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    """``swarm.pso``, ``swarm.cuckoo``, ``evo.ga`` and ``evo.fuzzy_ga``."""
    from pathzoo_baselines.cuckoo import CuckooPlanner
    from pathzoo_baselines.fuzzy_ga import FuzzyGaPlanner
    from pathzoo_baselines.ga import GaPlanner
    from pathzoo_baselines.pso import PsoPlanner

    return [PsoPlanner, CuckooPlanner, GaPlanner, FuzzyGaPlanner]
