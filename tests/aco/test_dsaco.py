"""aco.dsaco: the q0 schedule, p decay, S·M·D heuristic, fitness and best-ant update, each in isolation."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget, Scenario, VehicleModel
from pathzoo.rules import validate_path
from pathzoo_aco.engine import ColonyProblem, Pheromone, Walks, WalkEngine
from pathzoo_aco.dsaco import p_schedule, q0_schedule


def _volume() -> Scenario:
    """4 x 4 columns of 1 km, 3 layers of 200 m; ground 200 m except 260 m under column (row 1, col 1)."""
    ground = np.full((4, 4), 200.0)
    ground[1, 1] = 260.0
    return Scenario(id="volume", kind="air3d", occupancy=np.zeros((3, 4, 4), bool), cell_size=1000.0,
                    vertical_cell_size=200.0, start=(500.0, 500.0, 300.0), goal=(3500.0, 500.0, 300.0),
                    elevation=ground)


def _state(planner, scenario):
    problem = ColonyProblem(scenario)
    rules = planner.walk_rules(problem)
    trail = Pheromone(problem.graph.n_edges, planner.initial_trail(problem))
    return planner.init_state(problem, rules, trail, WalkEngine(problem), np.random.default_rng(0))


def _edge(problem: ColonyProblem, a: tuple[int, ...], b: tuple[int, ...]) -> int:
    g = problem.graph
    u, v = (int(np.ravel_multi_index(c, g.shape)) for c in (a, b))
    edges = np.arange(g.indptr[u], g.indptr[u + 1])
    return int(edges[g.indices[edges] == v][0])


def _walks(problem: ColonyProblem, *paths: list[tuple[int, ...]]) -> Walks:
    """Walks made of given cell sequences (all reaching the goal)."""
    flat = [_edge(problem, a, b) for path in paths for a, b in zip(path[:-1], path[1:])]
    offsets = np.cumsum([0] + [len(p) - 1 for p in paths])
    n = len(paths)
    return Walks(np.array(flat, dtype=np.int64), offsets, np.zeros(n, np.int8), np.array([len(p) for p in paths]), n)


# ------------------------------------------------------------------ eq. 15 and eq. 19
def test_q0_schedule_falls_then_jumps_to_half_and_rises():
    q = [q0_schedule(k, 100, 0.9) for k in (0, 50, 69, 70, 85, 100, 150)]
    assert q == pytest.approx([0.9, 0.45, 0.279, 0.45, 0.585, 0.72, 0.72])


@pytest.mark.slow
def test_the_colony_uses_the_scheduled_q0():
    planner = pathzoo.make_planner("aco.dsaco", iterations=10, q0_initial=0.6)
    state = _state(planner, _volume())
    for k in (0, 3, 7, 10):
        state.iteration = k
        assert planner.before_iteration(state).q0 == pytest.approx(q0_schedule(k, 10, 0.6))


def test_p_decays_by_gamma_every_100_iterations():
    assert [p_schedule(t, 1.0, 0.9) for t in (1, 100, 101, 200, 201, 301)] == pytest.approx(
        [1.0, 1.0, 0.9, 0.9, 0.81, 0.729])


# ------------------------------------------------------------------ eqs. 11-13
def test_search_heuristic_s_m_d_on_a_hand_example():
    scenario = _volume()
    planner = pathzoo.make_planner("aco.dsaco", h_c=50.0)
    problem = ColonyProblem(scenario)
    eta = planner.search_heuristic(problem)
    # layer 1 (300 m) from column 0 to column 1 of row 0: h = 0.3 cells, step 1 cell, 2 cells left to the target
    e = _edge(problem, (1, 0, 0), (1, 0, 1))
    assert eta[e] == pytest.approx((1 / (1 + 0.3)) * (1 / (1 + math.sqrt(1 + 2**2))))
    # a diagonal climb to layer 2 (500 m): step sqrt(1 + 1 + 0.2^2), target sqrt(2^2 + 1 + 0.2^2) away
    e = _edge(problem, (1, 0, 0), (2, 1, 1))
    s_ok = 500.0 >= 260.0 + 50.0
    assert s_ok and eta[e] == pytest.approx((1 / 1.5) / (math.sqrt(2.04) + math.sqrt(1 + 5.04)))
    # S = 0: 300 m is less than 50 m above the 260 m ground of column (1, 1)
    assert eta[_edge(problem, (1, 0, 0), (1, 1, 1))] == 0.0


@pytest.mark.parametrize("step_rule", ["graph", "longitude"])
def test_heuristic_per_node_and_step_length_equals_the_per_edge_one(step_rule):
    planner = pathzoo.make_planner("aco.dsaco", step_rule=step_rule, beta=2.5)
    problem = ColonyProblem(pathzoo.load_scenario("dsaco.simple"))
    for of_eta, refused in ((lambda t: t, 0.0), (lambda t: np.power(t, 2.5), 0.0)):
        by_node = planner._per_edge(problem, of_eta, refused)
        by_edge = planner._per_edge(problem, of_eta, refused, by_node=False)
        assert np.array_equal(by_node.view(np.int64), by_edge.view(np.int64))  # bit for bit
    eta = planner.search_heuristic(problem)
    assert np.array_equal(planner.heuristic_power(problem), np.power(eta, 2.5))
    assert (eta > 0).any() and (step_rule == "graph" or (eta == 0).any())


@pytest.mark.slow
def test_longitude_rule_advances_one_column_per_step():
    scenario = pathzoo.load_scenario("dsaco.complex")
    planner = pathzoo.make_planner("aco.dsaco", step_rule="longitude")
    problem = ColonyProblem(scenario)
    allowed = planner.allowed_moves(problem)
    dx = problem.graph.offsets[problem.graph.offset_id][:, -1]
    assert set(dx[allowed > 0]) == {1} and (allowed[dx != 1] == 0).all()
    result = planner.plan(scenario, budget=Budget(iterations=1), rng=np.random.default_rng(0))
    assert result.solved and len(result.path) == 50  # 49 one-column steps from column 0 to column 49


# ------------------------------------------------------------------ eqs. 20-23
def test_fitness_sums_length_heights_and_turns():
    planner = pathzoo.make_planner("aco.dsaco", f1=1.0, f2=0.5, f3=2.0)
    state = _state(planner, _volume())
    # along row 0 at layer 1, a climb to layer 2 in column 2, then straight on
    path = [(1, 0, 0), (1, 0, 1), (2, 0, 2), (2, 0, 3)]
    walks = _walks(state.problem, path)
    d0, dh, dt = (v[0] for v in planner.fitness_terms(state, walks))
    climb = math.sqrt(1 + 0.2**2)
    assert d0 == pytest.approx(1 + climb + 1)
    assert dh == pytest.approx(0.3 + 0.4 + 0.5)  # mean height of each segment, cells
    assert dt == pytest.approx(2 * math.atan(0.2))  # up into the climb, then level again
    assert planner.walk_costs(state, walks)[0] == pytest.approx(d0 + 0.5 * dh + 2.0 * dt)


# ------------------------------------------------------------------ eqs. 16-18
def test_only_the_iteration_best_ant_deposits_the_fitness_weighted_amount():
    planner = pathzoo.make_planner("aco.dsaco", q=0.05, rho=0.2, p=1.0, gamma_p=0.9)
    state = _state(planner, _volume())
    short = [(1, 0, 0), (1, 0, 1), (1, 0, 2), (1, 0, 3)]
    long = [(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 1, 2), (1, 0, 3)]
    walks = _walks(state.problem, long, short)
    costs = planner.walk_costs(state, walks)
    assert costs[1] < costs[0]
    state.iteration, state.best_cost = 150, 0.5 * float(costs[1])  # p = 0.9 at iteration 150
    state.trail.x[:] = 0.5
    planner.update_trail(state, walks, costs)
    amount = 0.05 / (0.1 * costs[1] + 0.9 * state.best_cost)
    expected = np.full(state.trail.x.size, 0.4)
    expected[walks.edges(1)] += amount
    np.testing.assert_allclose(state.trail.values(), np.clip(expected, 0.03, 0.9))


def test_trails_stay_within_tau_min_and_tau_max():
    planner = pathzoo.make_planner("aco.dsaco", rho=0.9)
    state = _state(planner, _volume())
    walks = _walks(state.problem, [(1, 0, 0), (1, 0, 1), (1, 0, 2), (1, 0, 3)])
    state.best_cost = float(planner.walk_costs(state, walks)[0])
    for t in range(1, 4):
        state.iteration = t
        planner.update_trail(state, walks, planner.walk_costs(state, walks))
    values = state.trail.values()
    assert values.min() == pytest.approx(0.03) and values.max() == pytest.approx(0.9)


# ------------------------------------------------------------------ smoke on the paper's pack
@pytest.mark.parametrize("scenario_id", [pytest.param("dsaco.complex", marks=pytest.mark.slow),
                                         "movingai.maze-32-32-2.b9.83"])
def test_solves_the_paper_volume_and_a_grid_with_a_tiny_budget(scenario_id):
    scenario = pathzoo.load_scenario(scenario_id)
    result = pathzoo.make_planner("aco.dsaco").plan(scenario, budget=Budget(iterations=2),
                                                    rng=np.random.default_rng(0))
    assert result.solved, result.message
    verdict = validate_path(scenario, result.path)
    assert verdict, verdict.reason


def test_turn_limited_vehicle_is_respected():
    scenario = _volume()
    limited = Scenario(id="limited", kind="air3d", occupancy=scenario.occupancy, cell_size=1000.0,
                       vertical_cell_size=200.0, start=scenario.start, goal=scenario.goal,
                       elevation=scenario.elevation, vehicle=VehicleModel(max_turn_deg=45.0))
    result = pathzoo.make_planner("aco.dsaco").plan(limited, budget=Budget(iterations=3), rng=np.random.default_rng(1))
    assert result.solved and validate_path(limited, result.path)


# ------------------------------------------------------------------ eqs. 2-3
def test_segments_split_at_every_change_of_move_and_the_last_is_exempt():
    from pathzoo_aco.dsaco_fitness import infeasible_walks

    # three walks over edges 0-5 (edge = move id here): moves 0 0 1 | (failed) | 1 1 1 2; every step 1 cell
    flat = np.array([0, 0, 1, 1, 1, 1, 2])
    offsets = np.array([0, 3, 3, 7])
    reached = np.array([True, False, True])
    length, move = np.ones(3), np.arange(3)
    # l_min 1.5: walk 0's first segment is 2 cells, its last (1 cell) is exempt; walk 2's segments are 3 and 1 (last)
    np.testing.assert_array_equal(infeasible_walks(flat, offsets, reached, length, move, 1.0, 0.0, 1.5),
                                  [False, False, False])
    np.testing.assert_array_equal(infeasible_walks(flat, offsets, reached, length, move, 1.0, 0.0, 2.5),
                                  [True, False, False])  # walk 0's 2-cell segment is short; walk 2's 3 is not
    np.testing.assert_array_equal(infeasible_walks(flat, offsets, reached, length, move, 1.0, 3.5, 0.0),
                                  [False, True, True])  # 3 and 4 cells against l_max; the failed walk counts


@pytest.mark.parametrize(
    ("params", "feasible"),
    [
        ({}, (True, True)),
        ({"l_max": 3.5}, (True, False)),  # eq. 2: the zigzag is 2 sqrt 2 + 1 = 3.83 cells long
        ({"l_max": 3.9}, (True, True)),
        ({"l_min": 1.5}, (True, False)),  # eq. 3: its two diagonal segments are 1.41 cells, before a turn
        ({"l_min": 1.4}, (True, True)),
        ({"l_min": 3.5}, (True, False)),  # the straight walk is one segment, which ends at the target
    ],
)
def test_eqs_2_3_make_walks_infeasible(params, feasible):
    planner = pathzoo.make_planner("aco.dsaco", **params)
    state = _state(planner, _volume())
    straight = [(1, 0, 0), (1, 0, 1), (1, 0, 2), (1, 0, 3)]
    zigzag = [(1, 0, 0), (1, 1, 1), (1, 0, 2), (1, 0, 3)]
    walks = _walks(state.problem, straight, zigzag)
    costs = planner.walk_costs(state, walks)
    assert tuple(np.isfinite(costs)) == feasible
    base = pathzoo.make_planner("aco.dsaco").walk_costs(_state(pathzoo.make_planner("aco.dsaco"), _volume()), walks)
    np.testing.assert_array_equal(costs[np.isfinite(costs)], base[np.isfinite(costs)])  # feasible costs unchanged


def test_l_max_below_the_optimum_leaves_no_feasible_path():
    scenario = _volume()
    budget = Budget(iterations=3)
    assert pathzoo.make_planner("aco.dsaco").plan(scenario, budget=budget, rng=np.random.default_rng(0)).solved
    result = pathzoo.make_planner("aco.dsaco", l_max=2.5).plan(scenario, budget=budget, rng=np.random.default_rng(0))
    assert not result.solved  # the target is 3 cells away


def test_move_lengths_in_one_pass_equal_the_array_version():
    from pathzoo_aco.dsaco import _move_lengths

    g = pathzoo.load_scenario("dsaco.simple").graph
    step, consistent = _move_lengths(g.offset_id, g.length, len(g.offsets) + 1)  # one move without edges
    want = np.zeros(len(g.offsets) + 1)
    want[g.offset_id] = g.length
    assert consistent and np.array_equal(step, want)
    other = g.length.copy()
    other[len(other) // 2] *= 1.0 + 1e-15  # one edge of a move a little longer than the others
    assert not _move_lengths(g.offset_id, other, len(g.offsets))[1]
    other[len(other) // 2] = np.nan
    assert not _move_lengths(g.offset_id, other, len(g.offsets))[1]
