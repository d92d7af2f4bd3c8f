"""Small maps shared by the ant-colony tests."""

from __future__ import annotations

import numpy as np
from pathzoo import Scenario, VehicleModel


def open_grid(n: int = 8, **kw) -> Scenario:
    """An obstacle-free ``n x n`` grid from the top-left to the bottom-right cell centre."""
    return Scenario(id=f"open{n}", kind="grid2d", occupancy=np.zeros((n, n), bool), cell_size=1.0,
                    start=(0.5, 0.5), goal=(n - 0.5, n - 0.5), **kw)


def walled_grid(reachable: bool = True) -> Scenario:
    """10 x 10 with a wall in column 5 (gap in rows 7-9); optionally the goal walled in."""
    occ = np.zeros((10, 10), bool)
    occ[0:7, 5] = True
    if not reachable:
        occ[0:3, 7:10] = True
        occ[1, 8] = False
    return Scenario(id="walled", kind="grid2d", occupancy=occ, cell_size=1.0, start=(1.3, 1.7), goal=(8.5, 1.5))


def hill(vehicle: VehicleModel | None = None) -> Scenario:
    """A 12 x 12 terrain of 2 m cells with a hill between start and goal."""
    rows, cols = np.mgrid[0:12, 0:12]
    elevation = 4.0 * np.exp(-((rows - 6.0) ** 2 + (cols - 6.0) ** 2) / 10.0)
    return Scenario(id="hill", kind="terrain", occupancy=np.zeros((12, 12), bool), cell_size=2.0,
                    start=(1.0, 13.0), goal=(23.0, 11.0), elevation=elevation,
                    vehicle=vehicle or VehicleModel(max_climb_deg=30.0, max_descent_deg=30.0))
