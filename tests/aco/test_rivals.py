"""The ant-colony rivals of the papers' tables: aco.flaco (rank-based update, fuzzy impedance) and aco.aco_astar."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import skfuzzy
from skfuzzy import control as ctrl

import pathzoo
from pathzoo import Budget, MovingObstacle, Scenario
from pathzoo.rules import validate_path
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo_aco.engine import ColonyProblem, Pheromone
from pathzoo_aco.flaco import rank_deposits
from pathzoo_aco.flaco_fuzzy import RULES, TERM_VERTICES, UNIVERSE, impedance, traffic_share

from aco_maps import hill, walled_grid

TERMS = ("low", "medium", "high")


def _length(path: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


# ------------------------------------------------------------------ FLACO: rank-based update
def test_rank_deposits_follow_the_rank_weights():
    costs = np.array([5.0, 2.0, np.inf, 4.0, 3.0, 9.0])
    reached = np.array([True, True, False, True, True, True])
    ants, amounts = rank_deposits(costs, reached, w=4, q=1.0)
    # the w - 1 = 3 best ants: costs 2, 3, 4 with weights 3, 2, 1
    assert ants.tolist() == [1, 4, 3]
    np.testing.assert_allclose(amounts, [3 / 2, 2 / 3, 1 / 4])
    few, _ = rank_deposits(costs, np.zeros(6, bool), w=4, q=1.0)
    assert few.size == 0


def _corridor_state(planner, n_ants: int, seed: int = 0):
    """One colony on a 1 x 4 corridor (one possible walk), through the planner's hooks, best tracked as in plan()."""
    scenario = Scenario(id="line", kind="grid2d", occupancy=np.zeros((1, 4), bool), cell_size=1.0,
                        start=(0.5, 0.5), goal=(3.5, 0.5))
    problem = ColonyProblem(scenario)
    rules = planner.walk_rules(problem)
    trail = Pheromone(problem.graph.n_edges, planner.initial_trail(problem))
    engine = planner.walk_engine(problem)
    state = planner.init_state(problem, rules, trail, engine, np.random.default_rng(seed))
    walks = engine.walk(state.rules, state.trail, n_ants, seed)
    costs = planner.walk_costs(state, walks)
    k = int(np.argmin(costs))
    state.best_cost, state.best_edges = float(costs[k]), walks.edges(k).copy()
    return state, walks, costs


def test_update_lays_rank_weights_and_the_elitist_deposit_by_hand():
    planner = pathzoo.make_planner("aco.flaco", n_ants=3, w=6, q=2.0, rho=0.25)
    state, walks, costs = _corridor_state(planner, n_ants=3)
    assert walks.reached.all()
    path = walks.edges(0)
    assert all(np.array_equal(walks.edges(a), path) for a in range(3)) and len(path) == 3
    virtual = float(state.virtual[path].sum())
    assert costs == pytest.approx([virtual] * 3)
    tau0 = 6 * 5 / (2 * 0.25 * 3.0)  # w (w - 1) / (2 ρ L), L = 3 m straight
    assert state.trail.values() == pytest.approx(tau0)
    planner.update_trail(state, walks, costs)
    expected = np.full(state.trail.x.size, 0.75 * tau0)
    # ranks 1, 2, 3 lay (6-1) Q/L, (6-2) Q/L, (6-3) Q/L; the best-so-far walk lays 6 Q/L
    expected[path] += (5 + 4 + 3 + 6) * 2.0 / virtual
    np.testing.assert_allclose(state.trail.values(), expected)


def test_virtual_length_is_length_times_one_plus_kappa_impedance():
    scenario = walled_grid()
    problem = ColonyProblem(scenario)
    planner = pathzoo.make_planner("aco.flaco", kappa=2.5, sensing_m=4.0)
    c = planner.node_impedance(problem)
    g = problem.graph
    np.testing.assert_allclose(planner.virtual_lengths(problem), g.length * (1 + 2.5 * c[g.indices]))
    # no moving obstacles: the impedance follows the static clearance alone, lower far from the wall
    clear = np.minimum(scenario.clearance.ravel() / 4.0, 1.0)
    np.testing.assert_allclose(c, impedance(0.0, clear))
    free = np.flatnonzero(~scenario.occupancy.ravel())
    assert c[free][np.argmax(clear[free])] < c[free][np.argmin(clear[free])]


# ------------------------------------------------------------------ FLACO: fuzzy impedance
def _control_system() -> ctrl.ControlSystemSimulation:
    traffic = ctrl.Antecedent(UNIVERSE, "traffic")
    clearance = ctrl.Antecedent(UNIVERSE, "clearance")
    out = ctrl.Consequent(UNIVERSE, "impedance", defuzzify_method="centroid")
    for name, v in zip(TERMS, TERM_VERTICES):
        traffic[name] = skfuzzy.trimf(UNIVERSE, list(v))
        clearance[name] = skfuzzy.trimf(UNIVERSE, list(v))
        out[name] = skfuzzy.trimf(UNIVERSE, list(v))
    rules = [ctrl.Rule(traffic[TERMS[i]] & clearance[TERMS[j]], out[TERMS[k]]) for (i, j), k in RULES.items()]
    return ctrl.ControlSystemSimulation(ctrl.ControlSystem(rules))


@pytest.mark.filterwarnings("ignore:Passing more than 2 positional arguments:DeprecationWarning")  # inside skfuzzy
def test_impedance_matches_scikit_fuzzy_control_system():
    crisp = [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (0.3, 0.7), (0.55, 0.2), (0.8, 0.9), (0.5, 0.5)]
    sim = _control_system()
    ours = impedance(*np.array(crisp).T)
    for (t, c), mine in zip(crisp, ours):
        sim.input["traffic"], sim.input["clearance"] = t, c
        sim.compute()
        # the control system adds the clip points to the universe; we integrate on the universe itself
        assert mine == pytest.approx(sim.output["impedance"], abs=2e-4)


def test_rule_base_is_complete_and_monotone():
    assert set(RULES) == set(itertools.product(range(3), repeat=2))
    for (t, c), term in RULES.items():
        if t > 0:
            assert RULES[(t - 1, c)] <= term  # more traffic never lowers the impedance
        if c > 0:
            assert RULES[(t, c - 1)] >= term  # more clearance never raises it
    # one rule fires fully at each corner: the centroid of the whole low (0, 0, 0.5) or high (0.5, 1, 1) triangle
    quiet, busy = impedance([0.0, 1.0], [1.0, 0.0])
    assert quiet == pytest.approx(1 / 6, abs=1e-12) and busy == pytest.approx(5 / 6, abs=1e-12)


def test_traffic_share_counts_sampled_presence_by_hand():
    parked = MovingObstacle(1.0, np.array([[5.0, 5.0]]), 0.0)
    share = traffic_share(np.array([[7.5, 5.0], [9.0, 5.0]]), [parked], sensing_m=2.0)
    assert share.tolist() == [1.0, 0.0]  # rim 1.5 m and 3 m away
    # 0 -> 10 -> 0 at 1 m/s: period 20 s, 64 samples 0.3125 s apart; the rim is within 1 m of
    # the origin while the centre is below x = 1.5: samples 0-4 outbound, 60-63 inbound
    patrol = MovingObstacle(0.5, np.array([[0.0, 0.0], [10.0, 0.0]]), 1.0)
    assert traffic_share(np.array([[0.0, 0.0]]), [patrol], sensing_m=1.0)[0] == pytest.approx(9 / 64)
    assert traffic_share(np.array([[0.0, 0.0]]), [patrol, parked, parked], sensing_m=7.0)[0] == 1.0


# ------------------------------------------------------------------ FLACO: solves
def test_flaco_solves_a_small_map_with_a_valid_path():
    scenario = walled_grid()
    result = pathzoo.make_planner("aco.flaco").plan(scenario, budget=Budget(iterations=5),
                                                   rng=np.random.default_rng(0))
    assert result.status.value == "solved" and validate_path(scenario, result.path)
    optimum = pathzoo.make_planner("exact.astar").plan(scenario, budget=Budget(), rng=np.random.default_rng(0))
    assert _length(result.path) >= _length(optimum.path) - 1e-9


def test_flaco_walks_avoid_moving_obstacles():
    scenario = check_scenario("dynamic")  # a disc patrols the gap the walks must use
    planner = pathzoo.make_planner("aco.flaco")
    problem = ColonyProblem(scenario)
    rules = planner.walk_rules(problem)
    engine = planner.walk_engine(problem)
    trail = Pheromone(problem.graph.n_edges, planner.initial_trail(problem))
    walks = engine.walk(rules, trail, 30, 3)
    assert walks.reached.sum() >= 15
    for a in np.flatnonzero(walks.reached):
        verdict = validate_path(scenario, problem.walk_points(walks.edges(a)))
        assert verdict, verdict.reason
    result = planner.plan(scenario, budget=Budget(iterations=3), rng=np.random.default_rng(2))
    assert result.status.value == "solved" and validate_path(scenario, result.path)


def test_flaco_same_seed_same_path():
    scenario = walled_grid()
    runs = [pathzoo.make_planner("aco.flaco").plan(scenario, budget=Budget(iterations=3),
                                                   rng=np.random.default_rng(7)) for _ in range(2)]
    np.testing.assert_array_equal(runs[0].path, runs[1].path)


# ------------------------------------------------------------------ ACO-A*
@pytest.mark.parametrize("scenario", [walled_grid(), hill(), check_scenario("air3d")], ids=lambda s: s.id)
def test_aco_astar_is_the_optimal_a_star_leg(scenario):
    rng = np.random.default_rng(0)
    ours = pathzoo.make_planner("aco.aco_astar").plan(scenario, budget=Budget(), rng=rng)
    reference = pathzoo.make_planner("exact.dijkstra").plan(scenario, budget=Budget(), rng=rng)
    assert ours.status.value == "solved" and validate_path(scenario, ours.path)
    assert _length(ours.path) == pytest.approx(_length(reference.path), rel=1e-9)


def test_aco_astar_minimises_length_not_energy():
    planner = pathzoo.make_planner("aco.aco_astar")
    assert planner.params == {} and planner.cost == "length"
    assert planner.kinds == frozenset({"grid2d", "terrain", "air3d"})
