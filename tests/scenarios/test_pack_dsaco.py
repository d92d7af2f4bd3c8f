"""DSACO pack: eq. 1 with Tables 1-3, the 50 x 50 x 2.4 km volume, UAV constraints of sections 2.2 and 5.3."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pathzoo
from pathzoo.rules import validate_path
from pathzoo_scenarios import dsaco

# Tables 1-3 of the paper, typed in again here: (x, y) km, height km, slope (x_s, y_s) km
TABLES = {
    "simple": [((30, 9), 0.66, (4, 3)), ((16, 17), 1.64, (7, 8)), ((35, 32), 1.3, (5, 8))],
    "medium": [((40, 10), 1.8, (4, 3)), ((12, 17), 0.66, (2, 1)), ((21, 25), 1.86, (4, 4)), ((33, 34), 1.64, (7, 8)),
               ((10, 41), 0.3, (5, 8)), ((14, 32), 0.96, (12, 8)), ((6, 26), 1.3, (6, 5)), ((33, 15), 2.3, (4, 12))],
    "complex": [((40, 10), 1.08, (4, 3)), ((35, 45), 0.66, (2, 2)), ((36, 25), 1.86, (3, 5)), ((15, 40), 1.64, (2, 3)),
                ((10, 25), 0.3, (8, 5)), ((33, 44), 1.12, (10, 8)), ((47, 30), 1.6, (6, 6)), ((20, 24), 0.64, (7, 8)),
                ((10, 41), 1.34, (5, 8)), ((14, 32), 0.96, (12, 8)), ((6, 26), 1.3, (6, 5)), ((33, 42), 1.5, (4, 8))],
}
SHIFT_M = np.array([500.0, 500.0, 100.0])  # paper frame = world frame + half a cell


def eq1_km(x, y, peaks):
    return sum(h * math.exp(-((x - xo) ** 2) / xs**2 - ((y - yo) ** 2) / ys**2) for (xo, yo), h, (xs, ys) in peaks)


@pytest.mark.parametrize("env", list(TABLES))
def test_peak_heights_at_peak_centres(env):
    s = pathzoo.load_scenario(f"dsaco.{env}")
    for (xo, yo), h, _ in TABLES[env]:
        # the column whose paper node is the peak centre: x = col + 1 km, y = row + 1 km
        ground_m = s.elevation[yo - 1, xo - 1] + SHIFT_M[2]
        assert ground_m == pytest.approx(1000.0 * eq1_km(xo, yo, TABLES[env]), rel=1e-12)
        assert ground_m >= 1000.0 * h
        # and the world-frame ground under that column's centre is the same number
        centre = np.array([(xo - 0.5) * 1000.0, (yo - 0.5) * 1000.0, 0.0])
        assert s.elevation_at(centre)[0] + SHIFT_M[2] == pytest.approx(ground_m)


@pytest.mark.parametrize("env", list(TABLES))
def test_volume_endpoints_and_steps(env):
    s = pathzoo.load_scenario(f"dsaco.{env}")
    assert s.kind == "air3d"
    assert s.shape == (12, 50, 50)
    np.testing.assert_allclose(s.extent, [50_000.0, 50_000.0, 2_400.0])
    assert (s.cell_size, s.vertical_cell_size) == (1000.0, 200.0)
    assert s.max_step == (2, 1)
    np.testing.assert_allclose(s.start + SHIFT_M, [1000.0, 17000.0, 600.0])
    np.testing.assert_allclose(s.goal + SHIFT_M, [50000.0, 42000.0, 600.0])
    assert s.metadata["choices"]["max_pitch_deg"].startswith(str(s.vehicle.max_pitch_deg))
    assert s.metadata["choices"]["max_turn_deg"].startswith(str(s.vehicle.max_turn_deg))


@pytest.mark.parametrize("env", list(TABLES))
def test_height_above_ground_band(env):
    """A voxel is free exactly when 50 m < height above ground < 2 km at its node."""
    s = pathzoo.load_scenario(f"dsaco.{env}")
    layers, rows, cols = np.indices(s.shape)
    node_z = (layers + 1) * 200.0
    ground = np.array([[1000.0 * eq1_km(c + 1, r + 1, TABLES[env]) for c in range(50)] for r in range(50)])
    agl = node_z - ground[None]
    np.testing.assert_array_equal(~s.occupancy, (agl > 50.0) & (agl < 2000.0))


@pytest.mark.parametrize("env", list(TABLES))
def test_solvable_within_uav_limits(env, shortest_points):
    s = pathzoo.load_scenario(f"dsaco.{env}")
    path = shortest_points(s)
    steps = np.abs(np.diff(s.cell_of(path), axis=0))
    assert steps[:, 1:].max() <= 2 and steps[:, 0].max() <= 1  # at most 2 cells across, 1 cell up or down
    assert validate_path(s, path)  # pitch and turn limits included


def test_pitch_limit_never_cuts_a_lattice_move():
    s = pathzoo.load_scenario("dsaco.simple")
    steepest = math.degrees(math.atan2(200.0, 1000.0))
    assert steepest < s.vehicle.max_pitch_deg
    assert len(s.graph.offsets) == 5 * 5 * 3 - 1
    assert dsaco.PACK_VERSION == s.metadata["pack_version"]
