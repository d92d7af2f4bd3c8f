"""The Dask executor supervises each planner in a child process: saboteurs end as the process executor records them.

Before issue 11 these planners ran inside the Dask worker; with the workers
as threads of the test process (``processes=False``) ``os._exit`` or
``SIGKILL`` would have ended the test run itself, and ``sleep`` would have
kept the only worker thread busy for an hour.
"""

from __future__ import annotations

import pytest

import pathzoo
from pathzoo import Budget
from pathzoo.harness.executors import dask_executor

pytest.importorskip("distributed")

TIMEOUT_S = 1.5


@pytest.mark.parametrize("how, status, message", [
    ("exit", "crash", "worker process died (exit code 3)"),
    ("kill", "crash", "worker process died (signal 9 (SIGKILL))"),
    ("sleep", "timeout", "stopped at the hard limit"),
])
def test_saboteurs_are_recorded_and_the_next_run_still_runs(forged, tmp_path, how, status, message):
    frame = pathzoo.run([("test.sabotage", {"how": how}), "test.honest"], ["test.wall"], seeds=1,
                        db=tmp_path / "r.sqlite", jobs=1, budget=Budget(time_s=0.2), timeout_s=TIMEOUT_S,
                        executor=dask_executor(jobs=1, processes=False), progress=False)
    by = frame.set_index("planner")
    bad = by.loc["test.sabotage"]
    assert bad.status == status and bad.message.startswith(message), (bad.status, bad.message)
    assert by.loc["test.honest"].status == "solved"
    if how == "sleep":
        assert TIMEOUT_S <= bad.wall_time_s < TIMEOUT_S + 5


def test_daemonic_workers_of_an_external_cluster_are_refused_with_a_clear_error():
    """Dask's default workers are daemonic and may not start the planners' processes: say so at once."""
    from distributed import LocalCluster

    from pathzoo.core.errors import PathzooError

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with pytest.raises(PathzooError, match="daemonic processes .* DASK_DISTRIBUTED__WORKER__DAEMON=False"):
            dask_executor(cluster.scheduler_address)
