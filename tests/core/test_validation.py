"""The validator rejects every kind of forged path and accepts honest ones."""

import math

import numpy as np
import pytest

from pathzoo import MovingObstacle, Scenario, VehicleModel
from pathzoo.rules import validate_path


@pytest.fixture
def wall():
    occ = np.zeros((5, 5), dtype=bool)
    occ[1:5, 2] = True  # vertical wall with a gap at row 0
    return Scenario(id="wall", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 4.5), goal=(4.5, 4.5))


def test_honest_path_is_valid(wall):
    path = [(0.5, 4.5), (0.5, 1.5), (1.5, 0.5), (2.5, 0.5), (3.5, 0.5), (4.5, 1.5), (4.5, 4.5)]
    assert validate_path(wall, path)


def test_path_through_wall(wall):
    v = validate_path(wall, [(0.5, 4.5), (4.5, 4.5)])
    assert not v and "blocked cell" in v.reason


def test_corner_cut(wall):
    # (1.5, 1.5) -> (2.5, 0.5) cuts the corner of the wall cell (row 1, col 2)
    path = [(0.5, 4.5), (1.5, 1.5), (2.5, 0.5), (3.5, 0.5), (4.5, 1.5), (4.5, 4.5)]
    v = validate_path(wall, path)
    assert not v and "row 1, col 2" in v.reason


def test_wrong_endpoints_and_nan(wall):
    assert "not at the goal" in validate_path(wall, [(0.5, 4.5), (0.5, 3.5)]).reason
    assert "not at the start" in validate_path(wall, [(1.5, 4.5), (4.5, 4.5)]).reason
    assert "NaN" in validate_path(wall, [(0.5, 4.5), (np.nan, 1.0), (4.5, 4.5)]).reason
    assert "shape" in validate_path(wall, np.zeros((3, 3))).reason
    assert not validate_path(wall, "not a path")


def test_leaving_the_map(wall):
    v = validate_path(wall, [(0.5, 4.5), (-1.0, 0.5), (4.5, 4.5)])
    assert not v


def test_terrain_slope_limit():
    elev = np.array([[0.0, 0.5, 1.5]])
    v = VehicleModel(max_climb_deg=40.0, max_descent_deg=60.0)
    s = Scenario(id="t", kind="terrain", occupancy=np.zeros((1, 3), bool), cell_size=1.0, start=(0.5, 0.5),
                 goal=(2.5, 0.5), elevation=elev, vehicle=v)
    res = validate_path(s, [(0.5, 0.5), (1.5, 0.5), (2.5, 0.5)])
    assert not res and "climbs 45.000 deg" in res.reason
    back = Scenario(id="t", kind="terrain", occupancy=np.zeros((1, 3), bool), cell_size=1.0, start=(2.5, 0.5),
                    goal=(0.5, 0.5), elevation=elev, vehicle=v)
    assert validate_path(back, [(2.5, 0.5), (1.5, 0.5), (0.5, 0.5)])


def test_turn_limit():
    s = Scenario(id="t", kind="grid2d", occupancy=np.zeros((3, 3), bool), cell_size=1.0, start=(0.5, 0.5),
                 goal=(0.5, 2.5), vehicle=VehicleModel(max_turn_deg=60))
    assert "turn limit" in validate_path(s, [(0.5, 0.5), (2.5, 0.5), (0.5, 2.5)]).reason
    assert validate_path(s, [(0.5, 0.5), (0.5, 2.5)])


def dyn_scenario():
    ob = MovingObstacle(radius=0.6, waypoints=np.array([[5.5, 0.5], [5.5, 9.5]]), speed=1.0)
    return Scenario(id="d", kind="dynamic", occupancy=np.zeros((10, 10), bool), cell_size=1.0, start=(0.5, 0.5),
                    goal=(9.5, 0.5), moving_obstacles=(ob,), vehicle=VehicleModel(cruise_speed=2.0))


def test_moving_obstacle_hit_and_avoided_by_waiting():
    s = dyn_scenario()
    straight = [(0.5, 0.5), (9.5, 0.5)]
    res = validate_path(s, straight)  # reaches x=5.5 at t=2.5 while the obstacle is at y=3.0: clear
    assert res
    # an obstacle that starts on the route: collide
    ob = MovingObstacle(radius=0.6, waypoints=np.array([[5.5, 0.5], [5.5, 9.5]]), speed=0.1)
    s2 = Scenario(id="d", kind="dynamic", occupancy=np.zeros((10, 10), bool), cell_size=1.0, start=(0.5, 0.5),
                  goal=(9.5, 0.5), moving_obstacles=(ob,))
    res2 = validate_path(s2, straight)
    assert not res2 and "moving obstacle 0" in res2.reason
    # waiting 30 s at the start lets the slow obstacle move away: at t = 32.5 s,
    # when the vehicle crosses x = 5.5, the obstacle is at y = 0.5 + 3.25
    times = [0.0, 30.0, 30.0 + 9.0 / 2.0]
    assert validate_path(s2, [(0.5, 0.5), (0.5, 0.5), (9.5, 0.5)], times=times)


def test_timed_path_cannot_teleport():
    s = dyn_scenario()
    res = validate_path(s, [(0.5, 0.5), (9.5, 0.5)], times=[0.0, 1.0])  # 9 m in 1 s at 2 m/s cruise
    assert not res and "faster than cruise speed" in res.reason


def test_min_distance_is_exact_against_sampling():
    rng = np.random.default_rng(1)
    ob = MovingObstacle(radius=1.0, waypoints=rng.uniform(0, 10, (4, 2)), speed=1.3, mode="loop", phase_s=0.7)
    for _ in range(50):
        p0, p1 = rng.uniform(0, 10, (2, 2))
        t0 = rng.uniform(0, 20)
        t1 = t0 + rng.uniform(0.1, 15)
        exact = ob.min_distance(p0, p1, t0, t1)
        ts = np.linspace(t0, t1, 20001)
        veh = p0 + ((ts - t0) / (t1 - t0))[:, None] * (p1 - p0)
        sampled = np.linalg.norm(veh - ob.position(ts), axis=1).min()
        assert exact <= sampled + 1e-12
        assert math.isclose(exact, sampled, abs_tol=2e-3)


def _slow_verdict(scenario, path):
    """The definition: the first segment, in order, that segment_problem rejects."""
    from pathzoo.rules import segment_problem

    for k in range(len(path) - 1):
        problem = segment_problem(scenario, path[k], path[k + 1])
        if problem is not None:
            return f"segment {k}: {problem}"
    return None


@pytest.mark.parametrize("kind", ["grid2d", "terrain", "air3d"])
def test_vectorised_screening_gives_the_per_segment_verdict(kind):
    rng = np.random.default_rng(11)
    for trial in range(40):
        if kind == "air3d":
            occ = rng.random((4, 12, 12)) < 0.15
            occ[0, 0, 0] = occ[-1, -1, -1] = False
            s = Scenario(id="a", kind="air3d", occupancy=occ, cell_size=1.0, vertical_cell_size=0.5,
                         start=(0.5, 0.5, 0.25), goal=(11.5, 11.5, 1.75), vehicle=VehicleModel(max_pitch_deg=20))
            inner = rng.uniform([0, 0, 0], [12, 12, 2], (rng.integers(0, 6), 3))
        else:
            occ = rng.random((12, 12)) < 0.15
            occ[0, 0] = occ[-1, -1] = False
            extra = {}
            if kind == "terrain":
                extra = dict(elevation=rng.uniform(0, 1.2, (12, 12)),
                             vehicle=VehicleModel(max_climb_deg=35, max_descent_deg=40))
            s = Scenario(id="g", kind=kind, occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(11.5, 11.5), **extra)
            inner = rng.uniform(0, 12, (rng.integers(0, 6), 2))
            if trial % 3 == 0:  # honest grid paths too
                from scipy.sparse.csgraph import dijkstra

                _, pred = dijkstra(s.graph.to_sparse(), indices=s.start_node, return_predecessors=True)
                if pred[s.goal_node] >= 0:
                    nodes = [s.goal_node]
                    while nodes[-1] != s.start_node:
                        nodes.append(pred[nodes[-1]])
                    inner = s.point_of(nodes[::-1])[1:-1]
        path = np.vstack([s.start, inner, s.goal])
        slow = _slow_verdict(s, path)
        fast = validate_path(s, path)
        assert fast.valid == (slow is None)
        if slow is not None:
            assert fast.reason == slow


def test_slope_range_is_exact_against_dense_sampling():
    from pathzoo.grid.terrain import bilinear_elevation, segment_slope_range

    rng = np.random.default_rng(4)
    z = rng.uniform(0, 5, (6, 7))
    for _ in range(40):
        x0, x1 = rng.uniform(-0.5, 7.5, 2)
        y0, y1 = rng.uniform(-0.5, 6.5, 2)
        lo, hi = segment_slope_range(z, x0, y0, x1, y1)
        t = np.linspace(0, 1, 200_001)
        heights = bilinear_elevation(z, np.stack([x0 + t * (x1 - x0), y0 + t * (y1 - y0)], axis=1))
        grad = np.diff(heights) / (math.hypot(x1 - x0, y1 - y0) / 200_000)
        if math.isclose(x1 - x0, y1 - y0, abs_tol=1e-12) or math.isclose(x1 - x0, y0 - y1, abs_tol=1e-12):
            continue  # diagonal lattice lines follow the lattice model, not the bilinear surface
        assert lo <= grad.min() + 1e-9 and hi >= grad.max() - 1e-9  # never narrower than the truth
        assert grad.min() - lo < 1e-3 and hi - grad.max() < 1e-3  # and tight


def test_slope_range_of_a_segment_snapping_to_an_edge_node_reads_only_the_grid():
    """A segment within the margin of a lattice node on the last row or column is on a lattice diagonal; its range
    comes from the diagonal step that ends at the node (it read heights past the grid, whatever memory held)."""
    from pathzoo.grid.terrain import segment_slope_range

    z = np.arange(6 * 7, dtype=float).reshape(6, 7) ** 1.5
    h, w = z.shape
    r2 = math.sqrt(2.0)
    bottom = (z[h - 1, 3] - z[h - 2, 2]) / r2  # X - Y = k through (3, h-1), step from (2, h-2)
    right = -(z[1, w - 2] - z[2, w - 1]) / r2  # X + Y = k through (w-1, 2), step from (w-2, 3), travelled towards +x
    assert segment_slope_range(z, 3.5, h - 0.5, 3.5 + 1e-12, h - 0.5) == pytest.approx((bottom, bottom), rel=1e-12)
    assert segment_slope_range(z, w - 0.5, 2.5, w - 0.5 + 1e-12, 2.5 - 1e-12) == pytest.approx((right, right), rel=1e-12)
    # a corner node whose diagonal leaves the grid both ways: a point, no gradient
    assert segment_slope_range(z, w - 0.5, 0.5, w - 0.5 + 1e-12, 0.5 - 1e-12) == (0.0, 0.0)


def test_air_segment_within_the_margin_of_a_voxel_is_blocked():
    from pathzoo.grid.segments import segment_blocked_3d

    blocked = np.zeros((3, 3, 3), bool)
    blocked[1, 1, 1] = True
    # a segment passing 5e-10 below the blocked voxel's bottom face, then 2e-9 below it
    assert segment_blocked_3d(blocked, np.array([0.5, 1.5, 1 - 5e-10]), np.array([2.5, 1.5, 1 - 5e-10]))
    assert not segment_blocked_3d(blocked, np.array([0.5, 1.5, 1 - 2e-9]), np.array([2.5, 1.5, 1 - 2e-9]))


@pytest.mark.parametrize("limit", [0.0005, 0.001, 20.0, 25.0, 45.0, 89.999, 90.0])
@pytest.mark.parametrize("cell_size", [0.5, 1.0, 30.0])
def test_slope_limit_test_is_the_angle_expression_at_the_cut(limit, cell_size):
    """slope_exceeds compares gradients with the limit's gradient: the verdicts are the angle expression's, ulp by ulp."""
    from types import SimpleNamespace

    from pathzoo.grid.slope_limit import slope_exceeds

    rng = np.random.default_rng(3)
    vehicle = SimpleNamespace(max_climb_deg=limit, max_descent_deg=limit / 2)
    cuts = [cell_size * math.tan(math.radians(d)) for d in (limit, limit / 2)]
    values = [rng.normal(0.0, 3.0 * cell_size, 20_000), np.array([np.nan, np.inf, -np.inf, 0.0, -0.0])]
    for cut in cuts:
        values.append(cut + np.arange(-3000, 3000) * np.spacing(cut))  # every double around the cut
        values.append(cut * (1.0 + rng.uniform(-3e-6, 3e-6, 20_000)))  # across the exact-evaluation band
    grad = np.concatenate(values)
    lo, hi = -rng.permutation(grad), rng.permutation(grad)
    with np.errstate(invalid="ignore"):
        want = ~((np.degrees(np.arctan2(hi, cell_size)) <= vehicle.max_climb_deg)
                 & (np.degrees(np.arctan2(-lo, cell_size)) <= vehicle.max_descent_deg))
    got = slope_exceeds(lo, hi, cell_size, vehicle)
    np.testing.assert_array_equal(got, want)
    assert want.any() and not want.all()


def test_neighbour_moves_take_a_shortcut_with_the_general_result_bit_for_bit():
    """segment_slope_range's shortcut for moves between neighbouring centres equals the general path exactly."""
    from pathzoo.grid.terrain import _segment_slope_range, neighbour_slope_range, segment_slope_range

    rng = np.random.default_rng(11)
    grids = [rng.normal(0.0, 3.0, (9, 11)), rng.normal(0.0, 1.0, (1, 6)), rng.normal(0.0, 1.0, (6, 1)),
             rng.normal(0.0, 1.0, (2, 2)), np.zeros((4, 5)), -np.zeros((3, 3))]
    holed = rng.normal(0.0, 2.0, (12, 10))
    holed[rng.random(holed.shape) < 0.15] = np.nan
    grids.append(holed)
    grids.append(np.round(rng.normal(0.0, 2.0, (7, 8))))  # ties and exact zeros
    checked = 0
    for z in grids:
        h, w = z.shape
        for r in range(h):
            for c in range(w):
                for dr in (-1, 0, 1):
                    for dc in (-1, 0, 1):
                        if (dr, dc) == (0, 0) or not (0 <= r + dr < h and 0 <= c + dc < w):
                            continue
                        x0, y0 = c + 0.5, r + 0.5
                        got = np.array(segment_slope_range(z, x0, y0, x0 + float(dc), y0 + float(dr)))
                        want = np.array(_segment_slope_range(z, x0, y0, x0 + float(dc), y0 + float(dr)))
                        direct = np.array(neighbour_slope_range(z, r, c, dr, dc))
                        for value in (got, direct):
                            assert value.view(np.int64).tolist() == want.view(np.int64).tolist() or (
                                np.isnan(value).all() and np.isnan(want).all()), (z.shape, r, c, dr, dc, value, want)
                        checked += 1
    assert checked > 1000
