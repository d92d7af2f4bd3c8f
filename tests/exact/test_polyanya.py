"""Polyanya on the rectangle mesh against two independent exact searches, the mesh itself, and Theta*."""

import heapq
import math

import numpy as np
import pytest

from pathzoo import Budget, Status, make_planner
from pathzoo.grid.anyangle import SearchCapReached, anyangle_path
from pathzoo.grid.navmesh import navigation_mesh, polygons_at
from pathzoo.grid.visibility_graph import visible
from pathzoo.rules import validate_path


def _both(blocked, start, goal):
    fast = anyangle_path(blocked, np.asarray(start, float), np.asarray(goal, float), 1.0)
    slow = anyangle_path(blocked, np.asarray(start, float), np.asarray(goal, float), 1.0, method="visibility")
    return fast, slow


def _assert_same(fast, slow):
    assert (fast is None) == (slow is None)
    if fast is not None:
        assert fast.length == pytest.approx(slow.length, abs=1e-9)


def _random_map(rng, h, w):
    style = rng.integers(3)
    if style == 0:
        return rng.random((h, w)) < rng.uniform(0.1, 0.4)
    blocked = np.zeros((h, w), dtype=bool)
    if style == 1:  # rectangles that touch, overlap and leave one-cell gaps
        for _ in range(rng.integers(3, 12)):
            y, x = rng.integers(0, h), rng.integers(0, w)
            blocked[y : y + rng.integers(1, 5), x : x + rng.integers(1, 5)] = True
        return blocked
    blocked[::2, ::2] = rng.random(blocked[::2, ::2].shape) < 0.6  # many diagonal pinches
    blocked[1::2, 1::2] = rng.random(blocked[1::2, 1::2].shape) < 0.4
    return blocked


@pytest.mark.parametrize("seed", range(40))
def test_agrees_with_the_visibility_graph_on_random_maps(seed):
    rng = np.random.default_rng(seed)
    h, w = rng.integers(4, 24, 2)
    blocked = _random_map(rng, h, w)
    free = np.argwhere(~blocked)
    if len(free) < 2:
        return
    for k in range(8):
        i, j = rng.choice(len(free), 2, replace=False)
        _assert_same(*_both(blocked, free[i][::-1] + 0.5, free[j][::-1] + 0.5))  # cell centres
        # points on a 1, 1/2 or 1/4-cell lattice: on grid lines, on grid points, on obstacle boundaries
        den = (1, 2, 4)[k % 3]
        start = rng.integers(0, [w * den + 1, h * den + 1]) / den
        goal = rng.integers(0, [w * den + 1, h * den + 1]) / den
        _assert_same(*_both(blocked, start, goal))


def test_corner_touching_cases_by_hand():
    blocked = np.zeros((4, 4), dtype=bool)
    blocked[1, 1] = blocked[2, 2] = True  # a pinch at the grid point (2, 2)
    fast, slow = _both(blocked, (0.5, 3.5), (3.5, 0.5))
    _assert_same(fast, slow)
    assert fast.length == pytest.approx(2 * math.hypot(0.5, 2.5), abs=1e-12)
    # from the pinch point itself, each free side is reached, the way through is not
    fast, slow = _both(blocked, (2.0, 2.0), (3.5, 0.5))
    _assert_same(fast, slow)
    blocked = np.zeros((3, 6), dtype=bool)
    blocked[1, 1:5] = True  # a wall: slide along its top face from corner to corner
    fast, slow = _both(blocked, (0.0, 1.0), (6.0, 1.0))
    _assert_same(fast, slow)
    assert fast.length == pytest.approx(6.0, abs=1e-12)
    fast, slow = _both(blocked, (0.5, 2.5), (5.5, 0.5))  # round the wall's end corners
    _assert_same(fast, slow)
    wall = np.zeros((3, 5), dtype=bool)
    wall[:2, 2] = True  # no passage along the edge between the two blocked cells
    fast, slow = _both(wall, (0.5, 0.5), (4.5, 0.5))
    _assert_same(fast, slow)
    assert fast.length == pytest.approx(2 * math.hypot(1.5, 1.5) + 1.0, abs=1e-12)


def _all_grid_points_optimum(blocked, start, goal, scale=4):
    """Dijkstra over the start, the goal and every grid point, joined when :func:`visible` passes the segment."""
    h, w = blocked.shape
    pts = [tuple(int(v * scale) for v in start), tuple(int(v * scale) for v in goal)]
    pts += [(x * scale, y * scale) for y in range(h + 1) for x in range(w + 1)]
    dist = [math.inf] * len(pts)
    dist[0] = 0.0
    heap = [(0.0, 0)]
    while heap:
        d, i = heapq.heappop(heap)
        if d > dist[i]:
            continue
        if i == 1:
            return d / scale
        for j, q in enumerate(pts):
            nd = d + math.dist(pts[i], q)
            if nd < dist[j] and visible(blocked, scale, *pts[i], *q):
                dist[j] = nd
                heapq.heappush(heap, (nd, j))
    return None


@pytest.mark.parametrize("seed", range(12))
def test_matches_a_brute_force_over_every_grid_point_on_tiny_maps(seed):
    rng = np.random.default_rng(100 + seed)
    blocked = _random_map(rng, 6, 7)
    start = rng.integers(0, [7 * 4 + 1, 6 * 4 + 1]) / 4
    goal = rng.integers(0, [7 * 4 + 1, 6 * 4 + 1]) / 4
    fast = anyangle_path(blocked, start, goal, 1.0)
    brute = _all_grid_points_optimum(blocked, start, goal)
    if brute is None:
        assert fast is None
    else:
        assert fast is not None and fast.length == pytest.approx(brute, abs=1e-9)


def test_mesh_covers_the_free_cells_and_its_edges_pair_up():
    rng = np.random.default_rng(3)
    blocked = _random_map(rng, 30, 41)
    mesh = navigation_mesh(blocked)
    assert np.array_equal(mesh.cell_polygon < 0, blocked)
    w1 = blocked.shape[1] + 1
    for p in range(mesh.n_polygons):
        lo, hi = mesh.offsets[p], mesh.offsets[p + 1]
        xy = np.stack([mesh.vertex[lo:hi] % w1, mesh.vertex[lo:hi] // w1], axis=1)
        e = np.roll(xy, -1, axis=0) - xy
        assert (e[:, 0] * np.roll(e, -1, axis=0)[:, 1] - e[:, 1] * np.roll(e, -1, axis=0)[:, 0] >= 0).all()  # convex
        for i in range(lo, hi):
            q, t = mesh.neighbour[i], mesh.twin[i]
            if q >= 0:
                a, b = mesh.vertex[i], mesh.vertex[lo + (i - lo + 1) % (hi - lo)]
                qlo, qhi = mesh.offsets[q], mesh.offsets[q + 1]
                assert mesh.vertex[qlo + t] == b and mesh.vertex[qlo + (t + 1) % (qhi - qlo)] == a
                assert mesh.neighbour[qlo + t] == p
    # a pinch point belongs to the polygons on both free sides, which share no edge and no component
    pinch = np.zeros((2, 2), dtype=bool)
    pinch[0, 0] = pinch[1, 1] = True
    mesh = navigation_mesh(pinch)
    assert list(polygons_at(mesh, 1, 1, 1)) == [0, 1]
    assert (mesh.neighbour == -1).all()
    assert mesh.component[0] != mesh.component[1]
    assert anyangle_path(pinch, np.array([0.5, 1.5]), np.array([1.5, 0.5]), 1.0) is None


def test_expansion_cap_stops_the_search():
    blocked = np.zeros((20, 20), dtype=bool)
    blocked[2:18, 10] = True
    with pytest.raises(SearchCapReached):
        anyangle_path(blocked, np.array([0.5, 10.5]), np.array([19.5, 10.5]), 1.0, max_expansions=1)


def test_on_a_512_map_valid_and_never_longer_than_theta_star(load_scen):
    problems = load_scen("grid/rooms/8room_000.map.scen")
    chosen = [problems[k] for k in np.linspace(len(problems) // 2, len(problems) - 1, 4).astype(int)]
    planner = make_planner("exact.anyangle")
    for scenario in chosen:
        result = planner.plan(scenario, budget=Budget(), rng=np.random.default_rng(0))
        assert result.status is Status.SOLVED, result.message
        assert validate_path(scenario, result.path)
        theta = make_planner("exact.thetastar").plan(scenario, budget=Budget(), rng=np.random.default_rng(0))
        assert result.extras["optimum"] <= float(np.hypot(*np.diff(theta.path, axis=0).T).sum()) + 1e-9
        assert result.extras["optimum"] <= scenario.reference_length + 1e-5  # 8-connected, 5-6 digits
        assert 0.0 <= result.extras["excess"] <= 1e-4


def test_cell_centres_of_a_cell_size_that_is_no_power_of_two():
    # (i + 0.5) * 0.1 / 0.1 misses i + 0.5 by a rounding error for about one centre in seven
    rng = np.random.default_rng(5)
    blocked = rng.random((300, 300)) < 0.2
    free = np.argwhere(~blocked)
    misses = 0
    for _ in range(10):
        i, j = rng.choice(len(free), 2, replace=False)
        start, goal = free[i][::-1] + 0.5, free[j][::-1] + 0.5
        misses += bool(((start * 0.1) / 0.1 != start).any() or ((goal * 0.1) / 0.1 != goal).any())
        unit = anyangle_path(blocked, start, goal, 1.0)
        tenth = anyangle_path(blocked, start * 0.1, goal * 0.1, 0.1)
        assert (unit is None) == (tenth is None)
        if unit is not None:
            assert tenth.length == pytest.approx(0.1 * unit.length, rel=1e-12)
            assert np.array_equal(tenth.path[0], start * 0.1) and np.array_equal(tenth.path[-1], goal * 0.1)
    assert misses > 0


def test_the_mesh_is_built_once_per_scenario(monkeypatch):
    from pathzoo import Scenario
    from pathzoo.grid import navmesh
    from pathzoo.grid.reference import anyangle_length

    builds = []

    def counting(blocked):
        builds.append(1)
        return navigation_mesh(blocked)

    monkeypatch.setattr(navmesh, "navigation_mesh", counting)
    occ = np.zeros((12, 12), dtype=bool)
    occ[2:10, 6] = True
    scenario = Scenario(id="wall", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 5.5), goal=(11.5, 5.5))
    planner = make_planner("exact.anyangle")
    for seed in range(2):
        assert planner.plan(scenario, budget=Budget(), rng=np.random.default_rng(seed)).status is Status.SOLVED
    assert anyangle_length(scenario) == pytest.approx(math.hypot(5.5, 3.5) + 1 + math.hypot(4.5, 3.5), abs=1e-12)
    assert len(builds) == 1
