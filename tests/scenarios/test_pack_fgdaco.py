"""FGDACO pack: Table 5 obstacle counts, moving obstacles at 0.5-1.5 m/s, static variants, solvability."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import ndimage

import pathzoo
from pathzoo.rules import validate_path
from pathzoo_scenarios import fgdaco

TABLE5 = {1: (3, 3), 2: (4, 3), 3: (2, 3)}  # static, moving obstacles per scenario
TABLE7_FGDACO = {1: 126.65, 2: 135.96, 3: 197.69}


@pytest.mark.parametrize("k", [1, 2, 3])
def test_table5_obstacles(k):
    s = pathzoo.load_scenario(f"fgdaco.scenario{k}")
    n_static, n_moving = TABLE5[k]
    assert s.kind == "dynamic" and s.shape == (100, 100) and s.cell_size == 1.0
    assert len(fgdaco.SCENARIOS[k]["static"]) == n_static
    assert len(set(fgdaco.SCENARIOS[k]["static"][i][0] for i in range(n_static))) >= 2  # different shapes
    assert len(s.moving_obstacles) == n_moving
    # the blocked cells form exactly as many separate obstacles as Table 5 says
    _, n_parts = ndimage.label(s.occupancy, structure=np.ones((3, 3), dtype=bool))
    assert n_parts == n_static


@pytest.mark.parametrize("k", [1, 2, 3])
def test_moving_obstacle_speeds_and_determinism(k):
    s = pathzoo.load_scenario(f"fgdaco.scenario{k}")
    again = pathzoo.load_scenario(f"fgdaco.scenario{k}")
    t = np.linspace(0.0, 600.0, 6001)
    for ob, ob2 in zip(s.moving_obstacles, again.moving_obstacles):
        assert 0.5 <= ob.speed <= 1.5
        pos = ob.position(t)
        np.testing.assert_array_equal(pos, ob2.position(t))  # a deterministic function of time
        measured = np.linalg.norm(np.diff(pos, axis=0), axis=1) / np.diff(t)
        assert measured.max() <= 1.5 + 1e-9
        assert np.median(measured) == pytest.approx(ob.speed, rel=1e-6)
        assert measured.max() >= 0.5


@pytest.mark.parametrize("k", [1, 2, 3])
def test_moving_obstacles_stay_in_free_space_and_off_the_endpoints(k):
    s = pathzoo.load_scenario(f"fgdaco.scenario{k}")
    for ob in s.moving_obstacles:
        pos = ob.position(np.linspace(0.0, ob.period_s, 2000))
        assert s.in_bounds(pos).all()
        assert (s.clearance[tuple(s.cell_of(pos).T)] >= ob.radius).all()
        for end in (s.start, s.goal):
            assert np.linalg.norm(pos - end, axis=1).min() > ob.radius + 2.0


def test_start_and_goal_differ_per_scenario():
    ends = {tuple(np.r_[pathzoo.load_scenario(f"fgdaco.scenario{k}").start,
                        pathzoo.load_scenario(f"fgdaco.scenario{k}").goal]) for k in (1, 2, 3)}
    assert len(ends) == 3


@pytest.mark.parametrize("k", [1, 2, 3])
def test_static_variant(k, shortest_points):
    dyn = pathzoo.load_scenario(f"fgdaco.scenario{k}")
    s = pathzoo.load_scenario(f"fgdaco.scenario{k}_static")
    assert s.kind == "grid2d" and s.moving_obstacles == ()
    np.testing.assert_array_equal(s.occupancy, dyn.occupancy)
    np.testing.assert_array_equal(s.start, dyn.start)
    np.testing.assert_array_equal(s.goal, dyn.goal)
    path = shortest_points(s)
    assert validate_path(s, path)
    length = float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())
    # FGDACO's median length (Table 7) is reachable, and the static optimum is of its order
    assert 0.85 * TABLE7_FGDACO[k] <= length <= TABLE7_FGDACO[k]


@pytest.mark.parametrize("k", [1, 2, 3])
def test_dynamic_scenario_solvable_by_waiting(k, shortest_points):
    """Driving the static optimum after some wait at the start avoids every moving obstacle."""
    dyn = pathzoo.load_scenario(f"fgdaco.scenario{k}")
    path = shortest_points(pathzoo.load_scenario(f"fgdaco.scenario{k}_static"))
    drive = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(path, axis=0), axis=1))]) / dyn.vehicle.cruise_speed
    for wait in np.arange(0.0, 120.0, 0.5):
        timed = np.vstack([path[:1], path])
        times = np.concatenate([[0.0], wait + drive])
        if validate_path(dyn, timed, times):
            return
    pytest.fail("no departure time in [0, 120) s lets the static optimum pass the moving obstacles")


def test_trap_is_a_named_stress_test_not_a_paper_scenario(shortest_points):
    trap = pathzoo.load_scenario("fgdaco.trap")
    s3 = pathzoo.load_scenario("fgdaco.scenario3")
    assert trap.kind == "dynamic" and len(trap.moving_obstacles) == 3
    assert "not from the paper" in trap.metadata["source"]
    assert "Table 5" in s3.metadata["source"] and "fitted" in s3.metadata
    np.testing.assert_array_equal(trap.start, [6.5, 50.5])
    np.testing.assert_array_equal(trap.goal, [55.5, 50.5])
    assert not np.array_equal(trap.occupancy, s3.occupancy)
    # the goal sits inside the C: every route leaves it to the west and turns back
    static = pathzoo.load_scenario("fgdaco.trap_static")
    path = shortest_points(static)
    assert validate_path(static, path)
    assert path[:, 0].max() > 93.0  # around the C's open east side


def test_scenario3_needs_no_u_turn(shortest_points):
    """Along the optimum of scenario 3 the distance to the goal never grows by more than a cell."""
    s = pathzoo.load_scenario("fgdaco.scenario3_static")
    path = shortest_points(s)
    to_goal = np.linalg.norm(path - s.goal, axis=1)
    assert np.all(np.diff(to_goal) <= 1.0)
