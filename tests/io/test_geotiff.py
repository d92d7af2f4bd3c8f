"""GeoTIFF DEMs written by the tests themselves: nodata to obstacles, metres from the CRS, scenario files, show."""

from __future__ import annotations

import math

import numpy as np
import pytest

import rasterio  # the optional extra "geo", part of the test extras
from pyproj import Geod  # noqa: E402
from rasterio.transform import Affine  # noqa: E402

from pathzoo import InvalidScenarioError, load_scenario  # noqa: E402
from pathzoo.cli.main import main  # noqa: E402
from pathzoo.io import read_elevation  # noqa: E402

NODATA = -32768


def from_origin(west, north, xsize, ysize):
    """North-up geotransform (rasterio's own helper warns about its operator)."""
    return Affine(xsize, 0.0, west, 0.0, -ysize, north)


def write_tif(path, data, *, crs, transform, nodata=None, dtype="int16"):
    with rasterio.open(path, "w", driver="GTiff", height=data.shape[0], width=data.shape[1], count=1, dtype=dtype,
                       crs=crs, transform=transform, nodata=nodata) as ds:
        ds.write(data.astype(dtype), 1)
    return path


def terrain(h=30, w=40):
    yy, xx = np.mgrid[0:h, 0:w]
    return (1600 + 3 * xx + 2 * yy).astype(np.int16)


def test_geographic_int16_with_nodata(tmp_path):
    data = terrain()
    data[5, 7] = NODATA
    dlon = dlat = 1 / 1200  # 3 arc-seconds, as SRTM
    path = write_tif(tmp_path / "dem.tif", data, crs="EPSG:4326", transform=from_origin(-105.55, 40.21, dlon, dlat),
                     nodata=NODATA)
    dem = read_elevation(path)
    lat_c = 40.21 - 30 * dlat / 2
    geod = Geod(ellps="WGS84")
    dy = geod.inv(-105.5, lat_c - dlat / 2, -105.5, lat_c + dlat / 2)[2]
    dx = geod.inv(-105.5 - dlon / 2, lat_c, -105.5 + dlon / 2, lat_c)[2]
    assert dem.cell_size == pytest.approx(dy, rel=1e-9) and 92 < dem.cell_size < 93
    assert dem.elevation.shape == (30, math.floor(39 * dx / dy) + 1)
    assert dem.metadata["format"] == "geotiff" and dem.metadata["crs"] == "EPSG:4326"
    assert dem.metadata["nodata_cells"] == 1 and np.isnan(dem.elevation[5]).any()
    assert np.nanmin(dem.elevation) >= 1600 and not dem.elevation.flags.writeable
    assert dem.elevation[0, 0] == 1600  # row 0 is the northern edge, as written


def test_projected_crs_gives_metric_cells_and_blocked_nodata(tmp_path):
    data = terrain()
    data[3, 4] = NODATA
    path = write_tif(tmp_path / "utm.tif", data, crs="EPSG:32613", transform=from_origin(450000, 4450000, 30, 30),
                     nodata=NODATA)
    dem = read_elevation(path)
    assert dem.cell_size == 30.0 and dem.elevation.shape == (30, 40) and np.isnan(dem.elevation[3, 4])
    toml = tmp_path / "s.toml"
    toml.write_text('id = "geo.utm"\nkind = "terrain"\nstart_cell = [1, 1]\ngoal_cell = [28, 38]\n'
                    '[elevation]\nfile = "utm.tif"\n')
    sc = load_scenario(toml)
    assert sc.cell_size == 30.0 and sc.blocked[3, 4] and sc.blocked.sum() == 1


def test_bad_files_are_one_line_errors(tmp_path):
    data = terrain()
    rect = write_tif(tmp_path / "rect.tif", data, crs="EPSG:32613", transform=from_origin(0, 0, 30, 20))
    with pytest.raises(InvalidScenarioError, match="only square metric cells"):
        read_elevation(rect)
    with pytest.raises(InvalidScenarioError, match="CRS .* fixes the units"):
        read_elevation(rect, units="metres")
    junk = tmp_path / "junk.tif"
    junk.write_bytes(b"not a tiff")
    with pytest.raises(InvalidScenarioError, match="junk.tif.*cannot read as GeoTIFF"):
        read_elevation(junk)


def test_show_draws_a_geotiff_scenario(tmp_path, capsys):
    write_tif(tmp_path / "utm.tif", terrain(), crs="EPSG:32613", transform=from_origin(450000, 4450000, 30, 30))
    toml = tmp_path / "s.toml"
    toml.write_text('id = "geo.utm"\nkind = "terrain"\nstart_cell = [1, 1]\ngoal_cell = [28, 38]\n'
                    '[elevation]\nfile = "utm.tif"\n')
    out = tmp_path / "s.png"
    assert main(["show", str(toml), "-o", str(out)]) == 0
    assert out.read_bytes()[:4] == b"\x89PNG"
