"""Reading scenarios from files: scenario TOML, MovingAI maps and scenarios, occupancy arrays and DEMs."""

from pathzoo.io.arrays import as_elevation, as_occupancy, load_array, read_npz
from pathzoo.io.dem import DEM, read_asc, read_elevation
from pathzoo.io.loader import load_scenario_file, load_scenario_files
from pathzoo.io.movingai import read_map, read_scen, scenarios_from_scen
from pathzoo.io.scenario_toml import read_scenario_toml

__all__ = [
    "DEM",
    "as_elevation",
    "as_occupancy",
    "load_array",
    "load_scenario_file",
    "load_scenario_files",
    "read_asc",
    "read_elevation",
    "read_map",
    "read_npz",
    "read_scen",
    "read_scenario_toml",
    "scenarios_from_scen",
]
