"""GeoTIFF DEMs through rasterio: nodata to obstacles, cell size in metres from the CRS (pyproj for geographic CRSs).

Install the optional extra: ``pip install "pathzoo[geo]"``. Rows are returned
north first, as for ``.asc`` files. The first band is the elevation, in the
CRS's vertical unit, which is taken to be metres.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.io.arrays import NodataPolicy, as_elevation
from pathzoo.io.dem_grid import DEM
from pathzoo.io.geographic import GridUnits, detect_units, geographic_to_metric
from pathzoo.io.provenance import file_record

__all__ = ["GEOTIFF_SUFFIXES", "read_geotiff"]

GEOTIFF_SUFFIXES = (".tif", ".tiff")
"""File endings read as GeoTIFF."""


def _geodesic_cell(crs: Any, lon: float, lat: float, dlon: float, dlat: float) -> tuple[float, float, str]:
    """East-west and north-south size in metres of one ``dlon x dlat`` cell centred at ``(lon, lat)``.

    Geodesic distances on the CRS's ellipsoid, with :class:`pyproj.Geod`.
    """
    from pyproj import CRS, Geod

    ellipsoid = CRS.from_user_input(crs.to_wkt()).ellipsoid
    if ellipsoid is None:
        raise InvalidScenarioError(f"{crs} has no ellipsoid, so its degrees cannot be measured in metres", field="crs")
    geod = Geod(a=ellipsoid.semi_major_metre, b=ellipsoid.semi_minor_metre)
    _, _, dx = geod.inv(lon - dlon / 2, lat, lon + dlon / 2, lat)
    _, _, dy = geod.inv(lon, lat - dlat / 2, lon, lat + dlat / 2)
    return float(dx), float(dy), f"geodesic cell size at the grid centre on {ellipsoid.name} (pyproj.Geod)"


def read_geotiff(path: str | Path, *, units: GridUnits = "auto", nodata: NodataPolicy = "error") -> "DEM":
    """Read the first band of a GeoTIFF as a :class:`~pathzoo.io.dem_grid.DEM`.

    Parameters
    ----------
    path : path
        A ``.tif``/``.tiff`` file with a north-up (unrotated) geotransform.
    units : {"auto", "metres", "degrees"}
        Only for files without a CRS (then ``auto`` guesses as for ``.asc``).
        With a CRS, the CRS decides: a geographic CRS is resampled to square
        metric cells whose size comes from geodesics on its ellipsoid; a
        projected CRS's linear unit is converted to metres.
    nodata : {"error", "obstacle"}
        What NaN cells *not* declared by the file's nodata value mean. Cells
        equal to the declared nodata value always become obstacles (NaN).

    Raises
    ------
    InvalidScenarioError
        Naming the file: rasterio missing, unreadable file, rotated or
        non-square grid, ``units`` given for a file with a CRS.
    """
    path = Path(path)
    src = str(path)
    try:
        import rasterio
    except ImportError:
        raise InvalidScenarioError('reading GeoTIFF needs rasterio: pip install "pathzoo[geo]"', source=src) from None
    try:
        with rasterio.open(path) as ds:
            band = ds.read(1, masked=True)
            transform, crs, declared_nodata = ds.transform, ds.crs, ds.nodata
    except (rasterio.errors.RasterioError, OSError) as exc:
        raise InvalidScenarioError(f"cannot read as GeoTIFF: {exc}", source=src) from None
    if transform.b != 0 or transform.d != 0:
        raise InvalidScenarioError("rotated or sheared grids are not supported", source=src, field="transform")
    grid = np.ma.getdata(band).astype(np.float64)
    declared = np.ma.getmaskarray(band)
    if transform.e > 0:  # south-up file: make row 0 the northern edge
        grid, declared = grid[::-1], declared[::-1]
    elev = as_elevation(np.where(declared, 0.0, grid), nodata=nodata, source=src, field="band 1").copy()
    elev[declared] = np.nan
    cell_x, cell_y = abs(transform.a), abs(transform.e)
    h, w = grid.shape
    x0 = transform.c
    y_top = transform.f if transform.e < 0 else transform.f + h * transform.e
    x_range, y_range = (x0, x0 + w * cell_x), (y_top - h * cell_y, y_top)
    record: dict[str, Any] = {
        **file_record(path),
        "format": "geotiff",
        "crs": crs.to_string() if crs else None,
        "transform": list(transform)[:6],
        "nodata_value": declared_nodata,
        "nodata_cells": int(declared.sum()) + int(np.isnan(grid[~declared]).sum()),
        "row_0": "north",
    }
    if crs is None:
        resolved = detect_units(cell_x, cell_y, x_range, y_range) if units == "auto" else units
    else:
        if units != "auto":
            raise InvalidScenarioError(f"the file's CRS ({crs.to_string()}) fixes the units; remove units",
                                       source=src, field="units")
        resolved = "degrees" if crs.is_geographic else "metres"
        if not crs.is_geographic:
            factor = crs.linear_units_factor[1]
            cell_x, cell_y = cell_x * factor, cell_y * factor
            record["linear_unit"] = crs.linear_units_factor[0]
    record["units"] = resolved
    if resolved == "metres":
        if not math.isclose(cell_x, cell_y, rel_tol=1e-9):
            raise InvalidScenarioError(f"cells are {cell_x:g} x {cell_y:g} m; only square metric cells are supported",
                                       source=src, field="transform")
        elev.setflags(write=False)
        return DEM(elev, float(cell_x), record)
    lat_c, lon_c = 0.5 * (y_range[0] + y_range[1]), 0.5 * (x_range[0] + x_range[1])
    cell_metres = _geodesic_cell(crs, lon_c, lat_c, cell_x, cell_y) if crs is not None else None
    metric, cell_size, conversion = geographic_to_metric(elev, cell_x, cell_y, lat_c, cell_metres=cell_metres)
    record.update(conversion)
    metric.setflags(write=False)
    return DEM(metric, cell_size, record)
