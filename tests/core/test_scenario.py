"""Scenario construction checks and coordinate conversions."""

import pickle

import numpy as np
import pytest

from pathzoo import InvalidScenarioError, Scenario


def make(**kw):
    base = dict(id="s", kind="grid2d", occupancy=np.zeros((4, 6), bool), cell_size=0.5, start=(0.25, 0.25),
                goal=(2.75, 1.75))
    base.update(kw)
    return Scenario(**base)


def test_coordinates_follow_cell_centre_convention():
    s = make()
    assert s.extent.tolist() == [3.0, 2.0]
    assert s.cell_of(np.array([[2.75, 1.75]])).tolist() == [[3, 5]]
    assert s.node_of(np.array([2.75, 1.75]))[0] == 3 * 6 + 5
    assert s.point_of([s.goal_node]).tolist() == [[2.75, 1.75]]


@pytest.mark.parametrize(
    "kw, field",
    [
        ({"cell_size": 0}, "cell_size"),
        ({"cell_size": -1.0}, "cell_size"),
        ({"start": (5.0, 0.2)}, "start"),
        ({"goal": (0.25, np.nan)}, "goal"),
        ({"kind": "ocean"}, "kind"),
        ({"occupancy": np.zeros((2, 2, 2))}, "map"),
    ],
)
def test_bad_fields_are_named(kw, field):
    with pytest.raises(InvalidScenarioError, match=f"field '{field}'"):
        make(**kw)


def test_start_in_obstacle():
    occ = np.zeros((4, 6), bool)
    occ[0, 0] = True
    with pytest.raises(InvalidScenarioError, match="start.*obstacle"):
        make(occupancy=occ)


def test_arrays_are_read_only_and_pickle_drops_caches():
    s = make()
    with pytest.raises(ValueError):
        s.occupancy[0, 0] = True
    _ = s.graph
    state = s.__getstate__()
    assert "graph" not in state
    s2 = pickle.loads(pickle.dumps(s))
    assert np.array_equal(s2.occupancy, s.occupancy) and s2.graph.n_edges == s.graph.n_edges


def test_with_endpoints_shares_graph():
    s = make()
    g = s.graph
    t = s.with_endpoints((0.75, 0.25), (0.25, 1.75))
    assert t.graph is g and t.start_node == 1


def test_clearance_counts_border_as_obstacle():
    s = make()
    assert s.clearance[0, 0] == pytest.approx(0.5)
    assert s.clearance.max() == pytest.approx(1.0)
