"""Every ant-colony planner on its paper's kind of scenario, with a tiny budget."""

from __future__ import annotations

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget, Scenario, VehicleModel
from pathzoo.harness.validation import validate_path

from aco_maps import hill, walled_grid


def gant_space() -> Scenario:
    """Stand-in for gant.fig7: 10 x 10 cells, 16 obstacle cells, corner to corner, Table 3 vehicle."""
    occ = np.zeros(100, bool)
    occ[np.random.default_rng(0).choice(np.arange(1, 99), 16, replace=False)] = True
    return Scenario(id="gant-standin", kind="grid2d", occupancy=occ.reshape(10, 10), cell_size=1.0,
                    start=(0.5, 0.5), goal=(9.5, 9.5), vehicle=VehicleModel(mass_kg=30.0, cruise_speed=2.0))


def ggaco_terrain() -> Scenario:
    """Stand-in for a ggaco.* scenario: a hill whose too-steep cells are blocked (the traversable map)."""
    base = hill(VehicleModel(max_climb_deg=20.0, max_descent_deg=20.0))
    gy, gx = np.gradient(base.elevation, base.cell_size)
    steep = np.degrees(np.arctan(np.hypot(gx, gy))) > 15.0
    steep[base.cell_of(np.stack([base.start, base.goal]))[:, 0], base.cell_of(np.stack([base.start, base.goal]))[:, 1]] = False
    return Scenario(id="ggaco-standin", kind="terrain", occupancy=steep, cell_size=base.cell_size, start=base.start,
                    goal=base.goal, elevation=base.elevation, vehicle=base.vehicle)


CASES = [
    ("aco.as", walled_grid), ("aco.mmas", walled_grid), ("aco.acs", walled_grid),
    ("aco.as", hill), ("aco.mmas", hill), ("aco.acs", hill),
    ("aco.gant", gant_space), ("aco.gant", hill),
    ("aco.ggaco", ggaco_terrain), ("aco.ggaco", walled_grid),
]


@pytest.mark.parametrize(("planner_id", "make"), CASES, ids=[f"{p}-{m.__name__}" for p, m in CASES])
def test_solves_with_a_tiny_budget(planner_id, make):
    scenario = make()
    result = pathzoo.make_planner(planner_id).plan(scenario, budget=Budget(iterations=3), rng=np.random.default_rng(0))
    assert result.solved, result.message
    verdict = validate_path(scenario, result.path)
    assert verdict, verdict.reason
    assert result.iterations == 3
