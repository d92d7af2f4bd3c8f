"""Loading scenarios from any supported file: scenario TOML, or a MovingAI ``.scen`` problem list."""

from __future__ import annotations

from pathlib import Path

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.core.scenario import Scenario
from pathzoo.io.movingai import scenarios_from_scen
from pathzoo.io.scenario_toml import read_scenario_toml

__all__ = ["load_scenario_file", "load_scenario_files"]

_BARE_MAPS = (".map", ".npy", ".npz", ".asc", ".tif", ".tiff")


def load_scenario_file(path: str | Path) -> Scenario:
    """Load the one scenario a TOML file describes.

    Raises
    ------
    InvalidScenarioError
        The file is missing or malformed (the message names the file and the
        field), or is a ``.scen`` list (use :func:`load_scenario_files`) or a
        bare map, which has no start and goal.
    """
    path = Path(path)
    src = str(path)
    suffix = path.suffix.lower()
    if not path.is_file():
        raise InvalidScenarioError("file not found", source=src)
    if suffix == ".toml":
        return read_scenario_toml(path)
    if suffix == ".scen":
        raise InvalidScenarioError(
            "holds a list of problems; load it with load_scenarios / load_scenario_files", source=src
        )
    if suffix in _BARE_MAPS:
        raise InvalidScenarioError(
            f"a bare {suffix} map has no start and goal (nor kind or cell size); write a scenario TOML with "
            f"[map] file = {path.name!r} (or [elevation] for a DEM) and start/goal or start_cell/goal_cell, "
            "see docs/scenario-format.md",
            source=src,
        )
    raise InvalidScenarioError("unknown scenario file type; use .toml or .scen", source=src)


def load_scenario_files(path: str | Path) -> list[Scenario]:
    """Load every scenario a file describes: one per problem of a ``.scen`` file, or the one of a TOML file.

    Raises
    ------
    InvalidScenarioError
        As :func:`load_scenario_file` and
        :func:`~pathzoo.io.movingai.scenarios_from_scen`.
    """
    path = Path(path)
    if path.suffix.lower() == ".scen" and path.is_file():
        return scenarios_from_scen(path)
    return [load_scenario_file(path)]
