"""The ``ompl`` plugin: registers OMPL's sampling-based planners (``ompl.*``) through pathzoo's entry points.

OMPL itself is imported only when one of these planners plans, so listing
plugins stays fast and works without OMPL installed.
"""

from __future__ import annotations

from typing import Sequence

from pathzoo.core import Planner
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_planners"]


@hookimpl
def pathzoo_register_planners() -> Sequence[type[Planner]]:
    """The seven ``ompl.*`` planners of :data:`pathzoo_ompl.planners.OMPL_PLANNERS`."""
    from pathzoo_ompl.planners import OMPL_PLANNERS

    return list(OMPL_PLANNERS)
