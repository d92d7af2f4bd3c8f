"""Digital elevation models: ESRI ASCII grids (``.asc``), GeoTIFF (``.tif``) and NumPy DEMs (``.npz``/``.npy``).

Rows are kept in file order, so row 0 is the first data row: the northern
edge for ``.asc`` files, which list rows north to south. Cells equal to a
declared ``NODATA_value`` become NaN, which :attr:`Scenario.blocked` treats as
obstacles. Geographic grids (cell sizes in degrees) are resampled to square
metric cells by :func:`~pathzoo.io.geographic.geographic_to_metric`.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.io.arrays import NodataPolicy, as_elevation, load_array, read_npz, select_array
from pathzoo.io.dem_grid import DEM
from pathzoo.io.geographic import GridUnits, detect_units, geographic_to_metric
from pathzoo.io.geotiff import GEOTIFF_SUFFIXES, read_geotiff
from pathzoo.io.provenance import file_record
from pathzoo.io.text import read_lines

__all__ = ["DEM", "read_asc", "read_elevation", "ASC_HEADER_KEYS"]

ASC_HEADER_KEYS = ("ncols", "nrows", "xllcorner", "xllcenter", "yllcorner", "yllcenter", "cellsize", "nodata_value")
"""Header keywords of an ESRI ASCII grid (case-insensitive)."""

_NPZ_GEOMETRY = ("dx", "dy", "xmin", "xmax", "ymin", "ymax")


def _finish(
    elev: np.ndarray,
    cell_x: float,
    cell_y: float,
    x_range: tuple[float, float],
    y_range: tuple[float, float] | None,
    units: GridUnits,
    *,
    src: str,
    record: dict[str, Any],
) -> DEM:
    """Resolve the units and convert geographic grids; shared by the ``.asc`` and ``.npz`` readers."""
    resolved = detect_units(cell_x, cell_y, x_range, y_range) if units == "auto" else units
    record["units_given"] = units
    if resolved == "metres":
        if cell_x != cell_y:
            raise InvalidScenarioError(
                f"cells are {cell_x} x {cell_y} m; only square metric cells are supported", source=src, field="dx/dy"
            )
        record["units"] = "metres"
        elev.setflags(write=False)
        return DEM(elev, float(cell_x), record)
    if y_range is None:
        raise InvalidScenarioError("a grid in degrees needs its latitudes (ymin, ymax)", source=src, field="ymin/ymax")
    lat_centre = 0.5 * (y_range[0] + y_range[1])
    metric, cell_size, conversion = geographic_to_metric(elev, cell_x, cell_y, lat_centre)
    record.update(conversion)
    metric.setflags(write=False)
    return DEM(metric, cell_size, record)


def _is_number(token: str) -> bool:
    try:
        float(token)
    except ValueError:
        return False
    return True


def read_asc(path: str | Path, *, units: GridUnits = "auto", nodata: NodataPolicy = "error") -> DEM:
    """Read an ESRI ASCII grid.

    Parameters
    ----------
    path : path
        The ``.asc`` file: header lines ``ncols``, ``nrows``,
        ``xllcorner|xllcenter``, ``yllcorner|yllcenter``, ``cellsize`` and an
        optional ``NODATA_value``, then ``nrows x ncols`` numbers, rows north
        to south.
    units : {"auto", "metres", "degrees"}
        Unit of ``cellsize`` and the corner; ``auto`` guesses with
        :func:`~pathzoo.io.geographic.detect_units`.
    nodata : {"error", "obstacle"}
        What NaN values *not* declared by ``NODATA_value`` mean.

    Raises
    ------
    InvalidScenarioError
        Naming the file and the header key or data problem.
    """
    path = Path(path)
    src = str(path)
    lines = read_lines(path)
    header: dict[str, float] = {}
    i = 0
    while i < len(lines) and not _is_number(lines[i].split()[0] if lines[i].split() else "0"):
        parts = lines[i].split()
        key = parts[0].lower()
        if key not in ASC_HEADER_KEYS or len(parts) != 2:
            raise InvalidScenarioError(
                f"unexpected header line {i + 1}: {lines[i]!r}; allowed keys: {', '.join(ASC_HEADER_KEYS)}",
                source=src,
                field="header",
            )
        try:
            header[key] = float(parts[1])
        except ValueError:
            raise InvalidScenarioError(f"not a number: {parts[1]!r}", source=src, field=parts[0]) from None
        i += 1
    for key in ("ncols", "nrows", "cellsize"):
        if key not in header:
            raise InvalidScenarioError("missing from the header", source=src, field=key)
    n_cols, n_rows, cell = header["ncols"], header["nrows"], header["cellsize"]
    for key, value in (("ncols", n_cols), ("nrows", n_rows)):
        if value != int(value) or value < 1:
            raise InvalidScenarioError(f"must be a positive integer, got {value:g}", source=src, field=key)
    if not cell > 0:
        raise InvalidScenarioError(f"must be positive, got {cell:g}", source=src, field="cellsize")
    corner: dict[str, float] = {}
    for axis in ("x", "y"):
        given = [k for k in (f"{axis}llcorner", f"{axis}llcenter") if k in header]
        if len(given) != 1:
            raise InvalidScenarioError(
                "the header needs exactly one of them", source=src, field=f"{axis}llcorner/{axis}llcenter"
            )
        corner[axis] = header[given[0]] - (0.5 * cell if given[0].endswith("center") else 0.0)
    try:
        values = np.array(" ".join(lines[i:]).split(), dtype=np.float64)
    except ValueError as exc:
        raise InvalidScenarioError(f"non-numeric value in the data: {exc}", source=src, field="data") from None
    n_rows, n_cols = int(n_rows), int(n_cols)
    if values.size != n_rows * n_cols:
        raise InvalidScenarioError(
            f"header says {n_rows} x {n_cols} = {n_rows * n_cols} values, found {values.size}", source=src, field="data"
        )
    grid = values.reshape(n_rows, n_cols)
    declared = np.zeros(grid.shape, dtype=bool)
    if "nodata_value" in header:
        value = header["nodata_value"]
        declared = np.isnan(grid) if np.isnan(value) else grid == value
    elev = as_elevation(np.where(declared, 0.0, grid), nodata=nodata, source=src, field="data").copy()
    elev[declared] = np.nan
    record: dict[str, Any] = {
        **file_record(path),
        "format": "esri-ascii",
        "header": header,
        "nodata_cells": int(declared.sum()) + int(np.isnan(grid).sum()),
        "row_0": "north (first data row)",
    }
    x_range = (corner["x"], corner["x"] + n_cols * cell)
    y_range = (corner["y"], corner["y"] + n_rows * cell)
    return _finish(elev, cell, cell, x_range, y_range, units, src=src, record=record)


def read_elevation(
    path: str | Path, *, key: str | None = None, units: GridUnits = "auto", nodata: NodataPolicy = "error"
) -> DEM:
    """Read an elevation grid from ``.asc``, ``.tif``/``.tiff`` (:func:`~pathzoo.io.geotiff.read_geotiff`), ``.npz`` or ``.npy``.

    An ``.npz`` DEM holds the grid (``key``, default ``"elevation"`` or the
    only array) and may hold scalar ``dx``/``dy`` (cell size along columns and
    rows) with ``xmin``/``xmax``/``ymin``/``ymax`` (extent, needed for the
    latitude of grids in degrees), as matplotlib's ``jacksboro_fault_dem.npz``
    does. Without ``dx``/``dy`` (and for ``.npy``) the cell size is not known:
    :attr:`DEM.cell_size` is ``None``.

    Raises
    ------
    InvalidScenarioError
        Naming the file and the problem.
    """
    path = Path(path)
    src = str(path)
    suffix = path.suffix.lower()
    if suffix == ".asc":
        if key is not None:
            raise InvalidScenarioError("'key' applies to .npz files only", source=src, field="key")
        return read_asc(path, units=units, nodata=nodata)
    if suffix in GEOTIFF_SUFFIXES:
        if key is not None:
            raise InvalidScenarioError("'key' applies to .npz files only", source=src, field="key")
        return read_geotiff(path, units=units, nodata=nodata)
    if suffix not in (".npy", ".npz"):
        raise InvalidScenarioError("an elevation file must be .asc, .tif, .tiff, .npy or .npz", source=src)
    if suffix == ".npy":
        grid = load_array(path, key=key)
        return DEM(as_elevation(grid, nodata=nodata, source=src, field="elevation"), None, file_record(path))
    arrays = read_npz(path)
    geometry: dict[str, float] = {}
    for name in _NPZ_GEOMETRY:
        if name in arrays:
            value = arrays.pop(name)
            if value.shape != () or value.dtype.kind not in "iuf":
                raise InvalidScenarioError(f"must be a scalar number, got shape {value.shape}", source=src, field=name)
            geometry[name] = float(value)
    if key is None and "elevation" in arrays:
        key = "elevation"
    key, grid = select_array(arrays, key, source=src)
    elev = as_elevation(grid, nodata=nodata, source=src, field=key).copy()
    record = {**file_record(path), "format": "npz", "key": key, "geometry": geometry}
    if "dx" not in geometry and "dy" not in geometry:
        elev.setflags(write=False)
        return DEM(elev, None, record)
    if "dx" not in geometry or "dy" not in geometry or not (geometry["dx"] > 0 and geometry["dy"] > 0):
        raise InvalidScenarioError("dx and dy must both be given and positive", source=src, field="dx/dy")
    x_range = (geometry.get("xmin", 0.0), geometry.get("xmax", 0.0))
    y_range = (geometry["ymin"], geometry["ymax"]) if "ymin" in geometry and "ymax" in geometry else None
    return _finish(elev, geometry["dx"], geometry["dy"], x_range, y_range, units, src=src, record=record)
