"""Random endpoints: free, in the largest strongly connected component, far apart, reproducible."""

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra

from pathzoo import InvalidScenarioError, Scenario, VehicleModel
from pathzoo.generators import ENDPOINTS_VERSION, pick_endpoints, with_random_endpoints


def two_rooms():
    occ = np.zeros((12, 20), bool)
    occ[:, 14] = True  # a wall: 14 free columns on the left, 5 on the right
    return Scenario(id="two", kind="grid2d", occupancy=occ, cell_size=2.0, start=(1.0, 1.0), goal=(1.0, 1.0))


def reachable(scenario, a, b):
    d = dijkstra(scenario.graph.to_sparse(), indices=[scenario.node_of(a)[0]])
    return np.isfinite(d[0, scenario.node_of(b)[0]])


@pytest.mark.parametrize("seed", range(5))
def test_endpoints_are_in_the_largest_component_and_far_apart(seed):
    s = two_rooms()
    start, goal = pick_endpoints(s, np.random.default_rng(seed))
    assert s.cell_of(start)[0][1] < 14 and s.cell_of(goal)[0][1] < 14
    assert reachable(s, start, goal)
    # the goal is at least half the largest distance any left-room cell has from the start
    left = s.point_of(np.flatnonzero(~s.blocked.ravel() & (np.indices(s.shape)[1].ravel() < 14)))
    assert np.linalg.norm(goal - start) >= 0.5 * np.linalg.norm(left - start, axis=1).max()


def test_same_seed_same_endpoints_recorded_and_graph_shared():
    s = two_rooms()
    g = s.graph
    a, b, c = (with_random_endpoints(s, k) for k in (7, 7, 8))
    assert np.array_equal(a.start, b.start) and np.array_equal(a.goal, b.goal)
    assert not (np.array_equal(a.start, c.start) and np.array_equal(a.goal, c.goal))
    assert a.graph is g and a.occupancy is s.occupancy
    assert a.metadata["endpoints"] == {"method": "pick_endpoints", "version": ENDPOINTS_VERSION, "seed": 7,
                                       "min_separation": 0.5}


def test_one_way_terrain_uses_strong_connectivity():
    # a 3 m step between columns 4 and 5: the vehicle may drive down it but not up (climb limit 10 degrees)
    elev = np.zeros((6, 10))
    elev[:, :5] = 3.0
    vehicle = VehicleModel(max_climb_deg=10.0, max_descent_deg=90.0)
    s = Scenario(id="step", kind="terrain", occupancy=np.zeros((6, 10), bool), cell_size=1.0, start=(0.5, 0.5),
                 goal=(0.5, 0.5), elevation=elev, vehicle=vehicle)
    for seed in range(5):
        start, goal = pick_endpoints(s, np.random.default_rng(seed))
        assert reachable(s, start, goal) and reachable(s, goal, start)


def test_no_two_connected_cells_is_an_error():
    occ = np.ones((3, 3), bool)
    occ[1, 1] = False
    s = Scenario(id="cell", kind="grid2d", occupancy=occ, cell_size=1.0, start=(1.5, 1.5), goal=(1.5, 1.5))
    with pytest.raises(InvalidScenarioError, match="field 'map': no two free cells"):
        pick_endpoints(s, np.random.default_rng(0))
    with pytest.raises(InvalidScenarioError, match="min_separation"):
        pick_endpoints(two_rooms(), np.random.default_rng(0), min_separation=0.0)
