"""aco.aco_astar: ACO-A* of Yu et al. (IEEE TEVC 2018) on pathzoo's one-target missions, where it is A*.

ACO-A* has two layers (from the paper's abstract, the only part reachable):
an ant colony orders the mission's targets on a coarse cost graph (its
costs estimated by a "representative-based estimation"), and A* with an
admissible heuristic plans each leg between consecutive targets on the fine
grid. Every pathzoo scenario has one start and one goal, so the ordering
layer has a single target and nothing to decide; what remains is the A*
leg, which this planner runs: :class:`pathzoo_exact.astar.AStarPlanner` on
the scenario's cell graph, minimising 3-D length with its admissible,
consistent heuristic. The ordering layer is not implemented (no scenario
could exercise it). See ``docs/planners/aco.aco_astar.md``.
"""

from __future__ import annotations

from typing import ClassVar

from pathzoo_exact.astar import AStarPlanner

__all__ = ["AcoAStar"]


class AcoAStar(AStarPlanner):
    """ACO-A* (Yu and co-authors 2018) for a single target: its A* layer on 3-D length (see the module docstring)."""

    id: ClassVar[str] = "aco.aco_astar"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = ("ACO-A* (Yu et al. 2018) on one-target missions: the ACO layer only orders "
                              "targets, so this is its A* leg (3-D length, admissible heuristic)")
    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d", "terrain", "air3d"})
    params = {}
    cost: ClassVar[str] = "length"
    """ACO-A*'s legs minimise travel length (the A* parent's ``cost`` parameter is fixed here)."""
