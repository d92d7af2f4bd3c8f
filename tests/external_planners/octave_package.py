"""A planner package's plugin module declaring an Octave planner (loaded through a test entry point)."""

from __future__ import annotations

from pathlib import Path

import pathzoo
from pathzoo.plugins.external import ExternalPlanner

SHORTEST = str(Path(__file__).resolve().parent / "programs" / "shortest.m")


@pathzoo.hookimpl
def pathzoo_register_planners() -> list[ExternalPlanner]:
    return [ExternalPlanner("octpkg.shortest", "Random-tie shortest path in Octave", kinds=frozenset({"grid2d"}),
                            octave=SHORTEST, params={"unused": pathzoo.Param(1, "an example parameter", low=0)})]
