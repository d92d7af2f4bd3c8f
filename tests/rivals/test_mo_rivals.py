"""``swarm.mosfla`` and ``search.movns`` on a real DEM with tiny budgets: valid paths, honest costs, budgets kept."""

from __future__ import annotations

import numpy as np
import pytest

import pathzoo
from pathzoo.core import Budget, Scenario, Status
from pathzoo.rules import validate_path
from pathzoo.grid.paths import path_pieces
from pathzoo.metrics.geometry import travel_time_energy

IDS = ("swarm.mosfla", "search.movns")


@pytest.fixture(scope="module")
def hugo() -> Scenario:
    return pathzoo.load_scenario("ggaco.hugo")


@pytest.mark.parametrize("planner_id", IDS)
def test_solves_with_least_energy_route(hugo, planner_id):
    result = pathzoo.make_planner(planner_id).plan(hugo, budget=Budget(iterations=2), rng=np.random.default_rng(5))
    assert result.status == Status.SOLVED
    assert validate_path(hugo, result.path).valid
    assert result.extras["best_cost"] == pytest.approx(travel_time_energy(hugo, result.path)[1], rel=1e-12)
    front = np.array(result.extras["front"])
    assert front.ndim == 2 and front.shape[1] == 3 and len(front) >= 1
    assert result.iterations == 2


@pytest.mark.parametrize("planner_id", IDS)
def test_length_rule_returns_the_shortest_route_of_the_front(hugo, planner_id):
    planner = pathzoo.make_planner(planner_id, select="length")
    result = planner.plan(hugo, budget=Budget(iterations=2), rng=np.random.default_rng(5))
    front = np.array(result.extras["front"])
    assert result.extras["best_cost"] <= front[:, 0].min() + 1e-9
    lengths, _ = path_pieces(hugo, result.path)
    assert lengths.sum() >= result.extras["best_cost"] - 1e-6  # connectors only add length


@pytest.mark.parametrize("planner_id", IDS)
def test_evaluation_budget_is_exact(hugo, planner_id):
    result = pathzoo.make_planner(planner_id).plan(hugo, budget=Budget(evaluations=7), rng=np.random.default_rng(0))
    assert result.evaluations <= 7
    assert result.status == Status.SOLVED


@pytest.mark.parametrize("planner_id", IDS)
def test_more_iterations_never_cost_more(hugo, planner_id):
    planner = pathzoo.make_planner(planner_id)
    short = planner.plan(hugo, budget=Budget(iterations=1), rng=np.random.default_rng(2))
    longer = planner.plan(hugo, budget=Budget(iterations=4), rng=np.random.default_rng(2))
    assert longer.extras["best_cost"] <= short.extras["best_cost"]


@pytest.mark.parametrize("planner_id", IDS)
def test_start_and_goal_in_one_cell(planner_id):
    s = Scenario(id="test.one_cell", kind="grid2d", occupancy=np.zeros((6, 6), dtype=bool), cell_size=1.0,
                 start=np.array([0.3, 0.3]), goal=np.array([0.7, 0.6]))
    result = pathzoo.make_planner(planner_id).plan(s, budget=Budget(iterations=2), rng=np.random.default_rng(0))
    assert result.status == Status.SOLVED and validate_path(s, result.path).valid
    np.testing.assert_array_equal(result.path[[0, -1]], [s.start, s.goal])
