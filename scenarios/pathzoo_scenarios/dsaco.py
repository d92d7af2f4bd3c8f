"""DSACO pack: the three Gaussian-peak mountain volumes of Mai et al. (2023), eq. 1 and Tables 1-3.

The paper (section 5.1) models a 50 km x 50 km x 2.4 km volume in 1 km
horizontal and 0.2 km vertical cells, with mountains given by eq. 1

    Z(x, y) = sum_i h_i exp(-(x - x_oi)^2 / x_si^2 - (y - y_oi)^2 / y_si^2)

and the peak parameters of Tables 1 (simple), 2 (medium) and 3 (complex).
The UAV flies from (1, 17, 0.6) km to (50, 42, 0.6) km, moves at most two
cells horizontally and one cell vertically per step (section 5.3), and keeps
50 m < height above ground < 2 km (eq. 4 with the bounds of section 5.3).

Frame
-----
The paper's coordinates are grid *nodes*: x, y = 1 .. 50 km and
z = 0.2 .. 2.4 km. pathzoo puts nodes at voxel centres, so the pathzoo world is
the paper's frame shifted by half a cell on every axis:
``world = paper - (0.5 km, 0.5 km, 0.1 km)``. The whole scene moves rigidly
(ground included), so lengths, pitch angles and heights above ground are the
paper's; only absolute heights read 100 m lower (``elevation`` is
``Z(x, y) - 100 m``).

Choices the paper leaves open (recorded in ``metadata``)
--------------------------------------------------------
- The pitch limit alpha_max of eq. 5: 15 deg. The step rule alone already keeps
  every graph move below atan(0.2 / 1) = 11.31 deg, so the limit binds only
  planners that move off the lattice.
- The turn limit beta_max of eq. 6: 60 deg between consecutive horizontal headings
  (shortest lattice paths turn by at most 18.4 deg here).
- Heights above ground are tested at voxel centres against the ground under
  the voxel column's centre, as the paper's node model does.
"""

from __future__ import annotations

from functools import partial

import numpy as np

from pathzoo.core import Scenario, VehicleModel
from pathzoo.plugins.entries import ScenarioEntry
from pathzoo_scenarios.common import check_choice, pack_metadata

__all__ = [
    "PACK_VERSION",
    "PEAKS",
    "ENVIRONMENTS",
    "peaks_world_m",
    "load",
    "entries",
]

PACK_VERSION = 1

PEAKS: dict[str, tuple[tuple[float, float, float, float, float], ...]] = {
    # (x_o km, y_o km, h km, x_s km, y_s km) per peak
    "simple": (  # Table 1
        (30, 9, 0.66, 4, 3),
        (16, 17, 1.64, 7, 8),
        (35, 32, 1.3, 5, 8),
    ),
    "medium": (  # Table 2
        (40, 10, 1.8, 4, 3),
        (12, 17, 0.66, 2, 1),
        (21, 25, 1.86, 4, 4),
        (33, 34, 1.64, 7, 8),
        (10, 41, 0.3, 5, 8),
        (14, 32, 0.96, 12, 8),
        (6, 26, 1.3, 6, 5),
        (33, 15, 2.3, 4, 12),
    ),
    "complex": (  # Table 3
        (40, 10, 1.08, 4, 3),
        (35, 45, 0.66, 2, 2),
        (36, 25, 1.86, 3, 5),
        (15, 40, 1.64, 2, 3),
        (10, 25, 0.3, 8, 5),
        (33, 44, 1.12, 10, 8),
        (47, 30, 1.6, 6, 6),
        (20, 24, 0.64, 7, 8),
        (10, 41, 1.34, 5, 8),
        (14, 32, 0.96, 12, 8),
        (6, 26, 1.3, 6, 5),
        (33, 42, 1.5, 4, 8),
    ),
}
"""Peak parameters of Tables 1-3, in kilometres."""

ENVIRONMENTS = {"simple": "Table 1", "medium": "Table 2", "complex": "Table 3"}

SIZE_KM = (50.0, 50.0, 2.4)
H_CELL_KM = 1.0
V_CELL_KM = 0.2
START_KM = (1.0, 17.0, 0.6)
GOAL_KM = (50.0, 42.0, 0.6)
MIN_AGL_M = 50.0
MAX_AGL_M = 2000.0
MAX_STEP = (2, 1)
MAX_PITCH_DEG = 15.0
MAX_TURN_DEG = 60.0
_SHIFT_KM = np.array([H_CELL_KM / 2, H_CELL_KM / 2, V_CELL_KM / 2])


def peaks_world_m(environment: str) -> np.ndarray:
    """The peaks of eq. 1 in pathzoo's world frame: rows ``(x_o, y_o, h, x_s, y_s)`` in metres."""
    peaks = np.array(PEAKS[environment], dtype=np.float64) * 1000.0
    peaks[:, :2] -= _SHIFT_KM[:2] * 1000.0
    return peaks


def load(environment: str) -> Scenario:
    """Build ``dsaco.<environment>`` for ``environment`` in ``{"simple", "medium", "complex"}``."""
    from pathzoo.generators.peak_terrain import peaks_elevation  # here: the generators import scipy

    check_choice(environment, PEAKS, "environment")
    peaks = PEAKS[environment]
    nx, ny = int(SIZE_KM[0] / H_CELL_KM), int(SIZE_KM[1] / H_CELL_KM)
    nz = int(round(SIZE_KM[2] / V_CELL_KM))
    # eq. 1 at the paper's nodes x = col + 1 km, y = row + 1 km (voxel-column centres of the world frame)
    ground_m = peaks_elevation(peaks_world_m(environment), (ny, nx), H_CELL_KM * 1000.0)
    zs_m = (np.arange(nz) + 1) * V_CELL_KM * 1000.0  # paper node heights 0.2 .. 2.4 km
    agl = zs_m[:, None, None] - ground_m[None, :, :]
    occupancy = ~((agl > MIN_AGL_M) & (agl < MAX_AGL_M))
    vehicle = VehicleModel(max_pitch_deg=MAX_PITCH_DEG, max_turn_deg=MAX_TURN_DEG)
    meta = pack_metadata(
        "dsaco",
        PACK_VERSION,
        f"Mai et al. 2023 (DSACO), eq. 1 and {ENVIRONMENTS[environment]}; section 5.1 and 5.3",
        environment=environment,
        peaks_km=[list(p) for p in peaks],
        start_paper_km=list(START_KM),
        goal_paper_km=list(GOAL_KM),
        world_equals_paper_minus_m=[float(v) for v in _SHIFT_KM * 1000.0],
        height_above_ground_m=[MIN_AGL_M, MAX_AGL_M],
        max_step_cells=list(MAX_STEP),
        choices={
            "max_pitch_deg": f"{MAX_PITCH_DEG} (eq. 5 alpha_max, not given; lattice moves stay below 11.31 deg)",
            "max_turn_deg": f"{MAX_TURN_DEG} (eq. 6 beta_max, not given)",
            "ground_test": "height above ground tested at voxel centres over the column-centre ground",
        },
    )
    return Scenario(
        id=f"dsaco.{environment}",
        kind="air3d",
        occupancy=occupancy,
        cell_size=H_CELL_KM * 1000.0,
        vertical_cell_size=V_CELL_KM * 1000.0,
        start=(np.array(START_KM) - _SHIFT_KM) * 1000.0,
        goal=(np.array(GOAL_KM) - _SHIFT_KM) * 1000.0,
        vehicle=vehicle,
        elevation=ground_m - _SHIFT_KM[2] * 1000.0,
        max_step=MAX_STEP,
        description=f"DSACO {environment} mountains ({ENVIRONMENTS[environment]}, eq. 1), 50x50x2.4 km UAV volume",
        metadata=meta,
    )


def entries() -> list[ScenarioEntry]:
    """Registry entries of the pack."""
    return [
        ScenarioEntry(
            id=f"dsaco.{env}",
            summary=f"DSACO {env} mountains ({table}, {len(PEAKS[env])} peaks), 50x50x12 voxels, UAV",
            load=partial(load, env),
            kind="air3d",
        )
        for env, table in ENVIRONMENTS.items()
    ]
