"""Slots per planner configuration: a second worker of a configuration only where it pays for its start."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from pathzoo.harness.executors import ProcessExecutor
from pathzoo.harness.executors.slot_shares import DEFAULT_START_S, SlotShares
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.sandbox import sandbox_problem

A = ("exact.astar", "h1", "grid2d")
B = ("aco.as", "h2", "grid2d")


def _shares(capacity: int, **runs: int) -> SlotShares:
    shares = SlotShares(capacity)
    configs = {"a": A, "b": B}
    for name, n in runs.items():
        shares.left[configs[name]] += n
    return shares


def test_two_configurations_with_many_runs_on_two_slots_get_one_worker_each():
    shares = _shares(2, a=200, b=200)
    shares.ran(A, 0.03)
    shares.started(1.2)
    assert shares.shares() == {A: 1, B: 1}
    assert shares.worth_another(A, 0) and not shares.worth_another(A, 1)
    assert shares.pays_for_a_start(A, 1)  # only its share keeps it from a second: 200 x 0.03 s / 2 = 3 s > 1.2 s
    for _ in range(130):
        shares.taken(A)
    assert not shares.pays_for_a_start(A, 1)  # 70 x 0.03 s / 2 = 1.05 s: less than a start


def test_one_configuration_gets_every_slot_while_its_runs_outlast_a_start():
    shares = _shares(2, a=200)
    shares.ran(A, 0.03)
    shares.started(1.2)
    assert shares.shares() == {A: 2} and shares.worth_another(A, 1)  # 200 x 0.03 s / 2 workers = 3 s > 1.2 s
    for _ in range(130):
        shares.taken(A)
    assert not shares.worth_another(A, 1)  # 70 x 0.03 s / 2 = 1.05 s: less than a start
    assert not shares.worth_another(A, 2)  # never more than the slots


def test_slots_follow_the_work_left_not_the_run_count():
    shares = _shares(3, a=100, b=100)
    shares.ran(A, 0.01)
    shares.ran(B, 1.0)
    assert shares.shares() == {A: 1, B: 2}
    assert shares.worth_another(B, 1) and not shares.worth_another(A, 1)


def test_unannounced_configurations_and_the_first_worker_are_always_started():
    shares = SlotShares(2)
    assert shares.worth_another(A, 1)  # the executor was never told the runs: as before
    assert _shares(2, a=1).worth_another(A, 0)
    assert shares.start_seconds == DEFAULT_START_S and shares.run_seconds(A) == 1.0


def test_measured_times_are_means_and_unmeasured_configurations_take_the_overall_mean():
    shares = SlotShares(2)
    shares.ran(A, 0.1)
    shares.ran(A, 0.3)
    shares.ran(B, float("nan"))  # a run that waited for its worker's warm-up: not counted
    assert shares.run_seconds(A) == pytest.approx(0.2) and shares.run_seconds(B) == pytest.approx(0.2)
    shares.started(1.0)
    shares.started(2.0)
    assert shares.start_seconds == pytest.approx(1.5)


@pytest.fixture
def spawned(monkeypatch: pytest.MonkeyPatch) -> list[Any]:
    """The configurations of the workers that process executors start while the test runs, in order."""
    configs: list[Any] = []
    spawn = ProcessExecutor._spawn

    def recorded(executor: ProcessExecutor, config: Any) -> Any:
        configs.append(config)
        return spawn(executor, config)

    monkeypatch.setattr(ProcessExecutor, "_spawn", recorded)
    return configs


SWEEP = """
[experiment]
name = "sweep"
seeds = 1
budget = {{ iterations = 1 }}
scenarios = [{scenarios}]

[[planner]]
id = "exact.astar"

[[planner]]
id = "exact.dijkstra"
"""


@pytest.mark.skipif(bool(sandbox_problem()), reason=f"no OS sandbox here: {sandbox_problem()}")
def test_a_sweep_of_two_planners_on_two_slots_starts_two_workers(tmp_path: Path, spawned: list[Any]):
    from pathzoo.plugins.manager import get_registry

    problems = sorted(k for k in get_registry().scenarios if k.startswith("movingai.random-32-32-20."))[:20]
    ids = ", ".join(f'"{k}"' for k in problems)
    path = tmp_path / "sweep.toml"
    path.write_text(SWEEP.format(scenarios=ids))
    exp = Experiment.from_toml(path)
    runs = run_experiment(exp, db=tmp_path / "sweep.sqlite", executor=ProcessExecutor(2), progress=False)
    assert len(runs) == 40 and (runs.status == "solved").all() and runs.sandboxed.all()
    assert sorted(c[0] for c in spawned) == ["exact.astar", "exact.dijkstra"]  # not a second one of either


@pytest.mark.skipif(bool(sandbox_problem()), reason=f"no OS sandbox here: {sandbox_problem()}")
def test_a_slot_kept_for_a_configuration_with_no_run_waiting_goes_to_the_waiting_one(forged, tmp_path: Path,
                                                                                   spawned: list[Any]):
    # a paper's table: each configuration's seeds come together, and the runner hands the pool a few at a time, so
    # while the first configuration's nine runs wait the other's share of the slots would idle
    exp = Experiment.build(planners=[("test.honest", {"delay_s": 1.0}), ("test.honest", {"delay_s": 0.0})],
                           scenarios=["test.wall"], seeds=10, name="table")
    runs = run_experiment(exp, db=tmp_path / "table.sqlite", executor=ProcessExecutor(2), progress=False)
    assert len(runs) == 20 and (runs.status == "solved").all()
    slow = [c for c in spawned if c is not None and c[1] == exp.planners[0].params_hash]
    assert len(slow) == 2  # its second worker: the slow runs did not wait for one worker alone
