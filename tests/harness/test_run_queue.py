"""The runner's queue of runs: in order, or a lane's next out of order, so a fast lane's worker never waits."""

from __future__ import annotations

import threading
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Hashable

from pathzoo import Budget
from pathzoo.harness.executors.inline import InlineExecutor
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.outcome import RunOutcome
from pathzoo.harness.run_queue import RunQueue
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.specs import RunTask


def test_items_come_in_order_or_by_lane_each_once():
    queue = RunQueue(["a1", "b1", "a2", "b2", "a3"], lambda item: item[0])
    assert queue.next() == "a1"
    assert queue.next_of("a") == "a2"
    assert queue.next_of("a") == "a3"
    assert queue.next_of("a") is None
    assert queue.next() == "b1"
    assert queue.next_of("b") == "b2"
    assert queue.next() is None
    assert queue.next_of("b") is None
    assert queue.next_of("c") is None


class LaneWorkers(InlineExecutor):
    """Two slots, one worker thread per lane (the planner configuration), like the process executor's workers; a
    run is running once its lane's worker takes it. Records the lane of each submitted run."""

    capacity = 2
    lookahead = 2
    isolated = False

    def __init__(self, lanes: bool) -> None:
        self.lanes = lanes
        self.submitted: list[str] = []
        self._workers: dict[str, ThreadPoolExecutor] = {}
        self._lock = threading.Lock()

    def lane(self, task: RunTask) -> Hashable:
        return task.planner.name if self.lanes else None

    def submit(self, task: RunTask) -> "Future[RunOutcome]":
        future: "Future[RunOutcome]" = Future()
        with self._lock:
            self.submitted.append(task.planner.name)
            worker = self._workers.setdefault(task.planner.name, ThreadPoolExecutor(1))

        def run() -> None:
            future.set_running_or_notify_cancel()
            future.set_result(InlineExecutor.submit(self, task).result())

        worker.submit(run)
        return future

    def shutdown(self) -> None:
        for worker in self._workers.values():
            worker.shutdown(wait=True)


def _submitted(forged, tmp_path, lanes: bool) -> list[str]:
    experiment = Experiment.build(planners=[("test.honest", {"delay_s": 0.03}), "test.honest"],
                                  scenarios=["test.wall"], seeds=12, name="lanes", seed=3, budget=Budget(time_s=1.0),
                                  timeout_s=20)
    executor = LaneWorkers(lanes)
    run_experiment(experiment, db=tmp_path / f"lanes-{lanes}.sqlite", executor=executor, progress=False)
    return executor.submitted


def test_a_fast_lane_gets_its_runs_out_of_order_when_the_slow_lane_fills_the_queue(forged, tmp_path):
    # after a pilot of one run each, the runs come configuration by configuration, the slow one first: in order,
    # the queue ahead holds only the slow one's runs, and the fast one's worker waits until they are all submitted
    for lanes, fast_done_early in ((True, True), (False, False)):
        submitted = _submitted(forged, tmp_path, lanes)
        slow, fast = submitted[0], next(name for name in submitted if name != submitted[0])
        last_fast = max(i for i, name in enumerate(submitted) if name == fast)
        slow_before = submitted[:last_fast].count(slow)
        assert sorted(submitted) == sorted([slow] * 12 + [fast] * 12)
        assert (slow_before <= 6) is fast_done_early, (lanes, submitted)
