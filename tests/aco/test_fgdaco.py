"""aco.fgdaco: the fuzzy inference against scikit-fuzzy, the gain and update, and timed walks among moving obstacles."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
import skfuzzy
from skfuzzy import control as ctrl

import pathzoo
from pathzoo import Budget, MovingObstacle, Scenario
from pathzoo.rules import validate_path
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo_aco.engine import EXHAUSTED, ColonyProblem, Pheromone
from pathzoo_aco.fgdaco_fuzzy import (
    INPUT_SUPPORTS,
    OUTPUT_SUPPORTS,
    PAPER_RULES,
    RULES,
    TERMS,
    UNIVERSE,
    centroid,
    clipped_centroid,
    compiled_priority,
    consequents,
    fired_strengths,
    fuzzy_priority,
    priority_one,
    rule_ceilings,
    triangle,
)
from pathzoo_aco.fgdaco_moving import (
    floored_mod,
    obstacle_min_distance,
    obstacle_position,
    pack_obstacles,
    route_clearance,
)

from aco_maps import walled_grid

CRISP = [(0.05, 0.1, 0.9), (0.5, 0.5, 0.5), (0.95, 0.9, 0.1), (0.35, 0.65, 0.25), (0.62, 0.05, 0.68),
         (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), (0.2, 0.8, 0.45)]


def _control_system() -> ctrl.ControlSystemSimulation:
    """scikit-fuzzy's own Mamdani controller with the same universes, memberships and rules."""
    names = ("target", "angle", "obstacle")
    inputs = [ctrl.Antecedent(UNIVERSE, name) for name in names]
    for var, name in zip(inputs, names):
        for k, support in enumerate(INPUT_SUPPORTS[name]):
            var[TERMS[k]] = skfuzzy.trimf(UNIVERSE, triangle(support, k))
    out = ctrl.Consequent(UNIVERSE, "priority", defuzzify_method="centroid")
    for k, support in enumerate(OUTPUT_SUPPORTS):
        out[TERMS[k]] = skfuzzy.trimf(UNIVERSE, triangle(support, k))
    rules = [ctrl.Rule(inputs[0][TERMS[i]] & inputs[1][TERMS[j]] & inputs[2][TERMS[k]], out[TERMS[c]])
             for (i, j, k), c in RULES.items()]
    return ctrl.ControlSystemSimulation(ctrl.ControlSystem(rules))


# ------------------------------------------------------------------ fuzzy inference
def test_rule_base_is_complete_contains_table_4_and_is_monotone():
    assert set(RULES) == set(itertools.product(range(3), repeat=3))
    assert all(RULES[k] == v for k, v in PAPER_RULES.items()) and len(PAPER_RULES) == 12
    # a nearer target, a smaller turn or a farther obstacle never lowers the priority
    for (t, a, o), term in RULES.items():
        if t > 0:
            assert RULES[(t - 1, a, o)] >= term
        if a > 0:
            assert RULES[(t, a - 1, o)] >= term
        if o < 2:
            assert RULES[(t, a, o + 1)] >= term


@pytest.mark.filterwarnings("ignore:Passing more than 2 positional arguments:DeprecationWarning")  # inside skfuzzy
def test_priorities_match_scikit_fuzzy_control_system():
    sim = _control_system()
    ours = fuzzy_priority(*np.array(CRISP).T)
    for (t, a, o), mine in zip(CRISP, ours):
        sim.input["target"], sim.input["angle"], sim.input["obstacle"] = t, a, o
        sim.compute()
        # the control system adds the clip points to the universe; we integrate on the universe itself
        assert mine == pytest.approx(sim.output["priority"], abs=2e-4)


def test_priority_orders_the_obvious_cases():
    good, bad, blocked = fuzzy_priority([0.05, 0.95, 0.05], [0.05, 0.95, 0.05], [0.95, 0.95, 0.05])
    assert good > 0.75 and blocked < 0.25 and good > bad > blocked


def test_batched_centroid_equals_defuzz():
    rng = np.random.default_rng(3)
    mf = np.minimum(rng.random((5, 1)), consequents()[rng.integers(0, 3, 5)])
    mf[0] = 0.0  # no area at all: defuzz's convention (0 / eps)
    ours = centroid(UNIVERSE, mf)
    for row, value in zip(mf, ours):
        expected = 0.0 if not row.any() else skfuzzy.defuzz(UNIVERSE, row, "centroid")
        assert value == pytest.approx(expected, abs=1e-12)


def test_compiled_twin_equals_the_vectorised_inference():
    rng = np.random.default_rng(4)
    x = np.vstack([rng.random((200, 3)), np.array(CRISP)])
    cp = compiled_priority()
    twin = [priority_one(*row, cp.vertices, cp.rules, cp.consequents, cp.area_w, cp.moment_w,
                         np.zeros((3, 3)), np.zeros(3)) for row in x]
    np.testing.assert_allclose(twin, fuzzy_priority(*x.T), atol=1e-12)


def test_two_step_inference_of_the_walks_is_bit_identical_to_the_compiled_twin():
    # rule ceilings per move, then the obstacle input: the walks' shortcut must give the very same float
    rng = np.random.default_rng(8)
    on_universe = np.round(rng.random((3000, 3)) * 200) / 200  # on vertices and kinks
    x = np.vstack([rng.random((3000, 3)), on_universe, np.clip(on_universe + rng.normal(0, 1e-13, (3000, 3)), 0, 1),
                   np.array(CRISP)])
    cp = compiled_priority()
    ceilings = np.empty((1, 3, 3))
    for t, a, o in x:
        want = priority_one(t, a, o, cp.vertices, cp.rules, cp.consequents, cp.area_w, cp.moment_w,
                            np.zeros((3, 3)), np.zeros(3))
        rule_ceilings(t, a, cp.vertices, cp.rules, ceilings, 0)
        got = clipped_centroid(*fired_strengths(ceilings, 0, o, cp.vertices), cp.consequents, cp.area_w, cp.moment_w)
        assert got == want, (t, a, o)


# ------------------------------------------------------------------ moving obstacles, compiled
@pytest.mark.slow
def test_compiled_obstacle_geometry_matches_moving_obstacle():
    rng = np.random.default_rng(5)
    obstacles = [
        MovingObstacle(0.6, np.array([[3.0, 8.5], [8.0, 8.5]]), 0.5),
        MovingObstacle(2.0, rng.uniform(0, 20, (4, 2)), 1.3, mode="loop", phase_s=3.3),
        MovingObstacle(1.0, rng.uniform(0, 20, (3, 2)), 0.9, phase_s=1.1),
        MovingObstacle(1.0, np.array([[5.0, 5.0]]), 1.0),  # parked
    ]
    packed = pack_obstacles(obstacles)
    arrays = (packed.points, packed.cum, packed.count, packed.speed, packed.phase)
    for _ in range(400):
        k = int(rng.integers(len(obstacles)))
        t0 = rng.uniform(0, 100)
        t1 = t0 + rng.choice([0.0, rng.uniform(0, 1), rng.uniform(0, 40)])
        p0, p1 = rng.uniform(0, 20, (2, 2))
        assert obstacle_position(*arrays, k, t0) == pytest.approx(tuple(obstacles[k].position(t0)), abs=1e-9)
        expected = obstacles[k].min_distance(p0, p1, t0, t1)
        assert obstacle_min_distance(*arrays, k, *p0, *p1, t0, t1) == pytest.approx(expected, abs=1e-9)
    alone = pack_obstacles(obstacles[3:])  # only one route point in the whole pack: padded to a two-point piece
    alone_arrays = (alone.points, alone.cum, alone.count, alone.speed, alone.phase)
    assert obstacle_position(*alone_arrays, 0, 7.0) == (5.0, 5.0)
    assert obstacle_min_distance(*alone_arrays, 0, 5.0, 8.0, 5.0, 9.0, 0.0, 1.0) == 3.0
    # the clearance to a whole route bounds the distance to the disc at any time, and is reached on the route
    points = rng.uniform(-5, 25, (300, 2))
    bound = route_clearance(packed, points)
    for k, ob in enumerate(obstacles):
        period = ob.period_s if np.isfinite(ob.period_s) else 1.0
        centres = ob.position(np.linspace(0.0, period, 20001))
        gaps = np.linalg.norm(points[:, None, :] - centres[None, :, :], axis=2).min(axis=1) - ob.radius
        assert (bound[:, k] <= gaps).all()
        assert bound[:, k] == pytest.approx(gaps, abs=2e-3)  # sampled every ~1/20000 of the route


def test_floored_mod_is_python_modulo_bit_for_bit():
    # the obstacles' route positions use it instead of %: random operands, exact multiples and their neighbours
    rng = np.random.default_rng(11)
    b = rng.uniform(1e-3, 100.0, 20000)
    q = rng.integers(0, 10**6, 20000).astype(float)
    a = np.concatenate([rng.uniform(0.0, 5000.0, 20000), q * b, np.nextafter(q * b, np.inf), np.nextafter(q * b, -np.inf),
                        -rng.uniform(0.0, 50.0, 20000), [0.0, -0.0, 1e300, 5e-324, np.inf, np.nan, 7.0]])
    b = np.concatenate([b, b, b, b, b, [3.0, 3.0, 7.0, 3.0, 2.0, 2.0, np.inf]])
    for x, y in zip(a, b):
        with np.errstate(invalid="ignore"):  # inf % 2.0 is nan
            want = x % y
        got = floored_mod(x, y)
        assert got == want and math.copysign(1.0, got) == math.copysign(1.0, want) or (got != got and want != want), (x, y)


# ------------------------------------------------------------------ gain and update
def _state(planner, scenario, n_ants=6, seed=0):
    """Build a run's state through the planner's hooks and send one colony."""
    problem = ColonyProblem(scenario)
    rules = planner.walk_rules(problem)
    trail = Pheromone(problem.graph.n_edges, planner.initial_trail(problem))
    engine = planner.walk_engine(problem)
    state = planner.init_state(problem, rules, trail, engine, np.random.default_rng(seed))
    walks = engine.walk(state.rules, state.trail, n_ants, seed)
    return state, walks, planner.walk_costs(state, walks)


def test_gain_rewards_the_neighbour_nearest_the_target():
    planner = pathzoo.make_planner("aco.fgdaco", lam=0.7)
    scenario = walled_grid()
    problem = ColonyProblem(scenario)
    inputs = planner.fuzzy_inputs(problem)
    gain = planner.signed_gain(problem, inputs)
    g = problem.graph
    node = scenario.start_node
    edges = np.arange(g.indptr[node], g.indptr[node + 1])
    delta = inputs.target[g.indices[edges]]
    winners = edges[delta == delta.min()]
    assert (gain[winners] > 0).all() and (gain[np.setdiff1d(edges, winners)] < 0).all()
    e = edges[0]
    progress = (inputs.target[g.indices[e]] + inputs.obstacle[node]) / inputs.target[node]
    assert abs(gain[e]) == pytest.approx(1.0 / (1.0 + math.exp(-0.7 * progress)))


def test_update_evaporates_deposits_eq15_and_applies_the_gains():
    planner = pathzoo.make_planner("aco.fgdaco", rho=0.3)
    state, walks, costs = _state(planner, walled_grid())
    assert walks.reached.any()
    g = state.problem.graph
    src = state.problem.sources
    obstacle = planner.fuzzy_inputs(state.problem).obstacle
    floor = planner.tau_floor
    expected = np.maximum(state.trail.values() * 0.7, floor)
    for a in np.flatnonzero(walks.reached):
        for e in walks.edges(a):  # eq. 15: 1 / d_ij + d_io
            expected[e] = max(expected[e] + 1.0 / g.length[e] + obstacle[src[e]], floor)
    for a in np.flatnonzero(walks.reached):
        edges = walks.edges(a)
        for node in np.concatenate([[state.problem.start], g.indices[edges[:-1]]]):
            for e in range(g.indptr[node], g.indptr[node + 1]):
                expected[e] = max(expected[e] + state.gain[e], floor)
    planner.update_trail(state, walks, costs)
    np.testing.assert_allclose(state.trail.values(), expected)



@pytest.mark.parametrize("scale", [0.5**7, 0.3**4])  # a power of two (values kept in registers) and not
def test_gains_node_by_node_equal_the_walk_by_walk_updates(scale):
    from pathzoo_aco.fgdaco import _add_gains

    planner = pathzoo.make_planner("aco.fgdaco")
    state, walks, _ = _state(planner, walled_grid(), n_ants=12)
    ok = np.flatnonzero(walks.reached)
    assert ok.size > 1
    g = state.problem.graph
    rng = np.random.default_rng(3)
    lo, hi = 0.01, 40.0
    x = rng.uniform(0.0, 0.2, g.n_edges) / scale  # many values on or below the floor
    gain = rng.uniform(-0.8, 0.8, g.n_edges)
    expected = x.copy()
    for a in ok:  # the clamped read-modify-write of deposit_walks, walk by walk
        edges = walks.edges(a)
        for node in np.concatenate([[state.problem.start], g.indices[edges[:-1]]]):
            for e in range(g.indptr[node], g.indptr[node + 1]):
                expected[e] = min(max(min(max(scale * expected[e], lo), hi) + gain[e], lo), hi) / scale
    left = np.zeros(g.n_nodes, dtype=np.int32)
    _add_gains(x, scale, lo, hi, g.indptr, g.indices, walks.flat, walks.offsets, ok, state.problem.start, gain, left)
    true = lambda v: np.minimum(np.maximum(scale * v, lo), hi)  # noqa: E731  (stored values below the floor read lo)
    assert np.array_equal(true(x), true(expected))
    assert not left.any()


# ------------------------------------------------------------------ timed walks
@pytest.mark.slow
def test_every_timed_walk_is_valid_among_moving_obstacles():
    scenario = check_scenario("dynamic")  # a disc patrols the gap the walks must use
    planner = pathzoo.make_planner("aco.fgdaco")
    state, walks, _ = _state(planner, scenario, n_ants=40, seed=1)
    assert walks.reached.sum() >= 20
    for a in np.flatnonzero(walks.reached):
        verdict = validate_path(scenario, state.problem.walk_points(walks.edges(a)))
        assert verdict, verdict.reason


def _corridor(obstacle: MovingObstacle) -> Scenario:
    """A 3 x 12 corridor with a wall of one cell thickness and a one-cell gap in column 6."""
    occ = np.zeros((3, 12), bool)
    occ[0:2, 6] = True
    return Scenario(id="corridor", kind="dynamic", occupancy=occ, cell_size=1.0, start=(0.5, 1.5),
                    goal=(11.5, 1.5), moving_obstacles=(obstacle,))


def test_an_obstacle_parked_in_the_only_gap_fails_the_run_without_proving_unreachability():
    scenario = _corridor(MovingObstacle(0.8, np.array([[6.5, 2.5]]), 0.0))
    planner = pathzoo.make_planner("aco.fgdaco")
    state, walks, _ = _state(planner, scenario, n_ants=3)
    assert not walks.reached.any() and not (walks.flags == EXHAUSTED).any()
    result = planner.plan(scenario, budget=Budget(iterations=2), rng=np.random.default_rng(0))
    assert result.status.value == "failed" and "unreachable" not in result.message


def test_ants_time_their_passage_through_a_gap_an_obstacle_crosses():
    # the obstacle sweeps across the gap (row 2, column 6) at 1 m/s; the quickest ants would meet it there
    scenario = _corridor(MovingObstacle(0.6, np.array([[6.5, -1.0], [6.5, 6.0]]), 1.0))
    planner = pathzoo.make_planner("aco.fgdaco")
    state, walks, _ = _state(planner, scenario, n_ants=30, seed=2)
    assert walks.reached.sum() >= 5
    for a in np.flatnonzero(walks.reached):
        verdict = validate_path(scenario, state.problem.walk_points(walks.edges(a)))
        assert verdict, verdict.reason
    # the same map without the obstacle: some untimed walks would have collided, so the gap is really contested
    still = Scenario(id="still", kind="grid2d", occupancy=scenario.occupancy, cell_size=1.0, start=scenario.start,
                     goal=scenario.goal)
    state, walks, _ = _state(planner, still, n_ants=30, seed=2)
    untimed = [state.problem.walk_points(walks.edges(a)) for a in np.flatnonzero(walks.reached)]
    assert untimed and not all(validate_path(scenario, path) for path in untimed)


# ------------------------------------------------------------------ smoke on the paper's pack
@pytest.mark.parametrize("scenario_id", ["fgdaco.scenario1", "fgdaco.scenario2_static"])
def test_solves_the_paper_scenarios_with_a_tiny_budget(scenario_id):
    scenario = pathzoo.load_scenario(scenario_id)
    result = pathzoo.make_planner("aco.fgdaco").plan(scenario, budget=Budget(iterations=2),
                                                     rng=np.random.default_rng(0))
    assert result.solved, result.message
    verdict = validate_path(scenario, result.path)
    assert verdict, verdict.reason
