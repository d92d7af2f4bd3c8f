"""The penalised cost agrees with the harness's judge: zero violation exactly for paths it accepts."""

import numpy as np
import pytest

from pathzoo import Scenario, VehicleModel
from pathzoo.grid.segments import count_blocked_cells_2d, segment_blocked_2d
from pathzoo.grid.terrain import segment_profile
from pathzoo.rules import validate_path
from pathzoo.testing import check_scenario
from pathzoo_baselines.cost import PathCost


def _random_map(rng, shape=(12, 14), density=0.25):
    occ = rng.random(shape) < density
    occ[0, 0] = occ[-1, -1] = False
    return occ


def test_count_is_zero_exactly_when_the_segment_is_free():
    rng = np.random.default_rng(0)
    blocked = _random_map(rng)
    h, w = blocked.shape
    # random segments, plus segments between cell centres and along cell borders (the corner rule's cases)
    pts = np.concatenate([rng.uniform(0, [w, h], (400, 2)), rng.integers(0, [w, h], (400, 2)) + 0.5,
                          rng.integers(0, [w + 1, h + 1], (400, 2)).astype(float)])
    pairs = rng.integers(0, len(pts), (3000, 2))
    n_blocked = 0
    for i, j in pairs:
        (x0, y0), (x1, y1) = pts[i], pts[j]
        count = count_blocked_cells_2d(blocked, x0, y0, x1, y1)
        assert (count == 0) == (not segment_blocked_2d(blocked, x0, y0, x1, y1))
        n_blocked += count > 0
    assert 0 < n_blocked < len(pairs)


def test_count_grows_with_the_depth_of_the_cut():
    blocked = np.zeros((5, 10), dtype=bool)
    blocked[:, 3:7] = True
    assert count_blocked_cells_2d(blocked, 2.5, 2.5, 4.5, 2.5) == 2  # cols 3, 4
    assert count_blocked_cells_2d(blocked, 2.5, 2.5, 7.5, 2.5) == 4  # cols 3..6


def _random_polylines(rng, scenario, n, k):
    inner = rng.uniform(0, 1, (n, k, 2)) * scenario.extent
    ends = np.broadcast_to(scenario.start, (n, 1, 2)), np.broadcast_to(scenario.goal, (n, 1, 2))
    return np.concatenate([ends[0], inner, ends[1]], axis=1)


@pytest.mark.parametrize("kind", ["grid2d", "terrain"])
def test_zero_violation_iff_the_validator_accepts(kind):
    rng = np.random.default_rng(1)
    scenario = check_scenario(kind)
    cost = PathCost(scenario, penalty=1.0)
    paths = _random_polylines(rng, scenario, 800, 2)
    total, violation = cost(paths)
    verdicts = np.array([bool(validate_path(scenario, p)) for p in paths])
    assert verdicts.any() and (~verdicts).any()
    np.testing.assert_array_equal(violation == 0, verdicts)
    feasible = violation == 0
    diag = np.hypot(*scenario.extent)
    assert np.all(total[~feasible] >= diag)  # every violation costs at least one map diagonal


def test_slope_violation_is_counted_on_steep_terrain():
    rows, cols = np.mgrid[0:12, 0:12]
    elevation = 0.8 * cols + 0.3 * np.sin(rows)  # about 39 degrees along x on 1 m cells
    scenario = Scenario(
        id="steep", kind="terrain", occupancy=np.zeros((12, 12), bool), elevation=elevation, cell_size=1.0,
        start=[0.5, 0.5], goal=[11.5, 11.5], vehicle=VehicleModel(max_climb_deg=30.0, max_descent_deg=30.0),
    )
    rng = np.random.default_rng(2)
    paths = _random_polylines(rng, scenario, 500, 2)
    _, violation = PathCost(scenario, penalty=1.0)(paths)
    verdicts = np.array([bool(validate_path(scenario, p)) for p in paths])
    assert (violation > 0).any()
    np.testing.assert_array_equal(violation == 0, verdicts)


def test_terrain_length_is_the_3d_length_of_the_profile():
    scenario = check_scenario("terrain")
    rng = np.random.default_rng(3)
    paths = _random_polylines(rng, scenario, 20, 3)
    total, violation = PathCost(scenario, penalty=1.0)(paths)
    for path, t, v in zip(paths, total, violation):
        pieces = [segment_profile(scenario.elevation, a, b, scenario.cell_size)[0] for a, b in zip(path[:-1], path[1:])]
        expected = sum(p.sum() for p in pieces)
        weight = np.hypot(*scenario.extent)
        assert t - weight * v == pytest.approx(expected, rel=1e-12)


def test_turn_limit_violations_are_counted():
    occ = np.zeros((10, 10), dtype=bool)
    scenario = Scenario(id="turny", kind="grid2d", occupancy=occ, cell_size=1.0, start=[0.5, 0.5], goal=[9.5, 0.5],
                        vehicle=VehicleModel(max_turn_deg=60.0))
    sharp = np.array([[[0.5, 0.5], [5.0, 8.0], [9.5, 0.5]]])  # about 115 degrees at the apex
    gentle = np.array([[[0.5, 0.5], [5.0, 2.0], [9.5, 0.5]]])
    _, v_sharp = PathCost(scenario, 1.0)(sharp)
    _, v_gentle = PathCost(scenario, 1.0)(gentle)
    assert v_sharp[0] == 1 and not validate_path(scenario, sharp[0])
    assert v_gentle[0] == 0 and validate_path(scenario, gentle[0])
