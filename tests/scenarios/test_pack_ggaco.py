"""GGACO pack: slope-based traversable map (section 3.2.1) on real DEMs, and the paper-size resampled cases."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pathzoo
from pathzoo.rules import validate_path
from pathzoo_scenarios import ggaco

# section 4.1: the five test cases, rows x columns
PAPER_SIZES = {1: (2569, 1919), 2: (3018, 2178), 3: (1789, 1512), 4: (2789, 2003), 5: (1568, 1800)}


def test_horn_slope_of_a_tilted_plane():
    rows, cols = np.mgrid[0:6, 0:7]
    plane = 100.0 + cols * 10.0 * math.tan(math.radians(30.0)) + 0.0 * rows
    slope = ggaco.horn_slope_deg(plane, 10.0)
    np.testing.assert_allclose(slope[1:-1, 1:-1], 30.0)
    plane[2, 3] = np.nan
    slope = ggaco.horn_slope_deg(plane, 10.0)
    assert np.isnan(slope[2, 3]) and np.isfinite(np.delete(slope.ravel(), 2 * 7 + 3)).all()


def test_surpassing_bounds_are_strict_and_parametric():
    theta = np.array([0.0, 5.0, 10.0, 20.0, np.nan])
    np.testing.assert_array_equal(ggaco.traversable(theta, 5.0, 20.0), [False, False, True, False, False])
    np.testing.assert_array_equal(ggaco.traversable(theta, -math.inf, 20.0), [True, True, True, False, False])


@pytest.mark.parametrize("source", ["jacksboro", "frontrange", "hugo"])
def test_real_dem_scenarios(source, shortest_points):
    s = pathzoo.load_scenario(f"ggaco.{source}")
    assert s.kind == "terrain"
    slope = ggaco.horn_slope_deg(s.elevation, s.cell_size)
    free = np.isfinite(s.elevation) & (slope < ggaco.DEFAULT_SLOPE_MAX_DEG)
    np.testing.assert_array_equal(~s.blocked, free)
    assert s.metadata["slope_bounds_deg"] == [ggaco.DEFAULT_SLOPE_MIN_DEG, ggaco.DEFAULT_SLOPE_MAX_DEG]
    assert "sha256" in str(s.metadata["dem"])
    assert validate_path(s, shortest_points(s))


def test_hugo_nodata_cells_are_obstacles(shared_data):
    s = pathzoo.load_scenario("ggaco.hugo")
    grid = np.loadtxt(shared_data / "dem" / "hugo_site.asc", skiprows=6)
    nodata = grid == -9999
    assert nodata.sum() == 2028
    assert s.shape == grid.shape and s.cell_size == 10.0
    assert s.blocked[nodata].all()
    np.testing.assert_array_equal(s.elevation[~nodata], grid[~nodata])


def test_bounds_change_the_map():
    strict = ggaco.load("hugo", slope_max_deg=10.0)
    loose = pathzoo.load_scenario("ggaco.hugo")
    assert strict.blocked.sum() > loose.blocked.sum()
    assert strict.metadata["slope_bounds_deg"] == [-math.inf, 10.0]


@pytest.mark.parametrize("case", sorted(PAPER_SIZES))
def test_case_recipe_reaches_the_paper_size(case):
    rows, cols, source = ggaco.CASES[case]
    assert (rows, cols) == PAPER_SIZES[case]
    elevation, cell, _ = ggaco.source_dem(source)
    out, new_cell, how = ggaco.resample_to(elevation, cell, (rows, cols))
    assert out.shape == (rows, cols)
    assert how["anisotropy"] < 0.005
    # the physical extent is kept: the crop's height in metres equals the case's height in metres
    (r0, r1), _ = how["crop_rows_cols"]
    assert rows * new_cell == pytest.approx((r1 - r0) * cell)
    # order-1 zoom never leaves the source's height range
    assert np.nanmin(elevation) - 1e-6 <= out.min() and out.max() <= np.nanmax(elevation) + 1e-6


def test_case_scenario_construction():
    s = pathzoo.load_scenario("ggaco.case3")
    assert s.shape == PAPER_SIZES[3] and s.kind == "terrain"
    assert s.metadata["paper_case_shape"] == list(PAPER_SIZES[3])
    assert s.metadata["resampling"]["method"].startswith("scipy.ndimage.zoom")
    assert not s.blocked[tuple(s.cell_of(s.start)[0])] and not s.blocked[tuple(s.cell_of(s.goal)[0])]
    again = ggaco.load_case(3)
    np.testing.assert_array_equal(again.elevation, s.elevation)  # deterministic recipe
