"""Running experiments: same results on every executor, observer hooks, progress, resuming after a crash."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import pathzoo
from pathzoo import Budget
from pathzoo.harness.executors import dask_executor
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.sandbox import sandbox_problem
from pathzoo.harness.store import read_history, read_path
from pathzoo.plugins.manager import get_registry

TESTS_DIR = Path(__file__).resolve().parents[1]
TIMING = ["wall_time_s", "cpu_time_s", "planning_time", "cpu_time"]


@pytest.fixture(scope="module")
def small_scen(tmp_path_factory, shared_data) -> Path:
    """A two-problem ``.scen`` file on the MovingAI arena map."""
    folder = tmp_path_factory.mktemp("scen")
    src = shared_data / "movingai" / "grid" / "dao"
    (folder / "arena.map").write_text((src / "arena.map").read_text())
    lines = (src / "arena.map.scen").read_text().splitlines()
    (folder / "two.scen").write_text("\n".join([lines[0], lines[40], lines[120]]) + "\n")
    return folder / "two.scen"


def experiment(forged, small_scen, name="repro") -> Experiment:
    return Experiment.build(planners=["test.honest", ("test.honest", {"delay_s": 0.001})],
                            scenarios=["test.wall", small_scen, forged.street_scenario()], seeds=2, name=name, seed=9,
                            budget=Budget(time_s=1.0), timeout_s=20)


def comparable(db: Path, frame: pd.DataFrame) -> tuple[pd.DataFrame, list]:
    frame = frame.drop(columns=TIMING).sort_values("run_key").reset_index(drop=True)
    paths = [read_path(db, "repro", key) for key in frame.run_key]
    hist = read_history(db, "repro").sort_values(["run_key", "iteration"]).drop(columns="time_s").reset_index(drop=True)
    return frame, [paths, hist]


def test_same_results_inline_process_and_dask(forged, small_scen, tmp_path):
    results = {}
    for name, executor in [("inline", "inline"), ("process", "process"),
                           ("dask", dask_executor(jobs=1, processes=False))]:
        db = tmp_path / f"{name}.sqlite"
        frame = run_experiment(experiment(forged, small_scen), db=db, jobs=2, executor=executor, progress=False)
        results[name] = comparable(db, frame)
    assert not results["inline"][0].isolated.any() and results["process"][0].isolated.all()
    assert results["dask"][0].isolated.all()  # Dask workers are threads here, but planners run in their children
    sandboxed = not sandbox_problem()
    assert [results[name][0].sandboxed.all() for name in results] == [False, sandboxed, sandboxed]
    results = {name: (frame.drop(columns=["isolated", "sandboxed"]), rest) for name, (frame, rest) in results.items()}
    base, (paths, hist) = results["inline"]
    assert len(base) == 2 * 4 * 2 and (base.status == "solved").all()
    assert base.iterations.nunique() > 1  # the planner really draws from its rng
    for name in ("process", "dask"):
        frame, (other_paths, other_hist) = results[name]
        pd.testing.assert_frame_equal(frame, base)
        assert all(np.array_equal(a[0], b[0]) for a, b in zip(paths, other_paths))
        pd.testing.assert_frame_equal(other_hist, hist)


class Observer:
    def __init__(self) -> None:
        self.events: list[tuple] = []

    @pathzoo.hookimpl
    def pathzoo_run_started(self, run_key, planner_id, scenario_id, seed):
        self.events.append(("started", run_key, planner_id, scenario_id, seed))

    @pathzoo.hookimpl
    def pathzoo_run_finished(self, record):
        self.events.append(("finished", record.run_key, record.status.value))

    @pathzoo.hookimpl
    def pathzoo_experiment_finished(self, experiment, db, n_runs):
        self.events.append(("experiment", experiment, db, n_runs))


def test_hooks_resume_and_progress(forged, tmp_path, capfd):
    observer = Observer()
    pm = get_registry().pm
    pm.register(observer, name="observer-test")
    db = tmp_path / "r.sqlite"
    try:
        first = pathzoo.run(["test.honest"], ["test.wall"], seeds=2, db=db, executor="inline", experiment="grow",
                            progress=False)
        assert capfd.readouterr().err == ""  # quiet without a progress bar
        second = pathzoo.run(["test.honest"], ["test.wall"], seeds=4, db=db, executor="inline", experiment="grow",
                             progress=True)
        err = capfd.readouterr().err
    finally:
        pm.unregister(observer)
    assert len(first) == 2 and len(second) == 4
    pd.testing.assert_frame_equal(second.iloc[:2], first)  # stored runs are kept, not re-run
    kinds = [e[0] for e in observer.events]
    assert kinds == ["started", "finished"] * 2 + ["experiment"] + ["started", "finished"] * 2 + ["experiment"]
    started = [e for e in observer.events if e[0] == "started"]
    assert [e[1] for e in started] == second.run_key.tolist()
    assert [e[4] for e in started] == second.seed.tolist()
    assert observer.events[-1] == ("experiment", "grow", str(db), 4)
    assert "grow" in err and "2/2" in err and "failures=0" in err
    # nothing left to do: no executor is started, the stored runs come back
    third = pathzoo.run(["test.honest"], ["test.wall"], seeds=4, db=db, executor="process", experiment="grow",
                        progress=False)
    pd.testing.assert_frame_equal(third, second)


@pytest.mark.slow
def test_resume_after_the_harness_is_killed(forged, tmp_path):
    """SIGKILL the harness (a ``python -c`` process) mid-way, run it again: exactly one row per run key."""
    db = tmp_path / "killed.sqlite"
    n_runs = 6
    script = textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(TESTS_DIR)!r})
        import pathzoo
        from pathzoo.plugins.manager import get_registry
        from harness import forged
        get_registry().add_plugin(forged, "forged-test")
        pathzoo.run([("test.honest", {{"delay_s": 0.3}})], ["test.wall"], seeds={n_runs}, db={str(db)!r}, jobs=1,
                    experiment="killed", progress=False, executor=sys.argv[1])
    """)

    def rows() -> int:
        if not db.exists():
            return 0
        conn = sqlite3.connect(db, timeout=30)
        try:
            return conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
        except sqlite3.OperationalError:  # tables not created yet
            return 0
        finally:
            conn.close()

    proc = subprocess.Popen([sys.executable, "-c", script, "process"], stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 120
    while rows() < 2 and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.05)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    done_before = rows()
    assert 2 <= done_before < n_runs, "the harness must be killed mid-way"
    # the orphaned worker must not disturb the rerun (inline here only to save the worker start-up time)
    subprocess.run([sys.executable, "-c", script, "inline"], stderr=subprocess.DEVNULL, check=True, timeout=120)
    conn = sqlite3.connect(db)
    keys = [k for (k,) in conn.execute("SELECT run_key FROM runs WHERE experiment = 'killed'")]
    statuses = {s for (s,) in conn.execute("SELECT status FROM runs")}
    conn.close()
    assert len(keys) == n_runs and len(set(keys)) == n_runs and statuses == {"solved"}
