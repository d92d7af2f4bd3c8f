"""The start of an experiment: planners described in one child, an early sandboxed worker, the first run alone."""

from __future__ import annotations

from pathlib import Path

import pytest

from pathzoo.harness import planner_info
from pathzoo.harness.executors import ProcessExecutor
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.sandbox import sandbox_problem

EXPERIMENT = """
[experiment]
name = "{name}"
seeds = 1
budget = {{ iterations = 1 }}
scenarios = ["movingai.random-32-32-20.b10.13"]

[[planner]]
id = "exact.astar"

[[planner]]
id = "exact.dijkstra"

[[planner]]
id = "exact.thetastar"
"""

sandboxed = pytest.mark.skipif(bool(sandbox_problem()), reason=f"no OS sandbox here: {sandbox_problem()}")


def _experiment(tmp_path: Path, name: str) -> Experiment:
    path = tmp_path / f"{name}.toml"
    path.write_text(EXPERIMENT.format(name=name))
    return Experiment.from_toml(path)


def test_an_experiment_file_describes_its_planners_in_one_child(tmp_path, monkeypatch):
    asked: list[list[str]] = []
    ask = planner_info._ask_child

    def counted(requests, plugin_modules):
        asked.append([planner_id for planner_id, _ in requests])
        return ask(requests, plugin_modules)

    monkeypatch.setattr(planner_info, "_cache", {})
    monkeypatch.setattr(planner_info, "_unloaded", lambda planner_id: True)  # as in a fresh harness process
    monkeypatch.setattr(planner_info, "_ask_child", counted)
    exp = _experiment(tmp_path, "described")
    assert asked == [["exact.astar", "exact.dijkstra", "exact.thetastar"]]
    assert [p.id for p in exp.planners] == ["exact.astar", "exact.dijkstra", "exact.thetastar"]


class _Spawns:
    """Records each sandboxed worker start (its configuration, and whether it started while the first run had not
    planned yet and a worker not ready yet was there) and each run handed to a worker while the first run, held by
    another, had not planned yet."""

    def __init__(self, monkeypatch: pytest.MonkeyPatch) -> None:
        self.configs: list[tuple[str, str] | None] = []
        self.beside_unready: list[bool] = []
        self.beside_first_run: list[bool] = []
        spawn, assign = ProcessExecutor._spawn, ProcessExecutor._assign

        def recorded(executor: ProcessExecutor, config: tuple[str, str] | None):  # type: ignore[no-untyped-def]
            self.configs.append(config)
            self.beside_unready.append(executor._first_alone and any(not w.was_ready for w in executor._workers))
            return spawn(executor, config)

        def assigned(executor: ProcessExecutor, worker, task, future):  # type: ignore[no-untyped-def]
            self.beside_first_run.append(executor._first_alone and any(w.task is not None for w in executor._workers))
            return assign(executor, worker, task, future)

        monkeypatch.setattr(ProcessExecutor, "_spawn", recorded)
        monkeypatch.setattr(ProcessExecutor, "_assign", assigned)


@sandboxed
def test_an_early_worker_takes_the_first_run_of_its_planner(tmp_path, monkeypatch):
    exp = _experiment(tmp_path, "early")
    spawns = _Spawns(monkeypatch)
    pool = ProcessExecutor(1)
    pool.start_worker("exact.astar")
    runs = run_experiment(exp, db=tmp_path / "early.sqlite", executor=pool, progress=False)
    assert (runs.status == "solved").all() and runs.sandboxed.all()
    astar = next(p for p in exp.planners if p.id == "exact.astar")
    assert spawns.configs[0] == ("exact.astar", "", "")
    assert not any(c[:2] == ("exact.astar", astar.params_hash) for c in spawns.configs)  # the early worker ran it
    assert len(spawns.configs) == 3


@sandboxed
def test_the_first_workers_start_together_and_only_the_first_run_goes_before_it_plans(tmp_path, monkeypatch):
    exp = _experiment(tmp_path, "alone")
    spawns = _Spawns(monkeypatch)
    runs = run_experiment(exp, db=tmp_path / "alone.sqlite", executor=ProcessExecutor(2), progress=False)
    assert (runs.status == "solved").all() and runs.sandboxed.all()
    assert len(spawns.configs) == 3
    assert spawns.beside_unready[:2] == [False, True]  # the second started with the first, before it was ready
    assert len(spawns.beside_first_run) >= 3 and not any(spawns.beside_first_run)


def test_the_judge_is_forked_without_holding_up_the_first_runs(monkeypatch):
    import threading

    from pathzoo import Budget
    from pathzoo.harness import judge_worker
    from pathzoo.harness.worker import execute_task

    task = Experiment.build(planners=["exact.astar"], scenarios=["gant.fig7"], seeds=1,
                            budget=Budget(iterations=1)).tasks()[0]
    outcome = execute_task(task)
    fork = threading.Event()
    launch = judge_worker._launch_judge

    def held_up():  # as a fork server that is still importing
        assert fork.wait(60)
        return launch()

    monkeypatch.setattr(judge_worker, "_launch_judge", held_up)
    with judge_worker.JudgeWorker() as judge:
        judge.prepare(task)  # neither entering nor asking for a warm-up waits for the fork
        assert judge._conn is None and judge._warm_later == [task]
        fork.set()
        record = judge.judge(task, outcome)
        assert not judge._warm_later
    assert record.status.value == "solved" and record.valid


PARENT_PROBE = """
import sys
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.store import ResultStore
from pathzoo.plugins.metric_lookup import metric_info

metric_info("length")  # what `pathzoo run` checks --metric with
heavy = []
insert = ResultStore.insert

def first_insert(self, *args, **kwargs):
    if not heavy:
        heavy.append(sorted(m for m in ("numba", "scipy", "pandas") if m in sys.modules))
    return insert(self, *args, **kwargs)

ResultStore.insert = first_insert
run_experiment(Experiment.from_toml(sys.argv[1]), db=sys.argv[2], progress=False, jobs=1)
print(heavy[0])
"""


def test_the_harness_process_loads_no_numba_scipy_or_pandas_before_its_first_result(tmp_path):
    """The judge and the workers need them, not the process that stores the runs: it would only spend CPU that the
    first run's workers need (docs/startup.md)."""
    import subprocess
    import sys

    path = tmp_path / "probe.toml"
    path.write_text(EXPERIMENT.format(name="probe"))
    out = subprocess.run([sys.executable, "-c", PARENT_PROBE, str(path), str(tmp_path / "probe.sqlite")],
                         capture_output=True, text=True, timeout=300, check=True)
    assert out.stdout.strip().splitlines()[-1] == "[]"


def test_the_fork_server_has_every_builtin_metric_module_loaded_for_the_judge():
    """The judge is forked from the server, so the metric modules it computes with are imported there, once."""
    import subprocess
    import sys

    probe = ("import sys\nimport pathzoo.harness.executors.warmup\nloaded = set(sys.modules)\n"
             "from pathzoo.metrics.catalogue import BUILTIN_METRICS\n"
             "print(sorted({c.__module__ for c in BUILTIN_METRICS} - loaded))\n")
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=300, check=True)
    assert out.stdout.strip().splitlines()[-1] == "[]"
