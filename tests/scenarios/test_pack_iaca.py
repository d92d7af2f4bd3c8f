"""IACA pack: section 4.1 terrain, eqs. 1-2, Table 1 slopeW, eq. 12 / Table 3 soils, M1A1 limits, Table 5."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import pathzoo
from pathzoo.core import TerrainRules
from pathzoo.rules import validate_path
from pathzoo_scenarios import iaca


@pytest.fixture(scope="module")
def scen():
    return pathzoo.load_scenario("iaca.offroad")


def test_grid_size_and_heights(scen):
    assert scen.shape == (21, 21) and scen.cell_size == 10.0
    np.testing.assert_allclose(scen.extent, [210.0, 210.0])
    corners = iaca.corner_heights(scen.metadata["seed"])
    assert corners.shape == (22, 22)
    assert corners.min() == pytest.approx(0.0) and corners.max() == pytest.approx(100.0)
    # eq. 2: the centre height is the mean of the four corner heights
    for i, j in [(0, 0), (9, 2), (20, 20), (13, 7)]:
        mean4 = (corners[i, j] + corners[i + 1, j] + corners[i + 1, j + 1] + corners[i, j + 1]) / 4
        assert scen.elevation[i, j] == pytest.approx(mean4)


def test_m1a1_limits_and_endpoints(scen):
    assert scen.vehicle.max_climb_deg == 31.0
    assert scen.vehicle.max_descent_deg == 60.0
    assert scen.rules.min_soil_strength == 50.0  # VCI50
    # start (10, 3) and goal (8, 5) as 1-based (row, column)
    assert tuple(scen.cell_of(scen.start)[0]) == (9, 2)
    assert tuple(scen.cell_of(scen.goal)[0]) == (7, 4)


def test_rci_per_soil_at_30_percent(scen):
    # eq. 12 with Table 3's (a, b), typed in again
    table3 = {"MH": (21.6000, -4.6228), "CH": (13.0541, -2.5091), "SM": (11.3445, -2.4497)}
    expected = {k: math.exp(a + b * math.log(30.0)) for k, (a, b) in table3.items()}
    assert expected["MH"] == pytest.approx(356.5, abs=0.5)
    assert expected["CH"] == pytest.approx(91.8, abs=0.1)
    assert expected["SM"] == pytest.approx(20.34, abs=0.01)
    rules = scen.rules
    for k, name in enumerate(rules.soil_names):
        cells = rules.soil_types == k
        assert cells.any(), f"soil {name} does not occur"
        np.testing.assert_allclose(rules.soil_strength[cells], expected[name])
        # RCI > VCI50 is GO: MH and CH pass, SM (20.3) does not
        assert (scen.blocked[cells]).all() == (expected[name] <= 50.0)
    assert iaca.rci("SM", 30.0) == pytest.approx(expected["SM"])


@pytest.mark.parametrize(
    "slope, weight",
    [(-75, 0), (-60, 0), (-50, 0.8), (-35, 0.85), (-25, 0.9), (-15, 0.95), (-5, 1), (0, 1), (3, 1), (10, 0.95),
     (17, 0.9), (22, 0.85), (27, 0.8), (30, 0.8), (30.5, 0), (45, 0)],
)
def test_slopew_lookup(scen, slope, weight):
    assert float(scen.rules.slope_weight(slope)) == weight


def test_edge_slopes_follow_eqs_3_to_10(scen):
    """An edge's slope is atan(dH' / L) straight and atan(dH' / (sqrt 2 L)) diagonally."""
    g = scen.graph
    h = scen.elevation
    for e in range(0, g.n_edges, 97):
        u, v = int(g.sources[e]), int(g.indices[e])
        (ru, cu), (rv, cv) = divmod(u, 21), divmod(v, 21)
        run = 10.0 * math.hypot(rv - ru, cv - cu)
        assert math.degrees(g.slope[e]) == pytest.approx(math.degrees(math.atan((h[rv, cv] - h[ru, cu]) / run)))
        assert -60.0 - 1e-9 <= math.degrees(g.slope[e]) <= 31.0 + 1e-9


def test_table5_dijkstra_result(scen, shortest):
    """Under eq. 21 the optimal path has 21 points and distance 33.5, as Table 5 reports."""
    cost, nodes = shortest(scen, iaca.eq21_weights(scen))
    assert len(nodes) == 21
    assert cost == pytest.approx(33.5, abs=0.12)
    # it is the weak soil that bars the short way (section 4.2): without soil rules the path is short
    no_soil = replace(scen, rules=TerrainRules(slope_weights=scen.rules.slope_weights))
    _, direct = shortest(no_soil, iaca.eq21_weights(no_soil))
    assert 0 < len(direct) <= 5


def test_solvable(scen, shortest_points):
    assert validate_path(scen, shortest_points(scen))
