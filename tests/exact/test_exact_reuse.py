"""What the exact planners keep between searches: a spare search state per thread, endpoints per scenario."""

from __future__ import annotations

import numpy as np
import pytest
from pathzoo_exact import base
from pathzoo_exact.astar import _E_MIN, least_energy_per_metre
from pathzoo_exact.base import endpoints
from pathzoo_exact.waypoints import straight_run_ends

import pathzoo
from pathzoo.core import Budget, PlanResult, Scenario, Status
from pathzoo.generators import random_obstacles
from pathzoo.core.tiny_scenarios import check_scenario

RNG = np.random.default_rng(0)


def maze(start: tuple[float, float], goal: tuple[float, float]) -> Scenario:
    occ = random_obstacles((30, 40), seed=11, density=0.3)
    for x, y in (start, goal):
        occ[int(y), int(x)] = False
    return Scenario(id="maze", kind="grid2d", occupancy=occ, cell_size=1.0, start=start, goal=goal)


def plan(planner_id: str, scenario: Scenario, budget: Budget | None = None) -> PlanResult:
    return pathzoo.make_planner(planner_id).plan(scenario, budget=budget or Budget(), rng=RNG)


def same(a: PlanResult, b: PlanResult) -> None:
    assert a.status == b.status and a.evaluations == b.evaluations and a.extras == b.extras
    np.testing.assert_array_equal(a.path, b.path)


@pytest.mark.parametrize("planner_id", ["exact.astar", "exact.dijkstra", "exact.thetastar"])
def test_a_search_in_a_used_state_is_the_search_in_a_fresh_one(planner_id: str) -> None:
    first, second = maze((0.5, 0.5), (39.5, 29.5)), maze((35.2, 2.7), (3.5, 27.5))
    base._SPARE.state = None
    fresh = plan(planner_id, second)
    for budget in (Budget(), Budget(evaluations=40)):  # a finished search, and one stopped with a full heap
        plan(planner_id, first, budget)
        used = base._SPARE.state
        assert used is not None and used.closed.any()
        again = plan(planner_id, second)
        assert base._SPARE.state is used  # the same arrays served the second search
        same(again, fresh)
        assert fresh.status is Status.SOLVED


def test_results_share_no_memory_with_the_spare_state() -> None:
    result = plan("exact.astar", maze((0.5, 0.5), (39.5, 29.5)))
    spare = base._SPARE.state
    for name in ("g", "parent", "closed", "heap", "counters"):
        assert not np.shares_memory(result.path, getattr(spare, name))


def test_big_graphs_leave_no_spare(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(base, "SPARE_MAX_NODES", 10)
    base._SPARE.state = None
    assert plan("exact.astar", maze((0.5, 0.5), (39.5, 29.5))).status is Status.SOLVED
    assert base._SPARE.state is None


def test_a_spare_of_another_size_is_not_used() -> None:
    plan("exact.astar", maze((0.5, 0.5), (39.5, 29.5)))
    other = Scenario(id="open", kind="grid2d", occupancy=np.zeros((7, 9), bool), cell_size=1.0, start=(0.5, 0.5),
                     goal=(8.5, 6.5))
    result = plan("exact.astar", other)
    assert result.status is Status.SOLVED and result.extras["graph_cost"] == pytest.approx(2 + 6 * np.sqrt(2))
    assert base._SPARE.state.g.shape == (63,)


def test_endpoints_are_worked_out_once_per_scenario() -> None:
    s = maze((35.2, 2.7), (3.5, 27.5))
    ends = endpoints(s)
    assert endpoints(s) is ends
    assert ends == (s.start_node, s.goal_node, False, True)


def test_straight_run_ends_keeps_the_ends_and_the_turns() -> None:
    width = 10
    cells = [(0, 0), (0, 1), (0, 2), (1, 3), (2, 4), (3, 4), (4, 4), (4, 3)]  # east, diagonal, south, west
    nodes = np.array([r * width + c for r, c in cells], dtype=np.int64)
    keep = straight_run_ends(nodes, width)
    assert [cells[i] for i in np.flatnonzero(keep)] == [(0, 0), (0, 2), (2, 4), (4, 4), (4, 3)]
    assert straight_run_ends(nodes[:2], width).all() and straight_run_ends(nodes[:1], width).all()


def test_energy_heuristic_scale_is_worked_out_once_per_graph() -> None:
    graph = check_scenario("terrain").graph
    _E_MIN.pop(graph, None)
    e_min = least_energy_per_metre(graph)
    assert e_min == float(np.min(graph.energy / graph.length))
    assert _E_MIN[graph] == e_min
    _E_MIN[graph] = 0.5 * e_min  # a kept value is what later plans use
    assert least_energy_per_metre(graph) == 0.5 * e_min
    _E_MIN.pop(graph)
