"""The kernel of colonies with a local update (walk_kernel.py) against the generic kernel on the same colonies.

Both kernels (the walk body compiled for ants one after another, and for racing ants and pre-choice additions)
are called directly with fresh buffers, as ``WalkEngine.walk``
calls them, and must leave every output the same: outcomes, steps, depths,
counters, offsets, the walks' edges, the trail after the local updates, how
often they asked for room, and numba's random stream after the colony.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numba
import numpy as np
import pytest

from pathzoo import VehicleModel
from pathzoo_aco.engine import ABORTED, EXHAUSTED, REACHED, STEP_CAP, STUCK, ColonyProblem, Pheromone, WalkEngine
from pathzoo_aco.engine import WalkRules
from pathzoo_aco.engine.outcomes import DONE, FRESH
from pathzoo_aco.engine.walk import _seed
from pathzoo_aco.engine import walk_kernel
from pathzoo_aco.engine.walk_kernel import generic_colony, local_colony, unsigned_lists

from aco_maps import hill, open_grid, walled_grid


@numba.njit
def _next_draw():
    return np.random.random()


def _run(specialised: bool, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, n_ants: int, seed: int,
         allowance: int, flat_size: int, colonies: int) -> dict:
    """``colonies`` colonies in a row on a copy of ``trail`` (powers kept in one must not be used in the next)."""
    engine = WalkEngine(problem)
    adjacency = engine.adjacency(rules)
    assert engine.colony_weights(rules, trail) is None and not rules.race and rules.pre_add.size == 0
    x = trail.x.copy()
    stamps = np.zeros((1, problem.n_nodes), dtype=np.uint8)
    stacks = np.zeros((1, problem.n_free + 1), dtype=np.int64)
    prevs = np.zeros((1, problem.n_free + 1), dtype=np.int64)
    powers, power_stamp = np.zeros(x.size), np.zeros(x.size, dtype=np.int32)
    out: dict = {"calls": 0}
    scale = trail.scale
    for colony in range(1, colonies + 1):
        _seed(seed + colony - 1)  # as ``WalkEngine.walk`` seeds every colony
        scale *= 1.0 - EVAPORATION  # the trail evaporates before each colony
        cur, depth, prev, steps = (np.zeros(n_ants, dtype=np.int64) for _ in range(4))
        flags = np.full(n_ants, FRESH, dtype=np.int8)
        counters = np.zeros(4, dtype=np.int64)
        offsets = np.zeros(n_ants + 1, dtype=np.int64)
        flat = np.zeros(flat_size, dtype=np.int64)
        base = 1 + (colony - 1) * n_ants
        while True:
            out["calls"] += 1
            status = (local_colony if specialised else generic_colony)(
                *unsigned_lists(problem, engine.indices, adjacency), None, problem.horizontal_offsets, rules.turn, x,
                scale, trail.lo, trail.hi, trail.on_nodes, rules.tau_exp, rules.q0, rules.local_keep, rules.local_add,
                rules.pre_add, powers, power_stamp, colony, problem.start, problem.goal, rules.backtrack,
                rules.max_steps, allowance, False, base, stamps, stacks, prevs, engine.cand_w, cur, depth, prev, steps,
                flags, counters, flat, offsets, None)
            if status == DONE:
                break
            assert counters[3] == 1  # only ``flat`` ever runs out of room
            flat = np.concatenate([flat, np.zeros(max(flat.size, int(offsets[counters[0]] + depth[counters[0]])),
                                                  dtype=np.int64)])
        for name, value in (("flags", flags), ("steps", steps), ("depth", depth), ("counters", counters),
                            ("offsets", offsets), ("flat", flat[: offsets[-1]])):
            out[f"{name}{colony}"] = value
    out["x"] = x
    out["next_draw"] = _next_draw()
    return out


EVAPORATION = 0.2


def _trail(problem: ColonyProblem, on_nodes: bool = False, bounds=(0.0, math.inf)) -> Pheromone:
    n = problem.n_nodes if on_nodes else problem.graph.n_edges
    trail = Pheromone(n, np.random.default_rng(5).uniform(0.0, 1.5, n), on_nodes=on_nodes, lo=bounds[0],
                      hi=bounds[1])
    trail.evaporate(0.3)
    return trail


def _rules(problem: ColonyProblem, alpha: float = 1.0, factor: np.ndarray | None = None, **kw) -> WalkRules:
    g = problem.graph
    eta = 1.0 / (g.length + problem.goal_distance[g.indices])
    return WalkRules.product(alpha, eta, 2.0, factor, **{"max_steps": 10**9, "local_keep": 0.9,
                                                         "local_add": 0.01, **kw})


def _assert_same(problem, rules, trail, n_ants=12, seed=9, allowance=2**62, flat_size=1024, colonies=2) -> dict:
    want = _run(False, problem, rules, trail, n_ants, seed, allowance, flat_size, colonies)
    got = _run(True, problem, rules, trail, n_ants, seed, allowance, flat_size, colonies)
    assert got.keys() == want.keys()
    for name, value in want.items():
        np.testing.assert_array_equal(got[name], value, err_msg=name)
    return got


@pytest.mark.parametrize("alpha", [1.0, 3.0])
@pytest.mark.parametrize("on_nodes", [False, True])
def test_same_walks_and_trail_as_the_generic_kernel(alpha, on_nodes):
    """Edge and node trails, with the power kept per entry (alpha 3) and without (alpha 1), within bounds."""
    problem = ColonyProblem(walled_grid())
    got = _assert_same(problem, _rules(problem, alpha), _trail(problem, on_nodes, (0.05, 1.2)), n_ants=20)
    assert np.all(got["flags1"] == REACHED) and got["counters1"][2] > 100


def test_same_walks_with_q0_a_sum_rule_and_a_pure_decay():
    problem = ColonyProblem(walled_grid())
    g = problem.graph
    _assert_same(problem, _rules(problem, q0=0.9), _trail(problem))
    ties = WalkRules.product(1.0, np.ones(g.n_edges), 1.0, q0=0.9, local_keep=0.9, max_steps=10**9)
    _assert_same(problem, ties, Pheromone(g.n_edges, 1.0))  # equal weights: q0 takes the first of the heaviest
    _assert_same(problem, WalkRules.additive(0.4, 1.0 / g.length, 0.6, np.full(g.n_edges, 0.5), max_steps=10**9,
                                             local_keep=0.8), _trail(problem, True, (0.01, 1.0)))
    zero = Pheromone(problem.n_nodes, 0.0, on_nodes=True)  # every trail 0: the heuristic-only fallback
    for q0 in (0.0, 0.5):  # the heaviest of the heuristic-only candidates too
        got = _assert_same(problem, _rules(problem, 3.0, local_add=0.0, q0=q0), zero)
        assert np.all(got["flags1"] == REACHED)


@pytest.mark.slow
def test_same_walks_with_a_turn_limit_and_with_edges_left_out():
    problem = ColonyProblem(hill())
    k = len(problem.graph.offsets)
    turn = np.where(np.random.default_rng(0).random((k + 1, k)) < 0.3, 0.0, 0.5)
    _assert_same(problem, _rules(problem, alpha=1.5, turn=turn), _trail(problem))
    limited = ColonyProblem(open_grid(12, vehicle=VehicleModel(max_turn_deg=45.0)))
    _assert_same(limited, _rules(limited, turn=limited.turn_table), _trail(limited, True))
    g = problem.graph
    factor = np.where(np.random.default_rng(1).random(g.n_edges) < 0.2, 0.0, 1.0)  # adj_edge: a pruned list
    for on_nodes in (False, True):
        rules = _rules(problem, alpha=3.0, factor=factor)
        assert WalkEngine(problem).adjacency(rules)[2] is not None
        _assert_same(problem, rules, _trail(problem, on_nodes))


def test_same_outcomes_at_dead_ends_step_caps_and_an_exhausted_component():
    problem = ColonyProblem(walled_grid())
    stuck = _assert_same(problem, _rules(problem, backtrack=False), _trail(problem), n_ants=30)
    assert np.any(stuck["flags1"] == STUCK)
    capped = _assert_same(problem, _rules(problem, max_steps=15), _trail(problem))
    assert np.any(capped["flags1"] == STEP_CAP) and np.all(capped["steps1"] <= 15)
    closed = ColonyProblem(walled_grid(reachable=False))
    gone = _assert_same(closed, _rules(closed), _trail(closed), n_ants=4)
    assert gone["flags1"][0] == EXHAUSTED and np.all(gone["flags1"][1:] == ABORTED) and gone["counters1"][1] == 1


@pytest.mark.parametrize("allowance", [1, 40, 333])
def test_same_walks_when_the_allowance_ends_the_colony_mid_walk(allowance):
    problem = ColonyProblem(walled_grid())
    got = _assert_same(problem, _rules(problem, 3.0), _trail(problem, True), n_ants=20, allowance=allowance,
                       colonies=1)
    assert got["counters1"][2] == allowance and np.any(got["flags1"] == ABORTED)


def test_same_walks_when_they_wait_for_room_in_flat():
    problem = ColonyProblem(walled_grid())
    got = _assert_same(problem, _rules(problem), _trail(problem), n_ants=20, flat_size=4)
    assert got["calls"] > 6


def test_the_engine_dispatches_colonies_with_a_local_update_to_the_specialised_kernel(monkeypatch):
    """``WalkEngine.walk`` gives the generic kernel's walks and trail, through the specialised kernel when it applies.

    Two colonies on one engine: the powers kept in the first must not be taken for the second's.
    """
    problem = ColonyProblem(walled_grid())
    rules = _rules(problem, 3.0)
    trail = _trail(problem, True, (0.05, 1.2))
    want = _run(False, problem, rules, trail, 12, 3, 2**62, 1024, 2)
    calls = []
    monkeypatch.setitem(walk_kernel.KERNELS, (True, False, False), lambda *args: calls.append(1) or local_colony(*args))
    engine = WalkEngine(problem)
    for colony, seed in ((1, 3), (2, 4)):
        trail.evaporate(EVAPORATION)
        walks = engine.walk(rules, trail, 12, seed=seed)
        for name in ("flags", "steps", "offsets"):
            np.testing.assert_array_equal(getattr(walks, name), want[f"{name}{colony}"], err_msg=name)
        np.testing.assert_array_equal(walks.flat, want[f"flat{colony}"])
    np.testing.assert_array_equal(trail.x, want["x"])
    assert len(calls) == 2
    WalkEngine(problem).walk(replace(rules, race=True), trail, 12, seed=3)
    assert len(calls) == 2  # racing ants stay with the generic kernel
