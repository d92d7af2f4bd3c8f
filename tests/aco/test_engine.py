"""The shared ant-colony engine: lazy pheromone, the compiled walks and the colony loop."""

from __future__ import annotations

import gc
import math
import time
import weakref
from dataclasses import replace

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget, VehicleModel
from pathzoo.rules import validate_path
from pathzoo.rules import validate_path
from pathzoo_aco.engine import (
    ABORTED,
    EXHAUSTED,
    OUTRUN,
    REACHED,
    STEP_CAP,
    STUCK,
    ColonyProblem,
    Pheromone,
    WalkEngine,
    WalkRules,
    Walks,
    deposit_walks,
)
from pathzoo_aco.engine.walk import FILL_STEPS_PER_NODE

from aco_maps import hill, open_grid, walled_grid


def _rules(problem: ColonyProblem, **kw) -> WalkRules:
    g = problem.graph
    eta = 1.0 / (g.length + problem.goal_distance[g.indices])
    return WalkRules.product(1.0, eta, 2.0, max_steps=kw.pop("max_steps", 10**9), **kw)


def _check_walk(problem: ColonyProblem, edges: np.ndarray) -> None:
    g = problem.graph
    sources = problem.sources[edges]
    targets = g.indices[edges]
    assert sources[0] == problem.start and targets[-1] == problem.goal
    assert np.array_equal(sources[1:], targets[:-1])  # consecutive edges chain
    assert len(set(targets.tolist()) | {problem.start}) == len(edges) + 1  # a simple path (tabu list)


# ------------------------------------------------------------------ pheromone
def test_lazy_trail_matches_eager_updates():
    rng = np.random.default_rng(7)
    """Lazy evaporation and clamp-on-read equal the eager MMAS-style update, rising bounds included."""
    size = 50
    trail = Pheromone(size, 5.0)
    eager = np.full(size, 5.0)
    indices = np.arange(size)
    lo, hi = 0.0, math.inf
    for step in range(400):  # forces several renormalisations of the scale
        trail.evaporate(0.6)
        eager *= 0.4
        if step % 7 == 3:
            lo, hi = lo + 0.01, (2.0 if hi == math.inf else hi + 0.05)
            trail.set_bounds(lo, hi)
        eager = np.clip(eager, lo, hi)
        walk = rng.choice(size, 6, replace=False)
        amount = float(rng.uniform(0, 1))
        deposit_walks(trail, indices, walk, np.array([0, 6]), np.array([0]), amount)
        eager[walk] = np.clip(eager[walk] + amount, lo, hi)
        np.testing.assert_allclose(trail.values(), eager, rtol=1e-9, atol=1e-300)
    assert trail.scale >= 1e-150


def test_renormalisation_folds_the_scale_in_exactly_and_in_place():
    rng = np.random.default_rng(3)
    trail = Pheromone(1000, 1.0)
    trail.x[:] = rng.uniform(0.0, 10.0, 1000)
    trail.set_bounds(0.5e-150, 4e-150)
    trail.scale = 1.5e-150
    expected = np.clip(trail.scale * 0.5 * trail.x, trail.lo, trail.hi)  # the values after one more evaporation
    before = trail.x
    trail.evaporate(0.5)  # the scale falls below 1e-150: folded into x
    assert trail.scale == 1.0 and trail.x is before  # the same array, rewritten
    assert np.array_equal(trail.x, expected)  # bit for bit


def test_deposit_keep_and_per_edge_amounts():
    trail = Pheromone(4, 2.0)
    deposit_walks(trail, np.arange(4), np.array([1, 3]), np.array([0, 2]), np.array([0]), 0.5, keep=0.9,
                  per_edge=np.array([0.0, 1.0, 0.0, 2.0]))
    np.testing.assert_allclose(trail.values(), [2.0, 0.9 * 2 + 0.5 + 1.0, 2.0, 0.9 * 2 + 0.5 + 2.0])


def test_node_trail_deposits_on_target_nodes():
    trail = Pheromone(3, 0.0, on_nodes=True)
    indices = np.array([2, 1, 0])  # edge -> target node
    deposit_walks(trail, indices, np.array([0, 1]), np.array([0, 2]), np.array([0]), 1.0)
    np.testing.assert_allclose(trail.values(), [0.0, 1.0, 1.0])


# ------------------------------------------------------------------ walks
def test_walks_are_simple_chains_from_start_to_goal():
    problem = ColonyProblem(walled_grid())
    engine = WalkEngine(problem)
    walks = engine.walk(_rules(problem), Pheromone(problem.graph.n_edges, 1.0), 30, seed=3)
    assert walks.started == 30 and walks.reached.all()
    for a in range(30):
        _check_walk(problem, walks.edges(a))
    lengths = walks.totals(problem.graph.length)
    assert np.all(lengths >= 12.0)  # the wall forces a detour


def test_same_seed_same_walks_and_other_seed_differs():
    problem = ColonyProblem(walled_grid())
    trail = Pheromone(problem.graph.n_edges, 1.0)
    runs = [WalkEngine(problem).walk(_rules(problem), trail, 10, seed=s).flat for s in (5, 5, 6)]
    assert np.array_equal(runs[0], runs[1]) and not np.array_equal(runs[0], runs[2])


def test_dead_ends_backtrack_or_drop():
    problem = ColonyProblem(walled_grid(reachable=False))
    trail = Pheromone(problem.graph.n_edges, 1.0)
    back = WalkEngine(problem).walk(_rules(problem), trail, 3, seed=1)
    # the first ant searches the whole component, proving the goal unreachable; the rest are not sent
    assert back.flags[0] == EXHAUSTED and back.started == 1
    free = int((problem.graph.degree > 0).sum())
    assert back.steps[0] == 2 * (free - 1)  # depth-first: every free cell entered once and left once
    drop = WalkEngine(problem).walk(replace(_rules(problem), backtrack=False), trail, 5, seed=1)
    assert np.all(drop.flags == STUCK) and drop.started == 5


@pytest.mark.slow
def test_race_stops_the_colony_when_the_first_ant_arrives():
    problem = ColonyProblem(walled_grid())
    rules = replace(_rules(problem, local_keep=0.9, local_add=0.01), race=True)
    trail = Pheromone(problem.graph.n_edges, 1.0)
    walks = WalkEngine(problem).walk(rules, trail, 12, seed=4)
    winner = np.flatnonzero(walks.flags == REACHED)
    assert walks.started == 12 and len(winner) == 1
    assert np.all(walks.flags[walks.flags != REACHED] == OUTRUN)
    _check_walk(problem, walks.edges(winner[0]))
    # lock step: ants before the winner took as many steps as it, ants after it one fewer
    w = winner[0]
    assert np.all(walks.steps[:w] == walks.steps[w]) and np.all(walks.steps[w + 1 :] == walks.steps[w] - 1)
    again = WalkEngine(problem).walk(rules, Pheromone(problem.graph.n_edges, 1.0), 12, seed=4)
    assert np.array_equal(again.flat, walks.flat) and np.array_equal(again.steps, walks.steps)


@pytest.mark.slow
def test_race_grows_its_stacks_and_honours_the_allowance():
    problem = ColonyProblem(open_grid(64))
    g = problem.graph
    blind = WalkRules.product(1.0, np.ones(g.n_edges), 1.0, max_steps=10**9, race=True)
    walks = WalkEngine(problem).walk(blind, Pheromone(g.n_edges, 1.0), 3, seed=1)
    w = int(np.argmax(walks.reached))
    assert walks.reached.sum() == 1 and len(walks.edges(w)) > 256
    # still lock step across the regrowths: one step per ant per round, whatever the stacks' size
    assert np.all(walks.steps[:w] == walks.steps[w]) and np.all(walks.steps[w + 1 :] == walks.steps[w] - 1)
    cut = WalkEngine(problem).walk(blind, Pheromone(g.n_edges, 1.0), 3, seed=1, allowance=30)
    assert np.all(cut.flags == ABORTED) and cut.steps.sum() == 30


def test_race_stamps_stay_exact_across_their_byte_wrap():
    problem = ColonyProblem(walled_grid())
    rules = replace(_rules(problem), race=True)
    engine, fresh = WalkEngine(problem), WalkEngine(problem)
    for colony in range(300):  # the byte stamps are cleared after 255 colonies
        walks = engine.walk(rules, Pheromone(problem.graph.n_edges, 1.0), 5, seed=colony)
        winner = int(np.argmax(walks.reached))
        _check_walk(problem, walks.edges(winner))
        if colony in (0, 254, 255, 299):  # a used engine walks exactly as a new one
            again = fresh.walk(rules, Pheromone(problem.graph.n_edges, 1.0), 5, seed=colony)
            assert np.array_equal(again.flat, walks.flat) and np.array_equal(again.steps, walks.steps)


def test_step_cap_drops_the_ant():
    problem = ColonyProblem(open_grid(8))
    walks = WalkEngine(problem).walk(_rules(problem, max_steps=3), Pheromone(problem.graph.n_edges, 1.0), 4, seed=0)
    assert np.all(walks.flags == STEP_CAP) and np.all(walks.steps == 3)
    assert walks.flat.size == 0 and np.all(np.isinf(walks.totals(problem.graph.length)))


def test_q0_one_always_takes_the_heaviest_edge():
    problem = ColonyProblem(open_grid(8))
    g = problem.graph
    rules = _rules(problem, q0=1.0)
    walks = WalkEngine(problem).walk(rules, Pheromone(g.n_edges, 1.0), 1, seed=0)
    visited = {problem.start}
    for e in walks.edges(0):
        i = problem.sources[e]
        options = [f for f in range(g.indptr[i], g.indptr[i + 1]) if g.indices[f] not in visited]
        assert rules.weight_mul[e] == max(rules.weight_mul[f] for f in options)
        visited.add(int(g.indices[e]))
    assert len(walks.edges(0)) == 7  # the greedy walk is the diagonal


def test_local_update_marks_crossed_edges_only():
    problem = ColonyProblem(open_grid(6))
    trail = Pheromone(problem.graph.n_edges, 1.0)
    walks = WalkEngine(problem).walk(_rules(problem, local_keep=0.5, local_add=0.1), trail, 1, seed=2)
    values = trail.values()
    crossed = walks.edges(0)
    np.testing.assert_allclose(values[crossed], 0.6)
    assert np.all(np.delete(values, crossed) == 1.0)


def test_pre_choice_additions_touch_every_edge_leaving_a_visited_node():
    problem = ColonyProblem(open_grid(6))
    g = problem.graph
    trail = Pheromone(g.n_edges, 1.0, lo=0.2)
    pre = np.where(np.arange(g.n_edges) % 2 == 0, 0.5, -2.0)
    walks = WalkEngine(problem).walk(_rules(problem, pre_add=pre, q0=1.0), trail, 1, seed=2)  # no backtracking
    assert walks.steps[0] == len(walks.edges(0))
    left = np.isin(problem.sources, problem.sources[walks.edges(0)])
    values = trail.values()
    np.testing.assert_allclose(values[left], np.maximum(1.0 + pre[left], 0.2))
    assert np.all(values[~left] == 1.0)


def test_zero_weight_edges_are_not_allowed():
    problem = ColonyProblem(open_grid(5))
    g = problem.graph
    rules = _rules(problem)
    banned = g.indices == 6  # cell (1, 1): never entered
    mul = np.where(banned, 0.0, rules.weight_mul)
    walks = WalkEngine(problem).walk(replace(rules, weight_mul=mul), Pheromone(g.n_edges, 1.0), 20, seed=4)
    assert walks.reached.all() and not np.isin(6, g.indices[walks.flat])


def test_turn_limit_is_respected_and_validated():
    scenario = open_grid(10, vehicle=VehicleModel(max_turn_deg=45.0))
    problem = ColonyProblem(scenario)
    walks = WalkEngine(problem).walk(replace(_rules(problem), turn=problem.turn_table),
                                     Pheromone(problem.graph.n_edges, 1.0), 10, seed=9)
    assert walks.reached.any()
    for a in np.flatnonzero(walks.reached):
        path = problem.walk_points(walks.edges(a))
        assert validate_path(scenario, path)


def test_walk_points_add_exact_endpoints_off_centre():
    scenario = walled_grid()
    problem = ColonyProblem(scenario)
    walks = WalkEngine(problem).walk(_rules(problem), Pheromone(problem.graph.n_edges, 1.0), 1, seed=0)
    path = problem.walk_points(walks.edges(0))
    assert np.array_equal(path[0], scenario.start) and np.array_equal(path[1], [1.5, 1.5])  # start is off-centre
    assert np.array_equal(path[-1], scenario.goal) and len(path) == len(walks.edges(0)) + 2
    assert validate_path(scenario, path)


def test_buffers_grow_for_long_walks():
    problem = ColonyProblem(open_grid(64))
    engine = WalkEngine(problem)
    g = problem.graph
    flat_rules = WalkRules.product(1.0, np.ones(g.n_edges), 1.0, max_steps=10**9)  # no heuristic: long walks
    walks = engine.walk(flat_rules, Pheromone(g.n_edges, 1.0), 8, seed=1)
    assert walks.reached.all() and walks.flat.size > 1024
    for a in range(8):
        _check_walk(problem, walks.edges(a))


# ------------------------------------------------------------------ the colony loop
def test_evaluation_budget_shrinks_the_last_colony():
    planner = pathzoo.make_planner("aco.as", n_ants=10)
    calls = []
    result = planner.plan(walled_grid(), budget=Budget(evaluations=25), rng=np.random.default_rng(0),
                          progress=lambda *a: calls.append(a))
    assert result.evaluations == 25 and result.iterations == 3
    assert [c[:2] for c in calls] == [(1, 10), (2, 20), (3, 25)]


def test_unlimited_budget_runs_the_iterations_parameter():
    result = pathzoo.make_planner("aco.as", iterations=4, n_ants=3).plan(
        walled_grid(), budget=Budget(), rng=np.random.default_rng(0))
    assert result.iterations == 4 and result.evaluations == 12


def test_time_budget_is_respected_on_a_large_map():
    occ = np.zeros((300, 300), bool)
    occ[20:280, 150] = True
    scenario = pathzoo.Scenario(id="big", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 150.5),
                                goal=(299.5, 150.5))
    scenario.graph  # built outside the timed call
    planner = pathzoo.make_planner("aco.as", n_ants=50, beta=0.0)  # blind ants: long walks
    planner.plan(scenario, budget=Budget(iterations=1, time_s=5.0), rng=np.random.default_rng(0))  # compile
    started = time.perf_counter()
    planner.plan(scenario, budget=Budget(iterations=1), rng=np.random.default_rng(0))
    one_iteration = time.perf_counter() - started  # timed now: a loaded machine stretches both alike
    started = time.perf_counter()
    result = planner.plan(scenario, budget=Budget(time_s=0.5), rng=np.random.default_rng(0))
    # the conformance kit's tolerance (stopping granularity), or two iterations where one takes longer
    assert time.perf_counter() - started < 0.5 + max(1.0, 2 * one_iteration) and result.iterations >= 1


def test_progress_reports_best_so_far():
    calls = []
    result = pathzoo.make_planner("aco.as", n_ants=2).plan(
        hill(), budget=Budget(iterations=30), rng=np.random.default_rng(1), progress=lambda *a: calls.append(a))
    costs = [c[2] for c in calls]
    assert len(calls) == 30 and all(b <= a for a, b in zip(costs, costs[1:]))
    assert result.solved and math.isclose(costs[-1], float(np.linalg.norm(np.diff(
        result.path, axis=0), axis=1).sum()), rel_tol=0.2)


def test_start_and_goal_in_one_cell():
    scenario = open_grid(4).with_endpoints((0.2, 0.3), (0.7, 0.9))
    result = pathzoo.make_planner("aco.acs").plan(scenario, budget=Budget(iterations=3), rng=np.random.default_rng(0))
    assert result.solved and validate_path(scenario, result.path) and result.evaluations == 0


@pytest.mark.parametrize("walls", [False, True])
def test_reached_flag_matches_totals(walls):
    problem = ColonyProblem(walled_grid() if walls else open_grid(6))
    walks = WalkEngine(problem).walk(_rules(problem), Pheromone(problem.graph.n_edges, 1.0), 5, seed=0)
    assert np.all((walks.flags == REACHED) == np.isfinite(walks.totals(problem.graph.length)))


def test_tables_are_built_once_per_scenario_and_configuration():
    scenario = hill()
    problem = ColonyProblem.of(scenario)
    assert ColonyProblem.of(scenario).goal_distance is problem.goal_distance  # one set of tables per scenario
    planner = pathzoo.make_planner("aco.ggaco", n_ants=4)
    runs = [planner.plan(scenario, budget=Budget(iterations=3), rng=np.random.default_rng(5)) for _ in range(2)]
    rules = problem.memo(planner.table_key("walk_rules"), lambda: pytest.fail("rules were not kept"))
    assert np.array_equal(runs[0].path, runs[1].path) and runs[0].extras == {**runs[1].extras,
                                                                            "walk_time_s": runs[0].extras["walk_time_s"]}
    other = pathzoo.make_planner("aco.ggaco", n_ants=4, beta=1.5)
    assert other.table_key("walk_rules") != planner.table_key("walk_rules")
    other.plan(scenario, budget=Budget(iterations=1), rng=np.random.default_rng(5))
    assert problem.memo(other.table_key("walk_rules"), lambda: None) is not rules
    fresh = ColonyProblem(scenario)  # an unshared problem computes the same rules from scratch
    assert np.array_equal(planner.walk_rules(fresh).weight_mul, rules.weight_mul)
    gone = weakref.ref(scenario), weakref.ref(rules.weight_mul)  # the tables live exactly as long as the scenario
    assert set(vars(scenario)) <= {*scenario.__dataclass_fields__, "blocked", "graph", "clearance"}
    del problem, scenario, fresh, rules
    gc.collect()
    assert gone[0]() is None and gone[1]() is None


def test_walk_totals_equal_differences_of_one_running_sum():
    rng = np.random.default_rng(0)
    for _ in range(50):
        lengths = rng.integers(0, 40, rng.integers(1, 8))
        offsets = np.concatenate([[0], np.cumsum(lengths)])
        flat = rng.integers(0, 100, offsets[-1])
        per_edge = rng.random(100) * rng.choice([1.0, 1e-9, 1e9])
        walks = Walks(flat, offsets, np.where(lengths > 0, REACHED, STUCK).astype(np.int8), lengths, len(lengths))
        cum = np.concatenate([[0.0], np.cumsum(per_edge[flat])])  # the plain numpy definition, bit for bit
        want = np.where(lengths > 0, cum[offsets[1:]] - cum[offsets[:-1]], np.inf)
        assert np.array_equal(walks.totals(per_edge), want) and np.array_equal(walks.sums(per_edge[flat]), want)


@pytest.mark.parametrize("alpha, bounds, race, turns, zero_weights", [
    (1.0, (0.0, math.inf), False, False, False),  # AS, G-Ant: tau_exp 1
    (0.4, (0.05, 2.0), False, False, False),  # a power, a floor shared by many trails and a ceiling
    (2.0, (0.05, math.inf), True, False, True),  # race; edges of weight 0 left out of the list
    (1.5, (0.0, math.inf), False, True, False),  # turn factors on top of the weights
])
def test_precomputed_colony_weights_give_the_walks_of_the_per_step_weights(monkeypatch, alpha, bounds, race, turns,
                                                                           zero_weights):
    """A colony reading the weights filled before it walks takes exactly the walks of one computing them per step."""
    scenario = hill() if turns else walled_grid()
    problem = ColonyProblem(scenario)
    g = problem.graph
    rng = np.random.default_rng(2)
    eta = 1.0 / (g.length + problem.goal_distance[g.indices])
    factor = np.where(rng.random(g.n_edges) < 0.2, 0.0, 1.0) if zero_weights else None
    k = len(g.offsets)
    turn = np.where(np.random.default_rng(0).random((k + 1, k)) < 0.3, 0.0, 0.5) if turns else np.zeros((0, 0))
    rules = replace(WalkRules.product(alpha, eta, 2.0, factor, max_steps=10**9, turn=turn), race=race)
    trail = Pheromone(g.n_edges, rng.uniform(0.0, 1.5, g.n_edges), lo=bounds[0], hi=bounds[1])
    trail.evaporate(0.3)  # a scale other than 1
    fast = WalkEngine(problem)
    got = fast.walk(rules, trail, 12, seed=9)
    t = np.clip(trail.scale * trail.x, trail.lo, trail.hi)
    mul = rules.weight_mul.astype(np.float64)
    expected = (t * mul if alpha == 1.0 else np.where(t <= trail.lo, trail.lo**alpha, t**alpha) * mul)[mul != 0.0]
    np.testing.assert_allclose(fast.colony_weights(rules, trail), expected, rtol=1e-14, atol=0.0)
    monkeypatch.setattr(WalkEngine, "colony_weights", lambda self, rules, trail: None)
    want = WalkEngine(problem).walk(rules, trail, 12, seed=9)
    assert want.reached.any() and got.steps.sum() > 20
    for name in ("flat", "offsets", "flags", "steps"):
        np.testing.assert_array_equal(getattr(got, name), getattr(want, name))


def test_weights_are_filled_only_when_the_last_colony_took_enough_steps(monkeypatch):
    """The first colony fills; later ones fill only from FILL_STEPS_PER_NODE steps per node; the walks are the
    same whichever is chosen."""
    problem = ColonyProblem(walled_grid())
    g = problem.graph
    eta = 1.0 / (g.length + problem.goal_distance[g.indices])
    rules = WalkRules.product(2.0, eta, 2.0, None, max_steps=10**9)  # a power: 2.5 steps per node
    trail = Pheromone(g.n_edges, np.random.default_rng(3).uniform(0.1, 1.0, g.n_edges))
    engine = WalkEngine(problem)
    assert engine.weights_pay(rules, 1)
    engine.steps_per_ant = FILL_STEPS_PER_NODE[False] * g.n_nodes / 4
    assert engine.weights_pay(rules, 4) and not engine.weights_pay(rules, 3)
    assert engine.weights_pay(replace(rules, tau_exp=1.0), 1)  # 0.25 steps per node
    engine = WalkEngine(problem)
    filled: list[bool] = []
    choose = WalkEngine.weights_pay
    monkeypatch.setattr(WalkEngine, "weights_pay", lambda self, r, n: filled.append(choose(self, r, n)) or filled[-1])
    ants = (1, 2, 6, 1)
    chosen = [engine.walk(rules, trail, n, seed=n) for n in ants]
    assert filled == [True, False, True, False]  # 100 nodes; walks of 45-100 steps each
    monkeypatch.setattr(WalkEngine, "weights_pay", lambda self, r, n: True)
    always = WalkEngine(problem)
    for got, n in zip(chosen, ants):
        want = always.walk(rules, trail, n, seed=n)
        assert want.reached.any()
        for name in ("flat", "offsets", "flags", "steps"):
            np.testing.assert_array_equal(getattr(got, name), getattr(want, name))


def test_colonies_that_change_the_trail_while_walking_compute_weights_per_step():
    problem = ColonyProblem(walled_grid())
    engine = WalkEngine(problem)
    trail = Pheromone(problem.graph.n_edges, 1.0)
    assert engine.colony_weights(_rules(problem, local_keep=0.9, local_add=0.01), trail) is None
    assert engine.colony_weights(_rules(problem, pre_add=np.full(problem.graph.n_edges, 0.1)), trail) is None


def test_acs_choice_and_local_update_run_inside_the_timed_walks():
    """On a dynamic scenario ACS's q0 (argmax) choice and local update happen in the timed walk itself."""
    from pathzoo_aco.engine import ColonyProblem, Pheromone
    from pathzoo_aco.fgdaco_walk import TimedWalkEngine, timed_product_engine

    scenario = pathzoo.load_scenario("fgdaco.scenario1")
    planner = pathzoo.make_planner("aco.acs", n_ants=4)
    problem = ColonyProblem.of(scenario)
    engine = timed_product_engine(problem, planner.beta)
    assert isinstance(engine, TimedWalkEngine)
    rules = planner.walk_rules(problem)
    greedy = replace(rules, q0=1.0, local_keep=1.0, local_add=0.0)
    walks = engine.walk(greedy, Pheromone(problem.graph.n_edges, 1.0), 4, 3)
    assert walks.reached.all() and all(np.array_equal(walks.edges(0), walks.edges(k)) for k in range(4))
    trail = Pheromone(problem.graph.n_edges, 1.0)
    local = replace(rules, q0=1.0, local_keep=0.5, local_add=0.0)
    walk = engine.walk(local, trail, 1, 3)
    crossed = np.zeros(problem.graph.n_edges, bool)
    crossed[walk.edges(0)] = True
    assert walk.reached.all() and np.allclose(trail.x[crossed] * trail.scale, 0.5)
    assert np.allclose(trail.x[~crossed] * trail.scale, 1.0)


@pytest.mark.parametrize("pid", ["aco.as", "aco.mmas", "aco.acs"])
def test_the_classic_systems_plan_among_moving_obstacles(pid):
    scenario = pathzoo.load_scenario("fgdaco.scenario1")
    planner = pathzoo.make_planner(pid, n_ants=5)
    assert "dynamic" in planner.kinds
    result = planner.plan(scenario, budget=Budget(iterations=3), rng=np.random.default_rng(0))
    assert result.solved and validate_path(scenario, result.path)


def test_an_engine_calls_the_kernel_its_colonies_did_not_take_once_for_no_ant(monkeypatch):
    """So a worker's warm-up loads both, and no run loads one from numba's disk cache on its own CPU."""
    from pathzoo_aco.engine import walk as walk_module

    calls: list[tuple[tuple[bool, bool, bool], int]] = []
    for key, kernel in list(walk_module.KERNELS.items()):
        def spy(*args, _key=key, _kernel=kernel):  # type: ignore[no-untyped-def]
            calls.append((_key, args[-5].size))  # the ants: the size of ``flags`` (before four more arguments)
            return _kernel(*args)

        monkeypatch.setitem(walk_module.KERNELS, key, spy)
    pathzoo.make_planner("aco.as", n_ants=4).plan(open_grid(6), budget=Budget(iterations=3),
                                                   rng=np.random.default_rng(0))
    first = calls[1][0]  # the first colony fills its weights: the filled-weights kernel
    assert calls[0] == ((not first[0], first[1], False), 0) and first == (False, False, False)
    assert all(n == 4 for _, n in calls[1:])  # once per engine, then only real colonies
