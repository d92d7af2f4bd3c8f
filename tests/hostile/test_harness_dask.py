"""Hostile planners under the Dask executor: timings come from outside the planner's process, hangs are killed.

Before issue 11 the Dask task ran ``plan()`` in the Dask worker itself and
timed it there, with pathzoo's import-bound clocks: a planner that rebound
those clocks stored the times it liked, and a planner that never returned
kept its worker thread busy for good. Each test below fails on that executor.
"""

from __future__ import annotations

import pytest

from harness_support import experiment, hostile  # noqa: F401 - fixture
from pathzoo.harness import run_experiment
from pathzoo.harness.executors import dask_executor

pytest.importorskip("distributed")


def run(exp, tmp_path, **kw):
    return run_experiment(exp, db=tmp_path / "r.sqlite", jobs=1, executor=dask_executor(jobs=1, **kw),
                          progress=False)


def test_frozen_clocks_everywhere_do_not_change_the_stored_times(hostile, tmp_path):
    """The planner burns 0.3 s of CPU, then freezes ``time``, pathzoo's clocks and psutil in its process."""
    runs = run(experiment(["hostile.patch_all_clocks", "hostile.patch_clock"], ["hostile.wall"]), tmp_path,
               processes=False)
    by = runs.set_index("planner")
    assert (by.status == "solved").all() and runs.isolated.all()
    forged = by.loc["hostile.patch_all_clocks"]
    # psutil reads CPU time in clock ticks (10 ms), hence the slack over the wall time
    assert 0.28 <= forged.cpu_time_s <= forged.wall_time_s + 0.05 < 30, (forged.cpu_time_s, forged.wall_time_s)
    assert by.loc["hostile.patch_clock"].wall_time_s >= 0.35


def test_a_hung_planner_is_killed_at_the_hard_limit_and_frees_its_worker(hostile, tmp_path):
    """One Dask worker thread: the honest run after the hang only runs if the hung planner's process was killed."""
    # the limit leaves room for an honest run on a loaded machine (1.5 s once timed an A* run out in CI)
    exp = experiment(["hostile.spam_started", "exact.astar"], ["hostile.wall"], seeds=2, timeout_s=3.0)
    runs = run(exp, tmp_path, processes=False)
    by = runs.groupby("planner")
    assert list(by.status.agg(list)["hostile.spam_started"]) == ["timeout", "timeout"]
    assert all(3.0 <= wall < 8.0 for wall in by.wall_time_s.agg(list)["hostile.spam_started"])
    assert list(by.status.agg(list)["exact.astar"]) == ["solved", "solved"]


@pytest.mark.slow
def test_frozen_clocks_in_dask_worker_processes(hostile, tmp_path):
    """The same forgery with Dask workers as processes (a nanny, as with ``dask worker``)."""
    runs = run(experiment(["hostile.patch_all_clocks"], ["hostile.wall"], seeds=2), tmp_path)
    assert (runs.status == "solved").all() and runs.isolated.all()
    times = runs[["cpu_time_s", "wall_time_s"]]
    assert (runs.cpu_time_s >= 0.28).all() and (runs.wall_time_s + 0.05 >= runs.cpu_time_s).all(), times
