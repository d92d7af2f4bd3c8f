"""The encodings: waypoint and spline decoding, initialisation, and the grid-move walk."""

import numpy as np
import pytest

from pathzoo.rules import validate_path
from pathzoo.testing import check_scenario
from pathzoo_baselines.encodings import make_encoding

BASE = {"waypoints": 4, "spline_samples": 30, "penalty": 1.0, "moves_factor": 2.0}


@pytest.mark.parametrize("encoding", ["waypoints", "spline"])
def test_continuous_paths_run_exactly_from_start_to_goal_inside_the_map(encoding):
    scenario = check_scenario("grid2d")
    enc = make_encoding(scenario, {**BASE, "encoding": encoding})
    genes = np.random.default_rng(0).uniform(-5, 20, (50, enc.n_genes))  # partly outside the map: clipped
    paths = enc.polylines(genes)
    assert paths.shape == (50, 6 if encoding == "waypoints" else 30, 2)
    assert np.array_equal(paths[:, 0], np.broadcast_to(scenario.start, (50, 2)))
    assert np.array_equal(paths[:, -1], np.broadcast_to(scenario.goal, (50, 2)))
    assert scenario.in_bounds(paths.reshape(-1, 2)).all()


def test_spline_passes_near_its_control_points_only_by_approximation():
    scenario = check_scenario("grid2d")
    enc = make_encoding(scenario, {**BASE, "encoding": "spline", "waypoints": 1})
    control = np.array([[5.0, 9.0]])
    path = enc.path(control)
    # a clamped quadratic through start, c, goal: the curve bends towards c but stays strictly inside the hull
    assert 1.7 < path[:, 1].max() < 9.0


def test_initial_points_are_ordered_along_the_start_goal_axis():
    scenario = check_scenario("grid2d")
    enc = make_encoding(scenario, {**BASE, "encoding": "waypoints"})
    genes = enc.initial(np.random.default_rng(1), 20).reshape(20, 4, 2)
    along = (genes - scenario.start) @ (scenario.goal - scenario.start)
    assert np.all(np.diff(along, axis=1) >= 0)
    assert np.all((genes >= 0) & (genes < scenario.extent))


def test_grid_walk_follows_graph_edges_without_loops():
    scenario = check_scenario("grid2d")
    enc = make_encoding(scenario, {**BASE, "encoding": "grid"})
    rng = np.random.default_rng(2)
    detour = np.array([6] * 7 + [0] * 7 + [2] * 7 + [4, 0] * 10)  # S, E, N round the wall; loops after the goal
    wobble = np.array([0, 4] * 20)  # E, W, E, W, ...: every step back cuts a loop
    hand_made = np.stack([np.resize(detour, enc.n_genes), np.resize(wobble, enc.n_genes)])
    genes = np.concatenate([hand_made, rng.integers(0, 8, (100, enc.n_genes)), enc.initial(rng, 100)])
    cost, violation = enc.evaluate(genes)
    assert violation[0] == 0 and cost[0] == pytest.approx(21.0)  # 21 straight moves of 1 m
    assert len(enc.path(genes[1])) <= 3  # the wobble ends one cell from where it started
    graph = scenario.graph
    reached = 0
    for g, c, v in zip(genes, cost, violation):
        path = enc.path(g)
        offset = path / scenario.cell_size - 0.5
        is_centre = np.all(np.abs(offset - np.round(offset)) < 1e-12, axis=1)
        assert is_centre[1:-1].all()  # only an exact start or goal may be an extra, off-centre point
        walked = path[is_centre] if v == 0 else path[is_centre][:-1]  # an unfinished walk gets the goal appended
        nodes = scenario.node_of(walked)
        assert len(set(nodes.tolist())) == len(nodes)  # no cell twice: loops were cut
        for a, b in zip(nodes[:-1], nodes[1:]):
            assert b in graph.neighbours(a)
        if v == 0:
            reached += 1
            assert validate_path(scenario, path)
            lengths = [graph.length[graph.indptr[a] + np.flatnonzero(graph.neighbours(a) == b)[0]]
                       for a, b in zip(nodes[:-1], nodes[1:])]
            assert c == pytest.approx(sum(lengths))
        else:
            assert c > np.hypot(*scenario.extent)
    assert reached > 0


@pytest.mark.slow
def test_grid_genes_aim_at_the_goal_half_of_the_time():
    scenario = check_scenario("grid2d")  # goal due east of the start: gene 0
    enc = make_encoding(scenario, {**BASE, "encoding": "grid"})
    genes = enc.initial(np.random.default_rng(3), 400)
    share = np.mean(genes == 0)
    assert 0.5 < share < 0.65  # 1/2 aimed + 1/16 uniform draws of east
