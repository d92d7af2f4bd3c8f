"""The module named in the ``pathzoo.planners`` entry-point group: it tells pathzoo what this package provides.

It declares the planner without importing it: ``pathzoo list`` reads the
declaration, and pathzoo imports ``pathzoo_greedy.planner`` only when the
planner is built (and checks that the class agrees with what is declared).
"""

from __future__ import annotations

from typing import Sequence

import pathzoo

__all__ = ["pathzoo_register_planners"]


@pathzoo.hookimpl
def pathzoo_register_planners() -> Sequence[pathzoo.LazyPlanner]:
    """The planners of this plugin."""
    return [
        pathzoo.LazyPlanner(
            "greedy.best_first",
            "Greedy best-first search on the grid graph (octile heuristic)",
            "pathzoo_greedy.planner:GreedyBestFirst",
            kinds=frozenset({"grid2d", "terrain"}),
        )
    ]
