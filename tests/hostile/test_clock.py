"""Attacks on what a run is charged (``clock_hostile``, issue 32), and on the host through ``/proc/sys`` and the
resource tracker. Every experiment runs sandboxed (bubblewrap and cgroups v1, ``docs/sandbox.md``)."""

from __future__ import annotations

from pathlib import Path

import pytest

import clock_hostile
from pathzoo import Budget
from pathzoo.harness import Experiment, run_experiment
from pathzoo.harness.executors import ProcessExecutor
from pathzoo.harness.sandbox import sandbox_problem
from pathzoo.plugins.manager import get_registry, reset_registry

pytestmark = pytest.mark.skipif(bool(sandbox_problem()), reason=f"no OS sandbox here: {sandbox_problem()}")

PLUGIN = "clock-hostile"


@pytest.fixture()
def clocked():
    registry = get_registry()
    if registry.pm.get_plugin(PLUGIN) is None:
        registry.add_plugin(clock_hostile, PLUGIN)
    yield clock_hostile
    reset_registry()


def _run(planners: list, tmp_path: Path, *, scenario: str = "movingai.arena.b0.9", budget: Budget | None = None):
    exp = Experiment.build(planners=planners, scenarios=[scenario], seeds=1, name="clock",
                           budget=budget or Budget(iterations=5), timeout_s=60.0)
    runs = run_experiment(exp, db=tmp_path / "clock.sqlite", executor=ProcessExecutor(1, sandbox=True),
                          progress=False)
    return runs.set_index("planner")


def test_no_file_under_proc_sys_is_writable_in_the_sandbox(clocked, tmp_path):
    run = _run(["clock.proc_sys"], tmp_path).loc["clock.proc_sys"]
    assert run["message"].startswith("0 writable"), run["message"]
