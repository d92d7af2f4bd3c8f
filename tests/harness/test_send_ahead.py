"""A busy worker gets its configuration's next run in its pipe, and plans it only once the harness says go."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from pathzoo import Budget
from pathzoo.harness.executors.process import ProcessExecutor
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import run_experiment


@pytest.fixture
def promoted(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The run keys that became a worker's current run from its pipe (sent ahead), in order."""
    keys: list[str] = []
    original = ProcessExecutor._promote

    def spy(self: ProcessExecutor, worker: Any) -> None:
        if worker.ahead is not None:
            keys.append(worker.ahead[0].run_key)
        original(self, worker)

    monkeypatch.setattr(ProcessExecutor, "_promote", spy)
    return keys


def test_each_run_after_the_first_is_sent_ahead_and_all_are_stored_as_alone(forged, tmp_path: Path,
                                                                            promoted: list[str]):
    exp = Experiment.build(planners=[("test.honest", {"delay_s": 0.2})], scenarios=["test.wall"], seeds=5,
                           name="ahead", seed=4, budget=Budget(time_s=1.0), timeout_s=20)
    runs = run_experiment(exp, db=tmp_path / "ahead.sqlite", executor=ProcessExecutor(1), progress=False)
    alone = run_experiment(exp, db=tmp_path / "alone.sqlite", executor="inline", progress=False)
    assert (runs.status == "solved").all() and len(runs) == 5
    assert len(promoted) == 4 and set(promoted) < set(runs.run_key)  # every run once the first one plans
    # the same paths and metrics as runs that never waited in a pipe (the clocks differ, as they do between any
    # two runs; the delay is the planner's own)
    timing = ["wall_time_s", "cpu_time_s", "planning_time", "cpu_time", "isolated", "sandboxed"]
    assert runs.drop(columns=timing, errors="ignore").equals(alone.drop(columns=timing, errors="ignore"))
