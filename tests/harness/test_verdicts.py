"""Every forged, broken or hostile planner is recorded honestly by the process executor, and the experiment goes on."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest

import pathzoo
from pathzoo import Budget
from pathzoo.grid.reference import reference_path
from pathzoo.harness.store import read_history, read_path, read_record

HONEST_WALL_PATH = [[0.5, 5.5], [1.5, 4.5], [2.5, 3.5], [2.5, 0.5], [4.5, 0.5], [5.5, 1.5], [5.5, 5.5]]
CORNER_CUT = [[0.5, 5.5], [2.5, 3.5], [2.5, 1.5], [3.5, 0.5], [4.5, 0.5], [5.5, 1.5], [5.5, 5.5]]


def fixed(path, times=None, status="solved"):
    return ("test.fixed", {"path": json.dumps(path), "times": json.dumps(times), "status": status})


FORGERIES = {
    "through_wall": fixed([[0.5, 5.5], [5.5, 5.5]]),
    "corner_cut": fixed(CORNER_CUT),
    "jump": fixed([[0.5, 5.5], [2.5, 5.5], [4.5, 5.5], [5.5, 5.5]]),
    "too_fast": fixed(HONEST_WALL_PATH, times=[0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6]),
    "not_at_goal": fixed(HONEST_WALL_PATH[:-1]),
    "nan": fixed([[0.5, 5.5], [float("nan"), 1.0], [5.5, 5.5]]),
    "wrong_shape": fixed([[0.5, 5.5, 0.0], [5.5, 5.5, 0.0]]),
    "no_path_in_hand": fixed(None),
    "false_no_path": fixed(None, status="no_path"),
    "failed": fixed(None, status="failed"),
    "valid_but_fixed": fixed(HONEST_WALL_PATH),
}
SABOTAGE = ("raise", "sleep", "exit", "kill", "mutate", "garbage", "sysexit")
TIMEOUT_S = 1.5


@pytest.fixture(scope="module")
def runs(forged, tmp_path_factory) -> tuple[pd.DataFrame, str]:
    db = tmp_path_factory.mktemp("verdicts") / "runs.sqlite"
    planners = ["test.honest", *FORGERIES.values(), *(("test.sabotage", {"how": h}) for h in SABOTAGE)]
    frame = pathzoo.run(planners, ["test.wall"], seeds=1, db=db, jobs=2, budget=Budget(time_s=0.2),
                        timeout_s=TIMEOUT_S, experiment="verdicts", progress=False)
    sealed = pathzoo.run([fixed(None, status="no_path")], ["test.sealed"], seeds=1, db=db, jobs=1,
                         budget=Budget(time_s=0.2), timeout_s=TIMEOUT_S, experiment="sealed", progress=False)
    return pd.concat([frame, sealed], ignore_index=True), str(db)


def row(frame: pd.DataFrame, planner, scenario="test.wall", **params) -> pd.Series:
    if isinstance(planner, tuple):
        planner, params = planner
    same_params = frame.params.map(lambda p: all(p.get(k) == v for k, v in params.items()))
    hits = frame[(frame.planner == planner) & (frame.scenario == scenario) & same_params]
    assert len(hits) == 1, (planner, params)
    return hits.iloc[0]


def test_every_run_is_stored_once(runs):
    frame, _ = runs
    assert len(frame) == 1 + len(FORGERIES) + len(SABOTAGE) + 1
    assert frame.run_key.is_unique


def test_honest_planner_is_solved_with_metrics_and_history(runs, forged):
    frame, db = runs
    r = row(frame, "test.honest")
    assert r.status == "solved" and r.valid and r.invalid_reason == ""
    assert r.length == pytest.approx(9 + 3 * math.sqrt(2)) and r.length_ratio == pytest.approx(1.0)
    path, times = read_path(db, "verdicts", r.run_key)
    assert np.array_equal(path, reference_path(forged.wall_scenario()).path) and times is None
    hist = read_history(db, "verdicts")
    mine = hist[hist.run_key == r.run_key]
    assert len(mine) == r.iterations  # every improvement once; repeated reports are not stored
    assert mine.best_cost.is_monotonic_decreasing and mine.time_s.is_monotonic_increasing
    rec = read_record(db, "verdicts", r.run_key)
    assert rec.success and rec.metrics["length"] == r.length and rec.versions["pathzoo"] == pathzoo.__version__


@pytest.mark.parametrize("name, reason", [
    ("through_wall", "touches blocked cell"),
    ("corner_cut", "segment 2: segment (2.5, 1.5) -> (3.5, 0.5) touches blocked cell (row 1, col 3)"),
    ("jump", "touches blocked cell (row 5, col 3)"),
    ("too_fast", "faster than cruise speed"),
    ("not_at_goal", "not at the goal"),
    ("nan", "NaN"),
    ("wrong_shape", "shape"),
    ("no_path_in_hand", "claimed solved but the path is missing"),
    ("false_no_path", "claimed no path but one exists"),
])
def test_forgeries_are_invalid_never_solved(runs, name, reason):
    r = row(runs[0], FORGERIES[name])
    assert r.status == "invalid" and not r.valid
    assert reason in r.invalid_reason
    assert r.success == 0 and math.isnan(r.length) and math.isnan(r.energy)


def test_honest_claims_are_accepted(runs):
    frame, _ = runs
    assert row(frame, FORGERIES["valid_but_fixed"]).status == "solved"
    assert row(frame, FORGERIES["failed"]).status == "failed"
    sealed = frame[frame.scenario == "test.sealed"].iloc[0]
    assert sealed.status == "no_path" and sealed.invalid_reason == ""


@pytest.mark.parametrize("how, status, message", [
    ("raise", "crash", "ValueError: planted bug"),
    ("sysexit", "crash", "SystemExit: 4"),
    ("garbage", "crash", "plan() returned str, not a PlanResult"),
    ("exit", "crash", "worker process died (exit code 3)"),
    ("kill", "crash", "worker process died (signal 9 (SIGKILL))"),
    ("sleep", "timeout", f"stopped at the hard limit of {TIMEOUT_S:g} s"),
])
def test_saboteurs_crash_or_time_out(runs, how, status, message):
    r = row(runs[0], "test.sabotage", how=how)
    assert r.status == status and not r.valid
    assert r.message.startswith(message)
    assert math.isnan(r.iterations) and r.success == 0 and math.isnan(r.length)
    if how == "raise":
        assert "Traceback" in r.message and "forged.py" in r.message
    if how == "sleep":
        assert TIMEOUT_S <= r.wall_time_s < TIMEOUT_S + 5


def test_writing_into_the_scenario_is_refused_and_does_not_leak(runs):
    frame, _ = runs
    r = row(frame, "test.sabotage", how="mutate")  # its arrays are sealed read-only (pathzoo.harness.sealed)
    assert r.status == "crash" and "cannot set WRITEABLE flag" in r.message
    assert row(frame, "test.honest").status == "solved"


def test_unsupported_pairs_are_skipped_and_reported(forged, tmp_path, caplog):
    caplog.set_level("INFO", logger="pathzoo.harness")  # the list of pairs; the warning only counts them
    frame = pathzoo.run(["test.gridonly", "test.honest"], ["test.wall", "test.ramp"], seeds=1, db=tmp_path / "s.sqlite",
                        executor="inline", progress=False)
    assert sorted(zip(frame.planner, frame.scenario)) == [
        ("test.gridonly", "test.wall"), ("test.honest", "test.ramp"), ("test.honest", "test.wall")]
    assert "test.gridonly x test.ramp (terrain)" in caplog.text
    assert "skipping 1 unsupported planner x scenario pair(s) (scenario kind not supported: terrain 1)" in caplog.text
