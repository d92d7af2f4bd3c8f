"""Behaviour of the exact planners: registration, parameters, endpoints, budgets, statuses and kinds."""

from __future__ import annotations

import time

import numpy as np
import pytest

import pathzoo
from pathzoo.core import Budget, InvalidParameterError, Scenario, Status, UnsupportedScenarioError, VehicleModel
from pathzoo.rules import validate_path
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo_exact.astar import AStarPlanner
from pathzoo_exact.dijkstra import DijkstraPlanner
from pathzoo_exact.thetastar import ThetaStarPlanner

ALL = ("exact.dijkstra", "exact.astar", "exact.thetastar")
RNG = np.random.default_rng(0)


def plan(planner_id: str, scenario: Scenario, budget: Budget = Budget(), **params: object):
    calls: list[tuple[int, int, float]] = []
    result = pathzoo.make_planner(planner_id, **params).plan(
        scenario, budget=budget, rng=RNG, progress=lambda *a: calls.append(a)
    )
    return result, calls


def open_grid(shape=(40, 40), cell_size=1.0, start=(0.5, 0.5), goal=(39.5, 29.5)) -> Scenario:
    return Scenario(id="open", kind="grid2d", occupancy=np.zeros(shape, bool), cell_size=cell_size, start=start, goal=goal)


def test_registered_through_the_entry_point() -> None:
    entries = {e.id: e for e in pathzoo.list_plugins("planners")}
    assert entries["exact.dijkstra"].obj is DijkstraPlanner
    assert entries["exact.astar"].obj is AStarPlanner
    assert entries["exact.thetastar"].obj is ThetaStarPlanner
    assert {entries[i].plugin for i in ALL} == {"exact"}


def test_kinds() -> None:
    assert DijkstraPlanner.kinds == AStarPlanner.kinds == {"grid2d", "terrain", "air3d"}
    assert ThetaStarPlanner.kinds == {"grid2d"}
    for planner_id in ALL:  # dynamic scenarios would need time-aware search
        with pytest.raises(UnsupportedScenarioError, match=planner_id):
            plan(planner_id, check_scenario("dynamic"))


@pytest.mark.parametrize("planner_id", ["exact.dijkstra", "exact.astar"])
def test_cost_parameter_is_validated(planner_id: str) -> None:
    with pytest.raises(InvalidParameterError, match="'cost'"):
        pathzoo.make_planner(planner_id, cost="time")


@pytest.mark.parametrize("planner_id", ALL)
def test_result_fields_and_single_progress_call(planner_id: str) -> None:
    result, calls = plan(planner_id, open_grid())
    assert result.status is Status.SOLVED
    assert result.iterations == 1
    assert result.evaluations > 0
    assert calls == [(1, result.evaluations, result.extras["best_cost"])]
    length = float(np.linalg.norm(np.diff(result.path, axis=0), axis=1).sum())
    assert calls[0][2] == pytest.approx(length, rel=1e-12)


def test_octile_optimum_scales_with_cell_size() -> None:
    for cs in (1.0, 2.5):
        scenario = open_grid(cell_size=cs, start=(0.5 * cs, 0.5 * cs), goal=(39.5 * cs, 29.5 * cs))
        for planner_id in ("exact.dijkstra", "exact.astar"):
            result, calls = plan(planner_id, scenario)
            assert calls[0][2] == pytest.approx(cs * (10 + 29 * np.sqrt(2)), rel=1e-12)


def test_astar_expands_fewer_nodes_than_dijkstra() -> None:
    occ = np.zeros((60, 60), bool)
    occ[10:50, 30] = True
    scenario = Scenario(id="w", kind="grid2d", occupancy=occ, cell_size=1.0, start=(5.5, 30.5), goal=(55.5, 30.5))
    dij, _ = plan("exact.dijkstra", scenario)
    ast, _ = plan("exact.astar", scenario)
    assert ast.extras["best_cost"] == pytest.approx(dij.extras["best_cost"], rel=1e-12)
    assert ast.evaluations < dij.evaluations / 2


@pytest.mark.parametrize("planner_id", ALL)
def test_off_centre_endpoints_are_exact_and_valid(planner_id: str) -> None:
    scenario = open_grid(start=(0.2, 0.9), goal=(39.99, 29.01))
    result, calls = plan(planner_id, scenario)
    assert result.status is Status.SOLVED
    np.testing.assert_array_equal(result.path[0], scenario.start)
    np.testing.assert_array_equal(result.path[-1], scenario.goal)
    np.testing.assert_array_equal(result.path[1], [0.5, 0.5])  # the start's cell centre, then the search's path
    np.testing.assert_array_equal(result.path[-2], [39.5, 29.5])
    assert validate_path(scenario, result.path)
    length = float(np.linalg.norm(np.diff(result.path, axis=0), axis=1).sum())
    assert calls[0][2] == pytest.approx(length, rel=1e-12)


@pytest.mark.parametrize("planner_id", ALL)
def test_same_cell(planner_id: str) -> None:
    for start, goal, expected in [
        ((3.5, 4.5), (3.5, 4.5), [(3.5, 4.5), (3.5, 4.5)]),
        ((3.2, 4.5), (3.9, 4.1), [(3.2, 4.5), (3.5, 4.5), (3.9, 4.1)]),
        ((3.5, 4.5), (3.9, 4.1), [(3.5, 4.5), (3.9, 4.1)]),
    ]:
        scenario = open_grid(start=start, goal=goal)
        result, _ = plan(planner_id, scenario)
        assert result.status is Status.SOLVED
        np.testing.assert_array_equal(result.path, expected)
        assert validate_path(scenario, result.path)


def test_grid2d_paths_keep_only_turns_and_terrain_paths_keep_every_cell() -> None:
    result, _ = plan("exact.astar", open_grid())
    d = np.diff(result.path, axis=0)
    assert np.all((d[:, 0] == 0) | (d[:, 1] == 0) | (np.abs(d[:, 0]) == np.abs(d[:, 1])))  # runs of one move
    unit = np.sign(d)
    assert np.all(np.any(unit[1:] != unit[:-1], axis=1))  # every interior waypoint is a turn
    assert len(result.path) <= 5
    rows, cols = np.mgrid[0:20, 0:20]
    terrain = Scenario(
        id="hill", kind="terrain", occupancy=np.zeros((20, 20), bool), cell_size=1.0,
        elevation=0.05 * rows + 0.02 * cols, start=(0.5, 0.5), goal=(19.5, 15.5),
    )
    result, _ = plan("exact.astar", terrain)
    steps = np.abs(np.diff(result.path, axis=0)).max(axis=1)
    np.testing.assert_array_equal(steps, 1.0)  # one cell per segment
    assert validate_path(terrain, result.path)


@pytest.mark.parametrize("planner_id", ALL)
def test_unreachable_goal_is_no_path(planner_id: str) -> None:
    occ = np.zeros((20, 20), bool)
    occ[:, 10] = True
    scenario = Scenario(id="wall", kind="grid2d", occupancy=occ, cell_size=1.0, start=(2.5, 2.5), goal=(17.5, 2.5))
    result, calls = plan(planner_id, scenario)
    assert result.status is Status.NO_PATH
    assert result.path is None and calls == []
    assert result.evaluations == 200  # every cell left of the wall was expanded


@pytest.mark.parametrize("planner_id", ALL)
def test_evaluation_budget_caps_expansions(planner_id: str) -> None:
    result, calls = plan(planner_id, open_grid(), Budget(evaluations=7))
    assert result.status is Status.FAILED
    assert result.evaluations == 7
    assert "evaluation budget" in result.message and calls == []
    # the budget that exactly suffices solves it
    needed = plan(planner_id, open_grid())[0].evaluations
    assert plan(planner_id, open_grid(), Budget(evaluations=needed))[0].status is Status.SOLVED


def test_time_budget_is_checked_between_batches() -> None:
    occ = np.zeros((400, 400), bool)
    scenario = Scenario(id="big", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(399.5, 399.5))
    scenario.graph
    plan("exact.dijkstra", scenario, Budget(evaluations=10))  # warm up
    started = time.perf_counter()
    result, _ = plan("exact.dijkstra", scenario, Budget(time_s=1e-4))
    elapsed = time.perf_counter() - started
    assert result.status is Status.FAILED and "time budget" in result.message
    assert DijkstraPlanner.batch_expansions <= result.evaluations < 160_000
    assert elapsed < 0.5


class TinyHeapDijkstra(DijkstraPlanner):
    initial_heap_capacity = 1


def test_heap_grows_without_changing_the_answer() -> None:
    scenario = check_scenario("grid2d")
    small = TinyHeapDijkstra().plan(scenario, budget=Budget(), rng=RNG)
    normal = DijkstraPlanner().plan(scenario, budget=Budget(), rng=RNG)
    np.testing.assert_array_equal(small.path, normal.path)
    assert small.evaluations == normal.evaluations


def steep_step() -> Scenario:
    # the right column is a 100 m cliff; a start close to it sees a steep bilinear slope to its own centre
    elevation = np.zeros((3, 3))
    elevation[:, 2] = 100.0
    return Scenario(
        id="cliff", kind="terrain", occupancy=np.zeros((3, 3), bool), cell_size=1.0, elevation=elevation,
        start=(1.95, 1.5), goal=(0.5, 0.5), vehicle=VehicleModel(max_climb_deg=30.0, max_descent_deg=30.0),
    )


@pytest.mark.parametrize("planner_id", ["exact.dijkstra", "exact.astar"])
def test_bad_connector_is_failed_not_an_invalid_path(planner_id: str) -> None:
    result, calls = plan(planner_id, steep_step())
    assert result.status is Status.FAILED
    assert "connector" in result.message and "descends" in result.message
    assert calls == []


@pytest.mark.parametrize("cost", ["length", "energy"])
@pytest.mark.parametrize("planner_id", ["exact.dijkstra", "exact.astar"])
def test_air_volume(planner_id: str, cost: str) -> None:
    scenario = check_scenario("air3d")
    result, calls = plan(planner_id, scenario, cost=cost)
    assert result.status is Status.SOLVED
    assert validate_path(scenario, result.path)
    assert calls[0][2] > 0
