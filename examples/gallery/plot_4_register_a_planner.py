"""
Register a planner of your own
==============================

A planner is a :class:`pathzoo.Planner` subclass with an id, declared
parameters and one ``plan()`` method. This example writes one, registers it
with pathzoo while the script runs, checks it with the conformance kit
:mod:`pathzoo.testing` and runs it against the exact optimum.

A planner you want to share belongs in a package that registers it through
the ``pathzoo.planners`` entry-point group, so that ``pathzoo list`` and worker
processes find it: :doc:`/register-a-planner` walks through one.
"""

# %%
# The planner
# -----------
# Breadth-first search on the scenario's neighbourhood graph finds the path
# with the *fewest moves*. A diagonal move counts as one move like a straight
# one, though it is √2 times longer, so the path need not be the shortest.
#
# What pathzoo asks of ``plan()``: call ``self.check_supports(scenario)``
# first; stop when the budget runs out; take all randomness from ``rng``
# (this search needs none); report progress with a best cost that never
# increases; return a path that starts exactly at ``scenario.start`` and ends
# exactly at ``scenario.goal``; and report "no path" as a status, not an
# exception.

import collections
import os
import tempfile
import types
from pathlib import Path
from typing import ClassVar, Mapping

import matplotlib.pyplot as plt
import numpy as np

import pathzoo
from pathzoo import Budget, Param, PlanResult, Scenario, Status
from pathzoo.analysis import format_leaderboard, leaderboard
from pathzoo.core import ProgressCallback
from pathzoo.harness import read_path
from pathzoo.plotting.paths import plot_paths
from pathzoo.plugins.manager import get_registry
from pathzoo.testing import check_planner


class FewestMoves(pathzoo.Planner):
    """Breadth-first search: the path with the fewest moves on the cell graph."""

    id: ClassVar[str] = "demo.fewest_moves"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = "Breadth-first search for the fewest moves"
    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d"})
    params: ClassVar[Mapping[str, Param]] = {
        "check_every": Param(
            256, "node expansions between two looks at the clock", low=1, high=1_000_000
        ),
    }

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Search breadth-first from the start cell to the goal cell."""
        self.check_supports(scenario)
        clock = budget.start()
        start, goal = scenario.start_node, scenario.goal_node
        parent = {start: start}
        queue = collections.deque([start])
        expanded = 0
        while queue:
            node = queue.popleft()
            if node == goal:
                return self._solved(scenario, parent, goal, progress)
            expanded += 1
            if expanded % self.check_every == 0 and clock.exhausted():
                message = f"time budget out after {expanded} expansions"
                return PlanResult(Status.FAILED, iterations=1, message=message)
            for nxt in map(int, scenario.graph.neighbours(node)):
                if nxt not in parent:
                    parent[nxt] = node
                    queue.append(nxt)
        message = f"goal unreachable ({expanded} cells searched)"
        return PlanResult(Status.NO_PATH, iterations=1, message=message)

    @staticmethod
    def _solved(
        scenario: Scenario,
        parent: dict[int, int],
        goal: int,
        progress: ProgressCallback | None,
    ) -> PlanResult:
        nodes = [goal]
        while parent[nodes[-1]] != nodes[-1]:
            nodes.append(parent[nodes[-1]])
        centres = scenario.point_of(np.array(nodes[::-1]))
        # the exact start and goal need not be cell centres: add them as end points
        path = np.vstack([scenario.start, centres, scenario.goal])
        keep = np.ones(len(path), dtype=bool)
        keep[1:] = np.any(np.diff(path, axis=0) != 0, axis=1)
        path = path[keep]
        if progress is not None:
            progress(1, 1, float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum()))
        return PlanResult(Status.SOLVED, path=path, iterations=1, evaluations=1)


# %%
# Check it with the conformance kit
# ---------------------------------
# :func:`pathzoo.testing.check_planner` runs every check of pathzoo's planner
# contract (parameter validation, valid paths, same seed same path,
# unreachable goals, budgets, pickling, an unchanged scenario, a history that
# only improves) and raises one :class:`~pathzoo.testing.ConformanceError`
# listing every failure. In a test suite,
# :func:`pathzoo.testing.parametrize_with_checks` makes each check a pytest
# test instead.

check_planner(FewestMoves)
print("FewestMoves passes every conformance check")

# %%
# Register it
# -----------
# A plugin is any module with pathzoo's hook functions. Installed packages
# declare theirs in the ``pathzoo.planners`` entry-point group; here a module built on
# the fly is added to the registry by hand. From then on the planner is
# known by its id like the built-in ones.


@pathzoo.hookimpl
def pathzoo_register_planners() -> list[type[pathzoo.Planner]]:
    return [FewestMoves]


plugin = types.ModuleType("fewest_moves_plugin")
plugin.pathzoo_register_planners = pathzoo_register_planners
get_registry().add_plugin(plugin, "fewest-moves")
print(pathzoo.make_planner("demo.fewest_moves"))

# %%
# Run it against the others
# -------------------------
# Worker processes find plugins through entry points, or re-import a module
# registered by hand by its name. This module exists only in this script, so
# the experiment runs with the ``inline`` executor, in this process.

FULL = os.environ.get("PATHZOO_DOCS_BUDGET", "tiny") == "full"
scenarios = ["movingai.maze-32-32-2.b16.0", "movingai.room-32-32-4.b5.0"]
if FULL:
    scenarios += ["movingai.random-32-32-20.b7.0", "movingai.arena.b15.150"]
db = Path(tempfile.mkdtemp()) / "fewest-moves.sqlite"
runs = pathzoo.run(
    ["exact.astar", "demo.fewest_moves"],
    scenarios,
    seeds=1,
    budget=Budget(time_s=10),
    db=db,
    experiment="fewest-moves",
    executor="inline",
    progress=False,
)
print(format_leaderboard(leaderboard(runs, "length_ratio")))

# %%
# Both paths on the first map: the same number of moves can be a longer walk.

first = runs[runs["scenario"] == scenarios[0]]
paths = {
    row.planner: read_path(db, "fewest-moves", row.run_key)[0]
    for row in first.itertuples()
}
fig, ax = plt.subplots(figsize=(6.5, 7), layout="constrained")
plot_paths(pathzoo.load_scenario(scenarios[0]), paths, ax=ax)
