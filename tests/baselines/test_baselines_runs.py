"""Runs of the metaheuristic baselines, pure and hybrid: determinism under foreign global RNG state, budgets, failures, progress."""

import random

import numpy as np
import pytest

from pathzoo import Budget, Status, make_planner
from pathzoo.rules import validate_path
from pathzoo.testing import check_scenario
from pathzoo_baselines.search import DEFAULT_EVALUATIONS, Search

BASELINES = ["swarm.pso", "swarm.cuckoo", "swarm.coa", "evo.ga", "evo.fuzzy_rate_ga"]
HYBRIDS = ["swarm.pso_astar", "swarm.cuckoo_astar", "evo.ga_astar", "evo.fuzzy_rate_ga_astar"]
CONFIGS = [(pid, {}) for pid in BASELINES + HYBRIDS] + [
    ("swarm.pso", {"encoding": "spline"}),
    ("swarm.pso", {"repair_window": 0}),
    ("evo.ga", {"encoding": "grid"}),
    ("evo.ga_astar", {"encoding": "routed"}),
    ("evo.fuzzy_rate_ga", {"encoding": "grid"}),
]


def _plan(planner, scenario, budget, seed=7, progress=None):
    return planner.plan(scenario, budget=budget, rng=np.random.default_rng(seed), progress=progress)


@pytest.mark.parametrize(("pid", "params"), CONFIGS)
def test_same_seed_same_path_whatever_the_global_random_state(pid, params):
    """pyswarms draws from numpy.random and DEAP from random: plan() must seed both from rng and restore them."""
    planner = make_planner(pid, **params)
    scenario = check_scenario("grid2d")
    budget = Budget(iterations=15)
    results, curves = [], []
    for outside in (1, 2):
        random.seed(outside)
        np.random.seed(outside)
        before = random.getstate(), np.random.get_state()
        curves.append([])
        results.append(_plan(planner, scenario, budget, progress=lambda *c: curves[-1].append(c)))
        after = random.getstate(), np.random.get_state()
        assert after[0] == before[0], "Python's random state was not restored"
        assert all(np.array_equal(a, b) for a, b in zip(after[1], before[1])), "numpy's global state was not restored"
    a, b = results
    assert a.status is b.status
    assert a.extras["best_cost"] == b.extras["best_cost"]
    assert curves[0] == curves[1]
    if a.solved:
        np.testing.assert_array_equal(a.path, b.path)
    other: list = []
    _plan(planner, scenario, budget, seed=8, progress=lambda *c: other.append(c))
    assert other != curves[0]  # the seed matters


@pytest.mark.parametrize(("pid", "params"), CONFIGS)
def test_iteration_budget_and_monotone_progress(pid, params):
    planner = make_planner(pid, **params)
    calls = []
    result = _plan(planner, check_scenario("terrain"), Budget(iterations=6), progress=lambda *c: calls.append(c))
    assert result.iterations == 6
    assert [c[0] for c in calls] == list(range(7))  # initial population, then one report per generation
    costs = [c[2] for c in calls]
    assert costs == sorted(costs, reverse=True)
    assert np.all(np.diff([c[1] for c in calls]) > 0)
    assert calls[-1][1] == result.evaluations
    if result.solved:
        assert validate_path(check_scenario("terrain"), result.path)
        assert costs[-1] == pytest.approx(result.extras["best_cost"])


@pytest.mark.parametrize("pid", BASELINES)
@pytest.mark.parametrize("limit", [1, 7, 133])
def test_evaluation_budget_is_met_exactly(pid, limit):
    result = _plan(make_planner(pid), check_scenario("grid2d"), Budget(evaluations=limit))
    assert result.evaluations == limit


@pytest.mark.parametrize("pid", BASELINES)
def test_time_budget_stops_the_search(pid, monkeypatch):
    """A time limit ends the search; time here is a count of clock reads, so the machine's load cannot matter."""
    import itertools
    import time

    planner = make_planner(pid)
    scenario = check_scenario("grid2d")
    reads = itertools.count()
    monkeypatch.setattr(time, "perf_counter", lambda: 0.01 * next(reads))  # each look at the clock costs 10 ms
    result = _plan(planner, scenario, Budget(time_s=0.3))
    assert 1 < result.iterations < 30
    assert next(reads) < 0.3 / 0.01 + 20  # it stopped soon after the limit: a few reads past 30


@pytest.mark.parametrize("pid", BASELINES + HYBRIDS)
def test_unlimited_budget_runs_the_default_number_of_evaluations(pid):
    """Every metaheuristic, pure or hybrid, does the same work at its defaults: DEFAULT_EVALUATIONS evaluations."""
    result = _plan(make_planner(pid), check_scenario("grid2d"), Budget())
    assert result.evaluations == DEFAULT_EVALUATIONS


@pytest.mark.parametrize(("pid", "params"), CONFIGS)
def test_a_colliding_best_candidate_is_a_failure_never_a_path(pid, params):
    result = _plan(make_planner(pid, **params), check_scenario("grid2d", reachable=False), Budget(iterations=5))
    assert result.status is Status.FAILED and result.path is None
    assert "violates" in result.message
    assert result.extras["violation"] > 0


def test_the_validator_has_the_last_word():
    """A candidate the cost calls feasible is still returned only if validate_path accepts it."""

    class Lenient:  # an encoding that calls a wall-crossing straight line feasible
        n_genes, integer = 1, False
        low, high = np.zeros(1), np.ones(1)

        def evaluate(self, genes):
            return np.ones(len(genes)), np.zeros(len(genes))

        def path(self, genes):
            return np.stack([scenario.start, scenario.goal])

    scenario = check_scenario("grid2d")
    search = Search(scenario, Lenient(), Budget(iterations=1), None)
    search.evaluate(np.zeros((2, 1)))
    result = search.result()
    assert result.status is Status.FAILED and result.path is None
    assert "not a valid path" in result.message and "blocked" in result.message


def test_ga_rates_are_fixed_and_fuzzy_rates_adapt():
    scenario = check_scenario("grid2d")
    plain = _plan(make_planner("evo.ga", cxpb=0.7, mutpb=0.1), scenario, Budget(iterations=20))
    assert plain.extras["mean_cxpb"] == pytest.approx(0.7) and plain.extras["mean_mutpb"] == pytest.approx(0.1)
    fuzzy = _plan(make_planner("evo.fuzzy_rate_ga"), scenario, Budget(iterations=20))
    assert 0.5 <= fuzzy.extras["mean_cxpb"] <= 1.0 and 0.05 <= fuzzy.extras["mean_mutpb"] <= 0.5
    assert fuzzy.extras["mean_cxpb"] != pytest.approx(0.75)  # not just the middle of the range
