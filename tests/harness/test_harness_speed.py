"""The harness's speed-ups keep their guarantees: quick tamper check, warm-up shares, queue ahead, forked judge."""

from __future__ import annotations

import os
import sys
import types

import psutil
import pytest

import pathzoo
from pathzoo.harness import tamper
from pathzoo.harness import Experiment
from pathzoo.harness.executors import InlineExecutor, ProcessExecutor
from pathzoo.harness.judge_worker import JudgeWorker
from pathzoo.harness.tamper import ModuleFingerprint
from pathzoo.harness.worker import execute_task


class _LooksEqual:
    """An impostor that claims to equal everything (``==`` must never be what the tamper check trusts)."""

    def __eq__(self, other: object) -> bool:
        return True

    __hash__ = object.__hash__


def _module(name: str) -> types.ModuleType:
    module = types.ModuleType(name)
    exec("def f():\n    return 1\n\nclass K:\n    def m(self):\n        return 2\n", module.__dict__)
    sys.modules[name] = module
    return module


QUICK_PATHS = [
    pytest.param(True, id="version-tags",
                 marks=pytest.mark.skipif(not tamper._tags_readable(), reason="this interpreter's dicts have no tag")),
    pytest.param(False, id="identity"),
]


@pytest.fixture(params=QUICK_PATHS)
def quick_path(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> bool:
    """Run the test with the quick check on dict version tags, then on identities of every key and value."""
    monkeypatch.setattr(tamper, "_TAGS", request.param)
    return request.param


def test_the_quick_check_still_sees_every_replacement(quick_path: bool):
    module = _module("pathzoo_tamper_probe")
    try:
        fingerprint = ModuleFingerprint().update()
        assert fingerprint.changed() == [] and fingerprint._clean is not None  # the quick path is armed
        assert fingerprint.changed() == []
        module.counter = 3  # a new attribute is untracked: no alarm
        assert fingerprint.changed() == []
        module.counter = 4  # nor a changed one
        assert fingerprint.changed() == []
        module.f = _LooksEqual()  # replaced by an object that claims equality
        assert fingerprint.changed() == ["pathzoo_tamper_probe.f"]
    finally:
        del sys.modules["pathzoo_tamper_probe"]


def test_the_quick_check_sees_a_replaced_method_and_module(quick_path: bool):
    module = _module("pathzoo_tamper_probe2")
    try:
        fingerprint = ModuleFingerprint().update()
        assert fingerprint.changed() == []
        module.K.m = lambda self: 3
        assert fingerprint.changed() == ["pathzoo_tamper_probe2.K.m"]
        fingerprint = ModuleFingerprint().update()
        assert fingerprint.changed() == []
        sys.modules["pathzoo_tamper_probe2"] = types.ModuleType("pathzoo_tamper_probe2")
        assert fingerprint.changed() == ["sys.modules['pathzoo_tamper_probe2']"]
    finally:
        del sys.modules["pathzoo_tamper_probe2"]


def test_the_quick_check_sees_writes_that_keep_keys_and_size(quick_path: bool):
    """A value written straight into the namespace dict, a key deleted and put back: each is seen, every time."""
    module = _module("pathzoo_tamper_probe3")
    original = module.f
    try:
        fingerprint = ModuleFingerprint().update()
        assert fingerprint.changed() == []
        vars(module)["f"] = len  # a builtin in place of the function, same key, same size
        assert fingerprint.changed() == ["pathzoo_tamper_probe3.f"]
        vars(module)["f"] = original  # put back: clean again
        assert fingerprint.changed() == []
        del module.K
        assert fingerprint.changed() == ["pathzoo_tamper_probe3.K"]
        fingerprint = ModuleFingerprint().update()
        assert fingerprint.changed() == []
        module.counter = 1  # an untracked change is accepted ...
        assert fingerprint.changed() == []
        module.f = print  # ... and a later tracked one in the same namespace still seen
        assert fingerprint.changed() == ["pathzoo_tamper_probe3.f"]
        assert fingerprint.changed() == ["pathzoo_tamper_probe3.f"]  # and again: a tainted state is never accepted
    finally:
        del sys.modules["pathzoo_tamper_probe3"]


def test_modules_loaded_later_join_the_quick_check(quick_path: bool):
    """A module snapshotted by a later update() keeps the quick path armed, and a replacement in it is still seen."""
    fingerprint = ModuleFingerprint().update()
    assert fingerprint.changed() == []
    clean = fingerprint._clean
    module = _module("pathzoo_tamper_probe4")
    try:
        fingerprint.update()
        assert fingerprint._clean is clean is not None  # extended, not dropped: no full examination
        assert fingerprint.changed() == []
        module.K.m = lambda self: 3
        assert fingerprint.changed() == ["pathzoo_tamper_probe4.K.m"]
        module.f = len
        assert sorted(fingerprint.changed()) == ["pathzoo_tamper_probe4.K.m", "pathzoo_tamper_probe4.f"]
    finally:
        del sys.modules["pathzoo_tamper_probe4"]


def test_only_the_process_executor_queues_ahead():
    assert InlineExecutor().lookahead == 0
    with ProcessExecutor(2) as pool:
        assert pool.capacity == 2 and pool.lookahead == 2


def _solved_run() -> tuple:
    task = Experiment.build(planners=["exact.astar"], scenarios=["gant.fig7"], seeds=1,
                            budget=pathzoo.Budget(iterations=1)).tasks()[0]
    return task, execute_task(task)


def test_the_judge_is_a_fork_of_the_workers_server_and_judges():
    from multiprocessing import forkserver

    from pathzoo.harness.launch import default_start_method

    task, outcome = _solved_run()
    with JudgeWorker() as judge:
        record = judge.judge(task, outcome)
        assert judge._process is not None
        if default_start_method() == "forkserver":  # the server's imports are not paid again
            assert psutil.Process(judge._process.pid).ppid() == forkserver._forkserver._forkserver_pid
    assert record.status.value == "solved" and record.valid and record.metrics


def test_a_judge_that_died_between_runs_is_replaced():
    task, outcome = _solved_run()
    with JudgeWorker() as judge:
        assert judge.judge(task, outcome).status.value == "solved"
        dead = judge._process
        assert dead is not None
        dead.kill()
        dead.join()
        assert judge.judge(task, outcome).status.value == "solved"  # by a new judge process
        assert judge._process is not dead


def test_the_cpu_time_of_a_worker_is_read_from_outside_and_agrees_with_psutil():
    import subprocess

    import psutil

    from pathzoo.harness.executors.process import process_cpu_time

    child = subprocess.Popen([sys.executable, "-c", "import time\nt = time.process_time()\n"
                              "while time.process_time() - t < 0.3: pass\nprint(flush=True)\ninput()"],
                             stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        child.stdout.readline()  # it has burnt 0.3 s of CPU and waits
        ours = process_cpu_time(child.pid)
        theirs = sum(psutil.Process(child.pid).cpu_times()[:2])
        assert ours >= 0.3 and abs(ours - theirs) < 0.05  # psutil counts in 10 ms clock ticks
    finally:
        child.communicate("")
    assert process_cpu_time(child.pid) != process_cpu_time(child.pid)  # NaN once it is gone


def test_a_scenario_object_is_sent_to_each_process_once(monkeypatch: pytest.MonkeyPatch, tmp_path):
    """The worker and the judge get the pickled object with the first run on it, then its digest only."""
    from multiprocessing.connection import Connection

    from pathzoo.harness.runner import run_experiment
    from pathzoo.harness.specs import RunTask
    from pathzoo.plugins.manager import get_registry

    scenario = get_registry().get("scenarios", "gant.fig7").obj.load()
    exp = Experiment.build(name="objects", planners=["exact.astar"], scenarios=[scenario], seeds=4,
                           budget=pathzoo.Budget(iterations=1))
    sent: list[int] = []
    send = Connection.send

    def spy(self: Connection, obj: object) -> None:
        found = [o for o in (obj if isinstance(obj, tuple) else (obj,)) if isinstance(o, RunTask)]
        sent.extend(len(t.scenario.payload) for t in found)
        send(self, obj)

    monkeypatch.setattr(Connection, "send", spy)
    runs = run_experiment(exp, db=tmp_path / "o.sqlite", jobs=1, progress=False)
    assert (runs.status == "solved").all() and len(runs) == 4
    full = [n for n in sent if n]
    # worker: 1 full + 3 by reference; judge: the warm-up in full, then 4 runs by reference
    assert len(full) == 2 and len(sent) == 9 and full[0] == len(exp.tasks()[0].scenario.payload)


def test_a_judge_pool_judges_runs_side_by_side_in_its_own_processes():
    from pathzoo.harness.judge_worker import JudgePool

    task, outcome = _solved_run()
    with JudgeWorker() as judge:
        alone = judge.judge(task, outcome)
    with JudgePool(2) as pool:
        pool.prepare(task)
        futures = [pool.submit(task, outcome) for _ in range(4)]
        records = [f.result(timeout=120) for f in futures]
        pids = {j._process.pid for j in pool.judges if j._process is not None}
    assert len(pids) == 2 and os.getpid() not in pids  # two judge processes, neither the harness
    def shown(metrics):  # NaN (a metric without a value here) equals itself
        return {k: repr(v) for k, v in metrics.items()}

    assert all(r.status.value == "solved" and r.valid and shown(r.metrics) == shown(alone.metrics) for r in records)


def test_a_judge_judges_a_reference_path_ahead_once_per_scenario_kind(monkeypatch):
    from pathzoo.harness import judge as judge_module
    from pathzoo.harness import judge_worker

    judged: list[str] = []
    real = judge_module.judge

    def counted(task, outcome, scenario, metrics, **kwargs):  # type: ignore[no-untyped-def]
        judged.append(scenario.id)
        return real(task, outcome, scenario, metrics, **kwargs)

    monkeypatch.setattr(judge_module, "judge", counted)
    monkeypatch.setattr(judge_worker, "_WARMED_KINDS", set(), raising=False)
    tasks = Experiment.build(planners=["exact.astar"], scenarios=["gant.fig7", "movingai.random-32-32-20.b10.13"], seeds=1,
                             budget=pathzoo.Budget(iterations=1)).tasks()
    for task in tasks:  # two grid2d scenarios: loaded both, the reference judged on the first only
        judge_worker._warm(task)
    assert [t.scenario.kind for t in tasks] == ["grid2d", "grid2d"] and judged == [tasks[0].scenario.id]
