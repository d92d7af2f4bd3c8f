"""Reading scenarios from files: scenario TOML, MovingAI maps and scenarios, occupancy arrays and DEMs.

The names below are loaded on first use, so ``import pathzoo`` stays light.
"""

from __future__ import annotations

import importlib
from typing import Any

_WHERE = {
    "DEM": "dem",
    "as_elevation": "arrays",
    "as_occupancy": "arrays",
    "load_array": "arrays",
    "load_scenario_file": "loader",
    "load_scenario_files": "loader",
    "looks_like_path": "paths",
    "read_asc": "dem",
    "read_elevation": "dem",
    "read_map": "movingai",
    "read_npz": "arrays",
    "read_scen": "movingai",
    "read_scenario_toml": "scenario_toml",
    "scenarios_from_scen": "movingai",
}

__all__ = sorted(_WHERE)


def __getattr__(name: str) -> Any:
    if name in _WHERE:
        return getattr(importlib.import_module(f"pathzoo.io.{_WHERE[name]}"), name)
    raise AttributeError(f"module 'pathzoo.io' has no attribute {name!r}")
