"""The store and the runner against concurrency, retries and reruns.

Before issue 11: two harnesses on a fresh database failed with "duplicate
column name: metric:success"; crashed runs could never be retried; and
``run_experiment`` returned every row stored under the experiment's name.
"""

from __future__ import annotations

import pytest

from harness_support import experiment, hostile  # noqa: F401 - fixture
from pathzoo.core.results import RunRecord
from pathzoo.core.status import RunStatus
from pathzoo.harness import read_history, run_experiment
from pathzoo.harness.store import ResultStore, read_runs
from pathzoo.harness.executors import ProcessExecutor


def record(key: str, metrics: dict[str, float]) -> RunRecord:
    return RunRecord(run_key=key, experiment="e", planner_id="p", planner_version="1", params={}, params_hash="h",
                     scenario_id="s", seed_index=0, seed=1, status=RunStatus.FAILED, valid=False, invalid_reason="",
                     message="", wall_time_s=0.1, cpu_time_s=0.1, iterations=1, evaluations=1, path=None,
                     times=None, history=(), metrics=metrics, versions={}, started_at="")


def test_two_harnesses_on_a_fresh_database_add_metric_columns_without_clashing(hostile, tmp_path):
    db = tmp_path / "r.sqlite"
    with ResultStore(db) as first, ResultStore(db) as second:  # both opened before any metric column exists
        first.add_experiment(experiment(["exact.astar"], ["hostile.wall"], name="e"))
        assert first.insert(record("a", {"success": 1.0}))
        assert second.insert(record("b", {"success": 0.0}))  # its column cache is stale: the column exists now
    assert sorted(read_runs(db, "e").success) == [0.0, 1.0]


@pytest.mark.slow
def test_retry_reruns_stored_crashes_and_replaces_their_rows(hostile, tmp_path):
    marker = tmp_path / "missing-dependency"
    marker.touch()
    exp = experiment([("hostile.flaky", {"marker": str(marker)})], ["hostile.wall"], seeds=2)
    db = tmp_path / "r.sqlite"
    # unsandboxed: a sandboxed planner cannot see the marker under /tmp (tests/hostile/test_sandbox.py)
    with ProcessExecutor(1, sandbox=False) as pool:
        first = run_experiment(exp, db=db, executor=pool, progress=False)
    assert list(first.status) == ["crash", "crash"]
    marker.unlink()  # "pip install" the missing dependency
    with ProcessExecutor(1, sandbox=False) as pool:
        again = run_experiment(exp, db=db, executor=pool, progress=False)
    assert list(again.status) == ["crash", "crash"]  # without --retry, stored runs are kept
    with ProcessExecutor(1, sandbox=False) as pool:
        retried = run_experiment(exp, db=db, executor=pool, progress=False, retry=("crash", "timeout"))
    assert list(retried.status) == ["solved", "solved"]
    assert len(read_runs(db, "hostile")) == 2 and read_history(db, "hostile").empty


def test_run_returns_exactly_the_requested_runs(hostile, tmp_path):
    db = tmp_path / "r.sqlite"
    run_experiment(experiment(["exact.astar"], ["hostile.wall"], seeds=2), db=db, executor="inline", progress=False)
    second = run_experiment(experiment(["exact.dijkstra"], ["hostile.wall"], seeds=1), db=db, executor="inline",
                            progress=False)
    assert list(second.planner) == ["exact.dijkstra"] and list(second.seed_index) == [0]
    assert len(read_runs(db, "hostile")) == 3
