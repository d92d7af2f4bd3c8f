"""Reading scenarios from files: scenario TOML, MovingAI maps and scenarios, occupancy arrays and DEMs.

The names below are loaded on first use, so ``import pathzoo`` stays light.
"""

from __future__ import annotations

from pathzoo.lazy_names import lazy_getattr

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


__getattr__ = lazy_getattr(__name__, _WHERE)
