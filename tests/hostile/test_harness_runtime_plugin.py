"""A planner registered at run time from a module that exists only in the caller's process is still judged in full."""

from __future__ import annotations

import types

import pathzoo
from pathzoo.harness import run_experiment
from pathzoo.plugins.manager import get_registry, reset_registry
from pathzoo_exact.astar import AStarPlanner


class RuntimeAStar(AStarPlanner):
    """A* under another id, registered by hand from a module no other process can import."""

    id = "runtime.astar"


def test_a_hand_registered_planner_is_judged_with_every_metric(tmp_path):
    plugin = types.ModuleType("made_at_run_time_plugin")  # not importable by the judge process

    @pathzoo.hookimpl
    def pathzoo_register_planners() -> list[type[pathzoo.Planner]]:
        return [RuntimeAStar]

    plugin.pathzoo_register_planners = pathzoo_register_planners
    get_registry().add_plugin(plugin, "made-at-run-time")
    try:
        exp = pathzoo.harness.Experiment.build(planners=["runtime.astar"], scenarios=["movingai.arena.b15.150"],
                                               seeds=1, name="runtime")
        runs = run_experiment(exp, db=tmp_path / "r.sqlite", jobs=1, executor="inline", progress=False)
    finally:
        reset_registry()
    assert runs.status.item() == "solved", runs.invalid_reason.item()
    assert runs.length_ratio.item() == runs.length_ratio.item()  # computed (not NaN): the judge ran the metrics
