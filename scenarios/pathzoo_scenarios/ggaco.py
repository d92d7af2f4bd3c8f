"""GGACO pack: real DEMs with the slope-based traversable map of Sangeetha & Ravichandran (2024), section 3.2.1.

Section 3.2.1 computes a slope theta for every point of the terrain matrix
and keeps a point traversable ("surpassing") when ``z_lo < theta < z_hi``;
every other point is an obstacle ("searching"). The bounds depend on the
vehicle and are parameters here (:func:`load`).

- theta is the slope magnitude in degrees from Horn's 3 x 3 finite
  differences, the method of QGIS's slope tool (the paper prepares its
  terrain in QGIS). A missing neighbour (NaN) takes the centre's height.
- Defaults: ``z_lo = -inf`` (theta >= 0, so no cell is excluded for being too
  flat) and ``z_hi = 20 deg``; the paper leaves both open.
- NaN heights (NODATA) are obstacles.
- Start and goal: the free cells of the largest connected traversable
  region nearest to 10 % and 90 % of the map's height and width.
- The vehicle is G-Ant's (30 kg, phi = 2 m/s, b = 0), as GGACO's eq. 16 uses
  phi = 2 m/s; the traversable map replaces climb limits.

Sources (read with :func:`pathzoo.io.read_elevation`, which resamples
geographic grids to square metric cells):

- ``jacksboro``: matplotlib's ``jacksboro_fault_dem.npz`` (3 arc-second),
  344 x 323 cells of 92.66 m after resampling;
- ``frontrange``: ``data/dem/SRTMGL3_40.09_-105.55_40.21_-105.35.asc``
  (SRTM GL3), 144 x 183 cells of 92.66 m;
- ``hugo``: ``data/dem/hugo_site.asc``, 55 x 76 cells of 10 m, with its
  NODATA cells as obstacles.

The paper's five cases are images of 2569 x 1919, 3018 x 2178,
1789 x 1512, 2789 x 2003 and 1568 x 1800 points (read as rows x columns).
``ggaco.case<k>`` reaches each size by resampling a real DEM, recomputed at
load time (no file is stored): the source is cropped about its centre to the
case's aspect ratio, then zoomed with ``scipy.ndimage.zoom`` (order 1,
``grid_mode=True``), which is deterministic. The cell size shrinks by the zoom
factor, so the physical extent and the slopes are those of the real terrain.
"""

from __future__ import annotations

import importlib.util
import math
from functools import lru_cache, partial
from pathlib import Path
from typing import Any

import numpy as np

from pathzoo.core import InvalidParameterError, InvalidScenarioError, Scenario, VehicleModel
from pathzoo.plugins.entries import ScenarioEntry
from pathzoo_scenarios.common import (
    DATA_DIR,
    cell_centre,
    check_choice,
    largest_free_component,
    nearest_cell,
    pack_metadata,
)

__all__ = [
    "PACK_VERSION",
    "SOURCES",
    "CASES",
    "DEFAULT_SLOPE_MIN_DEG",
    "DEFAULT_SLOPE_MAX_DEG",
    "horn_slope_deg",
    "traversable",
    "source_dem",
    "resample_to",
    "load",
    "load_case",
    "entries",
]

PACK_VERSION = 1
DEFAULT_SLOPE_MIN_DEG = -math.inf
DEFAULT_SLOPE_MAX_DEG = 20.0
ENDPOINT_FRACTIONS = ((0.1, 0.1), (0.9, 0.9))
"""(row, column) fractions of the map the start and goal are snapped from."""

SOURCES: dict[str, str] = {
    "jacksboro": "matplotlib sample data jacksboro_fault_dem.npz (3 arc-second DEM, Jacksboro fault, Tennessee)",
    "frontrange": "SRTMGL3_40.09_-105.55_40.21_-105.35.asc (SRTM GL3, Colorado Front Range; via landlab)",
    "hugo": "hugo_site.asc (10 m DEM with NODATA outside the basin; via landlab)",
}

CASES: dict[int, tuple[int, int, str]] = {
    1: (2569, 1919, "jacksboro"),
    2: (3018, 2178, "jacksboro"),
    3: (1789, 1512, "jacksboro"),
    4: (2789, 2003, "jacksboro"),
    5: (1568, 1800, "frontrange"),
}
"""Case number to (rows, columns) of the paper's section 4.1 and the DEM resampled to it."""


def horn_slope_deg(elevation: np.ndarray, cell_size: float) -> np.ndarray:
    """Slope magnitude in degrees by Horn's method (1981); NaN cells stay NaN.

    Border cells repeat their edge, and a NaN neighbour takes the centre's
    height, so cells next to missing data keep a slope. The gradients are
    compiled (:func:`pathzoo_scenarios.horn.horn_gradients`, imported here:
    listing the packs does not load numba) and the angle is NumPy's, both a
    block of rows at a time, so no temporary is as large as the map.
    """
    from pathzoo_scenarios.horn import horn_gradients

    z = np.ascontiguousarray(elevation, dtype=np.float64)
    slope = np.empty(z.shape)
    rows = max(1, _HORN_BLOCK // max(1, z.shape[1]))
    for lo in range(0, z.shape[0], rows):
        dzdx, dzdy = horn_gradients(z, 8.0 * cell_size, lo, min(lo + rows, z.shape[0]))
        slope[lo : lo + rows] = np.degrees(np.arctan(np.hypot(dzdx, dzdy)))
    slope[~np.isfinite(z)] = np.nan
    return slope


_HORN_BLOCK = 1 << 18
"""Cells per block of :func:`horn_slope_deg`."""


def traversable(slope_deg: np.ndarray, slope_min_deg: float, slope_max_deg: float) -> np.ndarray:
    """Surpassing cells of section 3.2.1: ``z_lo < theta < z_hi`` (NaN slopes are not traversable)."""
    with np.errstate(invalid="ignore"):
        return (slope_deg > slope_min_deg) & (slope_deg < slope_max_deg)


@lru_cache(maxsize=None)
def source_dem(source: str) -> tuple[np.ndarray, float, dict[str, Any]]:
    """Elevation (read-only), square cell size in metres and file provenance of a bundled DEM."""
    from pathzoo.io import read_elevation

    check_choice(source, SOURCES, "source")
    path: str | Path
    if source == "jacksboro":
        path = _matplotlib_sample("jacksboro_fault_dem.npz")
    elif source == "frontrange":
        path = DATA_DIR / "dem" / "SRTMGL3_40.09_-105.55_40.21_-105.35.asc"
    else:
        path = DATA_DIR / "dem" / "hugo_site.asc"
    dem = read_elevation(path)
    return dem.elevation, float(dem.cell_size), dict(dem.metadata)


def _matplotlib_sample(name: str) -> str:
    """Path of a file of matplotlib's sample data, as ``matplotlib.cbook.get_sample_data`` gives it.

    Found from the package's location without importing matplotlib (about
    a quarter of a second of the scenario's load time).
    """
    spec = importlib.util.find_spec("matplotlib")
    if spec is None or spec.origin is None:
        raise ModuleNotFoundError("the jacksboro DEM is matplotlib's sample data: matplotlib is not installed")
    return str(Path(spec.origin).with_name("mpl-data") / "sample_data" / name)


def resample_to(elevation: np.ndarray, cell_size: float, shape: tuple[int, int]) -> tuple[np.ndarray, float, dict]:
    """Crop a DEM about its centre to the aspect ratio of ``shape``, then zoom it to exactly ``shape``.

    Returns the resampled grid, its cell size (source cell size times the
    row zoom) and a record of the crop and zoom for ``Scenario.metadata``.
    """
    from scipy import ndimage

    rows, cols = shape
    h, w = elevation.shape
    if rows / cols >= h / w:  # taller than the source: keep every row
        ch, cw = h, max(1, min(w, round(h * cols / rows)))
    else:
        ch, cw = max(1, min(h, round(w * rows / cols))), w
    r0, c0 = (h - ch) // 2, (w - cw) // 2
    crop = np.asarray(elevation[r0 : r0 + ch, c0 : c0 + cw], dtype=np.float64)
    zoom = (rows / ch, cols / cw)
    out = ndimage.zoom(crop, zoom, order=1, mode="nearest", grid_mode=True)
    new_cell = cell_size * ch / rows
    record = {
        "resampled_from_shape": [h, w],
        "crop_rows_cols": [[r0, r0 + ch], [c0, c0 + cw]],
        "zoom": list(zoom),
        "method": "scipy.ndimage.zoom(order=1, mode='nearest', grid_mode=True)",
        "cell_size_source_m": cell_size,
        "anisotropy": abs(zoom[0] / zoom[1] - 1.0),
    }
    return out, new_cell, record


def _build(
    sid: str,
    elevation: np.ndarray,
    cell_size: float,
    slope_min_deg: float,
    slope_max_deg: float,
    description: str,
    meta: dict[str, Any],
) -> Scenario:
    if not slope_min_deg < slope_max_deg:
        raise InvalidParameterError(
            f"slope_min_deg must be below slope_max_deg, got {slope_min_deg!r} and {slope_max_deg!r}"
        )
    slope = horn_slope_deg(elevation, cell_size)
    free = traversable(slope, slope_min_deg, slope_max_deg) & np.isfinite(elevation)
    region = largest_free_component(free)
    if not region.any():
        raise InvalidScenarioError(
            f"no cell has a slope strictly between {slope_min_deg} and {slope_max_deg} deg", source=sid,
            field="slope bounds",
        )
    h, w = free.shape
    (fr0, fc0), (fr1, fc1) = ENDPOINT_FRACTIONS
    start = nearest_cell(region, fr0 * (h - 1), fc0 * (w - 1))
    goal = nearest_cell(region, fr1 * (h - 1), fc1 * (w - 1))
    meta.update(
        slope_method="Horn (1981) 3x3, degrees",
        slope_bounds_deg=[slope_min_deg, slope_max_deg],
        traversable_fraction=float(free.mean()),
        start_cell=list(start),
        goal_cell=list(goal),
    )
    return Scenario(
        id=sid,
        kind="terrain",
        occupancy=~free,
        cell_size=cell_size,
        start=cell_centre(*start, cell_size),
        goal=cell_centre(*goal, cell_size),
        vehicle=VehicleModel(),
        elevation=elevation,
        description=description,
        metadata=meta,
    )


def load(
    source: str, slope_min_deg: float = DEFAULT_SLOPE_MIN_DEG, slope_max_deg: float = DEFAULT_SLOPE_MAX_DEG
) -> Scenario:
    """Build ``ggaco.<source>``: a bundled DEM at its own resolution with the traversable map."""
    elevation, cell, record = source_dem(source)
    meta = pack_metadata(
        "ggaco",
        PACK_VERSION,
        f"Sangeetha & Ravichandran 2024 (GGACO), section 3.2.1; DEM: {SOURCES[source]}",
        dem=record,
    )
    h, w = elevation.shape
    return _build(
        f"ggaco.{source}",
        elevation,
        cell,
        slope_min_deg,
        slope_max_deg,
        f"GGACO traversable map of the {source} DEM, {h}x{w} cells of {cell:.4g} m",
        meta,
    )


def load_case(
    case: int, slope_min_deg: float = DEFAULT_SLOPE_MIN_DEG, slope_max_deg: float = DEFAULT_SLOPE_MAX_DEG
) -> Scenario:
    """Build ``ggaco.case<k>``: a real DEM resampled to the size of the paper's case ``k``."""
    check_choice(case, CASES, "case")
    rows, cols, source = CASES[case]
    elevation, cell, record = source_dem(source)
    resampled, new_cell, how = resample_to(elevation, cell, (rows, cols))
    resampled.setflags(write=False)  # the scenario keeps this array rather than a copy
    meta = pack_metadata(
        "ggaco",
        PACK_VERSION,
        f"Sangeetha & Ravichandran 2024 (GGACO), section 4.1 case {case} size; DEM: {SOURCES[source]}",
        dem=record,
        resampling=how,
        paper_case_shape=[rows, cols],
    )
    return _build(
        f"ggaco.case{case}",
        resampled,
        new_cell,
        slope_min_deg,
        slope_max_deg,
        f"GGACO case {case} size ({rows}x{cols}), {source} DEM resampled to {new_cell:.3g} m cells",
        meta,
    )


def entries() -> list[ScenarioEntry]:
    """Registry entries of the pack."""
    out = [
        ScenarioEntry(
            id=f"ggaco.{source}",
            summary=f"GGACO traversable map (slope < {DEFAULT_SLOPE_MAX_DEG:g} deg) of {what.split(' (')[0]}",
            load=partial(load, source),
            kind="terrain",
        )
        for source, what in SOURCES.items()
    ]
    out += [
        ScenarioEntry(
            id=f"ggaco.case{case}",
            summary=f"GGACO case {case}: {source} DEM resampled to {rows}x{cols} (paper's size), traversable map",
            load=partial(load_case, case),
            kind="terrain",
        )
        for case, (rows, cols, source) in CASES.items()
    ]
    return out
