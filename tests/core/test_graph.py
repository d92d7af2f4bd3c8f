"""Neighbourhood graph construction on grids, terrain and air volumes."""

import math

import numpy as np

from pathzoo import Scenario, VehicleModel


def grid(occ, start=(0.5, 0.5), goal=None, **kw):
    occ = np.asarray(occ, dtype=bool)
    goal = goal or ((occ.shape[1] - 0.5), (occ.shape[0] - 0.5))
    return Scenario(id="t", kind="grid2d", occupancy=occ, cell_size=1.0, start=start, goal=goal, **kw)


def test_open_grid_degrees():
    g = grid(np.zeros((3, 3))).graph
    assert g.degree[4] == 8  # centre
    assert g.degree[0] == 3  # corner
    assert g.n_edges == 4 * 3 + 4 * 5 + 8


def test_no_corner_cutting_edges():
    occ = np.zeros((2, 2), dtype=bool)
    occ[0, 1] = True
    s = grid(occ)
    assert 3 not in s.graph.neighbours(0)  # (0,0) -> (1,1) would cut the corner of (0,1)
    assert set(s.graph.neighbours(0)) == {2}


def test_edge_lengths_scale_with_cell_size():
    s = Scenario(id="t", kind="grid2d", occupancy=np.zeros((2, 2), bool), cell_size=2.0, start=(1, 1), goal=(3, 3))
    g = s.graph
    lengths = dict(zip(g.neighbours(0), g.length[g.indptr[0] : g.indptr[1]]))
    assert lengths[1] == 2.0 and math.isclose(lengths[3], 2 * math.sqrt(2))


def test_terrain_slope_limits_are_directional():
    elev = np.array([[0.0, 1.0]])  # 1 m rise over 1 m -> 45 degrees
    occ = np.zeros((1, 2), bool)
    v = VehicleModel(max_climb_deg=30, max_descent_deg=60)
    s = Scenario(id="t", kind="terrain", occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(1.5, 0.5),
                 elevation=elev, vehicle=v)
    g = s.graph
    assert list(g.neighbours(0)) == []  # uphill 45 > 30 removed
    assert list(g.neighbours(1)) == [0]  # downhill 45 < 60 kept
    assert math.isclose(g.length[0], math.sqrt(2))
    assert math.isclose(g.slope[0], -math.pi / 4)


def test_nan_elevation_is_blocked():
    elev = np.array([[0.0, np.nan, 0.0]])
    s = Scenario(id="t", kind="terrain", occupancy=np.zeros((1, 3), bool), cell_size=1.0, start=(0.5, 0.5),
                 goal=(2.5, 0.5), elevation=elev)
    assert s.blocked[0, 1]
    assert s.graph.degree[1] == 0 and 1 not in s.graph.neighbours(0)


def test_air3d_offsets_and_pitch_limit():
    occ = np.zeros((3, 5, 5), bool)
    v = VehicleModel(max_pitch_deg=30)
    s = Scenario(id="t", kind="air3d", occupancy=occ, cell_size=1.0, vertical_cell_size=1.0, start=(2.5, 2.5, 1.5),
                 goal=(0.5, 0.5, 0.5), max_step=(2, 1), vehicle=v)
    centre = s.node_of(np.array([2.5, 2.5, 1.5]))[0]
    nbrs = s.graph.neighbours(centre)
    pts = s.point_of(nbrs) - np.array([2.5, 2.5, 1.5])
    horiz = np.hypot(pts[:, 0], pts[:, 1])
    assert np.all(np.degrees(np.arctan2(np.abs(pts[:, 2]), horiz)) <= 30 + 1e-9)
    assert len(nbrs) == 24 + 2 * 16  # level: 5x5-1; up/down: only horizontal step 2 (pitch 26.6 deg)


def test_graph_matches_pathlengths_of_scipy():
    from scipy.sparse.csgraph import dijkstra

    rng = np.random.default_rng(0)
    occ = rng.random((30, 30)) < 0.2
    occ[0, 0] = occ[-1, -1] = False
    s = grid(occ)
    d = dijkstra(s.graph.to_sparse(), indices=s.start_node)
    # every finite distance is a sum of 1 and sqrt(2): check the triangle inequality against octile
    pts = s.point_of(np.arange(s.graph.n_nodes))
    dx = np.abs(pts[:, 0] - 0.5)
    dy = np.abs(pts[:, 1] - 0.5)
    octile = np.maximum(dx, dy) + (math.sqrt(2) - 1) * np.minimum(dx, dy)
    finite = np.isfinite(d)
    assert np.all(d[finite] >= octile[finite] - 1e-9)
