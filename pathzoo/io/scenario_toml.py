"""Scenario TOML files: check every field and build the Scenario (the format is in docs/scenario-format.md)."""

from __future__ import annotations

import tomllib
from dataclasses import fields
from pathlib import Path
from types import SimpleNamespace
from typing import Any

import numpy as np

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.core.moving import MovingObstacle
from pathzoo.core.rules import TerrainRules
from pathzoo.core.scenario import SCENARIO_KINDS, Scenario
from pathzoo.core.vehicle import VehicleModel
from pathzoo.generators.checks import relocated
from pathzoo.generators.endpoints import with_random_endpoints
from pathzoo.generators.registry import GENERATORS, generate
from pathzoo.generators.volume import terrain_volume
from pathzoo.io.arrays import as_occupancy, load_array
from pathzoo.io.dem import read_elevation
from pathzoo.io.movingai import read_map
from pathzoo.io.provenance import file_record
from pathzoo.io.schema import Table

__all__ = ["read_scenario_toml", "SCENARIO_FORMAT"]

SCENARIO_FORMAT = "pathzoo-scenario-toml/1"
"""Recorded as ``metadata["format"]``."""

_TOP_KEYS = (
    "id", "kind", "description", "cell_size", "start", "goal", "start_cell", "goal_cell", "endpoint_seed",
    "reference_length", "vertical_cell_size", "max_step", "layers",
    "map", "elevation", "vehicle", "rules", "moving_obstacles", "metadata",
)  # fmt: skip
_AIR3D_KEYS = ("vertical_cell_size", "max_step", "layers")
_RESERVED_METADATA = ("source", "format", "map", "elevation", "endpoints")
_OCCUPANCY_SUFFIXES = (".map", ".npy", ".npz")


def _parse(path: Path) -> dict[str, Any]:
    src = str(path)
    try:
        text = path.read_bytes().decode("utf-8")
    except OSError as exc:
        raise InvalidScenarioError(f"cannot read: {exc.strerror or exc}", source=src) from None
    except UnicodeDecodeError:
        raise InvalidScenarioError("is not UTF-8 text", source=src) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InvalidScenarioError(f"malformed TOML: {' '.join(str(exc).split())}", source=src) from None


def _data_file(table: Table, base: Path, suffixes: tuple[str, ...]) -> Path:
    """The existing file named by ``table["file"]``, relative to the scenario file's folder."""
    name = table.string("file")
    path = (base / name).resolve()
    if path.suffix.lower() not in suffixes:
        raise table.error("file", f"{name!r} must end in {', '.join(suffixes)}")
    if not path.is_file():
        raise table.error("file", f"file not found: {path}")
    return path


def _in_data_file(error: InvalidScenarioError, table: Table, key: str) -> InvalidScenarioError:
    """An error about a data file, reported at the scenario file's field that names it (message kept whole)."""
    return InvalidScenarioError(str(error), source=table.source, field=table.field(key))


def _source_of(table: Table) -> None:
    """A table must name exactly one of ``file`` and ``generator``."""
    if ("file" in table) == ("generator" in table):
        raise table.error("file", "give exactly one of 'file' and 'generator'")


def _run_generator(table: Table, cell_size: float, produces: str) -> tuple[np.ndarray, dict[str, Any]]:
    name = table.string("generator")
    info = GENERATORS.get(name)
    if info is not None and info.produces != produces:
        other = "elevation" if produces == "occupancy" else "map"
        raise table.error("generator", f"generator {name!r} makes {info.produces}; put it under [{other}]")
    params = {k: v for k, v in table.data.items() if k != "generator"}
    return generate(name, params, cell_size=cell_size, source=table.source, table=table.name)


def _elevation(table: Table, base: Path, cell_size: float | None, top: Table) -> tuple[np.ndarray, float, dict]:
    """Elevation grid, the cell size it fixes, and its provenance."""
    _source_of(table)
    nodata = table.string("nodata", default="error", choices=("error", "obstacle"))
    if "generator" in table:
        if "nodata" in table:
            raise table.error("nodata", "applies to elevation files only")
        size = 1.0 if cell_size is None else cell_size
        elev, record = _run_generator(table, size, "elevation")
        return elev, size, record
    table.reject_unknown(("file", "key", "units", "nodata"))
    path = _data_file(table, base, (".asc", ".tif", ".tiff", ".npy", ".npz"))
    units = table.string("units", default="auto", choices=("auto", "metres", "degrees"))
    try:
        dem = read_elevation(path, key=table.string("key", default=None), units=units, nodata=nodata)
    except InvalidScenarioError as exc:
        raise _in_data_file(exc, table, "file") from None
    if dem.cell_size is None:
        if "units" in table:
            raise table.error("units", f"{path.name} gives no cell size for units to apply to")
        return dem.elevation, 1.0 if cell_size is None else cell_size, dem.metadata
    if cell_size is not None:
        raise top.error("cell_size", f"{path.name} sets the cell size ({dem.cell_size:g} m); remove cell_size")
    return dem.elevation, dem.cell_size, dem.metadata


def _occupancy(table: Table, base: Path, cell_size: float, ndim: int) -> tuple[np.ndarray, dict]:
    """Obstacle grid and its provenance."""
    _source_of(table)
    if "generator" in table:
        occ, record = _run_generator(table, cell_size, "occupancy")
        return as_occupancy(occ, ndim=ndim, source=table.source, field=table.field("generator")), record
    table.reject_unknown(("file", "key"))
    if table.string("file").lower().endswith(".asc"):
        raise table.error("file", "an .asc file is an elevation grid; put it under [elevation]")
    path = _data_file(table, base, _OCCUPANCY_SUFFIXES)
    key = table.string("key", default=None)
    is_map = path.suffix.lower() == ".map"
    if is_map and key is not None:
        raise table.error("key", "applies to .npz files only")
    try:
        grid = read_map(path) if is_map else load_array(path, key=key)
        occ = as_occupancy(grid, ndim=ndim, source=str(path), field=key or "map")
    except InvalidScenarioError as exc:
        raise _in_data_file(exc, table, "file") from None
    return occ, {**file_record(path), **({"key": key} if key else {})}


def _soil_array(rules: Table, key: str, base: Path, shape: tuple[int, ...]) -> np.ndarray:
    """A per-cell soil array given inline, as a file name, or as ``{file, key}``."""
    value = rules.data[key]
    if isinstance(value, list):
        try:
            arr = np.array(value)
        except ValueError:
            raise rules.error(key, "ragged rows: every row needs the same length") from None
    elif isinstance(value, (str, dict)):
        spec = Table({"file": value} if isinstance(value, str) else value, rules.source, rules.field(key))
        spec.reject_unknown(("file", "key"))
        path = _data_file(spec, base, (".npy", ".npz"))
        try:
            arr = load_array(path, key=spec.string("key", default=None))
        except InvalidScenarioError as exc:
            raise _in_data_file(exc, rules, key) from None
    else:
        raise rules.error(key, "must be a 2-D list, a file name, or a table {file, key}")
    kinds = "iu" if key == "soil_types" else "iuf"
    if arr.dtype.kind not in kinds or (arr.dtype.kind == "f" and not np.isfinite(arr).all()):
        what = "integers" if key == "soil_types" else "finite numbers"
        raise rules.error(key, f"must hold {what}, got dtype {arr.dtype}")
    if arr.shape != shape:
        raise rules.error(key, f"shape {arr.shape} differs from the map {shape}")
    return arr


def _pairs(table: Table, key: str) -> list[tuple[float, ...]]:
    """A list of number pairs, e.g. ``[[upper_slope_deg, weight], ...]`` or ``[[x, y], ...]``."""
    if key not in table:
        raise table.error(key, "missing")
    value = table.data[key]
    if not isinstance(value, list) or not value:
        raise table.error(key, f"must be a non-empty list of [a, b] pairs, got {value!r}")
    return [Table({key: row}, table.source, table.name).vector(key, (2,)) for row in value]


def _rules(table: Table, base: Path, shape: tuple[int, ...]) -> TerrainRules:
    table.reject_unknown(f.name for f in fields(TerrainRules))
    data = dict(table.data)
    for key in ("soil_strength", "soil_types"):
        if key in data:
            data[key] = _soil_array(table, key, base, shape)
    if "slope_weights" in data:
        data["slope_weights"] = _pairs(table, "slope_weights")
    if "min_soil_strength" in data:
        table.number("min_soil_strength")
    names = data.get("soil_names", [])
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise table.error("soil_names", f"must be a list of strings, got {names!r}")
    return TerrainRules.from_mapping(data, source=table.source)


def _moving_obstacles(top: Table) -> tuple[MovingObstacle, ...]:
    items = top.data["moving_obstacles"]
    if not isinstance(items, list):
        raise top.error("moving_obstacles", "must be an array of tables [[moving_obstacles]]")
    obstacles = []
    for i, item in enumerate(items):
        entry = f"moving_obstacles[{i}]"
        if not isinstance(item, dict):
            raise top.error(entry, "must be a table")
        table = Table(item, top.source, entry)
        table.reject_unknown(f.name for f in fields(MovingObstacle))
        try:
            obstacles.append(
                MovingObstacle(
                    radius=table.number("radius"),
                    waypoints=_pairs(table, "waypoints"),
                    speed=table.number("speed"),
                    mode=table.string("mode", default="pingpong"),
                    phase_s=table.number("phase_s", default=0.0),
                )
            )
        except InvalidScenarioError as exc:
            if exc.source is not None:
                raise
            name = (exc.field or "").removeprefix("moving_obstacles.")
            raise relocated(exc, source=top.source, field=f"{entry}.{name}") from None
    return tuple(obstacles)


def _endpoint(top: Table, name: str, dim: int, shape: tuple[int, ...], cell_sizes: np.ndarray) -> np.ndarray | None:
    """``name`` (world metres) or ``name_cell`` (grid index) as world coordinates; ``None`` if neither is given."""
    cell_key = f"{name}_cell"
    if name in top and cell_key in top:
        raise top.error(cell_key, f"give {name} or {cell_key}, not both")
    if name in top:
        return np.array(top.vector(name, (dim,)), dtype=np.float64)
    if cell_key not in top:
        return None
    idx = np.array(top.vector(cell_key, (dim,), integer=True))
    if np.any(idx < 0) or np.any(idx >= np.array(shape)):
        raise top.error(cell_key, f"{idx.tolist()} lies outside the grid of shape {list(shape)}")
    return (idx[::-1] + 0.5) * cell_sizes


def _free_point(top: Table, kind: str, occupancy: np.ndarray, elevation: np.ndarray | None, rules: TerrainRules,
                cell_sizes: np.ndarray) -> np.ndarray:
    """Centre of the first cell that :attr:`Scenario.blocked` leaves free, evaluated before the Scenario exists."""
    probe = SimpleNamespace(kind=kind, occupancy=occupancy, elevation=elevation, rules=rules)
    # the Scenario's own rule, so the two cannot drift apart (``func`` of the cached_property)
    blocked = Scenario.blocked.func(probe)  # type: ignore[attr-defined]
    free = np.argwhere(~blocked)
    if len(free) == 0:
        raise top.error("map", "every cell is blocked; there is no room for a start and a goal")
    return (free[0][::-1] + 0.5) * cell_sizes


def read_scenario_toml(path: str | Path) -> Scenario:
    """Read a scenario TOML file (see ``docs/scenario-format.md``).

    Raises
    ------
    InvalidScenarioError
        One line naming the file and the field: malformed TOML, unknown keys,
        missing or bad values, missing or malformed data files, NaN elevation
        without ``nodata = "obstacle"``, or a start/goal outside the map or in
        an obstacle.
    """
    path = Path(path)
    src = str(path)
    base = path.parent
    top = Table(_parse(path), src)
    top.reject_unknown(_TOP_KEYS)
    scenario_id = top.string("id")
    kind = top.string("kind", choices=SCENARIO_KINDS)
    if kind != "air3d":
        for key in _AIR3D_KEYS:
            if key in top:
                raise top.error(key, "applies to kind 'air3d' only")
    dim = 3 if kind == "air3d" else 2
    cell_size = top.number("cell_size", default=None, low=0.0, low_open=True)
    map_table, elev_table = top.table("map"), top.table("elevation")
    if kind == "terrain" and elev_table is None:
        raise top.error("elevation", "a terrain scenario needs an [elevation] table")
    if map_table is None and elev_table is None:
        raise top.error("map", "missing; give a [map] table (file or generator)")

    metadata: dict[str, Any] = {"source": src, "format": SCENARIO_FORMAT}
    elevation = None
    if elev_table is not None:
        elevation, cell_size, metadata["elevation"] = _elevation(elev_table, base, cell_size, top)
    cell_size = 1.0 if cell_size is None else float(cell_size)

    vcs = float(top.number("vertical_cell_size", low=0.0, low_open=True)) if kind == "air3d" else None
    occupancy = None
    if map_table is not None:
        occupancy, metadata["map"] = _occupancy(map_table, base, cell_size, dim)
        if elevation is not None and occupancy.shape[-2:] != elevation.shape:
            raise top.error("elevation", f"shape {elevation.shape} differs from the map {occupancy.shape[-2:]}")
    if kind == "air3d" and elevation is not None and vcs is not None:
        if occupancy is not None and "layers" in top:
            raise top.error("layers", "the [map] volume already sets the number of layers")
        layers = occupancy.shape[0] if occupancy is not None else top.number("layers", low=1, integer=True)
        ground = terrain_volume(elevation, layers, vcs)
        occupancy = ground if occupancy is None else ground | occupancy
    elif "layers" in top:
        raise top.error("layers", "applies to air volumes made from an [elevation] table only")
    if occupancy is None:  # a 2-D map given by its elevation alone: no obstacles but missing data
        assert elevation is not None  # a file without a [map] has an [elevation] (checked above)
        occupancy = np.zeros(elevation.shape, dtype=bool)

    vehicle_table = top.table("vehicle")
    vehicle = VehicleModel.from_mapping(vehicle_table.data, source=src) if vehicle_table else VehicleModel()
    rules_table = top.table("rules")
    rules = _rules(rules_table, base, occupancy.shape[-2:]) if rules_table else TerrainRules()
    moving = _moving_obstacles(top) if "moving_obstacles" in top else ()
    user_meta = top.table("metadata")
    if user_meta is not None:
        for key in _RESERVED_METADATA:
            if key in user_meta:
                raise user_meta.error(key, f"is set by the reader; reserved keys: {', '.join(_RESERVED_METADATA)}")
        metadata.update(user_meta.data)

    cell_sizes = np.array([cell_size, cell_size] + ([vcs] if kind == "air3d" else []))
    start = _endpoint(top, "start", dim, occupancy.shape, cell_sizes)
    goal = _endpoint(top, "goal", dim, occupancy.shape, cell_sizes)
    reference_length = top.number("reference_length", default=None, low=0.0)
    endpoint_seed = top.number("endpoint_seed", default=None, low=0, integer=True)
    generator_seeds = [metadata[t]["seed"] for t in ("map", "elevation") if "generator" in metadata.get(t, {})]
    auto = start is None and goal is None
    if not auto and (start is None or goal is None):
        missing = "start" if start is None else "goal"
        raise top.error(missing, f"missing (the other endpoint is given); give {missing} or {missing}_cell")
    if not auto and endpoint_seed is not None:
        raise top.error("endpoint_seed", "only used when start and goal are not given")
    if auto:
        if endpoint_seed is None and not generator_seeds:
            raise top.error(
                "start", "missing; give start and goal (or start_cell and goal_cell), or endpoint_seed to draw them"
            )
        if reference_length is not None:
            raise top.error("reference_length", "needs a given start and goal")
        start = goal = _free_point(top, kind, occupancy, elevation, rules, cell_sizes)
    assert start is not None and goal is not None  # both given, or placed above
    try:
        scenario = Scenario(
            id=scenario_id,
            kind=kind,
            occupancy=occupancy,
            cell_size=cell_size,
            start=start,
            goal=goal,
            vehicle=vehicle,
            elevation=elevation,
            rules=rules,
            moving_obstacles=moving,
            vertical_cell_size=vcs,
            max_step=top.vector("max_step", (2,), integer=True, default=(1, 1)),
            reference_length=reference_length,
            description=top.string("description", default=""),
            metadata=metadata,
        )
    except InvalidScenarioError as exc:
        if exc.field in ("start", "goal") and f"{exc.field}_cell" in top:
            raise relocated(exc, source=src, field=f"{exc.field}_cell") from None
        raise
    if not auto:
        return scenario
    try:
        return with_random_endpoints(scenario, endpoint_seed if endpoint_seed is not None else generator_seeds[0])
    except InvalidScenarioError as exc:
        raise relocated(exc, source=src) from None
