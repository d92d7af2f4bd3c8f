"""The ``rivals`` plugin: registers the non-ant rivals of the papers' tables through pathzoo's entry points."""

from __future__ import annotations

from typing import Sequence

from pathzoo.core import Planner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners"]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    """``exact.zstar``, and the reconstructions ``swarm.mosfla`` and ``search.movns`` (Hidalgo-Paniagua et al.)."""
    from pathzoo_rivals.mosfla import MosflaPlanner
    from pathzoo_rivals.movns import MovnsPlanner
    from pathzoo_rivals.zstar import ZStarPlanner

    return [ZStarPlanner, MosflaPlanner, MovnsPlanner]
