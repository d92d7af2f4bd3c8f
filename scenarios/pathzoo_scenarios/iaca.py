"""IACA pack: the 21 x 21 off-road terrain of Wang et al. (2018), section 4.1, with slope and soil rules.

What the paper fixes, and how it is used here:

- 210 m x 210 m x 100 m terrain in 21 x 21 square cells (10 m); heights 0-100 m.
- Cell heights are the mean of the four corner heights, eqs. 1-2, so the
  terrain is defined by a 22 x 22 lattice of corner heights.
- Slopes to the 8 neighbours, eqs. 3-10: ``atan(dH' / L)`` (``L`` or ``sqrt 2 L``),
  which is exactly the slope of pathzoo's terrain graph edges.
- M1A1 limits (sections 2.1 and 4.1): climb +31 deg, descent -60 deg, VCI50 = 50.
- slopeW of Table 1, as :attr:`TerrainRules.slope_weights`.
- Soils MH, CH and SM at 30 % moisture with RCI = exp(a + b ln M), eq. 12 and
  Table 3 (SM uses the "SM + SC" row); a cell is passable when RCI > VCI50.
- Start (10, 3) and goal (8, 5), read as 1-based (row i, column j) indices as
  in eqs. 1-10: cells (9, 2) and (7, 4).

What the paper shows only in figures (Figs. 5 and 6) is built here from a
seed: the corner heights are a sum of ten Gaussian hills scaled to exactly
0-100 m, and the soil map is a Voronoi partition of eight seeded sites, each
given one of the three soils, crossed by a band of SM (two cell diagonals
wide, from the west edge to column 9) between start and goal. Section 4.2
says the optimal path is not the physically shortest one because of slope
and soil; the band and the terrain reproduce Table 5: the optimal path under
eq. 21 has 21 points and distance 33.5. Eq. 21 sums segment lengths divided
by slopeW; we read ``EuclideanDist`` between terrain points as the 3-D
distance in cell units (the grid width L = 10 m is one unit), see
:func:`eq21_weights`. The seed is the one closest to 33.5 with 21 points
among the seeds tried (0-17999). The layout is therefore **fitted to
Table 5** (the seed search and the hand-added SM band): agreement with the
paper's 33.5 is by construction. ``docs/reproduction.md`` reports IACA
against the optimum over many other seeds of the same generator.

Note: Table 1 gives slopeW = 0 above 30 deg (and the tabu rule of section 2.1
uses tan 30 deg), while the text states a 31 deg climb limit. The vehicle
keeps 31 deg; a planner that uses slopeW treats 30-31 deg as NO GO.
"""

from __future__ import annotations

import numpy as np

from pathzoo.core import Scenario, TerrainRules, VehicleModel
from pathzoo.plugins.entries import ScenarioEntry
from pathzoo_scenarios.common import cell_centre, pack_metadata

__all__ = [
    "PACK_VERSION",
    "SEED",
    "SLOPE_WEIGHTS",
    "SOIL_AB",
    "SOILS",
    "MOISTURE_PERCENT",
    "VCI50",
    "rci",
    "corner_heights",
    "centre_heights",
    "soil_map",
    "eq21_weights",
    "eq21_path_distance",
    "load",
    "entries",
]

PACK_VERSION = 1
SEED = 18
"""Seed of the terrain and soil layout (chosen to reproduce Table 5, see the module docstring)."""

N_CELLS = 21
CELL_M = 10.0
HEIGHT_RANGE_M = (0.0, 100.0)
START_IJ = (10, 3)
GOAL_IJ = (8, 5)
MAX_CLIMB_DEG = 31.0
MAX_DESCENT_DEG = 60.0
VCI50 = 50.0
MOISTURE_PERCENT = 30.0

SLOPE_WEIGHTS = np.array(
    [
        # (upper slope in degrees, slopeW): Table 1, a slope theta takes the first row with theta <= upper
        (-60.0, 0.0),
        (-40.0, 0.8),
        (-30.0, 0.85),
        (-20.0, 0.9),
        (-10.0, 0.95),
        (0.0, 1.0),
        (5.0, 1.0),
        (15.0, 0.95),
        (20.0, 0.9),
        (25.0, 0.85),
        (30.0, 0.8),
        (90.0, 0.0),
    ]
)
"""slopeW of Table 1."""

SOIL_AB: dict[str, tuple[float, float]] = {
    "SM + SC": (11.3445, -2.4497),
    "CL": (15.2821, -3.4542),
    "CH": (13.0541, -2.5091),
    "MH + CH": (12.2076, -1.9434),
    "ML": (11.7046, -2.3319),
    "ML + CL": (13.8927, -3.0272),
    "MH": (21.6000, -4.6228),
}
"""``(a, b)`` of eq. 12 per USCS soil type, Table 3."""

SOILS: tuple[str, ...] = ("MH", "CH", "SM")
"""The three soils of section 4.1 (Fig. 6); SM takes Table 3's "SM + SC" row."""
_SOIL_ROW = {"MH": "MH", "CH": "CH", "SM": "SM + SC"}

_HILLS = 10
_SOIL_SITES = 8
_SM_BAND_DIAGONALS = (5, 6)
_SM_BAND_END_COL = 9


def rci(soil: str, moisture_percent: float) -> float:
    """Rating cone index of eq. 12, ``exp(a + b ln M)``, with ``(a, b)`` from Table 3."""
    a, b = SOIL_AB[_SOIL_ROW.get(soil, soil)]
    return float(np.exp(a + b * np.log(moisture_percent)))


def corner_heights(seed: int = SEED) -> np.ndarray:
    """The ``22 x 22`` lattice of corner heights in metres (seeded Gaussian hills, exactly 0-100 m)."""
    rng = np.random.default_rng(seed)
    n = N_CELLS + 1
    rr, cc = np.mgrid[0:n, 0:n].astype(np.float64)
    h = np.zeros((n, n))
    for _ in range(_HILLS):
        r0, c0 = rng.uniform(0, n - 1, 2)
        sigma = rng.uniform(2.0, 5.0)
        amp = rng.uniform(0.3, 1.0)
        h += amp * np.exp(-((rr - r0) ** 2 + (cc - c0) ** 2) / (2 * sigma**2))
    lo, hi = HEIGHT_RANGE_M
    return lo + (h - h.min()) / (h.max() - h.min()) * (hi - lo)


def centre_heights(corners: np.ndarray) -> np.ndarray:
    """Cell-centre heights of eq. 2: the mean of each cell's four corner heights."""
    return (corners[:-1, :-1] + corners[1:, :-1] + corners[1:, 1:] + corners[:-1, 1:]) / 4.0


def soil_map(seed: int = SEED) -> np.ndarray:
    """Soil class per cell (index into :data:`SOILS`): Voronoi cells of seeded sites."""
    rng = np.random.default_rng([seed, 1])
    sites = rng.uniform(0, N_CELLS, (_SOIL_SITES, 2))
    kinds = rng.integers(0, len(SOILS), _SOIL_SITES)
    rr, cc = np.mgrid[0:N_CELLS, 0:N_CELLS]
    d2 = (rr[..., None] + 0.5 - sites[:, 0]) ** 2 + (cc[..., None] + 0.5 - sites[:, 1]) ** 2
    soils = kinds[np.argmin(d2, axis=-1)].astype(np.int8)
    band = np.isin(rr - cc, _SM_BAND_DIAGONALS) & (cc <= _SM_BAND_END_COL)
    soils[band] = SOILS.index("SM")
    return soils


def eq21_weights(scenario: Scenario) -> np.ndarray:
    """Graph edge weights of eq. 21: 3-D step length in cell units over slopeW (``inf`` where slopeW = 0)."""
    graph = scenario.graph
    w = scenario.rules.slope_weight(np.degrees(graph.slope))
    with np.errstate(divide="ignore"):
        return np.where(w > 0, graph.length / scenario.cell_size / w, np.inf)


def eq21_path_distance(scenario: Scenario, path: np.ndarray) -> float:
    """Eq. 21 distance of a path through cell centres: the sum of :func:`eq21_weights` over its steps.

    ``path`` holds world points (``x, y``, an optional third column is
    ignored); each step must join neighbouring cells of the scenario's graph.
    NaN when a step is not a graph edge (e.g. an any-angle shortcut), ``inf``
    when it crosses a slope whose slopeW is 0.
    """
    graph = scenario.graph
    weights = eq21_weights(scenario)
    nodes = scenario.node_of(np.asarray(path, dtype=np.float64)[:, :2])
    nodes = nodes[np.r_[True, np.diff(nodes) != 0]]
    total = 0.0
    for u, v in zip(nodes[:-1], nodes[1:]):
        lo, hi = graph.indptr[u], graph.indptr[u + 1]
        hit = np.flatnonzero(graph.indices[lo:hi] == v)
        if len(hit) == 0:
            return float("nan")
        total += float(weights[lo + hit[0]])
    return total


def load(seed: int = SEED) -> Scenario:
    """Build ``iaca.offroad``: terrain, soils, slopeW and the M1A1 vehicle of section 4.1."""
    corners = corner_heights(seed)
    soils = soil_map(seed)
    strength = np.array([rci(s, MOISTURE_PERCENT) for s in SOILS])[soils]
    rules = TerrainRules(
        slope_weights=SLOPE_WEIGHTS,
        soil_strength=strength,
        min_soil_strength=VCI50,
        soil_types=soils,
        soil_names=SOILS,
    )
    vehicle = VehicleModel(max_climb_deg=MAX_CLIMB_DEG, max_descent_deg=MAX_DESCENT_DEG)
    (si, sj), (gi, gj) = START_IJ, GOAL_IJ
    meta = pack_metadata(
        "iaca",
        PACK_VERSION,
        "Wang et al. 2018 (IACA), section 4.1; eqs. 1-2, 3-10, 12; Tables 1, 3 and 5",
        seed=seed,
        start_paper_ij=list(START_IJ),
        goal_paper_ij=list(GOAL_IJ),
        moisture_percent=MOISTURE_PERCENT,
        rci_per_soil={s: rci(s, MOISTURE_PERCENT) for s in SOILS},
        vci50=VCI50,
        table5_dijkstra={"points": 21, "eq21_distance": 33.5},
        layout="seeded equivalent of Figs. 5 and 6 (terrain and soils shown only as figures)",
    )
    return Scenario(
        id="iaca.offroad",
        kind="terrain",
        occupancy=np.zeros((N_CELLS, N_CELLS), dtype=bool),
        cell_size=CELL_M,
        start=cell_centre(si - 1, sj - 1, CELL_M),
        goal=cell_centre(gi - 1, gj - 1, CELL_M),
        vehicle=vehicle,
        elevation=centre_heights(corners),
        rules=rules,
        description="IACA off-road terrain, 21x21 cells of 10 m, slopeW and soils (MH, CH, SM at 30 %)",
        metadata=meta,
    )


def entries() -> list[ScenarioEntry]:
    """Registry entries of the pack."""
    return [
        ScenarioEntry(
            id="iaca.offroad",
            summary="IACA section 4.1: 210x210 m terrain, 21x21 cells, slopeW, soils MH/CH/SM, M1A1 limits",
            load=load,
            kind="terrain",
        )
    ]
