"""pathzoo-greedy's own tests: the pathzoo conformance kit plus one behavioural test."""

import numpy as np

import pathzoo
from pathzoo.testing import check_scenario, parametrize_with_checks
from pathzoo_greedy import GreedyBestFirst


@parametrize_with_checks([GreedyBestFirst, GreedyBestFirst(heuristic="euclidean")])
def test_conformance(planner, check):
    check(planner)


def test_greedy_reaches_the_goal_around_the_wall():
    scenario = check_scenario("grid2d")
    result = GreedyBestFirst().plan(scenario, budget=pathzoo.Budget(), rng=np.random.default_rng(0))
    assert result.status is pathzoo.Status.SOLVED
    np.testing.assert_array_equal(result.path[0], scenario.start)
    np.testing.assert_array_equal(result.path[-1], scenario.goal)
    # the wall occupies column 5, rows 0..6: the path must pass below it
    crossing = result.path[np.argmin(np.abs(result.path[:, 0] - 5.5))]
    assert crossing[1] > 7.0
