"""The Dask pool follows the cluster: it waits, saying so, for a first worker, and a worker that joins late runs runs.

With the capacity fixed when the executor connected (the threads present
then, at least 1) and no run queued beyond it, a second worker that joined
later got nothing to do: the experiment stayed serial. Each test fails so.
"""

from __future__ import annotations

import logging
import sqlite3
import threading
import time
from datetime import datetime

import pytest

from pathzoo import Budget
from pathzoo.harness.executors import dask_executor
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import run_experiment

pytest.importorskip("distributed")

SLEEP_S = 1.5


def _intervals(db) -> list[tuple[float, float]]:
    """Each run's time in its planner's child: from its start to the end of ``plan()`` (never before it)."""
    with sqlite3.connect(db) as conn:
        rows = conn.execute("SELECT started_at, wall_time_s FROM runs").fetchall()
    out = []
    for started, wall in rows:
        start = datetime.fromisoformat(started).timestamp()
        out.append((start, start + wall))
    return out


def _most_at_once(intervals: list[tuple[float, float]]) -> int:
    events = sorted([(a, 1) for a, _ in intervals] + [(b, -1) for _, b in intervals], key=lambda e: (e[0], e[1]))
    now = most = 0
    for _, step in events:
        now += step
        most = max(most, now)
    return most


@pytest.mark.slow
def test_a_worker_that_joins_late_runs_in_parallel_and_none_means_a_clear_wait(forged, tmp_path, caplog):
    import dask
    from distributed import LocalCluster

    experiment = Experiment.build(planners=[("test.honest", {"delay_s": SLEEP_S})], scenarios=["test.wall"],
                                  seeds=10, name="late", budget=Budget(iterations=5), timeout_s=60)
    db = tmp_path / "late.sqlite"
    with dask.config.set({"distributed.worker.daemon": False}), \
            LocalCluster(n_workers=0, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        executor = dask_executor(cluster.scheduler_address)
        joined: dict[str, float] = {}

        def grow() -> None:
            time.sleep(2.0)
            joined["first"] = time.time()
            cluster.scale(1)
            time.sleep(8.0)
            joined["second"] = time.time()
            cluster.scale(2)

        grower = threading.Thread(target=grow)
        with caplog.at_level(logging.WARNING, logger="pathzoo.harness"):
            grower.start()
            runs = run_experiment(experiment, db=db, executor=executor, progress=False)
            grower.join()
    assert len(runs) == 10 and (runs.status == "solved").all()
    waits = [r.getMessage() for r in caplog.records if "no Dask worker is connected" in r.getMessage()]
    assert waits and "waiting for one" in waits[0]
    intervals = _intervals(db)
    assert all(start >= joined["first"] for start, _ in intervals)  # nothing ran before a worker came
    late = [iv for iv in intervals if iv[1] > joined["second"]]
    assert _most_at_once(intervals) >= 2 and _most_at_once(late) >= 2, intervals
    before = [iv for iv in intervals if iv[1] <= joined["second"]]
    assert _most_at_once(before) <= 1  # the control: one worker thread, one run at a time (none if it started slowly)
