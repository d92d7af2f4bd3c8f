"""The compiled answer path of the exact searches is what ``centre_path`` gives, bit for bit."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from pathzoo_exact.base import endpoints
from pathzoo_exact.waypoints import path_ends, path_layout, straight_run_ends, waypoints

from pathzoo.core import Scenario
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo.grid.paths import centre_path


def chain(n_nodes: int, nodes: list[int]) -> np.ndarray:
    """Parent links that lead from ``nodes[-1]`` back to ``nodes[0]`` (the source)."""
    parent = np.full(n_nodes, -7, dtype=np.int64)
    parent[nodes[0]] = -1
    for a, b in zip(nodes, nodes[1:]):
        parent[b] = a
    return parent


def with_ends(scenario: Scenario, source: int, target: int, start_off: bool, goal_off: bool) -> Scenario:
    """``scenario`` from cell ``source`` to cell ``target``, each end on its centre or a little off it."""
    centres = scenario.point_of(np.array([source, target]))
    shift = 0.23 * scenario.cell_sizes
    return scenario.with_endpoints(centres[0] + shift * start_off, centres[1] - shift * goal_off, id="ends")


def node_paths(scenario: Scenario) -> list[list[int]]:
    """A one-node path, a straight run, and a run with turns, moved on ``scenario``'s grid until both ends are free."""
    shape, free = scenario.shape, ~scenario.blocked
    runs = [[(0, 0)], [(0, c) for c in range(4)], [(0, 0), (0, 1), (1, 2), (2, 3), (3, 3), (4, 3), (4, 2), (3, 1)]]
    paths = []
    for run in runs:
        cells = np.array(run)
        for corner in itertools.product(*(range(n) for n in shape)):
            moved = np.zeros((len(run), len(shape)), dtype=np.int64) + corner
            moved[:, -2:] += cells  # rows and columns; a volume's run stays in one layer
            if (moved < shape).all() and free[tuple(moved[0])] and free[tuple(moved[-1])]:
                paths.append([int(np.ravel_multi_index(tuple(c), shape)) for c in moved])
                break
    assert len(paths) == len(runs)
    return paths


@pytest.mark.parametrize("kind", ["grid2d", "terrain", "air3d"])
def test_waypoints_are_centre_path_of_the_kept_nodes(kind: str) -> None:
    base = check_scenario(kind)
    dims = np.array((1,) * (3 - len(base.shape)) + tuple(base.shape), dtype=np.int64)
    width = base.shape[1] if kind == "grid2d" else 0
    cases = 0
    for nodes, start_off, goal_off in itertools.product(node_paths(base), (False, True), (False, True)):
        s = with_ends(base, nodes[0], nodes[-1], start_off, goal_off)
        ends = endpoints(s)
        assert (ends.start_on_centre, ends.goal_on_centre) == (not start_off, not goal_off)
        node_arr = np.array(nodes, dtype=np.int64)
        kept = node_arr[straight_run_ends(node_arr, width)] if width else node_arr
        expected = centre_path(s, kept)
        got = waypoints(chain(int(np.prod(base.shape)), nodes), nodes[-1],
                        path_layout(dims, width, ends.start_on_centre, ends.goal_on_centre),
                        path_ends(s.cell_sizes, s.start, s.goal))
        assert got.dtype == expected.dtype and got.shape == expected.shape
        assert got.tobytes() == expected.tobytes()
        cases += 1
    assert cases == 12


def test_straight_runs_lose_their_inner_waypoints_on_grids_only() -> None:
    s = check_scenario("grid2d")
    nodes = node_paths(s)[1]
    ends = path_ends(s.cell_sizes, s.point_of(np.array(nodes[:1]))[0], s.point_of(np.array(nodes[-1:]))[0])
    parent, dims = chain(int(np.prod(s.shape)), nodes), np.array((1, *s.shape))
    assert len(waypoints(parent, nodes[-1], path_layout(dims, s.shape[1], True, True), ends)) == 2
    assert len(waypoints(parent, nodes[-1], path_layout(dims, 0, True, True), ends)) == len(nodes)
