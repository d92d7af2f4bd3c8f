"""``compare_results`` / ``pathzoo compare``: identical reruns pass, any changed stored value fails; stopped_by is stored."""

from __future__ import annotations

import shutil
import sqlite3

import numpy as np
import pytest

import pathzoo
from pathzoo.analysis.repeatability import compare_results
from pathzoo.cli.main import main
from pathzoo.harness import Experiment
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.store import ResultStore, read_record, read_runs


@pytest.fixture(scope="module")
def two_runs(tmp_path_factory):
    """The same small experiment run twice into two databases."""
    tmp = tmp_path_factory.mktemp("repeat")
    exp = Experiment.build(planners=["exact.astar", ("aco.as", {"iterations": 3, "n_ants": 4})],
                           scenarios=["gant.fig7"], seeds=2, budget=pathzoo.Budget(), name="twice")
    dbs = [tmp / "a.sqlite", tmp / "b.sqlite"]
    for db in dbs:
        run_experiment(exp, db=db, executor="inline", progress=False)
    return dbs


def test_two_runs_of_one_experiment_compare_identical_times_aside(two_runs):
    a, b = two_runs
    assert not read_runs(a)["wall_time_s"].equals(read_runs(b)["wall_time_s"])  # the times differ ...
    result = compare_results(a, b)
    assert result.identical and result.n_runs == 4  # ... and nothing else
    assert main(["compare", str(a), str(b)]) == 0


@pytest.mark.parametrize("change, field", [
    (("UPDATE runs SET metrics = json_set(metrics, '$.length', json_extract(metrics, '$.length') + 1e-9) "
      "WHERE run_key LIKE 'aco.as%|1'"), "length"),
    ("UPDATE runs SET iterations = 2 WHERE run_key LIKE 'aco.as%|0'", "iterations"),
    ("UPDATE runs SET stopped_by = 'cpu_time' WHERE run_key LIKE 'exact.astar%|0'", "stopped_by"),
    ("UPDATE history SET best_cost = best_cost * 2 WHERE run_key LIKE 'aco.as%|0'", "history"),
    ("DELETE FROM runs WHERE run_key LIKE 'exact.astar%|1'", "run"),
])
def test_any_changed_value_fails_the_comparison(two_runs, tmp_path, change, field):
    a, b = two_runs
    changed = tmp_path / "changed.sqlite"
    shutil.copy(b, changed)
    with sqlite3.connect(changed) as conn:
        conn.execute(change)
    result = compare_results(a, changed)
    assert not result.identical and {d.field for d in result.differences} == {field}
    assert main(["compare", str(a), str(changed)]) == 1


def test_a_changed_path_fails_the_comparison(two_runs, tmp_path):
    a, b = two_runs
    changed = tmp_path / "path.sqlite"
    shutil.copy(b, changed)
    key = next(k for k in read_runs(b)["run_key"] if k.startswith("exact.astar"))
    path = read_record(b, "twice", key).path.copy()
    path[1, 0] = np.nextafter(path[1, 0], np.inf)  # one bit
    with sqlite3.connect(changed) as conn:
        conn.execute("UPDATE runs SET path = ? WHERE run_key = ?", (path.tobytes(), key))
    assert [d.field for d in compare_results(a, changed).differences] == ["path"]


def test_runs_store_which_limit_ended_them(two_runs):
    runs = read_runs(two_runs[0]).set_index("planner")
    assert set(runs.loc["exact.astar", "stopped_by"]) == {"none"}  # an exact search ends by itself
    assert set(runs.loc["aco.as", "stopped_by"]) == {"none"}  # its own 3 iterations: no count in the budget


def test_a_database_from_before_stopped_by_stays_readable(two_runs, tmp_path):
    old = tmp_path / "old.sqlite"
    shutil.copy(two_runs[0], old)
    with sqlite3.connect(old) as conn:
        conn.execute("ALTER TABLE runs DROP COLUMN stopped_by")  # the layout before the column
    assert set(read_runs(old)["stopped_by"]) == {""}  # unknown
    with ResultStore(old) as store:  # opening for writing adds it back, keeping the rows
        assert store.count_runs("twice") == 4
    assert set(read_runs(old)["stopped_by"]) == {""}
