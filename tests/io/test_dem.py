"""DEM readers: ESRI ASCII grids (real files) and NumPy DEMs, NODATA, and geographic conversion."""

import math

import numpy as np
import pytest
from matplotlib.cbook import get_sample_data

from pathzoo import InvalidScenarioError
from pathzoo.io import read_asc, read_elevation
from pathzoo.io.geographic import EARTH_RADIUS_M

SRTM = "SRTMGL3_40.09_-105.55_40.21_-105.35.asc"


def first_data_row(path):
    lines = path.read_text().splitlines()
    return np.array(lines[6].split(), dtype=float)


def test_hugo_site_nodata_cells_become_nan(shared_data):
    path = shared_data / "dem" / "hugo_site.asc"
    dem = read_asc(path)
    assert dem.elevation.shape == (55, 76) and dem.cell_size == 10.0
    assert np.isnan(dem.elevation).sum() == 2028 == dem.metadata["nodata_cells"]
    assert np.nanmin(dem.elevation) == 1660 and np.nanmax(dem.elevation) == 1711
    row0 = first_data_row(path)
    assert np.array_equal(np.isnan(dem.elevation[0]), row0 == -9999)  # row 0 = first data row (north)
    assert dem.metadata["units"] == "metres" and not dem.elevation.flags.writeable


def test_srtm_degrees_are_converted_to_square_metric_cells(shared_data):
    path = shared_data / "dem" / SRTM
    dem = read_asc(path)
    cs_deg = 0.000833333333
    lat_c = 40.090416666671 + 144 * cs_deg / 2
    dy = EARTH_RADIUS_M * math.radians(cs_deg)
    dx = EARTH_RADIUS_M * math.cos(math.radians(lat_c)) * math.radians(cs_deg)
    assert dem.cell_size == pytest.approx(dy) and 92 < dem.cell_size < 93
    assert dem.elevation.shape == (144, math.floor(239 * dx / dy) + 1)
    assert dem.metadata["latitude_centre_deg"] == pytest.approx(lat_c)
    assert dem.metadata["cell_dx_m"] == pytest.approx(dx)
    # rows kept one to one; column 0 is not moved, the rest is interpolated along the row
    row0 = first_data_row(path)
    assert dem.elevation[0, 0] == row0[0]
    x_src = np.arange(240) * dx
    assert np.allclose(dem.elevation[0], np.interp(np.arange(dem.elevation.shape[1]) * dy, x_src, row0))
    # east-west extent is kept to within one cell
    assert abs(dem.elevation.shape[1] * dy - 240 * dx) < dy


def test_units_can_be_forced(shared_data):
    dem = read_asc(shared_data / "dem" / SRTM, units="metres")
    assert dem.cell_size == pytest.approx(0.000833333333) and dem.elevation.shape == (144, 240)


def test_jacksboro_npz_is_geographic(tmp_path):
    path = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)
    with np.load(path) as raw:
        z, lat = raw["elevation"], 0.5 * (float(raw["ymin"]) + float(raw["ymax"]))
    dem = read_elevation(path)
    assert dem.metadata["units"] == "degrees" and dem.metadata["key"] == "elevation"
    assert dem.metadata["latitude_centre_deg"] == pytest.approx(lat)
    assert dem.elevation.shape[0] == z.shape[0] and dem.elevation.shape[1] < z.shape[1]
    assert np.array_equal(dem.elevation[:, 0], z[:, 0])


def test_npy_dem_has_no_cell_size_and_nan_needs_a_policy(tmp_path):
    z = np.arange(12, dtype=float).reshape(3, 4)
    np.save(tmp_path / "z.npy", z)
    dem = read_elevation(tmp_path / "z.npy")
    assert dem.cell_size is None and np.array_equal(dem.elevation, z)
    z[1, 2] = np.nan
    np.save(tmp_path / "z.npy", z)
    with pytest.raises(InvalidScenarioError, match=r"z.npy: field 'elevation': 1 cells are NaN .*nodata = \"obstacle"):
        read_elevation(tmp_path / "z.npy")
    assert np.isnan(read_elevation(tmp_path / "z.npy", nodata="obstacle").elevation[1, 2])


def test_npz_dem_in_metres(tmp_path):
    np.savez(tmp_path / "d.npz", elevation=np.ones((2, 3)), dx=5.0, dy=5.0)
    assert read_elevation(tmp_path / "d.npz").cell_size == 5.0
    np.savez(tmp_path / "d.npz", elevation=np.ones((2, 3)), dx=5.0, dy=4.0)
    with pytest.raises(InvalidScenarioError, match="d.npz: field 'dx/dy': .*square"):
        read_elevation(tmp_path / "d.npz")
    np.savez(tmp_path / "d.npz", elevation=np.ones((2, 3)), dx=0.001, dy=0.001, xmin=10.0, xmax=10.003)
    with pytest.raises(InvalidScenarioError, match="field 'ymin/ymax'"):
        read_elevation(tmp_path / "d.npz", units="degrees")


HEADER = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 5\nNODATA_value -1\n"


@pytest.mark.parametrize(
    "text, field",
    [
        (HEADER.replace("cellsize 5\n", ""), "cellsize"),
        (HEADER.replace("cellsize 5", "cellsize 0"), "cellsize"),
        (HEADER.replace("ncols 3", "ncols 2.5"), "ncols"),
        (HEADER.replace("xllcorner 0", "xllcenter 0\nxllcorner 0"), "xllcorner/xllcenter"),
        (HEADER.replace("nrows 2", "nrows 2\nrotation 4"), "header"),
        (HEADER + "1 2 3\n4 5\n", "data"),
        (HEADER + "1 2 3\n4 5 x\n", "data"),
        (HEADER + "1 2 3\n4 5 nan\n", "data"),
        (HEADER + "nan 2 3\n4 5 6\n", "data"),
    ],
)
def test_malformed_asc_names_file_and_field(tmp_path, text, field):
    path = tmp_path / "bad.asc"
    path.write_text(text)
    with pytest.raises(InvalidScenarioError, match=rf"bad.asc: field '{field}'"):
        read_asc(path)


def test_asc_nodata_declared_and_cell_centre_corner(tmp_path):
    path = tmp_path / "ok.asc"
    path.write_text(HEADER.replace("xllcorner 0", "xllcenter 2.5") + "1 -1 3\n4 5 6\n")
    dem = read_asc(path)
    assert np.isnan(dem.elevation[0, 1]) and dem.elevation[1, 2] == 6.0 and dem.metadata["nodata_cells"] == 1
    assert dem.metadata["units"] == "metres"
