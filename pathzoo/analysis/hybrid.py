"""Which planners are hybrids (a metaheuristic that hands part of its work to an exact search), from their declarations."""

from __future__ import annotations

from typing import Iterable

from pathzoo.plugins.entries import HYBRID_MARK

__all__ = ["HYBRID_MARK", "HYBRID_NOTE", "hybrid_planners"]

HYBRID_NOTE = (
    f"{HYBRID_MARK}: a hybrid planner, a metaheuristic whose decoder or operators call an exact search "
    "(A* routes between its points); its results are not the metaheuristic's alone."
)
"""The note under a table that shows the mark."""


def hybrid_planners(planner_ids: Iterable[str]) -> set[str]:
    """The ids among ``planner_ids`` whose registered declaration says ``hybrid`` (unknown ids are not hybrids).

    Reads the plugins' declarations only; no planner class is imported.
    """
    from pathzoo.plugins.manager import get_registry

    table = get_registry().table("planners")
    return {pid for pid in set(planner_ids) if pid in table and bool(table[pid].declared("hybrid", False))}
