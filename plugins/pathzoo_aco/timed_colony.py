"""The classic ant systems among moving obstacles: AS, MMAS and ACS on ``dynamic`` scenarios too.

On a scenario with moving obstacles their ants walk the timed engine of
FGDACO (:func:`pathzoo_aco.fgdaco_walk.timed_product_engine`): each ant
keeps time at the vehicle's cruise speed and never takes an edge a moving
obstacle would hit while it is driven, and the edge weights stay the rule's
own ``τ^α η^β`` (ACS's ``q0`` choice and local update run inside the timed
walk). This is FGDACO's problem with its parent's rules, so the proposed
method can be measured against the colony it extends.
"""

from __future__ import annotations

from typing import ClassVar

from pathzoo_aco.engine import AntColonyPlanner, ColonyProblem, WalkEngine

__all__ = ["TimedProductColony", "KINDS"]

KINDS = frozenset({"grid2d", "terrain", "air3d", "dynamic"})
"""Scenario kinds of the classic ant systems."""


class TimedProductColony(AntColonyPlanner):
    """Base of AS, MMAS and ACS: the static walks, or timed walks when the scenario has moving obstacles."""

    kinds: ClassVar[frozenset[str]] = KINDS

    def walk_engine(self, problem: ColonyProblem) -> WalkEngine:
        """Timed walks of the product rule among moving obstacles, else the shared static engine."""
        from pathzoo_aco.fgdaco_walk import timed_product_engine

        return timed_product_engine(problem, self.beta)
