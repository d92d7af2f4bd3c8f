"""Each variant's distinctive mechanism, tested in isolation on small maps."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pathzoo
from pathzoo import Scenario
from pathzoo_aco.engine import ColonyProblem, Pheromone, WalkEngine, WalkRules
from pathzoo_aco.mmas import global_best_due

from aco_maps import hill, open_grid, walled_grid


def _colony(planner, scenario, n_ants=6, seed=0):
    """Build a run's state, send one colony and record the best walk as the loop does."""
    problem = ColonyProblem(scenario)
    rules = planner.walk_rules(problem)
    size = problem.n_nodes if planner.pheromone_on == "nodes" else problem.graph.n_edges
    trail = Pheromone(size, planner.initial_trail(problem))
    engine = WalkEngine(problem)
    state = planner.init_state(problem, rules, trail, engine, np.random.default_rng(seed))
    walks = engine.walk(state.rules, state.trail, n_ants, seed)
    costs = planner.walk_costs(state, walks)
    k = int(np.argmin(costs))
    state.iteration, state.best_cost, state.best_edges = 1, float(costs[k]), walks.edges(k).copy()
    return state, walks, costs


# ------------------------------------------------------------------ AS
def test_as_evaporates_everywhere_and_every_ant_lays_q_over_l():
    planner = pathzoo.make_planner("aco.as", rho=0.3, q=10.0, tau0=0.5)
    state, walks, costs = _colony(planner, walled_grid())
    expected = state.trail.values() * 0.7
    for a in range(walks.started):
        expected[walks.edges(a)] += 10.0 / costs[a]
    planner.update_trail(state, walks, costs)
    np.testing.assert_allclose(state.trail.values(), expected)


# ------------------------------------------------------------------ MMAS
def test_mmas_global_best_every_25th_iteration_or_on_the_growing_schedule():
    assert [t for t in range(1, 101) if global_best_due(t)] == [25, 50, 75, 100]
    due = [t for t in range(1, 261) if global_best_due(t, growing=True)]
    assert [t for t in due if t <= 25] == [25]
    assert [t for t in due if 25 < t <= 75] == [30, 35, 40, 45, 50, 55, 60, 65, 70, 75]
    assert [t for t in due if 75 < t <= 125] == list(range(78, 126, 3))
    assert [t for t in due if 125 < t <= 250] == list(range(126, 251, 2))
    assert due[-10:] == list(range(251, 261))


def test_mmas_trail_limits_formula():
    planner = pathzoo.make_planner("aco.mmas", rho=0.02, p_best=0.05)
    problem = ColonyProblem(open_grid(8))
    state, _, _ = _colony(planner, open_grid(8))
    lo, hi = planner.trail_limits(problem, state.best_edges, state.best_cost)
    assert math.isclose(hi, 1.0 / (0.02 * state.best_cost))
    n = len(state.best_edges)
    g = problem.graph
    nodes = np.concatenate([[problem.start], g.indices[state.best_edges[:-1]]])
    avg = g.degree[nodes].mean()
    root = 0.05 ** (1.0 / n)
    assert math.isclose(lo, hi * (1 - root) / ((avg - 1) * root))
    assert 0 < lo < hi


def test_mmas_one_ant_deposits_and_trails_stay_within_bounds():
    planner = pathzoo.make_planner("aco.mmas", rho=0.1, best_ant="iteration")
    state, walks, costs = _colony(planner, walled_grid())
    before = state.trail.values()
    planner.update_trail(state, walks, costs)
    lo, hi = planner.trail_limits(state.problem, state.best_edges, state.best_cost)
    after = state.trail.values()
    assert after.min() >= lo and after.max() <= hi and math.isclose(after.max(), hi)  # τ0 was above τmax
    best = walks.edges(int(np.argmin(costs)))
    expected = np.clip(before * 0.9, lo, hi)
    expected[best] = np.clip(expected[best] + 1.0 / costs.min(), lo, hi)
    np.testing.assert_allclose(after, expected)


def test_mmas_rejects_zero_evaporation():
    with pytest.raises(pathzoo.InvalidParameterError, match="rho"):
        pathzoo.make_planner("aco.mmas", rho=0.0)


# ------------------------------------------------------------------ ACS
def test_acs_tau0_from_the_greedy_walk_and_its_rules():
    planner = pathzoo.make_planner("aco.acs", xi=0.1, q0=0.9)
    problem = ColonyProblem(open_grid(8))
    rules = planner.walk_rules(problem)
    trail = Pheromone(problem.graph.n_edges, planner.initial_trail(problem))
    state = planner.init_state(problem, rules, trail, WalkEngine(problem), np.random.default_rng(0))
    tau0 = 1.0 / (7 * 7 * math.sqrt(2))  # the greedy walk is the diagonal: n = 7 edges, L_nn = 7 sqrt 2
    np.testing.assert_allclose(state.trail.values(), tau0)
    assert state.evaluations == 1
    assert state.rules.q0 == 0.9 and state.rules.local_keep == 0.9 and math.isclose(state.rules.local_add, 0.1 * tau0)


def test_acs_global_update_touches_the_global_best_only():
    planner = pathzoo.make_planner("aco.acs", rho=0.1)
    state, walks, costs = _colony(planner, walled_grid())
    before = state.trail.values()
    planner.update_trail(state, walks, costs)
    expected = before.copy()
    expected[state.best_edges] = 0.9 * before[state.best_edges] + 0.1 / state.best_cost
    np.testing.assert_allclose(state.trail.values(), expected)


# ------------------------------------------------------------------ GGACO
def _sigmoid(v, lam):
    return 1.0 / (1.0 + math.exp(-lam * v))


def test_ggaco_gain_added_toward_the_nearest_neighbour_and_subtracted_elsewhere():
    planner = pathzoo.make_planner("aco.ggaco", lam=0.7)
    problem = ColonyProblem(open_grid(8))
    g = problem.graph
    gain = planner.gain(problem)
    node = 2 * 8 + 2  # cell (2, 2); goal (7, 7)
    d = problem.goal_distance
    for e in range(g.indptr[node], g.indptr[node + 1]):
        j = g.indices[e]
        value = _sigmoid(d[j] / d[node], 0.7)
        sign = 1.0 if j == 3 * 8 + 3 else -1.0  # (3, 3) is the neighbour nearest the goal
        assert math.isclose(gain[e], sign * value)
        assert 0.5 < value < 1.0


def test_ggaco_gain_ties_all_get_the_addition():
    occ = np.zeros((5, 8), bool)
    occ[2, 3] = True  # blocks the straight move, and the diagonals by the corner rule
    scenario = Scenario(id="tie", kind="grid2d", occupancy=occ, cell_size=1.0, start=(2.5, 2.5), goal=(7.5, 2.5))
    problem = ColonyProblem(scenario)
    g = problem.graph
    gain = pathzoo.make_planner("aco.ggaco").gain(problem)
    node = 2 * 8 + 2
    positive = {int(g.indices[e]) for e in range(g.indptr[node], g.indptr[node + 1]) if gain[e] > 0}
    assert positive == {1 * 8 + 2, 3 * 8 + 2}  # (1, 2) and (3, 2) are equally near the goal


def test_ggaco_heuristic_and_deposit_follow_eqs_16_to_18():
    scenario = hill()
    planner = pathzoo.make_planner("aco.ggaco", phi=2.0, beta=0.6, alpha=0.4, rho=0.4)
    problem = ColonyProblem(scenario)
    g = problem.graph
    d = g.length * (1.0 + np.abs(np.tan(g.slope)))
    eta = 1.0 / d + scenario.vehicle.cruise_speed / 2.0
    np.testing.assert_allclose(planner.heuristic(problem), eta)
    assert np.any(d > g.length * 1.05)  # the hill really scales some distances
    rules = planner.walk_rules(problem)
    n = g.degree[g.indices]
    np.testing.assert_allclose(rules.weight_mul, eta**0.6 * n / (n + 1), rtol=1e-6)
    np.testing.assert_allclose(rules.pre_add, planner.gain(problem), rtol=1e-6)
    assert rules.tau_exp == 0.4
    state, walks, costs = _colony(planner, scenario)
    expected = np.maximum(state.trail.values() * 0.6, planner.tau_floor)  # evaporate, then the floor
    per_edge = 1.0 / d + 1.0 / np.maximum(g.energy, 1.0)
    for a in np.flatnonzero(walks.reached):
        expected[walks.edges(a)] += per_edge[walks.edges(a)]
    planner.update_trail(state, walks, costs)
    np.testing.assert_allclose(state.trail.values(), expected)
    np.testing.assert_allclose(costs[walks.reached], walks.totals(g.energy)[walks.reached])


# ------------------------------------------------------------------ G-Ant
def test_gant_additive_rule_with_neighbour_factor():
    planner = pathzoo.make_planner("aco.gant", alpha=0.4, beta=0.6, phi=2.0)
    problem = ColonyProblem(walled_grid())
    g = problem.graph
    rules = planner.walk_rules(problem)
    eta = 1.0 / g.length + problem.scenario.vehicle.cruise_speed / 2.0
    factor = g.degree[g.indices] / (g.degree[g.indices] + 1.0)
    assert rules.tau_exp == 1.0
    np.testing.assert_allclose(rules.weight_mul, 0.4 * factor, rtol=1e-6)
    np.testing.assert_allclose(rules.weight_add, 0.6 * eta * factor, rtol=1e-6)
    tau = 3.0  # the kernel's weight τ * mul + add is (α τ + β η) N/(N+1), eq. 13
    np.testing.assert_allclose(tau * rules.weight_mul + rules.weight_add, (0.4 * tau + 0.6 * eta) * factor, rtol=1e-6)


def test_gant_backward_ants_lay_inverse_time_plus_inverse_predicted_energy():
    scenario = hill()
    planner = pathzoo.make_planner("aco.gant", rho=0.3, tau0=0.2)
    state, walks, costs = _colony(planner, scenario, n_ants=8)
    g = state.problem.graph
    v = scenario.vehicle.cruise_speed
    pred = state.predictor
    power = np.maximum(scenario.vehicle.weight_n * v * (pred.c + g.slope), 0.0) + pred.b
    np.testing.assert_allclose(state.link_energy, power * g.length / v)
    assert abs(pred.c - scenario.vehicle.rolling_resistance) < 0.02  # fitted on generated flat-ground data
    expected = state.trail.values() * 0.7
    for a in np.flatnonzero(walks.reached):
        edges = walks.edges(a)
        travel_time = g.length[edges].sum() / v
        energy = state.link_energy[edges].sum()
        expected[edges] += 1.0 / travel_time + 1.0 / energy
    planner.update_trail(state, walks, costs)
    np.testing.assert_allclose(state.trail.values(), expected)
    extras = planner.result_extras(state)
    assert math.isclose(extras["predicted_energy_j"], state.link_energy[state.best_edges].sum())
    assert extras["predicted_energy_sd_j"] > 0


def test_ggaco_tables_built_block_by_block_equal_the_whole_graph_build(monkeypatch):
    scenario = hill()
    planner = pathzoo.make_planner("aco.ggaco")
    problem = ColonyProblem(scenario)
    whole = WalkRules.product(planner.alpha, planner.heuristic(problem), planner.beta,
                              planner.neighbour_factor(problem), pre_add=planner.gain(problem))
    blocks = list(problem.node_blocks(max_edges=50))
    assert len(blocks) > 10 and blocks[0].start == 0 and blocks[-1].stop == problem.n_nodes
    assert all(a.stop == b.start for a, b in zip(blocks, blocks[1:]))
    monkeypatch.setattr(ColonyProblem, "node_blocks", lambda self, max_edges=0: iter(blocks))
    rules = planner.walk_rules(problem)
    assert np.array_equal(rules.weight_mul, whole.weight_mul) and np.array_equal(rules.pre_add, whole.pre_add)
    some = np.array([0, 5, 17, problem.graph.n_edges - 1])
    assert np.array_equal(planner.edge_deposit(problem, some), planner.edge_deposit(problem)[some])


@pytest.mark.parametrize("make", [hill, open_grid])
def test_walk_geometry_equals_the_graph_arrays_of_the_walked_edges(make):
    scenario = make()
    planner = pathzoo.make_planner("aco.ggaco", colony="complete", n_ants=6)
    problem = ColonyProblem(scenario)
    rules = planner.walk_rules(problem)
    walks = WalkEngine(problem).walk(rules, Pheromone(problem.graph.n_edges, 0.0), 6, seed=4)
    assert walks.reached.sum() >= 2 and walks.flat.size > 20
    length, slope = problem.walk_geometry(walks.flat, walks.offsets)
    g = problem.graph
    assert np.array_equal(length, g.length[walks.flat]) and np.array_equal(slope, g.slope[walks.flat])
    assert np.array_equal(planner.deposit_of(problem, length, slope), planner.edge_deposit(problem, walks.flat))
