"""Theta* on the MovingAI maps: valid any-angle paths, never longer than the 8-connected optimum."""

from __future__ import annotations

from typing import Callable

import numpy as np
import pytest

import pathzoo
from pathzoo.core import Budget, Scenario, Status
from pathzoo.rules import validate_path

SAMPLES = {
    "grid/dao/arena.map.scen": 4,
    "grid/rooms/8room_000.map.scen": 40,
    "mapf/random-32-32-20-random-1.scen": 5,
    "mapf/room-32-32-4-random-1.scen": 5,
    "mapf/maze-32-32-2-random-1.scen": 5,
}
"""Each ``.scen`` file with the stride of its sample."""


def path_length(path: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


@pytest.mark.parametrize(("scen", "stride"), [
    pytest.param(scen, stride, marks=[pytest.mark.slow] if "8room" in scen else []) for scen, stride in SAMPLES.items()
])
def test_thetastar_is_valid_and_no_longer_than_grid_optimum(
    load_scen: Callable[[str], list[Scenario]], scen: str, stride: int
) -> None:
    theta = pathzoo.make_planner("exact.thetastar")
    astar = pathzoo.make_planner("exact.astar")
    rng = np.random.default_rng(0)
    shorter = 0
    sample = load_scen(scen)[::stride]
    for scenario in sample:
        result = theta.plan(scenario, budget=Budget(), rng=rng)
        assert result.status is Status.SOLVED, scenario.id
        verdict = validate_path(scenario, result.path)
        assert verdict, (scenario.id, verdict.reason)
        length = path_length(result.path)
        grid = path_length(astar.plan(scenario, budget=Budget(), rng=rng).path)
        assert length <= grid + 1e-9, scenario.id
        assert length >= float(np.linalg.norm(scenario.goal - scenario.start)) - 1e-9, scenario.id
        assert result.extras["best_cost"] == pytest.approx(length, rel=1e-12)
        shorter += length < grid - 1e-6
    assert shorter > len(sample) // 2  # any-angle paths are usually strictly shorter


def test_thetastar_line_of_sight_gives_straight_path() -> None:
    occ = np.zeros((20, 30), dtype=bool)
    occ[5:15, 10] = True
    scenario = Scenario(id="t", kind="grid2d", occupancy=occ, cell_size=2.0, start=[1.0, 1.0], goal=[59.0, 11.0])
    result = pathzoo.make_planner("exact.thetastar").plan(scenario, budget=Budget(), rng=np.random.default_rng(0))
    assert result.status is Status.SOLVED
    np.testing.assert_array_equal(result.path, [scenario.start, scenario.goal])  # the wall does not cut the sight line
