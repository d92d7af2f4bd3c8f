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


ATTACKERS = ["clock.forged_planned", "clock.array_works", "clock.lazy_path", "clock.burning_message",
             "clock.warm_up_memo"]


def test_work_hidden_from_the_clock_is_charged_like_honest_work(clocked, tmp_path):
    """2 CPU s of busy work plus an A* search, hidden before a forged "planned" frame, in the path's conversion, in
    the message's ``__str__`` or in the warm-up: each run is charged at least 1.8 CPU s, as the honest one is."""
    runs = _run(["clock.honest", *ATTACKERS], tmp_path)
    cpu = runs["cpu_time_s"].to_dict()
    assert all(runs["status"] == "solved"), runs[["status", "message"]]
    assert all(cpu[planner] >= 0.9 * clock_hostile.WORK_CPU_S for planner in ["clock.honest", *ATTACKERS]), cpu
    assert runs.loc["clock.forged_planned", "message"] == "forged on 0 sockets"  # the child holds no socket at all


def test_a_cpu_limit_stops_hidden_work(clocked, tmp_path):
    """The clock a ``cpu_s`` limit reads is the one the run is charged on: hidden work is stopped like honest work."""
    runs = _run(["clock.forged_planned", "clock.array_works"], tmp_path,
                budget=Budget(iterations=5, cpu_s=0.5))
    for planner, run in runs.iterrows():
        assert run["stopped_by"] == "cpu_time" and run["cpu_time_s"] >= 0.5, (planner, run["stopped_by"])


_TRACKER_SCRIPT = """
import sys
import clock_hostile
from pathzoo import Budget
from pathzoo.harness import Experiment, run_experiment
from pathzoo.harness.executors import ProcessExecutor
from pathzoo.plugins.manager import get_registry

get_registry().add_plugin(clock_hostile, "clock-hostile")
exp = Experiment.build(planners=[("clock.tracker_unlink", {"victim": sys.argv[1]})], scenarios=["movingai.arena.b0.9"],
                       seeds=1, name="tracker", budget=Budget(iterations=1))
runs = run_experiment(exp, db=sys.argv[2], executor=ProcessExecutor(1, sandbox=True), progress=False)
print(runs["message"].iloc[0])
"""


def test_a_planner_cannot_have_a_host_file_removed_through_the_resource_tracker(tmp_path):
    import os
    import subprocess
    import sys
    import time
    import uuid

    name = f"/pathzoo-victim-{uuid.uuid4().hex[:12]}"
    victim = Path("/dev/shm" + name)
    victim.write_bytes(b"keep me")
    try:
        env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(Path(__file__).parent), *sys.path])}
        done = subprocess.run([sys.executable, "-c", _TRACKER_SCRIPT, name, str(tmp_path / "t.sqlite")], env=env,
                              capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stderr[-2000:]
        assert "registered on 0 pipes" in done.stdout, done.stdout
        time.sleep(2.0)  # the tracker cleans up after the harness has exited
        assert victim.read_bytes() == b"keep me"
    finally:
        victim.unlink(missing_ok=True)
