"""What the stored times cover (docs/timing.md): the constructor and child processes are charged, harness work is not;
clock limits only stop a run, and the run is stored with the limit that ended it."""

from __future__ import annotations

import time

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget
from pathzoo.harness import Experiment
from pathzoo.harness.runner import run_experiment


def _run(forged, tmp_path, params, budget, executor="process", name="timing"):
    exp = Experiment.build(planners=[("test.burner", params)], scenarios=["test.wall"], seeds=1, budget=budget,
                           name=name)
    return run_experiment(exp, db=tmp_path / "t.sqlite", jobs=1, executor=executor, progress=False).iloc[0]


@pytest.mark.parametrize("executor", ["process", "inline"])
def test_work_in_the_constructor_is_charged(forged, tmp_path, executor):
    run = _run(forged, tmp_path, {"init_cpu_s": 0.4, "step_cpu_s": 0.0}, Budget(iterations=1), executor)
    assert run["status"] == "solved" and run["stopped_by"] == "iterations"
    assert run["cpu_time_s"] >= 0.4


def test_a_child_process_is_charged(forged, tmp_path):
    run = _run(forged, tmp_path, {"child_cpu_s": 0.4, "step_cpu_s": 0.0}, Budget(iterations=1))
    assert run["status"] == "solved"
    assert run["cpu_time_s"] >= 0.4  # the worker itself burns nothing: the child's CPU time is in the stored one


def test_the_scenario_check_after_the_run_is_not_charged(forged, tmp_path, monkeypatch):
    from pathzoo.harness.sealed import ScenarioSeal

    intact = ScenarioSeal.intact

    def slow_check(self):
        end = time.process_time() + 0.5
        while time.process_time() < end:
            pass
        return intact(self)

    monkeypatch.setattr(ScenarioSeal, "intact", slow_check)  # inline: the worker's code runs in this process
    run = _run(forged, tmp_path, {"step_cpu_s": 0.0}, Budget(iterations=1), "inline")
    assert run["status"] == "solved" and run["cpu_time_s"] < 0.25  # 0.5 s burnt per check, none of it stored


@pytest.mark.parametrize("executor", ["process", "inline"])
def test_a_cpu_limit_stops_the_run_and_is_recorded(forged, tmp_path, executor):
    run = _run(forged, tmp_path, {"step_cpu_s": 0.005}, Budget(iterations=10**6, cpu_s=0.3), executor)
    assert run["status"] == "solved" and run["stopped_by"] == "cpu_time"
    assert 0.3 <= run["cpu_time_s"] and run["iterations"] < 10**6


def test_a_wall_limit_stops_the_run_and_is_recorded(forged, tmp_path):
    run = _run(forged, tmp_path, {"step_cpu_s": 0.005}, Budget(iterations=10**6, time_s=0.3))
    assert run["stopped_by"] == "wall_time" and run["wall_time_s"] >= 0.3 and run["iterations"] < 10**6


def test_a_count_limit_reached_first_is_recorded(forged, tmp_path):
    run = _run(forged, tmp_path, {"step_cpu_s": 0.0}, Budget(evaluations=7, cpu_s=100.0, time_s=100.0))
    assert run["stopped_by"] == "evaluations" and run["iterations"] == 7


def test_a_clock_stop_is_marked_machine_dependent_in_the_leaderboard(forged, tmp_path):
    from pathzoo.analysis.leaderboard import CLOCK_MARK, format_leaderboard, leaderboard
    from pathzoo.harness.store import read_runs

    _run(forged, tmp_path, {"step_cpu_s": 0.005}, Budget(cpu_s=0.1), "inline", name="clocked")
    table = leaderboard(read_runs(tmp_path / "t.sqlite", "clocked"), "length")
    assert table["clock_stops"].tolist() == [1]
    row = next(line for line in format_leaderboard(table).splitlines() if line.startswith("test.wall"))
    assert CLOCK_MARK in row


class _NeverStop:
    def reason(self):
        return None


def test_a_clock_limit_changes_no_result_that_the_counts_end(monkeypatch):
    """The colony's behaviour ignores clocks: with a clock that races ahead, a counted run is unchanged."""
    from pathzoo_aco.engine import colony

    scenario = pathzoo.load_scenario("gant.fig7")
    planner = pathzoo.make_planner("aco.as", n_ants=5)
    plain = planner.plan(scenario, budget=Budget(iterations=4), rng=np.random.default_rng(3))
    fake = iter(time.perf_counter() + np.arange(1e3, 1e9, 1e3))  # every reading 1000 s later than the last
    monkeypatch.setattr(colony.time, "perf_counter", lambda: float(next(fake)))
    timed = planner.plan(scenario, budget=Budget(iterations=4, time_s=5.0, stop=_NeverStop()),
                         rng=np.random.default_rng(3))
    assert timed.iterations == plain.iterations == 4
    np.testing.assert_array_equal(timed.path, plain.path)


_COMPILE_PROBE = """
import gc
import multiprocessing
import numpy as np
from numba.core.registry import CPUDispatcher
import pathzoo
from pathzoo.harness import Experiment
from pathzoo.harness.clock_stop import SharedClockStop
from pathzoo.harness.scenario_cache import load_cached
from pathzoo.harness.zygote import WarmUp, Zygote

def signatures():
    return {id(o): len(o.signatures) for o in gc.get_objects() if isinstance(o, CPUDispatcher)}

for planner, scenario in [("aco.gant", "iaca.offroad"), ("exact.dijkstra", "dsaco.simple"),
                          ("aco.fgdaco", "fgdaco.scenario1"), ("aco.dsaco", "dsaco.simple"),
                          ("exact.astar", "movingai.arena.b0.9")]:
    task = Experiment.build(planners=[planner], scenarios=[scenario], seeds=1,
                            budget=pathzoo.Budget(iterations=2)).tasks()[0]
    zygote = Zygote(SharedClockStop(multiprocessing.RawArray("b", 1)))
    zygote.warm_up(WarmUp.of(task), lambda event: None)
    scenario_object, _ = load_cached(task.scenario)
    before = signatures()
    task.build_planner().plan(scenario_object, budget=task.budget, rng=np.random.default_rng(task.seed))
    new = sum(n > before.get(k, 0) for k, n in signatures().items())
    print(planner, scenario, new)
"""


def test_no_numba_kernel_is_compiled_or_loaded_inside_a_measured_run():
    """A process worker warms up on synthetic scenarios of the run's kind (never the run's own), which hold every
    optional part a kernel is specialised on, so the measured run finds every kernel ready. Tiny scenarios alone
    missed some: zero-weight edge tables (gant on terrain with soil rules), read-only graph arrays (the exact
    searches), the timed walks among moving obstacles (fgdaco), an air volume's edge list with every edge open
    (dsaco)."""
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _COMPILE_PROBE], capture_output=True, text=True, check=True).stdout
    assert [line.rsplit(" ", 1)[1] for line in out.splitlines()] == ["0"] * 5, out
