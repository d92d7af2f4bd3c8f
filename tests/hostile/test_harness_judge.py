"""Hostile planners against the judge: forgeries, a shared process, unhashed scenario parts, self-reported timing.

Each test fails on the harness before issue 11: the validator was patched in
the planner's own (inline) process, ``graph``/``vehicle``/``moving_obstacles``
were not in the scenario digest, and times came from the worker's clock.
"""

from __future__ import annotations

import pytest

from harness_support import experiment, hostile  # noqa: F401 - fixture
from pathzoo.harness import run_experiment
from pathzoo.harness.executors import dask_executor

EXECUTORS = ["inline", "process"]


def run(exp, tmp_path, executor, jobs=1, **kw):
    return run_experiment(exp, db=tmp_path / "r.sqlite", jobs=jobs, executor=executor, progress=False, **kw)


@pytest.mark.parametrize("executor", EXECUTORS)
def test_a_patched_validator_fools_nobody(hostile, tmp_path, executor):
    runs = run(experiment(["hostile.patch_validator", "exact.astar"], ["hostile.wall"], seeds=2), tmp_path, executor)
    by = runs.set_index("planner").status
    assert list(by["hostile.patch_validator"]) == ["invalid", "invalid"]
    assert list(by["exact.astar"]) == ["solved", "solved"]  # the validator still accepts honest paths


@pytest.mark.parametrize("executor", EXECUTORS)
def test_dropping_obstacles_or_replacing_the_vehicle_is_caught(hostile, tmp_path, executor):
    runs = run(experiment(["hostile.drop_obstacles"], ["hostile.crossing"], seeds=2), tmp_path, executor)
    assert list(runs.status) == ["invalid", "invalid"]
    assert runs.invalid_reason.str.contains("modified or replaced").all()


@pytest.mark.parametrize("executor", EXECUTORS)
def test_a_replaced_graph_is_caught_and_never_reaches_the_next_run(hostile, tmp_path, executor):
    planners = ["hostile.replace_graph", "exact.astar", "exact.thetastar"]
    runs = run(experiment(planners, ["hostile.wall"], seeds=2), tmp_path, executor)
    by = runs.set_index("planner")
    assert list(by.loc["hostile.replace_graph"].status) == ["invalid", "invalid"]
    assert (by.loc[["exact.astar", "exact.thetastar"]].status == "solved").all()


def test_a_monkeypatched_class_never_reaches_the_next_run(hostile, tmp_path):
    """Under the process executor the patched worker is replaced (one worker, so A* would get it)."""
    runs = run(experiment(["hostile.patch_class", "exact.astar"], ["hostile.wall"], seeds=2), tmp_path, "process")
    by = runs.set_index("planner").status
    assert list(by["hostile.patch_class"]) == ["invalid", "invalid"]
    assert list(by["exact.astar"]) == ["solved", "solved"]


@pytest.mark.parametrize("executor", EXECUTORS)
def test_a_frozen_clock_does_not_shorten_the_planning_time(hostile, tmp_path, executor):
    runs = run(experiment(["hostile.patch_clock"], ["hostile.wall"]), tmp_path, executor)
    assert runs.status.item() == "solved"
    assert runs.wall_time_s.item() >= 0.35 and runs.cpu_time_s.item() > 0.02  # the forged values are 0


def test_repeated_start_announcements_do_not_postpone_the_hard_limit(hostile, tmp_path):
    runs = run(experiment(["hostile.spam_started"], ["hostile.wall"], timeout_s=1.5), tmp_path, "process")
    assert runs.status.item() == "timeout"
    assert 1.4 <= runs.wall_time_s.item() < 10


def test_inline_runs_are_marked_not_isolated(hostile, tmp_path):
    inline = run(experiment(["exact.astar"], ["hostile.wall"]), tmp_path, "inline")
    process = run_experiment(experiment(["exact.astar"], ["hostile.wall"]), db=tmp_path / "p.sqlite", jobs=1,
                             executor="process", progress=False)
    assert not inline.isolated.any() and process.isolated.all()


@pytest.mark.slow
def test_dask_workers_are_isolated_too(hostile, tmp_path):
    planners = ["hostile.patch_validator", "hostile.patch_class", "exact.astar"]
    exp = experiment(planners, ["hostile.wall"], seeds=2)
    runs = run(exp, tmp_path, dask_executor(jobs=1))
    by = runs.groupby("planner").status.agg(list)
    # one Dask worker: each planner runs in a child of it, and a tainted child is replaced before the next run
    assert by["exact.astar"] == ["solved", "solved"]
    assert by["hostile.patch_validator"] == by["hostile.patch_class"] == ["invalid", "invalid"]
    assert runs.isolated.all()
