"""Planners that change the cached scenario a worker's later runs see: refused or caught, never silent.

``hostile.overwrite`` attacks in its first run of a process (numpy writes
after setting the writeable flag, ``np.copyto``, in-place operators,
rebinding attributes of the scenario and its graph, a dict field, the
vehicle, an array's shape, raw writes through ``ctypes``, ``mprotect`` and
``/proc/self/mem``) and reports what it sees as a ``failed`` run's message.
The attacking run must be a ``crash`` or ``invalid`` (the attack refused or
caught), and every ``failed`` run must see the scenario as it was loaded.

Each attack is also run against a deliberately weakened harness (the
scenario neither sealed nor checked, :mod:`pathzoo.harness.sealed` switched
off in-process under the inline executor), where it must reach the later
runs: the attacks are real, and the tests fail without the protection.
"""

from __future__ import annotations

from collections import OrderedDict

import pytest

from harness_support import experiment, hostile  # noqa: F401 - fixture
from pathzoo.harness import run_experiment

ATTACKS = ["setflags", "copyto", "inplace", "rebind", "graph_array", "metadata", "vehicle", "shape", "ctypes",
           "ctypes_flags", "mprotect", "proc_mem"]
SEEDS = 3


def attack(tmp_path, how, executor):
    exp = experiment([("hostile.overwrite", {"how": how})], ["hostile.wall"], seeds=SEEDS, name=f"overwrite-{how}")
    runs = run_experiment(exp, db=tmp_path / "r.sqlite", jobs=1, executor=executor, progress=False)
    return runs.sort_values("seed_index")


def test_every_attack_is_listed(hostile):
    assert sorted(ATTACKS) == sorted(hostile.SCENARIO_ATTACKS)


@pytest.mark.parametrize("how", ATTACKS)
def test_an_attack_on_the_cached_scenario_never_reaches_a_later_run(hostile, tmp_path, how):
    runs = attack(tmp_path, how, "process")
    first = runs.iloc[0]
    assert first.status in ("crash", "invalid"), (first.status, first.message)  # refused or caught, in its own run
    # a worker that crashed is replaced, and the fresh one's planner attacks again in its first run
    assert set(runs.status) <= {"failed", "crash", "invalid"}, list(runs.status)
    seen = runs[runs.status == "failed"].message
    assert (seen == hostile.observe(hostile.wall_scenario())).all(), list(seen)


class _NoSeal:
    """The weakened harness: nothing sealed, nothing checked."""

    def __init__(self, scenario):
        pass

    def intact(self) -> bool:
        return True


@pytest.mark.parametrize("how", ATTACKS)
def test_each_attack_reaches_later_runs_of_a_weakened_harness(hostile, tmp_path, monkeypatch, how):
    from pathzoo.harness import scenario_cache, worker_warmup

    monkeypatch.setattr(scenario_cache, "seal", _NoSeal)
    monkeypatch.setattr(worker_warmup, "seal", _NoSeal)
    monkeypatch.setattr(scenario_cache, "_scenarios", OrderedDict())  # this process's cache, restored afterwards
    monkeypatch.setattr(worker_warmup, "_twins", OrderedDict())
    hostile.ATTACKED.discard(how)
    runs = attack(tmp_path, how, "inline")
    pristine = hostile.observe(hostile.wall_scenario())
    assert list(runs.status) == ["failed"] * SEEDS  # not caught
    assert runs.iloc[0].message == pristine and (runs.iloc[1:].message != pristine).all()  # and it leaks
