"""Geographic (longitude/latitude) grids to square metric cells: detection, formula and resampling."""

from __future__ import annotations

import math
from typing import Any, Literal

import numpy as np

__all__ = ["EARTH_RADIUS_M", "GridUnits", "detect_units", "geographic_to_metric"]

EARTH_RADIUS_M = 6_371_008.8
"""Mean Earth radius (IUGG), metres."""

GridUnits = Literal["auto", "metres", "degrees"]

_MAX_DEGREE_CELL = 0.1
"""Coarsest cell (degrees) that ``auto`` takes for geographic; 0.1 degree is about 11 km."""


def detect_units(
    cell_x: float, cell_y: float, x_range: tuple[float, float], y_range: tuple[float, float] | None
) -> str:
    """Guess whether a grid is geographic.

    ``"degrees"`` when both cell sizes are at most 0.1, the x coordinates lie
    in ``[-180, 360]`` and the y coordinates in ``[-90, 90]``; otherwise
    ``"metres"``. A metric grid with sub-decimetre cells near the origin would
    be mistaken for a geographic one: scenario files can say ``units`` to
    override the guess.
    """
    if y_range is None or max(cell_x, cell_y) > _MAX_DEGREE_CELL:
        return "metres"
    in_lon = -180.0 <= min(x_range) and max(x_range) <= 360.0
    in_lat = -90.0 <= min(y_range) and max(y_range) <= 90.0
    return "degrees" if in_lon and in_lat else "metres"


def geographic_to_metric(
    elevation: np.ndarray,
    dlon: float,
    dlat: float,
    lat_centre: float,
    *,
    cell_metres: tuple[float, float, str] | None = None,
) -> tuple[np.ndarray, float, dict[str, Any]]:
    """Resample a longitude/latitude grid to square cells in metres.

    On a sphere of radius ``R`` (:data:`EARTH_RADIUS_M`), at the latitude
    ``φ_c`` of the grid's centre, a cell spans

    - ``dy = R · radians(dlat)`` metres north-south, and
    - ``dx = R · cos(φ_c) · radians(dlon)`` metres east-west.

    The cell size becomes ``dy`` and rows are kept one to one (row 0 stays the
    first row of the file); each row is linearly interpolated from its
    column spacing ``dx`` to ``dy``, so the grid keeps its east-west extent
    and gets ``floor((ncols - 1) dx / dy) + 1`` columns. A new cell is missing
    (NaN) when either source cell it is interpolated from is missing. The
    spherical formula and the single latitude are within about 0.5 % of the
    ellipsoid over a few tenths of a degree.

    ``cell_metres = (dx, dy, how)`` replaces the spherical formula by cell
    sizes measured otherwise (e.g. geodesics on the CRS's ellipsoid, see
    :func:`pathzoo.io.geotiff.read_geotiff`); ``how`` is recorded.

    Returns
    -------
    elevation : ndarray of float64
        Resampled grid.
    cell_size : float
        ``dy`` in metres.
    record : dict
        The numbers used, for ``Scenario.metadata``.
    """
    if cell_metres is None:
        dy = EARTH_RADIUS_M * math.radians(dlat)
        dx = EARTH_RADIUS_M * math.cos(math.radians(lat_centre)) * math.radians(dlon)
        how = "dy = R*radians(dlat); dx = R*cos(lat_centre)*radians(dlon)"
    else:
        dx, dy, how = cell_metres
    n_cols = elevation.shape[1]
    new_cols = int(math.floor((n_cols - 1) * dx / dy + 1e-9)) + 1
    pos = np.arange(new_cols) * (dy / dx)  # new centres in source-column units
    left = np.minimum(np.floor(pos).astype(np.int64), n_cols - 1)
    right = np.minimum(left + 1, n_cols - 1)
    w = pos - left
    resampled = elevation[:, left] * (1.0 - w) + elevation[:, right] * w
    record = {
        "units": "degrees",
        "earth_radius_m": EARTH_RADIUS_M,
        "latitude_centre_deg": lat_centre,
        "cell_lon_deg": dlon,
        "cell_lat_deg": dlat,
        "cell_dx_m": dx,
        "cell_dy_m": dy,
        "columns_in_file": n_cols,
        "columns_resampled": new_cols,
        "conversion": f"{how}; rows kept, columns linearly resampled from spacing dx to dy",
    }
    return resampled, dy, record
