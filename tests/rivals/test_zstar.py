"""Z* (``exact.zstar``): its cost and heuristic by hand, consistency, and optimality against SciPy's Dijkstra."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import dijkstra

import pathzoo
from pathzoo.core import Budget, Scenario, Status, VehicleModel
from pathzoo.core.vehicle import GRAVITY
from pathzoo.rules import validate_path
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo_rivals.zstar import ZStarPlanner, reduced_costs, zstar_edge_cost, zstar_heuristic

MU = 0.1
MASS = 10.0
W = MASS * GRAVITY


def ramp(heights: list[float], goal_col: int, **vehicle: float) -> Scenario:
    """A one-row DEM of 10 m cells, start in column 0, goal in ``goal_col``."""
    elevation = np.array([heights], dtype=float)
    return Scenario(
        id="test.ramp",
        kind="terrain",
        occupancy=np.zeros(elevation.shape, dtype=bool),
        cell_size=10.0,
        start=np.array([5.0, 5.0]),
        goal=np.array([10.0 * goal_col + 5.0, 5.0]),
        elevation=elevation,
        vehicle=VehicleModel(mass_kg=MASS, rolling_resistance=MU, **vehicle),
    )


def test_heuristic_matches_the_three_cases_by_hand():
    s = ramp([0.0, 2.0, 3.0, 10.0], goal_col=3)
    d, dh = 30.0, 10.0  # cell 0 to the goal
    # straight line below the climb limit: W (mu D + dh) = W d3 (mu cos t + sin t)
    h = zstar_heuristic(s, math.radians(90.0))
    assert h[0] == pytest.approx(W * (MU * d + dh), rel=1e-12)
    t = math.atan2(dh, d)
    assert h[0] == pytest.approx(W * math.hypot(d, dh) * (MU * math.cos(t) + math.sin(t)), rel=1e-12)
    assert h[3] == 0.0
    # goal above the climb limit (18.4 deg > 10 deg): the zigzag climbs dh at theta_M
    tm = math.radians(10.0)
    h = zstar_heuristic(s, tm)
    assert h[0] == pytest.approx(W * dh * (MU * math.cos(tm) + math.sin(tm)) / math.sin(tm), rel=1e-6)
    assert h[0] > W * (MU * d + dh)
    # goal below the braking angle: nothing to pay
    down = ramp([10.0, 3.0, 2.0, 0.0], goal_col=3)
    assert zstar_heuristic(down, math.radians(90.0))[0] == 0.0


def test_edge_cost_by_hand():
    s = ramp([0.0, 2.0, 3.0, 10.0], goal_col=3)
    g = s.graph
    edges = {(int(u), int(v)): e for e, (u, v) in enumerate(zip(g.sources, g.indices))}
    cost = zstar_edge_cost(s, math.radians(90.0))
    up = math.atan2(2.0, 10.0)
    assert cost[edges[0, 1]] == pytest.approx(W * math.hypot(10.0, 2.0) * (MU * math.cos(up) + math.sin(up)), rel=1e-12)
    assert cost[edges[1, 0]] == 0.0  # -11.3 deg is steeper than the braking angle -atan(0.1) = -5.7 deg
    gentle = math.atan2(-1.0, 10.0)  # -5.71 deg: above the braking angle by a hair, friction still costs
    assert -gentle < math.atan(MU) + 1e-3
    expected = max(0.0, W * math.hypot(10.0, 1.0) * (MU * math.cos(gentle) + math.sin(gentle)))
    assert cost[edges[2, 1]] == pytest.approx(expected, abs=1e-9)
    limited = zstar_edge_cost(s, math.radians(10.0))
    assert math.isinf(limited[edges[0, 1]]) and math.isinf(limited[edges[2, 3]])
    assert limited[edges[1, 2]] == pytest.approx(cost[edges[1, 2]])


@pytest.fixture(scope="module")
def hugo() -> Scenario:
    return pathzoo.load_scenario("ggaco.hugo")


@pytest.fixture(params=[90.0, 12.0], ids=lambda deg: f"theta{deg:g}")
def hugo_tables(hugo, request) -> tuple[float, np.ndarray, np.ndarray]:
    """``(max climb in rad, heuristic, edge costs)`` of Z* on ``ggaco.hugo`` at a 90 and a 12 degree climb limit."""
    tm = math.radians(request.param)
    return tm, zstar_heuristic(hugo, tm), zstar_edge_cost(hugo, tm)


def test_heuristic_is_consistent_on_every_edge(hugo, hugo_tables):
    _, h, cost = hugo_tables
    g = hugo.graph
    ok = np.isfinite(cost)
    slack = h[g.sources] - (cost + h[g.indices])
    assert np.all(slack[ok] <= 1e-9 * cost[ok].max())
    assert h[hugo.goal_node] == 0.0


def test_reduced_costs_and_single_nodes_give_the_array_expressions_bit_for_bit(hugo, hugo_tables):
    tm, h, cost = hugo_tables
    g = hugo.graph
    np.testing.assert_array_equal(reduced_costs(hugo, cost, h), cost + h[g.indices] - h[g.sources])
    for node in np.random.default_rng(0).choice(g.n_nodes, 50, replace=False).tolist() + [hugo.start_node]:
        assert zstar_heuristic(hugo, tm, np.array([node]))[0] == h[node]


@pytest.mark.parametrize("theta_deg", [90.0, 15.0, 12.0])
def test_optimal_energy_equals_scipy_dijkstra(hugo, theta_deg):
    planner = ZStarPlanner(max_climb_deg=theta_deg)
    result = planner.plan(hugo, budget=Budget(), rng=np.random.default_rng(0))
    cost = zstar_edge_cost(hugo, math.radians(theta_deg))
    g = hugo.graph
    keep = np.isfinite(cost)
    matrix = csr_matrix((cost[keep], (g.sources[keep], g.indices[keep])), shape=(g.n_nodes, g.n_nodes))
    reference = dijkstra(matrix, indices=hugo.start_node)[hugo.goal_node]
    assert result.status == Status.SOLVED
    assert result.extras["graph_cost"] == pytest.approx(reference, rel=1e-9)
    assert validate_path(hugo, result.path).valid
    pieces = np.diff(result.path, axis=0)
    rise = np.diff(hugo.elevation_at(result.path))
    slope = np.degrees(np.arctan2(rise, np.hypot(pieces[:, 0], pieces[:, 1])))
    assert slope.max() <= theta_deg + 1e-9


def test_expands_fewer_nodes_than_dijkstra(hugo):
    z = ZStarPlanner().plan(hugo, budget=Budget(), rng=np.random.default_rng(0))
    d = pathzoo.make_planner("exact.dijkstra", cost="energy").plan(hugo, budget=Budget(), rng=np.random.default_rng(0))
    assert z.extras["best_cost"] == pytest.approx(d.extras["best_cost"], rel=1e-9)
    assert z.evaluations < d.evaluations


def test_no_path_above_the_climb_limit():
    s = ramp([0.0, 5.0, 10.0, 15.0], goal_col=3)
    result = ZStarPlanner(max_climb_deg=10.0).plan(s, budget=Budget(), rng=np.random.default_rng(0))
    assert result.status == Status.NO_PATH
    assert ZStarPlanner().plan(s, budget=Budget(), rng=np.random.default_rng(0)).status == Status.SOLVED


def test_grid2d_is_flat_energy_search():
    s = check_scenario("grid2d")
    result = ZStarPlanner().plan(s, budget=Budget(), rng=np.random.default_rng(0))
    assert result.status == Status.SOLVED and validate_path(s, result.path).valid
