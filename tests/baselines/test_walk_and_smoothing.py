"""The pure metaheuristics' obstacle-aware start and local smoothing (issue 37): what they do, and their reach."""

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget, make_planner
from pathzoo.metrics.optimality import LengthRatio
from pathzoo.rules import validate_path
from pathzoo_baselines.encodings import make_encoding
from pathzoo_baselines.margin import MARGIN_CELLS, polylines_clear
from pathzoo_baselines.smoothing import smooth_polylines
from pathzoo_baselines.walk_init import goal_biased_walk, walk_waypoints

from exact_touch import touching_segments

MAZE = "movingai.maze-32-32-2.b25.210"  # a long maze problem (upper third of the map's lengths)


def _cells(sid):
    sc = pathzoo.load_scenario(sid)
    r0, c0 = int(sc.start[1]), int(sc.start[0])
    r1, c1 = int(sc.goal[1]), int(sc.goal[0])
    return sc, (r0, c0, r1, c1)


@pytest.mark.parametrize("bias", [0.0, 0.5, 1.0])
def test_walk_is_a_simple_chain_of_free_cells_without_cut_corners(bias):
    sc, (r0, c0, r1, c1) = _cells(MAZE)
    walk = goal_biased_walk(sc.blocked, r0, c0, r1, c1, bias, 20 * sc.blocked.size, 11)
    assert len(walk) > 0
    assert tuple(walk[0]) == (r0, c0) and tuple(walk[-1]) == (r1, c1)
    assert not sc.blocked[walk[:, 0], walk[:, 1]].any()
    steps = np.diff(walk, axis=0)
    assert np.all(np.abs(steps).max(axis=1) == 1)  # 8-connected moves
    for (r, c), (dr, dc) in zip(walk[:-1], steps):
        if dr and dc:
            assert not sc.blocked[r, c + dc] and not sc.blocked[r + dr, c]  # no corner cut
    assert len({tuple(cell) for cell in walk}) == len(walk)  # loops erased


def test_walk_is_reproducible_and_gives_up_on_an_unreachable_goal():
    sc, ends = _cells(MAZE)
    a = goal_biased_walk(sc.blocked, *ends, 0.5, 20_000, 3)
    assert np.array_equal(a, goal_biased_walk(sc.blocked, *ends, 0.5, 20_000, 3))
    assert not np.array_equal(a, goal_biased_walk(sc.blocked, *ends, 0.5, 20_000, 4))
    walled = np.zeros((10, 10), dtype=bool)
    walled[:, 5] = True
    assert len(goal_biased_walk(walled, 2, 2, 2, 8, 0.5, 10_000, 0)) == 0


def test_walk_waypoints_are_evenly_spaced_in_free_cells():
    sc, ends = _cells(MAZE)
    walk = goal_biased_walk(sc.blocked, *ends, 0.5, 20_000, 5)
    pts = walk_waypoints(walk, 16)
    assert not sc.blocked[np.floor(pts[:, 1]).astype(int), np.floor(pts[:, 0]).astype(int)].any()
    centres = walk[:, ::-1] + 0.5
    total = np.hypot(*np.diff(centres, axis=0).T).sum()
    # consecutive points are at most one arc-length step apart in a straight line
    gaps = np.hypot(*np.diff(pts, axis=0).T)
    assert np.all(gaps <= total / 17 + 1e-9)


def test_walk_initial_candidates_already_follow_free_space():
    sc = pathzoo.load_scenario(MAZE)
    params = {"encoding": "waypoints", "waypoints": 16, "spline_samples": 40, "penalty": 1.0}
    walk = make_encoding(sc, {**params, "init": "walk", "repair_window": 8, "smoothing": 8})
    uniform = make_encoding(sc, {**params, "init": "uniform", "repair_window": 8, "smoothing": 8})
    rng = np.random.default_rng(0)
    v_walk = walk.evaluate(walk.initial(rng, 20))[1]
    v_uniform = uniform.evaluate(uniform.initial(rng, 20))[1]
    assert np.mean(v_walk == 0) >= 0.5 and not np.any(v_uniform == 0)


def test_smoothing_looks_at_most_lookahead_points_ahead():
    blocked = np.zeros((10, 10), dtype=bool)
    line = np.array([[[0.5 + i, 5.5] for i in range(5)]])
    out = line.copy()
    n = smooth_polylines(blocked, out, np.array([5]), 2, MARGIN_CELLS)
    assert n[0] == 3 and np.array_equal(out[0, :3], line[0, [0, 2, 4]])
    out = line.copy()
    assert smooth_polylines(blocked, out, np.array([5]), 8, MARGIN_CELLS)[0] == 2


def test_smoothing_keeps_ends_never_lengthens_and_never_adds_a_collision():
    sc = pathzoo.load_scenario("movingai.room-32-32-4.b12.82")
    rng = np.random.default_rng(2)
    paths = rng.uniform(0, 32, (60, 10, 2))
    paths[:, 0], paths[:, -1] = sc.start, sc.goal
    lengths = np.full(60, 10, dtype=np.int64)
    out = paths.copy()
    new = smooth_polylines(sc.blocked, out, lengths, 8, MARGIN_CELLS)
    assert np.all(out[:, 0] == paths[:, 0]) and np.all(out[np.arange(60), new - 1] == paths[:, -1])
    length = lambda p: np.hypot(*np.diff(p, axis=1).transpose(2, 0, 1)).sum(axis=1)  # noqa: E731
    assert np.all(length(out) <= length(paths) + 1e-9)
    assert np.all(polylines_clear(sc.blocked, out, MARGIN_CELLS) <= polylines_clear(sc.blocked, paths, MARGIN_CELLS))
    assert np.any(new < 10)


@pytest.mark.parametrize("pid", ["swarm.pso", "evo.ga"])
def test_defaults_solve_a_long_maze_problem(pid):
    """At its defaults (5,000 evaluations) a pure planner solves a long maze problem within 1.25x the grid optimum."""
    sc = pathzoo.load_scenario(MAZE)
    for seed in (0, 1):
        result = make_planner(pid).plan(sc, budget=Budget(), rng=np.random.default_rng(seed))
        assert result.solved and validate_path(sc, result.path)
        assert not touching_segments(sc.blocked, result.path, sc.cell_size)
        assert LengthRatio().measure(sc, result.path, None) <= 1.25
