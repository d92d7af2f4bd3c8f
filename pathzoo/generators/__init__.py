"""Seeded, versioned map generators: obstacle fields, rooms, mazes and synthetic terrain.

Each generator is a function ``f(shape, seed, **params) -> ndarray`` that
draws all its randomness from ``numpy.random.default_rng(seed)``, so the same
arguments always give the same array, and each module has a
``GENERATOR_VERSION`` that is bumped when that stops being true. Scenario
files call them by name through :data:`GENERATORS` (``[map] generator =
"rooms"``); :func:`pick_endpoints` places a solvable start and goal.
"""

from pathzoo.generators.endpoints import ENDPOINTS_VERSION, pick_endpoints, with_random_endpoints
from pathzoo.generators.fractal import fractal_terrain
from pathzoo.generators.peak_terrain import gaussian_peaks, peaks_elevation
from pathzoo.generators.perfect_maze import maze
from pathzoo.generators.random_field import random_obstacles
from pathzoo.generators.registry import GENERATORS, GeneratorInfo, generate
from pathzoo.generators.room_grid import rooms
from pathzoo.generators.volume import terrain_volume

__all__ = [
    "ENDPOINTS_VERSION",
    "GENERATORS",
    "GeneratorInfo",
    "fractal_terrain",
    "gaussian_peaks",
    "generate",
    "maze",
    "peaks_elevation",
    "pick_endpoints",
    "random_obstacles",
    "rooms",
    "terrain_volume",
    "with_random_endpoints",
]
