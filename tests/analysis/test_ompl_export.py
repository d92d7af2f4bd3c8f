"""OMPL benchmark logs: OMPL's own ompl_benchmark_statistics.py must turn them into Planner Arena's database."""

from __future__ import annotations

import importlib.util
import os
import sqlite3
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pathzoo.analysis.ompl_export import OMPL_STATUS, OMPL_STATUS_NAMES, export_ompl, write_ompl_logs
from pathzoo.analysis.synthetic import make_runs
from pathzoo.core.errors import InvalidParameterError


def ompl_script() -> Path:
    spec = importlib.util.find_spec("ompl")
    assert spec is not None and spec.submodule_search_locations, "the ompl wheel is a test dependency"
    script = Path(list(spec.submodule_search_locations)[0]) / "ompl_benchmark_statistics.py"
    assert script.is_file()
    return script


def to_arena(logs: list[Path], tmp_path: Path) -> sqlite3.Connection:
    db = tmp_path / "arena.db"
    done = subprocess.run([sys.executable, str(ompl_script()), "-d", str(db), *map(str, logs)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return sqlite3.connect(db)


def frame() -> tuple[pd.DataFrame, pd.DataFrame]:
    runs = make_runs(
        {"map one": {"p": [10.0, 11.0, np.nan], "q": [12.0, np.nan]}, "m2": {"p": [5.0]}},
        statuses={("map one", "q"): ["solved", "crash"]},
    )
    runs["planning_time"] = [0.5, 0.25, 0.125, 1.0, np.nan, 2.0]
    runs["iterations"] = [10.0, 20.0, 30.0, 40.0, np.nan, 7.0]
    runs["params"] = [{"rho": 0.5}] * 3 + [{}] * 3
    key = runs["run_key"].iloc[0]
    history = pd.DataFrame(dict(run_key=key, iteration=[1, 2, 3], evaluations=[5, 10, 15],
                                best_cost=[14.0, 12.0, 10.0], time_s=[0.1, 0.1, 0.3]))  # duplicate time
    return runs, history


def test_ompl_script_reads_our_logs(tmp_path):
    runs, history = frame()
    logs = write_ompl_logs(runs, tmp_path / "logs", history=history, seed=42, time_limit_s=5.0)
    assert [p.name for p in logs] == ["synthetic.m2.log", "synthetic.map_one.log"]
    con = to_arena(logs, tmp_path)
    exps = con.execute("SELECT name, timelimit, runcount, seed, version, scenario FROM experiments ORDER BY id").fetchall()
    assert exps == [("synthetic.m2", 5.0, 1, "42", "pathzoo " + __import__("pathzoo").__version__, "m2"),
                    ("synthetic.map_one", 5.0, 3, "42", "pathzoo " + __import__("pathzoo").__version__, "map one")]
    planners = dict(con.execute("SELECT name, settings FROM plannerConfigs").fetchall())
    assert set(planners) == {"p", "q"} and "rho = 0.5" in planners["p"]
    rows = con.execute(
        "SELECT e.scenario, c.name, r.seed_index, r.time, r.solved, r.correct_solution, r.solution_length, "
        "r.status, r.pathzoo_status, r.iterations FROM runs r JOIN experiments e ON r.experimentid = e.id "
        "JOIN plannerConfigs c ON r.plannerid = c.id ORDER BY e.scenario, c.name, r.seed_index"
    ).fetchall()
    expected = runs.sort_values(["scenario", "planner", "seed_index"])
    assert len(rows) == len(runs)
    for row, (_, r) in zip(rows, expected.iterrows()):
        assert row[:3] == (r.scenario, r.planner, r.seed_index)
        assert row[3] == (None if np.isnan(r.planning_time) else r.planning_time)
        assert row[4] == int(r.success) and row[5] == int(r.valid)
        assert row[6] == (None if np.isnan(r.length) else r.length)
        assert row[7] == OMPL_STATUS[r.status] and row[8] == r.status
        assert row[9] == (None if np.isnan(r.iterations) else int(r.iterations))
    status = dict(con.execute("SELECT value, description FROM enums WHERE name = 'status'").fetchall())
    assert status == dict(enumerate(OMPL_STATUS_NAMES)) and status[OMPL_STATUS["crash"]] == "Crash"
    progress = con.execute("SELECT time, best_cost, iterations FROM progress ORDER BY time").fetchall()
    assert progress == [(0.1, 12.0, 2), (0.3, 10.0, 3)]  # last point kept at a repeated time
    best = con.execute("SELECT count(*) FROM bestPlannerConfigs").fetchone()
    assert best == (2,)  # the script's views work on our columns


@pytest.mark.slow
def test_export_from_database(small_db, tmp_path):
    db, _ = small_db
    logs = export_ompl(db, tmp_path / "logs")
    con = to_arena(logs, tmp_path)
    runs = pd.read_sql("SELECT r.time, r.solved, r.solution_length, c.name FROM runs r JOIN plannerConfigs c "
                       "ON r.plannerid = c.id", con)
    assert sorted(runs["name"].unique()) == ["exact.astar", "exact.dijkstra"] and len(runs) == 6
    assert (runs["solved"] == 1).all() and runs["solution_length"].nunique() == 1
    assert con.execute("SELECT timelimit FROM experiments").fetchone() == (2.0,)
    host, memory = con.execute("SELECT hostname, memorylimit FROM experiments").fetchone()
    assert host != "unknown" and f"({os.cpu_count()}_cores)" in host  # recorded by each run's worker
    assert memory > 0
    with pytest.raises(InvalidParameterError, match="nothing to export"):
        write_ompl_logs(make_runs({}), tmp_path)


def test_host_and_memory_come_from_the_runs_versions(tmp_path):
    runs, _ = frame()
    assert list(runs["scenario"]) == ["map one"] * 5 + ["m2"]
    runs["versions"] = [{"cpu": "Other", "cpu_count": "2", "peak_rss_mb": "nan"}] + [
        {"cpu": "Model X", "cpu_count": "8", "peak_rss_mb": str(mb)} for mb in (350.4, 90.0, 80.0, 70.0, 60.0)]
    logs = write_ompl_logs(runs, tmp_path / "logs", seed=1)
    con = to_arena(logs, tmp_path)
    got = dict(con.execute("SELECT scenario, hostname || ' ' || memorylimit FROM experiments").fetchall())
    assert got == {"map one": "Model_X_(8_cores) 351.0", "m2": "Model_X_(8_cores) 60.0"}
    plain = write_ompl_logs(runs.drop(columns="versions"), tmp_path / "plain", seed=1)
    text = plain[0].read_text()
    assert "Running on unknown" in text and "\n0 MB per run" in text
