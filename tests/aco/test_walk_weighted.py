"""The weighted kernel (walk_kernel.py) against the generic kernel on the same weights and colonies.

Both kernels (the walk body compiled for ants one after another, and for racing ants and pre-choice additions)
are called directly with fresh buffers, as ``WalkEngine.walk``
calls them, and must leave every output the same: outcomes, steps, depths,
counters, offsets, the walks' edges, how often they asked for room, and
numba's random stream after the colony.
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
from pathzoo_aco.engine.walk_kernel import generic_weighted_colony, unsigned_lists, weighted_colony

from aco_maps import hill, open_grid, walled_grid


@numba.njit
def _next_draw():
    return np.random.random()


def _run(specialised: bool, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, n_ants: int, seed: int,
         allowance: int, flat_size: int) -> dict:
    engine = WalkEngine(problem)
    adjacency = engine.adjacency(rules)
    weights = engine.colony_weights(rules, trail)
    assert weights is not None and not rules.race
    stamps = np.zeros((1, problem.n_nodes), dtype=np.uint8)
    stacks = np.zeros((1, problem.n_free + 1), dtype=np.int64)
    prevs = np.zeros((1, problem.n_free + 1), dtype=np.int64)
    cur, depth, prev, steps = (np.zeros(n_ants, dtype=np.int64) for _ in range(4))
    flags = np.full(n_ants, FRESH, dtype=np.int8)
    counters = np.zeros(4, dtype=np.int64)
    offsets = np.zeros(n_ants + 1, dtype=np.int64)
    flat = np.zeros(flat_size, dtype=np.int64)
    calls = 0
    _seed(seed)
    while True:
        calls += 1
        status = (weighted_colony if specialised else generic_weighted_colony)(
            *unsigned_lists(problem, engine.indices, adjacency), weights, problem.horizontal_offsets, rules.turn,
            trail.x, trail.scale, trail.lo, trail.hi, trail.on_nodes, rules.tau_exp, rules.q0, rules.local_keep,
            rules.local_add, rules.pre_add, engine.powers, engine.power_stamp, 0, problem.start, problem.goal,
            rules.backtrack, rules.max_steps, allowance, False, 1, stamps, stacks, prevs, engine.cand_w, cur, depth,
            prev, steps, flags, counters, flat, offsets, None)
        if status == DONE:
            break
        assert counters[3] == 1  # only ``flat`` ever runs out of room
        flat = np.concatenate([flat, np.zeros(max(flat.size, int(offsets[counters[0]] + depth[counters[0]])),
                                              dtype=np.int64)])
    return {"flags": flags, "steps": steps, "depth": depth, "counters": counters, "offsets": offsets,
            "flat": flat[: offsets[-1]], "calls": calls, "next_draw": _next_draw()}


def _trail(problem: ColonyProblem, kind: str, bounds=(0.0, math.inf)) -> Pheromone:
    n = problem.graph.n_edges
    if kind == "zero":  # every weight of the product rule is 0: the heuristic-only fallback
        return Pheromone(n, 0.0)
    trail = Pheromone(n, np.random.default_rng(5).uniform(0.0, 1.5, n), lo=bounds[0], hi=bounds[1])
    trail.evaporate(0.3)
    return trail


def _product(problem: ColonyProblem, alpha: float = 1.0, factor: np.ndarray | None = None, **kw) -> WalkRules:
    g = problem.graph
    eta = 1.0 / (g.length + problem.goal_distance[g.indices])
    return WalkRules.product(alpha, eta, 2.0, factor, **{"max_steps": 10**9, **kw})


def _assert_same(problem, rules, trail, n_ants=12, seed=9, allowance=2**62, flat_size=1024) -> dict:
    want = _run(False, problem, rules, trail, n_ants, seed, allowance, flat_size)
    got = _run(True, problem, rules, trail, n_ants, seed, allowance, flat_size)
    for name, value in want.items():
        np.testing.assert_array_equal(got[name], value, err_msg=name)
    return got


def test_same_walks_as_the_generic_kernel_product_and_sum_rules():
    problem = ColonyProblem(walled_grid())
    g = problem.graph
    for rules in (_product(problem), _product(problem, alpha=0.4),
                  WalkRules.additive(0.4, 1.0 / g.length, 0.6, np.full(g.n_edges, 0.5), max_steps=10**9)):
        got = _assert_same(problem, rules, _trail(problem, "random", (0.05, 2.0)), n_ants=20)
        assert np.all(got["flags"] == REACHED) and got["counters"][2] > 100


@pytest.mark.slow
def test_same_walks_with_a_turn_limit_and_with_edges_left_out():
    problem = ColonyProblem(hill())
    k = len(problem.graph.offsets)
    turn = np.where(np.random.default_rng(0).random((k + 1, k)) < 0.3, 0.0, 0.5)
    _assert_same(problem, _product(problem, alpha=1.5, turn=turn), _trail(problem, "random"))
    limited = ColonyProblem(open_grid(12, vehicle=VehicleModel(max_turn_deg=45.0)))
    _assert_same(limited, _product(limited, turn=limited.turn_table), _trail(limited, "random"))
    g = problem.graph
    factor = np.where(np.random.default_rng(1).random(g.n_edges) < 0.2, 0.0, 1.0)  # adj_edge: a pruned list
    rules = _product(problem, factor=factor)
    assert WalkEngine(problem).adjacency(rules)[2] is not None
    _assert_same(problem, rules, _trail(problem, "random"))


def test_same_walks_when_every_trail_is_zero_and_with_q0():
    problem = ColonyProblem(walled_grid())
    got = _assert_same(problem, _product(problem), _trail(problem, "zero"))
    assert np.all(got["flags"] == REACHED)
    _assert_same(problem, _product(problem, q0=0.6), _trail(problem, "random"))


def test_same_outcomes_at_dead_ends_step_caps_and_an_exhausted_component():
    problem = ColonyProblem(walled_grid())
    stuck = _assert_same(problem, _product(problem, backtrack=False), _trail(problem, "random"), n_ants=30)
    assert np.any(stuck["flags"] == STUCK)
    capped = _assert_same(problem, _product(problem, max_steps=15), _trail(problem, "random"))
    assert np.any(capped["flags"] == STEP_CAP) and np.all(capped["steps"] <= 15)
    closed = ColonyProblem(walled_grid(reachable=False))
    gone = _assert_same(closed, _product(closed), _trail(closed, "random"), n_ants=4)
    assert gone["flags"][0] == EXHAUSTED and np.all(gone["flags"][1:] == ABORTED) and gone["counters"][1] == 1


@pytest.mark.parametrize("allowance", [1, 40, 333])
def test_same_walks_when_the_allowance_ends_the_colony_mid_walk(allowance):
    problem = ColonyProblem(walled_grid())
    got = _assert_same(problem, _product(problem), _trail(problem, "random"), n_ants=20, allowance=allowance)
    assert got["counters"][2] == allowance and np.any(got["flags"] == ABORTED)


def test_same_walks_when_they_wait_for_room_in_flat():
    problem = ColonyProblem(walled_grid())
    got = _assert_same(problem, _product(problem), _trail(problem, "random"), n_ants=20, flat_size=4)
    assert got["calls"] > 3


def test_the_engine_dispatches_weighted_colonies_to_the_specialised_kernel(monkeypatch):
    """``WalkEngine.walk`` gives the walks of the generic kernel, through the specialised one when it applies."""
    problem = ColonyProblem(walled_grid())
    rules, trail = _product(problem), _trail(problem, "random")
    fast = WalkEngine(problem).walk(rules, trail, 12, seed=3)
    calls = []
    monkeypatch.setitem(walk_kernel.KERNELS, (False, False, False),
                        lambda *args: calls.append(1) or weighted_colony(*args))
    WalkEngine(problem).walk(rules, trail, 12, seed=3)
    WalkEngine(problem).walk(replace(rules, race=True), trail, 12, seed=3)
    assert len(calls) == 1  # racing ants stay with the generic kernel
    monkeypatch.setattr(WalkEngine, "colony_weights", lambda self, rules, trail: None)
    slow = WalkEngine(problem).walk(rules, trail, 12, seed=3)  # per-step weights: the local kernel
    for name in ("flat", "offsets", "flags", "steps"):
        np.testing.assert_array_equal(getattr(fast, name), getattr(slow, name))
