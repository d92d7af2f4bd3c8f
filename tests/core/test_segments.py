"""The closed-cell segment rule: exact, and equal to the MovingAI corner rule for grid moves."""

import numpy as np
import pytest

from pathzoo.grid.segments import (
    first_blocked_cell_2d,
    segment_blocked_2d,
    segment_blocked_3d,
    to_cell_units,
    touched_cells_2d,
    touched_cells_3d,
)


def test_diagonal_move_touches_all_four_cells():
    cells = {tuple(c) for c in touched_cells_2d(0.5, 0.5, 1.5, 1.5)}
    assert cells == {(0, 0), (0, 1), (1, 0), (1, 1)}


def test_straight_move_touches_only_its_two_cells():
    assert {tuple(c) for c in touched_cells_2d(0.5, 0.5, 1.5, 0.5)} == {(0, 0), (0, 1)}
    assert {tuple(c) for c in touched_cells_2d(0.5, 0.5, 0.5, 2.5)} == {(0, 0), (1, 0), (2, 0)}


@pytest.mark.parametrize("blocked_cell", [(0, 1), (1, 0)])
def test_diagonal_blocked_by_either_orthogonal_neighbour(blocked_cell):
    grid = np.zeros((2, 2), dtype=bool)
    grid[blocked_cell] = True
    assert segment_blocked_2d(grid, 0.5, 0.5, 1.5, 1.5)
    assert segment_blocked_2d(grid, 1.5, 1.5, 0.5, 0.5)  # direction does not matter


def test_free_diagonal_passes():
    grid = np.zeros((2, 2), dtype=bool)
    assert not segment_blocked_2d(grid, 0.5, 0.5, 1.5, 1.5)


def test_grazing_a_corner_of_a_blocked_cell_is_blocked():
    # (0.5, 0.5) -> (2.5, 2.5) passes through the point (2, 2), a corner of
    # cell (row 2, col 1), which occupies x in [1, 2] and y in [2, 3]
    grid = np.zeros((3, 3), dtype=bool)
    grid[2, 1] = True
    assert segment_blocked_2d(grid, 0.5, 0.5, 2.5, 2.5)
    grid[2, 1] = False
    grid[2, 0] = True  # nowhere near the segment
    assert not segment_blocked_2d(grid, 0.5, 0.5, 2.5, 2.5)


def test_any_angle_segment_matches_dense_sampling_when_not_near_corners():
    rng = np.random.default_rng(3)
    grid = rng.random((20, 20)) < 0.25
    for _ in range(300):
        x0, y0, x1, y1 = rng.uniform(0.01, 19.99, 4)
        exact = {tuple(c) for c in touched_cells_2d(x0, y0, x1, y1)}
        t = np.linspace(0, 1, 20001)
        xs, ys = x0 + t * (x1 - x0), y0 + t * (y1 - y0)
        sampled = set(zip(np.floor(ys).astype(int), np.floor(xs).astype(int)))
        assert sampled <= exact  # every cell the segment passes through is found
        # any extra cell found exactly is one the segment touches within sampling resolution
        for r, c in exact - sampled:
            d = np.min(np.maximum(np.maximum(c - xs, xs - (c + 1)), np.maximum(r - ys, ys - (r + 1))))
            assert d <= 1e-3
        assert segment_blocked_2d(grid, x0, y0, x1, y1) == any(grid[r, c] for r, c in exact if 0 <= r < 20 and 0 <= c < 20)


def test_out_of_grid_counts_as_blocked():
    grid = np.zeros((3, 3), dtype=bool)
    r, c = first_blocked_cell_2d(grid, 0.5, 0.5, 3.5, 0.5)
    assert (r, c) == (0, 3)
    assert segment_blocked_2d(grid, 0.0, 0.5, 1.5, 0.5)  # touches column -1 at x = 0


def test_3d_rule_matches_2d_rule_on_a_single_layer_interior():
    rng = np.random.default_rng(5)
    grid = rng.random((10, 10)) < 0.3
    vol = np.stack([grid, grid, grid])  # the same 2-D map on every layer
    for _ in range(200):
        x0, y0, x1, y1 = rng.uniform(0.5, 9.5, 4)
        p0, p1 = np.array([x0, y0, 1.5]), np.array([x1, y1, 1.5])
        assert segment_blocked_3d(vol, p0, p1) == segment_blocked_2d(grid, x0, y0, x1, y1)


def test_3d_diagonal_touches_all_eight_voxels():
    assert len(touched_cells_3d(np.array([0.5, 0.5, 0.5]), np.array([1.5, 1.5, 1.5]))) == 8


def test_cell_units_are_a_plain_division():
    # no snapping: a point 5e-10 from a cell edge stays there (issue 15)
    u = to_cell_units(np.array([23.0000000005, 13.9999999995]), 1.0)
    assert u[0] == 23.0000000005 and u[1] == 13.9999999995
