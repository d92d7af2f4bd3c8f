"""Readers for the MovingAI benchmark formats: ``.map`` grids and ``.scen`` problem lists.

Format reference: N. Sturtevant, "Benchmarks for Grid-Based Pathfinding",
IEEE TCIAIG 4(2), 2012. Passable characters are ``.``, ``G`` and ``S``;
blocked are ``@``, ``O``, ``T`` and ``W``. Any other character is an error.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path, PureWindowsPath

import numpy as np

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.core.scenario import Scenario
from pathzoo.io.provenance import file_record
from pathzoo.io.text import read_lines

__all__ = ["read_map", "read_scen", "scenarios_from_scen", "ScenProblem", "PASSABLE", "BLOCKED"]

PASSABLE = frozenset(".GS")
BLOCKED = frozenset("@OTW")


def read_map(path: str | Path) -> np.ndarray:
    """Read a MovingAI ``.map`` file into a boolean ``(H, W)`` array, True = blocked.

    Raises
    ------
    InvalidScenarioError
        Naming the file and the header field or row that is wrong (ragged rows,
        unknown characters, missing header lines).
    """
    path = Path(path)
    src = str(path)
    lines = read_lines(path)
    header: dict[str, str] = {}
    i = 0
    while i < len(lines) and lines[i].strip() != "map":
        parts = lines[i].split()
        if len(parts) == 2:
            header[parts[0]] = parts[1]
        elif lines[i].strip():
            raise InvalidScenarioError(f"unexpected header line {i + 1}: {lines[i]!r}", source=src, field="header")
        i += 1
    if i == len(lines):
        raise InvalidScenarioError("no 'map' line after the header", source=src, field="map")
    try:
        height, width = int(header["height"]), int(header["width"])
    except KeyError as exc:
        raise InvalidScenarioError("missing in header", source=src, field=exc.args[0]) from None
    except ValueError:
        raise InvalidScenarioError("height and width must be integers", source=src, field="height/width") from None
    if height < 1 or width < 1:
        raise InvalidScenarioError(f"must be positive, got {height}x{width}", source=src, field="height/width")
    rows = [ln.rstrip("\r\n") for ln in lines[i + 1 :]]
    while rows and not rows[-1].strip():
        rows.pop()
    if len(rows) != height:
        raise InvalidScenarioError(f"header says {height} rows, found {len(rows)}", source=src, field="height")
    grid = np.zeros((height, width), dtype=bool)
    for r, row in enumerate(rows):
        if len(row) != width:
            raise InvalidScenarioError(
                f"row {r} has {len(row)} characters, header says width {width} (ragged rows)", source=src, field=f"map row {r}"
            )
        unknown = set(row) - PASSABLE - BLOCKED
        if unknown:
            raise InvalidScenarioError(
                f"unknown map character(s) {sorted(unknown)} in row {r}", source=src, field=f"map row {r}"
            )
        grid[r] = [ch in BLOCKED for ch in row]
    return grid


@dataclass(frozen=True)
class ScenProblem:
    """One problem line of a ``.scen`` file (cell indices, optimal length in cells)."""

    index: int
    bucket: int
    map_name: str
    width: int
    height: int
    start_col: int
    start_row: int
    goal_col: int
    goal_row: int
    optimal_length: float


def read_scen(path: str | Path) -> list[ScenProblem]:
    """Read a MovingAI ``.scen`` file (``version 1``), one :class:`ScenProblem` per line.

    Raises
    ------
    InvalidScenarioError
        Naming the file and line that is malformed.
    """
    path = Path(path)
    src = str(path)
    lines = read_lines(path)
    if not lines or not lines[0].startswith("version"):
        raise InvalidScenarioError("first line must be 'version 1'", source=src, field="version")
    problems: list[ScenProblem] = []
    for n, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        parts = line.split("\t") if "\t" in line else line.split()
        if len(parts) != 9:
            raise InvalidScenarioError(f"line {n} has {len(parts)} fields, expected 9", source=src, field=f"line {n}")
        try:
            bucket, width, height, sx, sy, gx, gy = (int(parts[k]) for k in (0, 2, 3, 4, 5, 6, 7))
            opt = float(parts[8])
        except ValueError:
            raise InvalidScenarioError(f"line {n} has a non-numeric field", source=src, field=f"line {n}") from None
        problems.append(ScenProblem(len(problems), bucket, parts[1], width, height, sx, sy, gx, gy, opt))
    return problems


def scenarios_from_scen(path: str | Path) -> list[Scenario]:
    """One ``grid2d`` Scenario per problem line of a MovingAI ``.scen`` file.

    - The map is found next to the ``.scen`` by its base name (``.scen``
      files name it with a path such as ``maps/rooms/8room_000.map``).
    - Ids are ``<map stem>.<index>`` with the 0-based problem index, e.g.
      ``8room_000.17``.
    - Cells are 1 m; start and goal are cell centres (``x`` = column + 0.5,
      ``y`` = row + 0.5) and ``reference_length`` is the file's optimal
      length times the cell size.
    - All problems on one map share one read-only map array, one
      neighbourhood graph and one clearance map: the first problem's
      Scenario is built (graph and clearance included) and the others are
      :meth:`Scenario.with_endpoints` copies.

    Raises
    ------
    InvalidScenarioError
        Naming the ``.scen`` file and the problem: missing map file, a map
        size that differs from the line's, or a start/goal outside the map or
        in an obstacle.
    """
    path = Path(path)
    src = str(path)
    problems = read_scen(path)
    if not problems:
        raise InvalidScenarioError("holds no problems", source=src)
    first: dict[str, Scenario] = {}
    records: dict[str, dict[str, str]] = {}
    scenarios: list[Scenario] = []
    for p in problems:
        name = PureWindowsPath(p.map_name).name  # also splits on "/"
        stem = Path(name).stem
        where = f"problem {p.index} ({p.map_name}): "
        if name not in first:
            map_path = path.parent / name
            if not map_path.is_file():
                raise InvalidScenarioError(
                    f"{where}map file not found next to the .scen: {map_path}", source=src, field="map"
                )
            occupancy = read_map(map_path)
            occupancy.setflags(write=False)
            records[name] = file_record(map_path)
        else:
            occupancy = first[name].occupancy
        if occupancy.shape != (p.height, p.width):
            raise InvalidScenarioError(
                f"{where}the line says {p.width}x{p.height} (width x height), the map is "
                f"{occupancy.shape[1]}x{occupancy.shape[0]}",
                source=src,
                field="map",
            )
        start = np.array([p.start_col + 0.5, p.start_row + 0.5])
        goal = np.array([p.goal_col + 0.5, p.goal_row + 0.5])
        metadata = {"source": src, "map": records[name], "problem_index": p.index, "bucket": p.bucket}
        sid = f"{stem}.{p.index}"
        try:
            if name in first:
                scenario = first[name].with_endpoints(
                    start, goal, id=sid, reference_length=p.optimal_length, metadata=metadata
                )
            else:
                scenario = Scenario(
                    id=sid,
                    kind="grid2d",
                    occupancy=occupancy,
                    cell_size=1.0,
                    start=start,
                    goal=goal,
                    reference_length=p.optimal_length,
                    description=f"MovingAI {stem}, problem {p.index} (bucket {p.bucket})",
                    metadata=metadata,
                )
                scenario.graph  # build them now so every copy shares them
                scenario.clearance
                first[name] = scenario
        except InvalidScenarioError as exc:
            from pathzoo.generators.checks import relocated  # not at the top: the generators import scipy

            raise relocated(exc, source=src, note=where) from None
        scenarios.append(scenario)
    return scenarios
