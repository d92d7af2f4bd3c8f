"""The ``aco`` plugin: registers the ant-colony planners built on the shared engine."""

from __future__ import annotations

from typing import Sequence

from pathzoo.core.planner import Planner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners"]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    """Every ant-colony planner of this family."""
    from pathzoo_aco.acs import AntColonySystem
    from pathzoo_aco.ant_system import AntSystem
    from pathzoo_aco.gant import GreenAnt
    from pathzoo_aco.ggaco import GGACO
    from pathzoo_aco.mmas import MaxMinAntSystem
    from pathzoo_aco.fgdaco import FGDACO
    from pathzoo_aco.dsaco import DSACO
    from pathzoo_aco.iaca import IACA
    from pathzoo_aco.flaco import FLACO
    from pathzoo_aco.aco_astar import AcoAStar

    return [AntSystem, MaxMinAntSystem, AntColonySystem, GGACO, GreenAnt, FGDACO, DSACO, IACA, FLACO, AcoAStar]
