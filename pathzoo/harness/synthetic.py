"""The scenarios a worker warms a planner up on: made in code, never the run's scenario or anything naming it.

A sandboxed or process worker (:mod:`pathzoo.harness.zygote`) warms its
planner up once, before any run, so that numba's compilation (or the load
from its cache) is not charged to a measured run. It must not warm up on
the run's own scenario: a planner could solve it during the untimed
warm-up and keep the answer for the run. So it warms up on these instead:
small maps made here, with contents that owe nothing to any scenario of an
experiment, and ids of their own.

Numba compiles one specialisation per combination of argument types, and
the types a kernel meets follow the scenario's optional parts (terrain
rules with slope weights, soil strength and soil classes; an air volume
with an elevation and a vertical step above one; moving obstacles), so
each kind has variants that together hold every optional part, and each
is loaded the way a run's scenario is: its shared geometry built and its
arrays sealed read-only (:func:`~pathzoo.harness.digest.warm`,
:func:`~pathzoo.harness.sealed.seal`).
"""

from __future__ import annotations

import numpy as np

from pathzoo.core.moving import MovingObstacle
from pathzoo.core.rules import TerrainRules
from pathzoo.core.scenario import Scenario
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo.core.vehicle import VehicleModel
from pathzoo.harness.digest import warm
from pathzoo.harness.sealed import seal

__all__ = ["synthetic_scenarios", "SYNTHETIC_PREFIX"]

SYNTHETIC_PREFIX = "pathzoo.warm-up."
"""The start of every synthetic scenario's id."""


def _terrain_with_rules() -> Scenario:
    rows, cols = np.mgrid[0:12, 0:12]
    elevation = 4.0 * np.sin(rows / 3.0) * np.cos(cols / 4.0)
    elevation[8:, 9:] += 12.0  # a cliff steeper than the vehicle may climb
    elevation[0:3, :] = 4.2 * cols[0:3, :]  # a 40 degree ramp: drivable, yet tabu to planners with tighter limits
    elevation[5:8, 2:5] = 0.0
    elevation[6, 3] = -8.0  # a pit one may drive into (58 and 48 degrees down) but not out of: a dead end
    occ = np.zeros((12, 12), dtype=bool)
    occ[2:9, 6] = True
    strength = np.full((12, 12), 80.0)
    strength[4:6, 2:4] = 20.0
    strength[9, 0:4] = 40.0  # exactly the vehicle's cone index: not blocked, yet too weak for some planners
    types = (rows % 3).astype(np.int8)
    weights = np.array([[-10.0, 1.2], [0.0, 1.0], [10.0, 1.5], [90.0, 3.0]])
    return Scenario(
        id=SYNTHETIC_PREFIX + "terrain.rules", kind="terrain", occupancy=occ, cell_size=5.0,
        start=np.array([3.1, 7.7]), goal=np.array([52.5, 17.5]), elevation=elevation,
        vehicle=VehicleModel(max_climb_deg=45.0, max_descent_deg=60.0),
        rules=TerrainRules(slope_weights=weights, soil_strength=strength, min_soil_strength=40.0, soil_types=types,
                           soil_names=("a", "b", "c")),
        description="synthetic warm-up terrain with slope weights and soil rules",
    )


def _air_volume(ground: float) -> Scenario:
    occ = np.zeros((6, 14, 14), dtype=bool)
    occ[0:4, 3:11, 7] = True
    rows, cols = np.mgrid[0:14, 0:14]
    return Scenario(
        id=SYNTHETIC_PREFIX + f"air3d.stepped.{'high' if ground > 0 else 'low'}", kind="air3d", occupancy=occ, cell_size=100.0,
        vertical_cell_size=40.0, max_step=(2, 1), start=np.array([120.0, 650.0, 20.0]),
        goal=np.array([1250.0, 720.0, 20.0]), elevation=ground + (rows + cols) * 0.5,
        vehicle=VehicleModel(max_turn_deg=60.0, max_pitch_deg=15.0),
        description="synthetic warm-up air volume with an elevation (above or below every layer) and a two-cell "
                    "horizontal step",
    )


def _dynamic() -> Scenario:
    occ = np.zeros((16, 16), dtype=bool)
    occ[0:11, 8] = True
    obstacles = (
        MovingObstacle(radius=0.7, waypoints=np.array([[4.0, 13.0], [12.0, 13.0]]), speed=0.6),
        MovingObstacle(radius=0.5, waypoints=np.array([[2.0, 3.0], [6.0, 6.0], [3.0, 9.0]]), speed=0.4, mode="loop"),
    )
    return Scenario(
        id=SYNTHETIC_PREFIX + "dynamic.moving", kind="dynamic", occupancy=occ, cell_size=1.0,
        start=np.array([1.4, 1.6]), goal=np.array([14.5, 2.5]), moving_obstacles=obstacles,
        description="synthetic warm-up map with two moving obstacles",
    )


def _renamed(scenario: Scenario) -> Scenario:
    from dataclasses import replace

    return replace(scenario, id=SYNTHETIC_PREFIX + scenario.id.split(".", 1)[-1], metadata={})


_VARIANTS = {
    "grid2d": lambda: [_renamed(check_scenario("grid2d"))],
    "terrain": lambda: [_renamed(check_scenario("terrain")), _terrain_with_rules()],
    "air3d": lambda: [_renamed(check_scenario("air3d")), _air_volume(0.0), _air_volume(-100.0)],
    "dynamic": lambda: [_renamed(check_scenario("dynamic")), _dynamic()],
}


def synthetic_scenarios(kind: str) -> list[Scenario]:
    """Fresh synthetic scenarios of ``kind``, geometry built and arrays sealed as a run's are (none for an unknown kind).

    Parameters
    ----------
    kind : str
        A scenario kind (:data:`~pathzoo.core.scenario.SCENARIO_KINDS`).
    """
    out = []
    for scenario in _VARIANTS.get(kind, lambda: [])():
        warm(scenario)
        seal(scenario)
        out.append(scenario)
    return out
