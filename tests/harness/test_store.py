"""The result database: round trips, one row per key, schema guard, and no data ever dropped."""

from __future__ import annotations

import math
import sqlite3

import numpy as np
import pytest

from pathzoo import Budget, RunRecord, RunStatus
from pathzoo.core.results import HistoryPoint
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.store import (
    RUN_COLUMNS,
    ResultsDatabaseError,
    ResultStore,
    read_experiments,
    read_history,
    read_path,
    read_record,
    read_runs,
)


@pytest.fixture
def experiment(forged) -> Experiment:
    return Experiment.build(planners=["test.honest"], scenarios=["test.wall"], seeds=2, name="store", seed=5,
                            budget=Budget(time_s=1.0))


def make_record(key: str, status=RunStatus.SOLVED, **kw) -> RunRecord:
    fields = dict(
        run_key=key, experiment="store", planner_id="test.honest", planner_version="1", params={"delay_s": 0.0},
        params_hash="abc", scenario_id="test.wall", seed_index=0, seed=2**62 + 3, status=status,
        valid=status is RunStatus.SOLVED, invalid_reason="", message="ok", wall_time_s=0.5, cpu_time_s=0.25,
        iterations=3, evaluations=30, path=np.array([[0.5, 5.5], [1 / 3, 2.0], [5.5, 5.5]]), times=None,
        history=(HistoryPoint(0, 10, math.inf, 0.01), HistoryPoint(2, 30, 9.5, 0.02)),
        metrics={"length": 9.25, "success": 1.0, "energy": math.nan, "odd id": 1.0}, versions={"pathzoo": "0"},
        started_at="2026-01-01T00:00:00+00:00",
    )
    fields.update(kw)
    return RunRecord(**fields)


def test_round_trip(tmp_path, experiment):
    db = tmp_path / "r.sqlite"
    with ResultStore(db) as store:
        store.add_experiment(experiment)
        assert store.insert(make_record("a"))
        assert store.insert(make_record("b", status=RunStatus.CRASH, path=None, metrics={"length": math.nan},
                                        history=(), times=None))
        assert not store.insert(make_record("a", message="again"))  # same key: ignored
        assert store.finished_keys("store") == {"a", "b"} and store.count_runs("store") == 2
    frame = read_runs(db, "store")
    assert list(frame.columns[: len(RUN_COLUMNS)]) == list(RUN_COLUMNS)
    assert list(frame.run_key) == ["a", "b"] and frame.message[0] == "ok"
    assert frame.params[0] == {"delay_s": 0.0} and frame.seed[0] == 2**62 + 3 and frame.valid.tolist() == [True, False]
    assert frame.iterations[0] == 3 and math.isnan(frame.iterations[1])  # no count for a crash
    assert frame.length[0] == 9.25 and math.isnan(frame.energy[0]) and math.isnan(frame.length[1])
    assert "odd id" in frame.columns
    path, times = read_path(db, "store", "a")
    assert np.array_equal(path, make_record("a").path) and times is None  # float64 exact
    assert read_path(db, "store", "b") == (None, None)
    hist = read_history(db, "store")
    assert hist.best_cost.tolist() == [math.inf, 9.5] and set(hist.run_key) == {"a"}
    rec = read_record(db, "store", "a")
    assert rec.history == make_record("a").history and rec.status is RunStatus.SOLVED and rec.success
    assert math.isnan(rec.metrics["energy"])
    conn = sqlite3.connect(db)
    assert conn.execute('SELECT "metric:length" FROM runs WHERE run_key = "a"').fetchone() == (9.25,)
    assert conn.execute("PRAGMA journal_mode").fetchone() == ("wal",)
    conn.close()
    exps = read_experiments(db)
    assert exps.name.tolist() == ["store"] and exps.n_runs.tolist() == [2] and exps.config[0]["seed"] == 5


def test_reader_errors(tmp_path, experiment):
    db = tmp_path / "r.sqlite"
    with pytest.raises(ResultsDatabaseError, match="no such results database"):
        read_runs(db)
    assert not db.exists()  # readers never create files
    with ResultStore(db) as store:
        store.add_experiment(experiment)
    with pytest.raises(ResultsDatabaseError, match=r"no experiment named 'other' \(stored: store\)"):
        read_runs(db, "other")
    with pytest.raises(ResultsDatabaseError, match="has no run 'zzz'"):
        read_path(db, "store", "zzz")
    assert len(read_runs(db)) == 0


def test_changed_settings_under_the_same_name_are_refused(tmp_path, experiment, forged):
    db = tmp_path / "r.sqlite"
    with ResultStore(db) as store:
        store.add_experiment(experiment)
        store.add_experiment(experiment)  # same settings: fine
        more = Experiment.build(planners=["test.honest", "test.gridonly"], scenarios=["test.wall"], seeds=5,
                                name="store", seed=5, budget=Budget(time_s=1.0))
        store.add_experiment(more)  # more planners and seeds: fine
        for change in ({"seed": 6}, {"budget": Budget(time_s=2.0)}, {"timeout_s": 99.0}):
            other = Experiment.build(planners=["test.honest"], scenarios=["test.wall"], seeds=2, name="store",
                                     **({"seed": 5, "budget": Budget(time_s=1.0)} | change))
            with pytest.raises(ResultsDatabaseError, match=f"stored with {next(iter(change))} = "):
                store.add_experiment(other)


def test_foreign_and_future_files_are_refused_and_left_alone(tmp_path):
    foreign = tmp_path / "foreign.sqlite"
    conn = sqlite3.connect(foreign)
    conn.execute("CREATE TABLE precious (x)")
    conn.execute("INSERT INTO precious VALUES (42)")
    conn.commit()
    conn.close()
    with pytest.raises(ResultsDatabaseError, match="not a pathzoo results database"):
        ResultStore(foreign)
    conn = sqlite3.connect(foreign)
    assert conn.execute("SELECT x FROM precious").fetchall() == [(42,)]
    conn.close()

    text = tmp_path / "notes.sqlite"
    text.write_text("hello " * 1000)
    with pytest.raises(ResultsDatabaseError, match="not a results database"):
        ResultStore(text)
    assert text.read_text() == "hello " * 1000

    future = tmp_path / "future.sqlite"
    ResultStore(future).close()
    conn = sqlite3.connect(future)
    conn.execute("UPDATE pathzoo_schema SET version = 99")
    conn.commit()
    conn.close()
    with pytest.raises(ResultsDatabaseError, match="schema version 99; this pathzoo reads version 1"):
        ResultStore(future)
    with pytest.raises(ResultsDatabaseError, match="schema version 99"):
        read_runs(future)

    with pytest.raises(ResultsDatabaseError, match="does not exist"):
        ResultStore(tmp_path / "no" / "dir.sqlite")


def test_reopening_keeps_everything(tmp_path, experiment):
    db = tmp_path / "r.sqlite"
    with ResultStore(db) as store:
        store.add_experiment(experiment)
        store.insert(make_record("a"))
    with ResultStore(db) as store:
        store.add_experiment(experiment)
        store.insert(make_record("c", metrics={"new_metric": 2.0}))  # a new metric column is added, none dropped
    frame = read_runs(db)
    assert frame.run_key.tolist() == ["a", "c"] and frame.length[0] == 9.25 and frame.new_metric[1] == 2.0


class _FullDisk:
    """A connection whose writes of runs fail as SQLite fails on a full disk (``error``); reads pass through."""

    def __init__(self, conn: sqlite3.Connection, error: str) -> None:
        self.conn, self.error = conn, error

    def execute(self, sql: str, *args):
        if sql.lstrip().startswith("INSERT") and "runs" in sql:
            raise sqlite3.OperationalError(self.error)
        return self.conn.execute(sql, *args)

    def __getattr__(self, name: str):
        return getattr(self.conn, name)


@pytest.mark.parametrize("error, free", [("database or disk is full", 10 << 30), ("disk I/O error", 4096)])
def test_a_full_disk_is_named_in_one_line_and_loses_nothing(tmp_path, experiment, monkeypatch, error, free):
    import os

    db = tmp_path / "r.sqlite"
    with ResultStore(db) as store:
        store.add_experiment(experiment)
        assert store.insert(make_record("a"))
        store.conn = _FullDisk(store.conn, error)  # type: ignore[assignment]
        statvfs = os.statvfs
        monkeypatch.setattr(os, "statvfs", lambda p: os.statvfs_result((4096, 4096, 10**6, 1, free // 4096,
                                                                        *statvfs(p)[5:])))
        with pytest.raises(ResultsDatabaseError) as caught:
            store.insert(make_record("b"))
        monkeypatch.undo()
        store.conn = store.conn.conn
        assert store.insert(make_record("b"))  # space freed: the same store goes on
    message = str(caught.value)
    assert "disk is full" in message and str(db) in message and "\n" not in message
    assert read_runs(db, "store").run_key.tolist() == ["a", "b"]


def test_another_io_error_is_not_called_a_full_disk(tmp_path, experiment):
    db = tmp_path / "r.sqlite"
    with ResultStore(db) as store:
        store.add_experiment(experiment)
        store.conn = _FullDisk(store.conn, "disk I/O error")  # type: ignore[assignment]
        with pytest.raises(sqlite3.OperationalError, match="disk I/O error"):
            store.insert(make_record("b"))
        store.conn = store.conn.conn


def test_insert_batch_stores_each_run_once_in_one_transaction(tmp_path, experiment):
    db = tmp_path / "b.sqlite"
    with ResultStore(db) as store:
        store.add_experiment(experiment)
        assert store.insert_batch([make_record("a"), make_record("b")], labels=["one", "two"]) == 2
        assert store.insert_batch([make_record("b"), make_record("c")]) == 1  # b is stored already
        with pytest.raises(ValueError, match="3 records but 1 labels"):
            store.insert_batch([make_record("d"), make_record("e"), make_record("f")], labels=["x"])
        assert store.count_runs("store") == 3
    frame = read_runs(db, "store")
    assert list(frame.run_key) == ["a", "b", "c"] and list(frame.label) == ["one", "two", ""]
    assert len(read_history(db, "store")) == 6
    assert list(read_runs(db, "store", run_keys=["c", "a", "zz"]).run_key) == ["a", "c"]  # filtered by SQLite
