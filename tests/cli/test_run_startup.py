"""``pathzoo run``'s start: the metric checked first, then the process executor built while the experiment is read."""

from __future__ import annotations

import pytest

from pathzoo.cli.main import main
from pathzoo.harness.executors import ProcessExecutor
from pathzoo.harness.store import read_runs

EXPERIMENT = """
[experiment]
name = "start"
seeds = 1
budget = { iterations = 1 }
scenarios = ["movingai.random-32-32-20.b10.13"]

[[planner]]
id = "exact.astar"
"""


@pytest.fixture
def built(monkeypatch):
    """The process executors built, with the planners named to ``start_worker`` and whether each was shut down."""
    pools: list[tuple[ProcessExecutor, list[str]]] = []
    init, start_worker = ProcessExecutor.__init__, ProcessExecutor.start_worker

    def recorded_init(self, *args, **kwargs):
        init(self, *args, **kwargs)
        pools.append((self, []))

    def recorded_start(self, planner_id):
        next(named for pool, named in pools if pool is self).append(planner_id)
        start_worker(self, planner_id)

    monkeypatch.setattr(ProcessExecutor, "__init__", recorded_init)
    monkeypatch.setattr(ProcessExecutor, "start_worker", recorded_start)
    return pools


def test_run_builds_its_executor_early_with_a_worker_for_the_first_planner(tmp_path, capsys, built):
    (tmp_path / "start.toml").write_text(EXPERIMENT)
    db = tmp_path / "r.sqlite"
    assert main(["run", str(tmp_path / "start.toml"), "--db", str(db), "--jobs", "1", "--no-progress"]) == 0
    assert (read_runs(db, "start").status == "solved").all()
    assert [named for _, named in built] == [["exact.astar"]]
    assert all(pool._closing for pool, _ in built)


def test_a_mistyped_metric_fails_before_any_run_and_before_any_worker_starts(tmp_path, capsys, built):
    (tmp_path / "start.toml").write_text(EXPERIMENT)
    db = tmp_path / "r.sqlite"
    assert main(["run", str(tmp_path / "start.toml"), "--db", str(db), "--metric", "lenght", "--no-progress"]) == 2
    assert "unknown metric 'lenght'" in capsys.readouterr().err
    assert not db.exists()
    assert built == []  # the metric is looked up in the declarations before the executor is built


def test_a_bad_experiment_stops_the_early_executor(tmp_path, capsys, built):
    (tmp_path / "start.toml").write_text(EXPERIMENT.replace('id = "exact.astar"', 'id = "exact.astar"\nparams = { nope = 1 }'))
    assert main(["run", str(tmp_path / "start.toml"), "--db", str(tmp_path / "r.sqlite"), "--no-progress"]) == 2
    assert "nope" in capsys.readouterr().err
    assert built and all(pool._closing for pool, _ in built)
