"""One budget rule for every family: a count ends the run, a clock-only budget runs until the clock, no budget
means the planner's own count (``Budget.or_default``, docs/timing.md)."""

from __future__ import annotations

import numpy as np
import pytest

from pathzoo.core.budget import Budget
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo.plugins.lookup import make_planner


def test_or_default_fills_in_a_count_only_when_no_limit_is_set():
    assert Budget().or_default(7) == Budget(iterations=7)
    assert Budget().or_default(evaluations=7) == Budget(evaluations=7)
    for budget in (Budget(cpu_s=1.0), Budget(time_s=1.0), Budget(evaluations=3), Budget(iterations=2, cpu_s=1.0)):
        assert budget.or_default(7) is budget


# (planner, parameters, its own count when the budget sets none)
OWN_COUNTS = [
    ("aco.acs", {"n_ants": 2, "iterations": 3}, 3),
    ("aco.dsaco", {"n_ants": 2, "iterations": 3}, 3),
    ("swarm.pso", {}, 99),  # 5,000 evaluations: the initial 50 particles, then 99 iterations of 50
    ("search.movns", {}, 50),
    ("ompl.rrtstar", {}, 200),
]


@pytest.mark.parametrize(("pid", "params", "own"), OWN_COUNTS, ids=[c[0] for c in OWN_COUNTS])
def test_no_budget_runs_the_planners_own_count_and_a_clock_only_budget_runs_past_it(pid, params, own):
    if pid.startswith("ompl."):
        pytest.importorskip("ompl")
    planner = make_planner(pid, **params)
    scenario = check_scenario("grid2d")
    planner.plan(scenario, budget=Budget(iterations=1), rng=np.random.default_rng(0))  # compile outside the clock
    assert planner.plan(scenario, budget=Budget(), rng=np.random.default_rng(0)).iterations == own
    timed = planner.plan(scenario, budget=Budget(cpu_s=0.3 if own < 50 else 3.0), rng=np.random.default_rng(0))
    assert timed.iterations > own
