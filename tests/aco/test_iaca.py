"""aco.iaca: slope and soil tabu tables, the slopeW heuristic and distance, the local and elite updates."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget, Scenario, TerrainRules, VehicleModel
from pathzoo.rules import validate_path
from pathzoo_aco.engine import REACHED, STUCK, ColonyProblem, Pheromone, WalkEngine
from pathzoo_scenarios.iaca import SLOPE_WEIGHTS

TAN = math.tan
RAD = math.radians


def _cross(strength_east: float = 80.0) -> Scenario:
    """3 x 3 cells of 10 m around a flat centre; each straight neighbour has a chosen slope from the centre.

    East +35 deg (NO GO), north +28 deg (slopeW 0.8), west -55 deg (slopeW 0.8),
    south -65 deg (NO GO); soil everywhere RCI 80 > VCI 50 except the east-north
    corner (``strength_east``).
    """
    z = np.zeros((3, 3))
    z[1, 2] = 10 * TAN(RAD(35))
    z[0, 1] = 10 * TAN(RAD(28))
    z[1, 0] = -10 * TAN(RAD(55))
    z[2, 1] = -10 * TAN(RAD(65))
    soil = np.full((3, 3), 80.0)
    soil[0, 2] = strength_east
    rules = TerrainRules(slope_weights=SLOPE_WEIGHTS, soil_strength=soil, min_soil_strength=50.0)
    return Scenario(id="cross", kind="terrain", occupancy=np.zeros((3, 3), bool), cell_size=10.0,
                    start=(15.0, 15.0), goal=(25.0, 5.0), elevation=z, rules=rules,
                    vehicle=VehicleModel(max_climb_deg=90.0, max_descent_deg=90.0))


def _edge(problem: ColonyProblem, a: tuple[int, int], b: tuple[int, int]) -> int:
    g = problem.graph
    u, v = (int(np.ravel_multi_index(c, g.shape)) for c in (a, b))
    edges = np.arange(g.indptr[u], g.indptr[u + 1])
    return int(edges[g.indices[edges] == v][0])


def test_slope_tabu_table_keeps_minus_60_to_30_degrees():
    problem = ColonyProblem(_cross())
    tabu = pathzoo.make_planner("aco.iaca").slope_tabu(problem)
    centre = (1, 1)
    assert tabu[_edge(problem, centre, (1, 2))] == 0.0  # +35 deg
    assert tabu[_edge(problem, centre, (0, 1))] == 1.0  # +28 deg
    assert tabu[_edge(problem, centre, (1, 0))] == 1.0  # -55 deg
    assert tabu[_edge(problem, centre, (2, 1))] == 0.0  # -65 deg
    assert tabu[_edge(problem, (1, 2), centre)] == 1.0  # -35 deg on the way back


def test_soil_tabu_table_needs_rci_above_vci():
    # RCI == VCI: passable for pathzoo's map (blocked only below VCI) but NO GO for IACA (RCI > VCI required)
    scenario = _cross(strength_east=50.0)
    problem = ColonyProblem(scenario)
    assert not scenario.blocked[0, 2]
    soil = pathzoo.make_planner("aco.iaca").soil_tabu(problem)
    assert soil.reshape(3, 3)[0, 2] == 0.0 and soil.reshape(3, 3)[1, 1] == 1.0
    eta = pathzoo.make_planner("aco.iaca").heuristic(problem)
    assert eta[_edge(problem, (0, 1), (0, 2))] == 0.0


def test_heuristic_is_j_slopew_over_step_plus_distance_to_target():
    problem = ColonyProblem(_cross())
    planner = pathzoo.make_planner("aco.iaca", j=200.0)
    eta = planner.heuristic(problem)
    # centre -> north: slope 28 deg (slopeW 0.8), 3-D step 1/cos(28) cells; from there the flat goal cell
    # (0, 2) is one cell east and tan(28) cells lower
    step = 1 / math.cos(RAD(28))
    to_goal = math.hypot(1.0, TAN(RAD(28)))
    assert eta[_edge(problem, (1, 1), (0, 1))] == pytest.approx(200 * 0.8 / (step + to_goal))
    assert eta[_edge(problem, (1, 1), (1, 2))] == 0.0  # NO GO slope


def test_distance_divides_each_step_by_its_slopew():
    scenario = _cross()
    planner = pathzoo.make_planner("aco.iaca")
    problem = ColonyProblem(scenario)
    dist = planner.edge_distance(problem)
    west = _edge(problem, (1, 1), (1, 0))
    assert dist[west] == pytest.approx((1 / math.cos(RAD(55))) / 0.8)  # -55 deg: slopeW 0.8
    level = _edge(problem, (1, 1), (0, 0))  # 0 deg: slopeW 1
    assert dist[level] == pytest.approx(math.sqrt(2.0))
    assert np.isinf(dist[_edge(problem, (1, 1), (1, 2))])


def _flat() -> Scenario:
    """8 x 8 flat cells of 10 m, corner to corner."""
    return Scenario(id="flat", kind="terrain", occupancy=np.zeros((8, 8), bool), cell_size=10.0,
                    start=(5.0, 5.0), goal=(75.0, 55.0), elevation=np.zeros((8, 8)))


def _colony(planner, scenario, n_ants, seed=0):
    problem = ColonyProblem(scenario)
    rules = planner.walk_rules(problem)
    trail = Pheromone(problem.n_nodes, planner.initial_trail(problem), on_nodes=True)
    engine = WalkEngine(problem)
    state = planner.init_state(problem, rules, trail, engine, np.random.default_rng(seed))
    walks = engine.walk(state.rules, state.trail, n_ants, seed)
    return state, walks, planner.walk_costs(state, walks)


def test_local_update_lowers_each_entered_cell_once():
    planner = pathzoo.make_planner("aco.iaca", decr=0.25, ph0=0.4)
    state, walks, costs = _colony(planner, _flat(), n_ants=1)
    assert walks.reached[0]
    entered = state.problem.graph.indices[walks.edges(0)]
    expected = np.full(state.problem.n_nodes, 0.4)
    expected[entered] = 0.4 * 0.75
    np.testing.assert_allclose(state.trail.values(), expected)
    assert costs[0] == pytest.approx(state.edge_distance[walks.edges(0)].sum())


@pytest.mark.parametrize("k", [5.0, 500.0])  # 500 (the paper's K) drives the path's cells to ph_max
def test_elite_update_reinforces_only_the_shortest_path_and_clamps(k):
    planner = pathzoo.make_planner("aco.iaca", rho=0.4, k=k)
    state, walks, costs = _colony(planner, _flat(), n_ants=10)
    assert walks.reached.sum() >= 2
    before = state.trail.values()
    planner.update_trail(state, walks, costs)
    best = int(np.argmin(costs))
    expected = before.copy()
    cells = state.problem.graph.indices[walks.edges(best)]
    expected[cells] = np.clip(0.6 * before[cells] + 0.4 * k / costs[best], 0.001, 0.8)
    np.testing.assert_allclose(state.trail.values(), expected)


def test_ants_that_get_stuck_are_dropped():
    planner = pathzoo.make_planner("aco.iaca")
    assert planner.dead_end == "die"
    _, walks, costs = _colony(planner, pathzoo.load_scenario("iaca.offroad"), n_ants=40)
    assert set(walks.flags.tolist()) <= {REACHED, STUCK} and (walks.flags == STUCK).any()
    assert np.isinf(costs[walks.flags == STUCK]).all()


def test_solves_the_paper_terrain_with_a_tiny_budget():
    scenario = pathzoo.load_scenario("iaca.offroad")
    result = pathzoo.make_planner("aco.iaca").plan(scenario, budget=Budget(iterations=3),
                                                   rng=np.random.default_rng(0))
    assert result.solved, result.message
    verdict = validate_path(scenario, result.path)
    assert verdict, verdict.reason
    # NO GO moves never appear: every step's slope is within [-60, 30] degrees
    z = scenario.elevation_at(result.path)
    run = np.linalg.norm(np.diff(result.path, axis=0), axis=1)
    assert np.all(np.degrees(np.arctan2(np.diff(z), run)) <= 30.0 + 1e-9)
