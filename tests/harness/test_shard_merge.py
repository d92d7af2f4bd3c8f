"""Shards (``--shard K/N``) split an experiment's runs disjointly; ``pathzoo merge`` joins them into one run's database."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import numpy as np
import pytest

from pathzoo import Budget
from pathzoo.analysis.repeatability import compare_results
from pathzoo.cli.main import main
from pathzoo.core.errors import InvalidExperimentError
from pathzoo.core.scenario import Scenario
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.merge import merge_databases
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.shard import Shard, parse_shard
from pathzoo.harness.store import ResultsDatabaseError, read_history, read_runs


def _open_grid(cells: int) -> Scenario:
    return Scenario(id="test.open", kind="grid2d", occupancy=np.zeros((cells, cells), bool), cell_size=1.0,
                    start=(0.5, 0.5), goal=(cells - 0.5, cells - 0.5))


def _experiment(forged, budget: Budget = Budget(iterations=50), open_cells: int = 6) -> Experiment:
    return Experiment.build(planners=["test.honest", ("test.honest", {"delay_s": 0.001})],
                            scenarios=["test.wall", forged.street_scenario(), _open_grid(open_cells)], seeds=3,
                            name="sharded", seed=4, budget=budget, timeout_s=20)


def _history_rows(db: Path) -> list[tuple]:
    frame = read_history(db, "sharded").drop(columns="time_s")
    return sorted(map(tuple, frame.itertuples(index=False)))


@pytest.mark.parametrize("count", [1, 2, 3, 7, 40])
def test_shards_are_disjoint_and_cover_the_runs(forged, count):
    keys = [t.run_key for t in _experiment(forged).tasks()]
    shards = [[t.run_key for t in Shard(k, count).select(_experiment(forged).tasks())] for k in range(1, count + 1)]
    assert sorted(k for shard in shards for k in shard) == sorted(keys)
    assert len({k for shard in shards for k in shard}) == len(keys) == 18
    assert max(map(len, shards)) - min(map(len, shards)) <= 1  # dealt out one by one


@pytest.mark.parametrize("text", ["0/2", "3/2", "1", "a/b", "1/0", "-1/2", ""])
def test_bad_shard_is_refused(text):
    with pytest.raises(InvalidExperimentError, match="shard"):
        parse_shard(text)


def test_merged_shards_equal_one_run(forged, tmp_path):
    whole = tmp_path / "whole.sqlite"
    run_experiment(_experiment(forged), db=whole, executor="inline", progress=False)
    shards = []
    for k in (1, 2):
        db = tmp_path / f"shard{k}.sqlite"
        frame = run_experiment(_experiment(forged), db=db, executor="inline", progress=False, shard=Shard(k, 2))
        assert len(frame) == 9
        shards.append(db)
    first, second = (set(read_runs(db)["run_key"]) for db in shards)
    assert not first & second and len(first | second) == 18

    out = tmp_path / "merged.sqlite"
    (merged,) = merge_databases(shards, out)
    assert (merged.added, merged.duplicates, merged.total) == (18, 0, 18)
    comparison = compare_results(whole, out)
    assert comparison.identical and comparison.n_runs == 18, comparison.summary()
    assert _history_rows(out) == _history_rows(whole) and _history_rows(out)

    # merging again, or a shard with the whole run, copies nothing twice
    (again,) = merge_databases([shards[1], whole], out)
    assert (again.added, again.duplicates, again.total) == (0, 27, 18)
    assert _history_rows(out) == _history_rows(whole)
    with sqlite3.connect(out) as conn:
        assert conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0] == 18


def test_a_different_experiment_is_refused_before_writing(forged, tmp_path):
    shard = tmp_path / "a.sqlite"
    run_experiment(_experiment(forged), db=shard, executor="inline", progress=False, shard=Shard(1, 2))
    others = {"budget": _experiment(forged, budget=Budget(iterations=51)),
              "scenario 'test.open' differs in digest": _experiment(forged, open_cells=7)}
    for i, (what, other) in enumerate(others.items()):
        db = tmp_path / f"other{i}.sqlite"
        run_experiment(other, db=db, executor="inline", progress=False, shard=Shard(2, 2))
        out = tmp_path / f"out{i}.sqlite"
        with pytest.raises(ResultsDatabaseError, match=what):
            merge_databases([shard, db], out)
        assert not out.exists()


def _set_planner_versions(db: Path, version: str | None) -> None:
    """Rewrite the stored planner versions (None: drop them, as in files written before they were stored)."""
    with sqlite3.connect(db) as conn:
        config = json.loads(conn.execute("SELECT config FROM experiments").fetchone()[0])
        for planner in config["planners"]:
            planner.pop("version")
            if version is not None:
                planner["version"] = version
        conn.execute("UPDATE experiments SET config = ?", (json.dumps(config),))


def test_another_planner_version_is_refused_and_a_file_without_versions_is_not(forged, tmp_path):
    a, b = tmp_path / "a.sqlite", tmp_path / "b.sqlite"
    for db, k in ((a, 1), (b, 2)):
        run_experiment(_experiment(forged), db=db, executor="inline", progress=False, shard=Shard(k, 2))
    with sqlite3.connect(a) as conn:
        assert all(p["version"] for p in json.loads(conn.execute("SELECT config FROM experiments").fetchone()[0])
                   ["planners"])
    _set_planner_versions(b, "9.9.9")
    with pytest.raises(ResultsDatabaseError, match="planner configurations differ"):
        merge_databases([a, b], tmp_path / "out.sqlite")
    _set_planner_versions(b, None)
    (merged,) = merge_databases([a, b], tmp_path / "out.sqlite")
    assert merged.total == 18


def test_merge_command_one_line_and_exit_codes(forged, tmp_path, capsys):
    a, b = tmp_path / "a.sqlite", tmp_path / "b.sqlite"
    run_experiment(_experiment(forged), db=a, executor="inline", progress=False, shard=Shard(1, 2))
    run_experiment(_experiment(forged, budget=Budget(iterations=51)), db=b, executor="inline", progress=False,
                   shard=Shard(2, 2))
    capsys.readouterr()
    assert main(["merge", str(a), str(b), "-o", str(tmp_path / "out.sqlite")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("pathzoo: error: ") and "budget" in err
    assert main(["merge", str(a), "-o", str(a)]) == 2
    assert "also an input" in capsys.readouterr().err
    assert main(["merge", str(a), "-o", str(tmp_path / "ok.sqlite")]) == 0
    assert "9 runs added; 9 runs in" in capsys.readouterr().err
