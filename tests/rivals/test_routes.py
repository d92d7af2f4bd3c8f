"""The route encoding of the multi-objective rivals: exact feasibility, objectives by hand, moves keep feasibility."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo.core import Scenario, VehicleModel
from pathzoo.rules import validate_path
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo_rivals.movns import shake
from pathzoo_rivals.route_moves import insert, leap, relocate, remove
from pathzoo_rivals.routes import RouteProblem


def node(s: Scenario, row: int, col: int) -> int:
    return row * s.shape[1] + col


def open_grid(blocked: list[tuple[int, int]] = ()) -> Scenario:
    occ = np.zeros((6, 6), dtype=bool)
    for rc in blocked:
        occ[rc] = True
    return Scenario(id="test.open", kind="grid2d", occupancy=occ, cell_size=1.0,
                    start=np.array([0.5, 0.5]), goal=np.array([5.5, 5.5]))


def test_segment_touching_a_blocked_corner_is_rejected():
    # the diagonal from (0,0) to (2,2) passes exactly through the corners of cells (0,1)/(1,0) and (1,2)/(2,1)
    s = open_grid(blocked=[(1, 2)])
    problem = RouteProblem(s)
    assert not problem.segment_ok(node(s, 0, 0), node(s, 2, 2))  # touches the corner (x 2, y 2) of cell (1, 2)
    assert not problem.segment_ok(node(s, 0, 0), node(s, 3, 3))
    assert problem.segment_ok(node(s, 0, 0), node(s, 5, 0))
    assert not problem.segment_ok(node(s, 1, 1), node(s, 1, 3))  # straight through the blocked cell


def test_slope_at_the_limit_is_rejected_with_a_margin():
    elevation = np.array([[0.0, 1.0, 2.0]])
    limit = math.degrees(math.atan2(1.0, 1.0))  # exactly the slope of each move
    s = Scenario(id="test.ramp", kind="terrain", occupancy=np.zeros((1, 3), dtype=bool), cell_size=1.0,
                 start=np.array([0.5, 0.5]), goal=np.array([2.5, 0.5]), elevation=elevation,
                 vehicle=VehicleModel(max_climb_deg=limit))
    assert not RouteProblem(s).segment_ok(0, 1)
    s2 = Scenario(id="test.ramp", kind="terrain", occupancy=np.zeros((1, 3), dtype=bool), cell_size=1.0,
                  start=np.array([0.5, 0.5]), goal=np.array([2.5, 0.5]), elevation=elevation,
                  vehicle=VehicleModel(max_climb_deg=limit + 1e-3))
    assert RouteProblem(s2).segment_ok(0, 1)


def test_objectives_by_hand():
    s = open_grid()
    problem = RouteProblem(s)
    straight = np.array([node(s, 0, 0), node(s, 5, 5)])
    f = problem.objectives(straight)
    assert f[0] == pytest.approx(5.0 * math.sqrt(2.0))
    assert f[2] == 0.0
    # ceil(5 sqrt 2 / 0.5) = 15 steps, so 16 samples at x = 0.5 + k / 3 (k = 0..15) along the diagonal;
    # they fall 2, 3, 3, 3, 3, 2 in cells (0,0)..(5,5), whose clearances are 1, 2, 3, 3, 2, 1 m
    # (the border counts as blocked)
    expected = (2 * 1 + 3 * 2 + 3 * 3 + 3 * 3 + 3 * 2 + 2 * 1) / 16
    assert f[1] == pytest.approx(-expected)
    bent = np.array([node(s, 0, 0), node(s, 0, 5), node(s, 5, 5)])
    g = problem.objectives(bent)
    assert g[0] == pytest.approx(10.0)
    assert g[2] == pytest.approx(math.pi / 2)


@pytest.mark.parametrize("kind", ["grid2d", "terrain"])
def test_random_routes_and_moves_stay_feasible(kind):
    s = check_scenario(kind)
    problem = RouteProblem(s)
    rng = np.random.default_rng(3)
    route = problem.random_route(rng)
    assert route is not None and problem.route_ok(route)
    other = problem.random_route(rng)
    made = 0
    for step in range(150):
        move = step % 5
        if move == 0:
            new = relocate(problem, route, rng, 2)
        elif move == 1:
            new = insert(problem, route, rng, 2)
        elif move == 2:
            new = remove(problem, route, rng)
        elif move == 3:
            new = shake(problem, route, 3, rng)
        else:
            new = leap(problem, route, other, rng)
        if new is None:
            continue
        made += 1
        assert problem.route_ok(new)
        assert validate_path(s, problem.world_path(new)).valid
        route = new
    assert made > 50


def test_unreachable_goal_has_no_random_route():
    s = check_scenario("grid2d", reachable=False)
    problem = RouteProblem(s)
    assert not problem.reachable()
    assert problem.random_route(np.random.default_rng(0)) is None


def test_snapped_diagonal_past_a_blocked_corner_goes_round_on_the_free_side():
    from pathzoo_rivals.route_moves import _bridge_corners

    s = open_grid(blocked=[(0, 1)])
    problem = RouteProblem(s)
    a, b = node(s, 0, 0), node(s, 1, 1)
    assert not problem.segment_ok(a, b)
    bridged = _bridge_corners(problem, np.array([a, b]))
    assert list(bridged) == [a, node(s, 1, 0), b]
    # both sides blocked: nothing to bridge with, the route is infeasible
    s2 = open_grid(blocked=[(0, 1), (1, 0)])
    assert _bridge_corners(RouteProblem(s2), np.array([a, b])) is None


@pytest.mark.parametrize("scenario_id", ["ggaco.frontrange", "ggaco.hugo"])
def test_segment_verdicts_equal_the_judges(scenario_id):
    """The collision-only fast path (frontrange: no limits, no missing heights) and the full path (hugo) agree
    with the judge's segment_problem on random segments."""
    import pathzoo
    from pathzoo.rules import segment_problem

    s = pathzoo.load_scenario(scenario_id)
    problem = RouteProblem(s)
    rng = np.random.default_rng(0)
    free = np.flatnonzero(~s.blocked.ravel())
    h, w = s.shape
    agree = rejected = 0
    for u in rng.choice(free, 400):
        r, c = divmod(int(u), w)
        rr, cc = np.clip(r + rng.integers(-8, 9), 0, h - 1), np.clip(c + rng.integers(-8, 9), 0, w - 1)
        v = int(rr * w + cc)
        if v == u or s.blocked[rr, cc]:
            continue
        judge = segment_problem(s, *s.point_of(np.array([u, v]))) is None
        assert problem.segment_ok(int(u), v) == judge
        agree += 1
        rejected += not judge
    assert agree > 200 and rejected > 10


@pytest.fixture(scope="module", params=["ggaco.hugo", "ggaco.frontrange", "one-way slopes"])
def ggaco_problem(request):
    import dataclasses

    import pathzoo

    if request.param == "one-way slopes":  # climb and descent limits differ: edges without their reverse
        s = check_scenario("terrain")
        s = dataclasses.replace(s, vehicle=dataclasses.replace(s.vehicle, max_climb_deg=8.0, max_descent_deg=30.0))
        graph = s.graph.to_sparse("length")
        assert (graph != graph.T).nnz > 0
        return RouteProblem(s)
    return RouteProblem(pathzoo.load_scenario(request.param))


def test_compiled_segment_test_agrees_with_the_judge():
    # ggaco.frontrange has no slope limit and no missing height: the compiled collision-only test must give the
    # verdicts of the judge's segment_problem
    import pathzoo

    problem = RouteProblem(pathzoo.load_scenario("ggaco.frontrange"))
    assert problem.collision_only
    slow = RouteProblem(problem.scenario)
    slow.collision_only = False  # the Python path: segment_problem, then the slope margin (90 degrees: never binding)
    rng = np.random.default_rng(5)
    h, w = problem.shape
    free = np.flatnonzero(problem.free.ravel())
    agree = 0
    for _ in range(400):
        u = int(rng.choice(free))
        r, c = divmod(u, w)
        v = int(np.clip(r + rng.integers(-12, 13), 0, h - 1) * w + np.clip(c + rng.integers(-12, 13), 0, w - 1))
        assert problem.segment_ok(u, v) == slow.segment_ok(u, v)
        agree += problem.segment_ok(u, v)
    assert 0 < agree < 400  # both verdicts occur
    route = problem.random_route(rng)
    assert route is not None
    nodes = np.concatenate([[problem.start], route[1:-1].repeat(1), [problem.goal]]).astype(np.int64)
    assert np.array_equal(problem.pull_string(route), slow.pull_string(route))


def test_random_route_is_the_shortest_route_through_its_via_cell(ggaco_problem):
    from scipy.sparse.csgraph import dijkstra

    problem = ggaco_problem
    from_start, to_goal, d_start, d_goal = problem._trees()
    graph = problem.scenario.graph.to_sparse("length")
    ref_start = dijkstra(graph, indices=problem.start)
    ref_goal = dijkstra(graph.T.tocsr(), indices=problem.goal)  # distances *to* the goal
    np.testing.assert_allclose(d_start, ref_start, rtol=1e-12)
    np.testing.assert_allclose(d_goal, ref_goal, rtol=1e-12)
    from pathzoo_rivals.route_kernels import via_route

    rng = np.random.default_rng(2)
    seen = np.full(len(d_start), -1, dtype=np.int64)
    lengths = problem.scenario.graph.length
    for via in rng.choice(np.flatnonzero(np.isfinite(d_start + d_goal)), 30):
        cells = via_route(from_start, to_goal, int(via), problem.goal, seen)
        assert cells[0] == problem.start and cells[-1] == problem.goal
        assert len(np.unique(cells)) == len(cells)  # no cell twice: loops are cut
        assert (seen == -1).all()
        hops = [lengths[problem.scenario.graph.indptr[a] + np.flatnonzero(problem.scenario.graph.neighbours(a) == b)[0]]
                for a, b in zip(cells[:-1], cells[1:])]
        assert sum(hops) <= d_start[via] + d_goal[via] + 1e-6  # the shortest route through via, or shorter (a cut loop)
    route = problem.random_route(rng)
    assert route is not None and problem.route_ok(route)
    assert validate_path(problem.scenario, problem.world_path(route)).valid


def test_compiled_neighbour_steps_agree_with_the_walk():
    # every step between neighbouring cells of ggaco.frontrange: the cell rule of segment_free equals the walk
    import pathzoo
    from pathzoo.grid.segments import first_blocked_cell_2d
    from pathzoo_rivals.route_kernels import segment_free

    problem = RouteProblem(pathzoo.load_scenario("ggaco.frontrange"))
    blocked, cs = problem.blocked, problem.cell_size
    h, w = blocked.shape
    free = np.flatnonzero(~blocked.ravel())
    diagonal_refused = 0
    for u in free[::3]:
        r, c = divmod(int(u), w)
        for dr, dc in ((-1, -1), (-1, 0), (-1, 1), (0, 1), (1, -1), (1, 0), (1, 1), (0, -1)):
            if not (0 <= r + dr < h and 0 <= c + dc < w):
                continue
            v = (r + dr) * w + c + dc
            walk = (not blocked[r + dr, c + dc]) and first_blocked_cell_2d(
                blocked, ((c + 0.5) * cs) / cs, ((r + 0.5) * cs) / cs,
                ((c + dc + 0.5) * cs) / cs, ((r + dr + 0.5) * cs) / cs)[0] == -2
            assert segment_free(blocked, cs, int(u), v) == walk
            diagonal_refused += dr != 0 and dc != 0 and not walk and not blocked[r + dr, c + dc]
    assert diagonal_refused > 0  # the corner rule is exercised
