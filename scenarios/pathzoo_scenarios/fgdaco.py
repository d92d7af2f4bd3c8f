"""FGDACO pack: the three 100 x 100 dynamic scenarios of Sangeetha et al. (2021), section 4.1 and Table 5.

The paper fixes: 100 x 100 occupancy grids at one cell per metre; 3, 4 and 2
static obstacles of different shapes (Table 5); three moving obstacles per
scenario, each at a speed drawn at random in 0.5-1.5 m/s; start and goal
fixed within a scenario but different between scenarios. The layouts appear
only in Figs. 11-12, so they are built here:

- static obstacles are rectangles, discs, triangles and an L or C shape, the
  cells whose centres lie inside them being blocked;
- start and goal are chosen so that the static shortest path is shorter than,
  but of the order of, FGDACO's median length in Table 7 (126.65, 135.96 and
  197.69 m): the moving obstacles and the planners' own detours account
  for the rest;
- each moving obstacle is a disc of radius 2 m going back and forth along a
  segment that crosses the free corridors, with speed ~ U(0.5, 1.5) m/s and a
  start phase ~ U(0, period) drawn from ``numpy.random.default_rng(SEED + k)``
  for scenario ``k``. Positions are therefore deterministic functions of time
  (:class:`~pathzoo.core.MovingObstacle`).

``fgdaco.scenarioK_static`` keeps the static obstacles only (kind ``grid2d``),
for planners that do not handle moving obstacles.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from pathzoo.core import MovingObstacle, Scenario, VehicleModel
from pathzoo.plugins.entries import ScenarioEntry
from pathzoo_scenarios.common import check_choice, pack_metadata

__all__ = [
    "PACK_VERSION",
    "SEED",
    "SIZE",
    "SPEED_RANGE",
    "MOVING_RADIUS",
    "TABLE7_FGDACO_LENGTHS",
    "SCENARIOS",
    "static_occupancy",
    "moving_obstacles",
    "load",
    "entries",
]

PACK_VERSION = 1
SEED = 2021
SIZE = 100
CELL_M = 1.0
SPEED_RANGE = (0.5, 1.5)
MOVING_RADIUS = 2.0
TABLE7_FGDACO_LENGTHS = {1: 126.65, 2: 135.96, 3: 197.69}
"""Median path length (m) of FGDACO per scenario, Table 7."""

# Shapes in world metres (x = column, y = row):
#   ("rect", x0, y0, x1, y1), ("disc", cx, cy, r), ("poly", ((x, y), ...))
SCENARIOS: dict[int, dict[str, object]] = {
    1: {
        "start": (10.5, 12.5),
        "goal": (92.5, 88.5),
        "static": (
            ("rect", 24.0, 22.0, 38.0, 40.0),
            ("disc", 60.0, 57.0, 10.0),
            ("poly", ((66.0, 88.0), (90.0, 66.0), (92.0, 88.0))),
        ),
        "moving": (((10.0, 60.0), (45.0, 60.0)), ((50.0, 20.0), (85.0, 40.0)), ((40.0, 80.0), (70.0, 72.0))),
    },
    2: {
        "start": (6.5, 92.5),
        "goal": (93.5, 8.5),
        "static": (
            ("rect", 15.0, 55.0, 35.0, 85.0),
            ("disc", 50.0, 50.0, 14.0),
            ("poly", ((55.0, 10.0), (85.0, 10.0), (70.0, 35.0))),
            ("poly", ((62.0, 62.0), (90.0, 62.0), (90.0, 70.0), (70.0, 70.0), (70.0, 92.0), (62.0, 92.0))),
        ),
        "moving": (((5.0, 45.0), (40.0, 20.0)), ((40.0, 95.0), (60.0, 70.0)), ((75.0, 40.0), (97.0, 55.0))),
    },
    3: {
        "start": (6.5, 50.5),
        "goal": (55.5, 50.5),
        "static": (
            # a C opening to the east around the goal
            ("poly", ((30.0, 6.0), (93.0, 6.0), (93.0, 14.0), (38.0, 14.0), (38.0, 86.0), (93.0, 86.0),
                      (93.0, 94.0), (30.0, 94.0))),
            ("disc", 18.0, 36.0, 9.0),
        ),
        "moving": (((86.0, 22.0), (86.0, 78.0)), ((45.0, 30.0), (80.0, 30.0)), ((45.0, 70.0), (80.0, 70.0))),
    },
}
"""Hand-built layouts: endpoints, static shapes and moving-obstacle segments (metres)."""


def _inside(shape: tuple, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    kind = shape[0]
    if kind == "rect":
        _, x0, y0, x1, y1 = shape
        return (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)
    if kind == "disc":
        _, cx, cy, r = shape
        return (x - cx) ** 2 + (y - cy) ** 2 <= r * r
    if kind == "poly":  # even-odd rule
        verts = np.asarray(shape[1], dtype=np.float64)
        inside = np.zeros(x.shape, dtype=bool)
        for (xa, ya), (xb, yb) in zip(verts, np.roll(verts, -1, axis=0)):
            crosses = (ya > y) != (yb > y)
            with np.errstate(divide="ignore", invalid="ignore"):
                xc = xa + (y - ya) * (xb - xa) / (yb - ya)
            inside ^= crosses & (x < xc)
        return inside
    raise ValueError(f"unknown shape {kind!r}")


def static_occupancy(scenario: int) -> np.ndarray:
    """Blocked cells: those whose centre lies inside a static shape of the scenario."""
    rows, cols = np.mgrid[0:SIZE, 0:SIZE]
    x, y = (cols + 0.5) * CELL_M, (rows + 0.5) * CELL_M
    occ = np.zeros((SIZE, SIZE), dtype=bool)
    for shape in SCENARIOS[scenario]["static"]:
        occ |= _inside(shape, x, y)
    return occ


def moving_obstacles(scenario: int) -> tuple[MovingObstacle, ...]:
    """The three moving discs: seeded speeds in :data:`SPEED_RANGE` and start phases."""
    rng = np.random.default_rng(SEED + scenario)
    out = []
    for a, b in SCENARIOS[scenario]["moving"]:
        speed = float(rng.uniform(*SPEED_RANGE))
        period = 2.0 * float(np.hypot(b[0] - a[0], b[1] - a[1])) / speed
        phase = float(rng.uniform(0.0, period))
        out.append(MovingObstacle(radius=MOVING_RADIUS, waypoints=np.array([a, b]), speed=speed, phase_s=phase))
    return tuple(out)


def load(scenario: int, dynamic: bool = True) -> Scenario:
    """Build ``fgdaco.scenario<k>`` (``dynamic=True``) or ``fgdaco.scenario<k>_static``."""
    check_choice(scenario, SCENARIOS, "scenario")
    spec = SCENARIOS[scenario]
    movers = moving_obstacles(scenario) if dynamic else ()
    suffix = "" if dynamic else "_static"
    meta = pack_metadata(
        "fgdaco",
        PACK_VERSION,
        f"Sangeetha et al. 2021 (FGDACO), section 4.1, Table 5 (scenario {scenario}), Table 7",
        seed=SEED + scenario,
        static_obstacles=len(spec["static"]),
        static_shapes=[s[0] for s in spec["static"]],
        moving_obstacles=len(spec["moving"]) if dynamic else 0,
        moving_speeds=[ob.speed for ob in movers],
        paper_fgdaco_length=TABLE7_FGDACO_LENGTHS[scenario],
        layout="hand-built equivalent of a layout the paper shows only as a figure",
    )
    what = "3 moving obstacles" if dynamic else "static obstacles only"
    return Scenario(
        id=f"fgdaco.scenario{scenario}{suffix}",
        kind="dynamic" if dynamic else "grid2d",
        occupancy=static_occupancy(scenario),
        cell_size=CELL_M,
        start=np.array(spec["start"]),
        goal=np.array(spec["goal"]),
        vehicle=VehicleModel(),
        moving_obstacles=movers,
        description=f"FGDACO scenario {scenario}: 100x100 m, {len(spec['static'])} static shapes, {what}",
        metadata=meta,
    )


def entries() -> list[ScenarioEntry]:
    """Registry entries of the pack."""
    out = []
    for k, spec in SCENARIOS.items():
        n = len(spec["static"])
        out.append(
            ScenarioEntry(
                id=f"fgdaco.scenario{k}",
                summary=f"FGDACO Table 5 scenario {k}: 100x100, {n} static + 3 moving obstacles (0.5-1.5 m/s)",
                load=partial(load, k, True),
                kind="dynamic",
            )
        )
        out.append(
            ScenarioEntry(
                id=f"fgdaco.scenario{k}_static",
                summary=f"FGDACO scenario {k} without moving obstacles: 100x100, {n} static obstacles",
                load=partial(load, k, False),
                kind="grid2d",
            )
        )
    return out
