"""Helpers for the scenario-pack tests: exact shortest paths with SciPy on a scenario's graph."""

from __future__ import annotations

from typing import Callable

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra

from pathzoo.core import Scenario


def shortest_nodes(scenario: Scenario, weights=None) -> tuple[float, np.ndarray]:  # noqa: ANN001
    """Optimal cost and node path from start to goal (``inf`` and an empty path when unreachable).

    ``weights`` (one per graph edge, ``inf`` = no edge) default to the edge lengths.
    """
    import scipy.sparse as sp

    g = scenario.graph
    if weights is None:
        matrix = g.to_sparse()
    else:
        keep = np.isfinite(weights)
        matrix = sp.csr_matrix((weights[keep], (g.sources[keep], g.indices[keep])), shape=(g.n_nodes, g.n_nodes))
    dist, pred = dijkstra(matrix, indices=scenario.start_node, return_predecessors=True)
    cost = float(dist[scenario.goal_node])
    if not np.isfinite(cost):
        return cost, np.empty(0, dtype=np.int64)
    nodes = [scenario.goal_node]
    while nodes[-1] != scenario.start_node:
        nodes.append(int(pred[nodes[-1]]))
    return cost, np.array(nodes[::-1])


def shortest_path_points(scenario: Scenario) -> np.ndarray:
    """The optimal node path as world points, ending exactly at the scenario's start and goal."""
    cost, nodes = shortest_nodes(scenario)
    assert np.isfinite(cost), f"{scenario.id}: goal unreachable"
    pts = scenario.point_of(nodes)
    pts[0], pts[-1] = scenario.start, scenario.goal
    return pts


@pytest.fixture
def shortest() -> Callable[..., tuple[float, np.ndarray]]:
    """:func:`shortest_nodes`."""
    return shortest_nodes


@pytest.fixture
def shortest_points() -> Callable[[Scenario], np.ndarray]:
    """:func:`shortest_path_points`."""
    return shortest_path_points
