"""Two process executors in one process (two threads of one Dask worker) keep their planners' cgroups apart.

Each executor numbered its workers' cgroups from ``w1``, under the same
``pathzoo-<pid>`` group: the two executors' first workers shared one cgroup,
so killing one at its hard limit killed the other's planner as well (and the
CPU time read from the group was the sum of both).
"""

from __future__ import annotations

from pathzoo import Budget
from pathzoo.harness.executors import ProcessExecutor
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.planner_info import extra_plugin_modules
from pathzoo.harness.sandbox import sandbox_problem
from pathzoo.plugins.manager import get_registry

import pytest


@pytest.mark.skipif(bool(sandbox_problem()), reason=f"no sandbox here: {sandbox_problem()}")
def test_a_kill_in_one_executor_spares_the_other_executors_planner(forged):
    modules = extra_plugin_modules(get_registry())  # the forged plugin, registered by hand
    hung = Experiment.build(planners=[("test.sabotage", {"how": "sleep"})], scenarios=["test.wall"], seeds=1,
                            name="hung", budget=Budget(time_s=0.5), timeout_s=1.0).tasks(modules)[0]
    honest = Experiment.build(planners=[("test.honest", {"delay_s": 4.0})], scenarios=["test.wall"], seeds=1,
                              name="honest", budget=Budget(iterations=5), timeout_s=60).tasks(modules)[0]
    with ProcessExecutor(1, sandbox=True) as first, ProcessExecutor(1, sandbox=True) as second:
        calm = second.submit(honest)
        killed = first.submit(hung)
        assert killed.result(timeout=60).timed_out
        outcome = calm.result(timeout=60)
    assert not outcome.crash and not outcome.timed_out, outcome.message
    assert outcome.cpu_time_s < 1.0  # the sleeping planner's CPU time alone, not its neighbour's as well
