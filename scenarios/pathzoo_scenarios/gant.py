"""G-Ant pack: the occupancy grids of Jabbarpour et al. (2017), section V, with the Table 3 vehicle.

The paper shows its obstacle layouts only as figures, so each space here is a
seeded equivalent of the stated size, obstacle count and character; the seeds
were chosen by the rules below (checked by ``tests/scenarios/test_gant.py``).

- ``gant.fig7``: 10 x 10 cells of 1 m, 16 obstacle cells, start (0.5, 0.5),
  goal (9.5, 9.5) (Fig. 7). Seed rule: the first seed whose layout blocks the
  straight diagonal (optimum > 9 sqrt 2) while keeping the optimum at or
  below Table 4's best length, 15.4225.
- ``gant.acopso``: the ACO/PSO comparison space of Figs. 8-13, start
  (0.5, 0.5), goal (8.5, 8.5). The paper gives neither size nor obstacle
  count; we use 10 x 10 cells and 16 obstacle cells like Fig. 7. Seed rule:
  the first seed whose layout blocks the straight diagonal.
- ``gant.<simple|moderate|complex>.<1|2|3>``: the three 500 x 500 spaces of
  Figs. 14-16 with the three start/goal pairs of Table 5. Obstacles are
  axis-aligned rectangles ("orange cells"), more of them as the space gets
  harder. Seed rule: among seeds 0-499, the one whose three shortest-path
  detour ratios (optimum / straight line) are closest (Euclidean norm) to the
  ratios of G-Ant's Table 5 lengths to the straight line. These layouts are
  therefore **fitted to Table 5**; note that G-Ant's 562.58 m on the simple
  space, pair 1, is below the 8-connected optimum with no obstacles at all
  (563.61 m), see ``docs/reproduction.md``.

Table 5 gives points as integers, read as cell indices (column, row); the
scenario points are those cells' centres.
"""

from __future__ import annotations

from functools import lru_cache, partial
from typing import Any

import numpy as np

from pathzoo.core import Scenario, VehicleModel
from pathzoo.plugins.entries import ScenarioEntry
from pathzoo_scenarios.common import cell_centre, check_choice, pack_metadata

__all__ = [
    "PACK_VERSION",
    "VEHICLE",
    "TABLE5_PAIRS",
    "TABLE5_GANT_LENGTHS",
    "SMALL_SPACES",
    "LARGE_SPACES",
    "small_layout",
    "rectangle_layout",
    "load_small",
    "load_large",
    "entries",
]

PACK_VERSION = 1

VEHICLE = VehicleModel(mass_kg=30.0, cruise_speed=2.0, onboard_power_w=0.0)
"""Table 3: UGV mass 30 kg, phi = 2 m/s, b = 0 W (other terms: pathzoo defaults)."""

TABLE5_PAIRS: tuple[tuple[tuple[int, int], tuple[int, int]], ...] = (
    ((5, 50), (400, 450)),
    ((20, 55), (460, 455)),
    ((30, 65), (465, 460)),
)
"""Start and goal (column, row) of Table 5's three columns."""

TABLE5_GANT_LENGTHS: dict[str, tuple[float, float, float]] = {
    "simple": (562.58, 626.67, 619.55),
    "moderate": (910.4, 700.44, 667.72),
    "complex": (913.82, 710.06, 674.95),
}
"""G-Ant's path lengths in Table 5, per space and pair."""

SMALL_SPACES: dict[str, dict[str, Any]] = {
    "fig7": {"size": 10, "obstacles": 16, "start": (0, 0), "goal": (9, 9), "seed": 0, "figure": "Fig. 7"},
    "acopso": {"size": 10, "obstacles": 16, "start": (0, 0), "goal": (8, 8), "seed": 0, "figure": "Figs. 8-13"},
}
"""The 10 x 10 spaces: size, obstacle cells, start/goal cells (row, col), seed."""

LARGE_SPACES: dict[str, dict[str, int]] = {
    "simple": {"rectangles": 10, "min_side": 30, "max_side": 80, "seed": 60},
    "moderate": {"rectangles": 25, "min_side": 30, "max_side": 100, "seed": 197},
    "complex": {"rectangles": 60, "min_side": 20, "max_side": 80, "seed": 334},
}
"""The 500 x 500 spaces (Figs. 14-16): rectangle count, side range in cells, seed."""

_LARGE_SIZE = 500
_ENDPOINT_MARGIN = 5


def small_layout(size: int, obstacles: int, keep_free: tuple[tuple[int, int], ...], seed: int) -> np.ndarray:
    """``obstacles`` distinct blocked cells drawn uniformly, never on ``keep_free`` cells."""
    rng = np.random.default_rng(seed)
    keep = {r * size + c for r, c in keep_free}
    candidates = np.array([k for k in range(size * size) if k not in keep])
    occ = np.zeros(size * size, dtype=bool)
    occ[rng.choice(candidates, size=obstacles, replace=False)] = True
    return occ.reshape(size, size)


def rectangle_layout(
    size: int, rectangles: int, min_side: int, max_side: int, keep_free: np.ndarray, margin: int, seed: int
) -> np.ndarray:
    """Axis-aligned rectangles of random sides in ``[min_side, max_side]`` placed uniformly.

    A rectangle that would come within ``margin`` cells of a ``keep_free``
    cell (rows of ``(col, row)``) is redrawn.
    """
    rng = np.random.default_rng(seed)
    occ = np.zeros((size, size), dtype=bool)
    placed = 0
    while placed < rectangles:
        w, h = rng.integers(min_side, max_side + 1, 2)
        x, y = rng.integers(0, size - w + 1), rng.integers(0, size - h + 1)
        near = (
            (keep_free[:, 0] >= x - margin)
            & (keep_free[:, 0] < x + w + margin)
            & (keep_free[:, 1] >= y - margin)
            & (keep_free[:, 1] < y + h + margin)
        )
        if near.any():
            continue
        occ[y : y + h, x : x + w] = True
        placed += 1
    return occ


def load_small(name: str) -> Scenario:
    """Build ``gant.fig7`` or ``gant.acopso``."""
    check_choice(name, SMALL_SPACES, "name")
    spec = SMALL_SPACES[name]
    size, start, goal = int(spec["size"]), spec["start"], spec["goal"]
    occ = small_layout(size, int(spec["obstacles"]), (start, goal), int(spec["seed"]))
    return Scenario(
        id=f"gant.{name}",
        kind="grid2d",
        occupancy=occ,
        cell_size=1.0,
        start=cell_centre(start[0], start[1], 1.0),
        goal=cell_centre(goal[0], goal[1], 1.0),
        vehicle=VEHICLE,
        description=f"G-Ant {spec['figure']} space, {size}x{size}, {spec['obstacles']} obstacle cells",
        metadata=pack_metadata(
            "gant",
            PACK_VERSION,
            f"Jabbarpour et al. 2017 (G-Ant), section V, {spec['figure']}, Table 3 vehicle",
            seed=int(spec["seed"]),
            obstacle_cells=int(spec["obstacles"]),
            layout="seeded equivalent of a layout the paper shows only as a figure",
        ),
    )


@lru_cache(maxsize=None)
def _large_base(space: str) -> Scenario:
    spec = LARGE_SPACES[space]
    ends = np.array([p for pair in TABLE5_PAIRS for p in pair])
    occ = rectangle_layout(
        _LARGE_SIZE, spec["rectangles"], spec["min_side"], spec["max_side"], ends, _ENDPOINT_MARGIN, spec["seed"]
    )
    (sc, sr), (gc, gr) = TABLE5_PAIRS[0]
    base = Scenario(
        id=f"gant.{space}",
        kind="grid2d",
        occupancy=occ,
        cell_size=1.0,
        start=cell_centre(sr, sc, 1.0),
        goal=cell_centre(gr, gc, 1.0),
        vehicle=VEHICLE,
        description=f"G-Ant {space} 500x500 space (Figs. 14-16), {spec['rectangles']} rectangles",
    )
    base.graph  # built once here, so the three pairs share it
    return base


def load_large(space: str, pair: int) -> Scenario:
    """Build ``gant.<space>.<pair>`` (``pair`` in 1..3, the columns of Table 5)."""
    check_choice(space, LARGE_SPACES, "space")
    check_choice(pair, range(1, len(TABLE5_PAIRS) + 1), "pair")
    spec = LARGE_SPACES[space]
    (sc, sr), (gc, gr) = TABLE5_PAIRS[pair - 1]
    base = _large_base(space)
    meta = pack_metadata(
        "gant",
        PACK_VERSION,
        f"Jabbarpour et al. 2017 (G-Ant), section V, Figs. 14-16 and Table 5 (pair {pair}), Table 3 vehicle",
        seed=spec["seed"],
        rectangles=spec["rectangles"],
        side_range_cells=[spec["min_side"], spec["max_side"]],
        start_cell_col_row=[sc, sr],
        goal_cell_col_row=[gc, gr],
        paper_gant_length=TABLE5_GANT_LENGTHS[space][pair - 1],
        layout="seeded equivalent of a layout the paper shows only as a figure",
    )
    return base.with_endpoints(
        cell_centre(sr, sc, 1.0), cell_centre(gr, gc, 1.0), id=f"gant.{space}.{pair}", metadata=meta
    )


def entries() -> list[ScenarioEntry]:
    """Registry entries of the pack."""
    out = [
        ScenarioEntry(
            id=f"gant.{name}",
            summary=f"G-Ant {spec['figure']}: {spec['size']}x{spec['size']}, {spec['obstacles']} obstacle cells",
            load=partial(load_small, name),
            kind="grid2d",
        )
        for name, spec in SMALL_SPACES.items()
    ]
    for space in LARGE_SPACES:
        for pair, ((sc, sr), (gc, gr)) in enumerate(TABLE5_PAIRS, start=1):
            out.append(
                ScenarioEntry(
                    id=f"gant.{space}.{pair}",
                    summary=f"G-Ant {space} 500x500 space (Figs. 14-16), ({sc},{sr}) -> ({gc},{gr}) of Table 5",
                    load=partial(load_large, space, pair),
                    kind="grid2d",
                )
            )
    return out
