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
  for the rest. **These layouts were fitted to Table 7**: in scenarios 1
  and 2 the endpoints were placed so that the static optimum is 98.9 % and
  97.8 % of FGDACO's median length, so agreement in absolute length there is
  partly by construction. In scenario 3 the size of the block
  (:data:`BLOCK_END`) was chosen so that the optimum (174.6 m) is of the
  order of Table 7's 197.69 m; nothing else was fitted;
- scenario 3 follows what the paper says of it (Table 5: two static
  obstacles of different shapes, three moving ones) and nothing more: a long
  polygonal block across the diagonal between the start and goal corners,
  open only near the south-east corner, and a disc. A goal inside a
  C-shaped obstacle is our invention, not the paper's: that layout is the
  stress test ``fgdaco.trap``;
- each moving obstacle is a disc of radius 2 m going back and forth along a
  segment that crosses the free corridors, with speed ~ U(0.5, 1.5) m/s and a
  start phase ~ U(0, period) drawn from ``numpy.random.default_rng(SEED + k)``
  for scenario ``k``. Positions are therefore deterministic functions of time
  (:class:`~pathzoo.core.MovingObstacle`).

``fgdaco.scenarioK_static`` (and ``fgdaco.trap_static``) keep the static
obstacles only (kind ``grid2d``), for planners that do not handle moving
obstacles.
"""

from __future__ import annotations

from functools import partial
from typing import Any

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
    "BLOCK_END",
    "SCENARIOS",
    "static_occupancy",
    "moving_obstacles",
    "load",
    "entries",
]

PACK_VERSION = 2
SEED = 2021
SIZE = 100
CELL_M = 1.0
SPEED_RANGE = (0.5, 1.5)
MOVING_RADIUS = 2.0
TABLE7_FGDACO_LENGTHS: dict[int | str, float] = {1: 126.65, 2: 135.96, 3: 197.69}
"""Median path length (m) of FGDACO per scenario, Table 7."""

BLOCK_END = 90.0
"""Scenario 3: x of the south-east end of the diagonal block (its free gap to the corner sets the detour)."""

# Shapes in world metres (x = column, y = row):
#   ("rect", x0, y0, x1, y1), ("disc", cx, cy, r), ("poly", ((x, y), ...))
SCENARIOS: dict[int | str, dict[str, Any]] = {
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
        "start": (6.5, 6.5),
        "goal": (93.5, 93.5),
        "static": (
            # a long block across the diagonal from the north-west edge, leaving a gap in the south-east corner
            ("poly", ((0.0, 88.0), (0.0, 100.0), (12.0, 100.0), (BLOCK_END + 6.0, 100.0 - BLOCK_END + 6.0),
                      (BLOCK_END - 6.0, 100.0 - BLOCK_END - 6.0))),
            ("disc", 72.0, 62.0, 7.0),
        ),
        "moving": (((50.0, 4.0), (50.0, 30.0)), ((78.0, 40.0), (96.0, 40.0)), ((20.0, 30.0), (36.0, 14.0))),
    },
    "trap": {
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
"""Hand-built layouts: endpoints, static shapes and moving-obstacle segments (metres), by scenario number,
and the stress test ``"trap"`` (not from the paper)."""


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


def static_occupancy(scenario: int | str) -> np.ndarray:
    """Blocked cells: those whose centre lies inside a static shape of the scenario."""
    rows, cols = np.mgrid[0:SIZE, 0:SIZE]
    x, y = (cols + 0.5) * CELL_M, (rows + 0.5) * CELL_M
    occ = np.zeros((SIZE, SIZE), dtype=bool)
    for shape in SCENARIOS[scenario]["static"]:
        occ |= _inside(shape, x, y)
    return occ


def _seed(scenario: int | str) -> int:
    return SEED + (3 if scenario == "trap" else int(scenario))


def moving_obstacles(scenario: int | str) -> tuple[MovingObstacle, ...]:
    """The three moving discs: seeded speeds in :data:`SPEED_RANGE` and start phases.

    The trap keeps the seed of the former scenario 3 (``SEED + 3``), so it is the same scenario as before.
    """
    rng = np.random.default_rng(_seed(scenario))
    out = []
    for a, b in SCENARIOS[scenario]["moving"]:
        speed = float(rng.uniform(*SPEED_RANGE))
        period = 2.0 * float(np.hypot(b[0] - a[0], b[1] - a[1])) / speed
        phase = float(rng.uniform(0.0, period))
        out.append(MovingObstacle(radius=MOVING_RADIUS, waypoints=np.array([a, b]), speed=speed, phase_s=phase))
    return tuple(out)


def _name(scenario: int | str) -> str:
    return "trap" if scenario == "trap" else f"scenario{scenario}"


def load(scenario: int | str, dynamic: bool = True) -> Scenario:
    """Build ``fgdaco.scenario<k>`` / ``fgdaco.trap`` (``dynamic=True``) or their ``_static`` variants."""
    check_choice(scenario, SCENARIOS, "scenario")
    spec = SCENARIOS[scenario]
    movers = moving_obstacles(scenario) if dynamic else ()
    suffix = "" if dynamic else "_static"
    seed = _seed(scenario)
    extra: dict[str, Any]
    if scenario == "trap":
        source = ("pathzoo stress test (not from the paper): the goal inside a C-shaped obstacle "
                  "open away from the start")
        extra = {"layout": "ours: a C-shaped trap around the goal; FGDACO cannot leave it (docs/reproduction.md)"}
        title = "FGDACO stress test: goal inside a C-shaped trap"
    else:
        source = f"Sangeetha et al. 2021 (FGDACO), section 4.1, Table 5 (scenario {scenario}), Table 7"
        extra = {
            "paper_fgdaco_length": TABLE7_FGDACO_LENGTHS[scenario],
            "layout": "hand-built equivalent of a layout the paper shows only as a figure",
            "fitted": ("endpoints placed so that the static optimum is close to Table 7's median length"
                       if scenario in (1, 2) else "block size chosen so that the optimum is of the order of Table 7's"),
        }
        title = f"FGDACO scenario {scenario}"
    meta = pack_metadata(
        "fgdaco",
        PACK_VERSION,
        source,
        seed=seed,
        static_obstacles=len(spec["static"]),
        static_shapes=[sh[0] for sh in spec["static"]],
        moving_obstacles=len(spec["moving"]) if dynamic else 0,
        moving_speeds=[ob.speed for ob in movers],
        **extra,
    )
    what = "3 moving obstacles" if dynamic else "static obstacles only"
    return Scenario(
        id=f"fgdaco.{_name(scenario)}{suffix}",
        kind="dynamic" if dynamic else "grid2d",
        occupancy=static_occupancy(scenario),
        cell_size=CELL_M,
        start=np.array(spec["start"]),
        goal=np.array(spec["goal"]),
        vehicle=VehicleModel(),
        moving_obstacles=movers,
        description=f"{title}: 100x100 m, {len(spec['static'])} static shapes, {what}",
        metadata=meta,
    )


def entries() -> list[ScenarioEntry]:
    """Registry entries of the pack."""
    out = []
    for k, spec in SCENARIOS.items():
        n = len(spec["static"])
        name = _name(k)
        what = (f"FGDACO Table 5 scenario {k}" if k != "trap"
                else "FGDACO stress test (ours, not the paper's): goal inside a C-shaped trap")
        out.append(
            ScenarioEntry(
                id=f"fgdaco.{name}",
                summary=f"{what}: 100x100, {n} static + 3 moving obstacles (0.5-1.5 m/s)",
                load=partial(load, k, True),
                kind="dynamic",
            )
        )
        out.append(
            ScenarioEntry(
                id=f"fgdaco.{name}_static",
                summary=f"{what}, without moving obstacles: 100x100, {n} static obstacles",
                load=partial(load, k, False),
                kind="grid2d",
            )
        )
    return out
