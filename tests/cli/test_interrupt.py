"""Ctrl-C during ``pathzoo run`` on the process executor: it ends within 3 s and the resume is exact.

The process executor keeps idle workers across switches of planner
configuration (``ProcessExecutor.kept_workers``), so an interrupt can come
while workers of several configurations are alive, some running and some
idle. Each case interrupts a real ``pathzoo run`` once some runs are stored,
resumes it, and compares the database with one from an uninterrupted run.
"""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

import pytest

SCENARIO = """
id = "interrupt.random{index}"
kind = "grid2d"
description = "random obstacles"
endpoint_seed = {index}

[map]
generator = "random"
seed = {index}
shape = [24, 24]
density = 0.2
"""

EXPERIMENT = """
[experiment]
name = "interrupt"
seeds = {seeds}
budget = {{ iterations = 3, time_s = 30.0 }}
scenarios = [{scenarios}]
{planners}
"""

CASES = {
    # one worker, two exact planners alternating over scenarios
    "jobs1-exact": (1, ["exact.astar", "exact.thetastar"], 4, 3),
    # two workers, up to four kept: an exact planner and a colony over many scenarios
    "jobs2-exact-aco": (2, ["exact.astar", "aco.as"], 8, 2),
    # two workers, three configurations: more configurations than running workers
    "jobs2-three-configs": (2, ["exact.astar", "exact.thetastar", "aco.as"], 4, 2),
}

DEADLINE_S = 3.0
"""Ctrl-C must end ``pathzoo run`` within this many seconds (issue 38, Build 4)."""


def _write_experiment(tmp_path: Path, planners: list[str], scenarios: int, seeds: int) -> Path:
    names = []
    for index in range(scenarios):
        name = f"random{index}.toml"
        (tmp_path / name).write_text(SCENARIO.format(index=index))
        names.append(f'"{name}"')
    tables = "".join(f'\n[[planner]]\nid = "{p}"\n' for p in planners)
    path = tmp_path / "interrupt.toml"
    path.write_text(EXPERIMENT.format(seeds=seeds, scenarios=", ".join(names), planners=tables))
    return path


def _command(experiment: Path, db: Path, jobs: int) -> list[str]:
    return [sys.executable, "-m", "pathzoo.cli.main", "run", str(experiment), "--db", str(db), "--jobs", str(jobs),
            "--executor", "process", "--no-progress"]


def _stored(db: Path) -> int:
    try:
        conn = sqlite3.connect(f"file:{db}?mode=ro", uri=True, timeout=0.1)
        try:
            return int(conn.execute("SELECT COUNT(*) FROM runs").fetchone()[0])
        finally:
            conn.close()
    except sqlite3.Error:  # not created yet, or locked by the writer for a moment
        return 0


def _contents(db: Path) -> tuple[list[tuple[object, ...]], list[tuple[object, ...]]]:
    """Every run's outcome and path and every history row, without clocks, dates or row ids."""
    conn = sqlite3.connect(db)
    try:
        runs = conn.execute(
            "SELECT run_key, planner, params, scenario, seed_index, seed, status, valid, invalid_reason, "
            "iterations, evaluations, path, path_shape, stopped_by, sandboxed FROM runs ORDER BY run_key").fetchall()
        history = conn.execute(
            "SELECT run_key, iteration, evaluations, best_cost FROM history ORDER BY run_key, iteration").fetchall()
    finally:
        conn.close()
    return runs, history


def _environment() -> dict[str, str]:
    env = dict(os.environ)
    env.pop("COLUMNS", None)
    return env


@pytest.mark.slow
@pytest.mark.parametrize("case", list(CASES))
def test_ctrl_c_ends_the_run_within_3_s_and_the_resume_equals_an_uninterrupted_run(case, tmp_path):
    jobs, planners, scenarios, seeds = CASES[case]
    experiment = _write_experiment(tmp_path, planners, scenarios, seeds)
    total = len(planners) * scenarios * seeds
    env = _environment()

    whole = tmp_path / "whole.sqlite"
    done = subprocess.run(_command(experiment, whole, jobs), env=env, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    assert _stored(whole) == total

    cut = tmp_path / "cut.sqlite"
    proc = subprocess.Popen(_command(experiment, cut, jobs), env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        give_up = time.monotonic() + 300
        while _stored(cut) < 2 and proc.poll() is None and time.monotonic() < give_up:
            time.sleep(0.02)
        assert proc.poll() is None, "the run ended before it could be interrupted: " + proc.stderr.read()
        sent = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
        took = time.monotonic() - sent
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert took <= DEADLINE_S, f"Ctrl-C took {took:.2f} s to end pathzoo run"
    assert proc.returncode != 0 and "interrupted" in err, err
    stored = _stored(cut)
    assert 2 <= stored < total, f"{stored} of {total} runs stored at the interrupt: nothing left to resume"

    resumed = subprocess.run(_command(experiment, cut, jobs), env=env, capture_output=True, text=True, timeout=600)
    assert resumed.returncode == 0, resumed.stderr
    assert _contents(cut) == _contents(whole)
