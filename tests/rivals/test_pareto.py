"""Dominance, the Pareto archive and NSGA-II order of the multi-objective rivals, on hand-made vectors."""

from __future__ import annotations

import numpy as np

from pathzoo_rivals.pareto import ParetoArchive, dominates, rank_and_crowding_order


def test_dominance():
    assert dominates(np.array([1.0, 2.0, 3.0]), np.array([1.0, 2.0, 4.0]))
    assert not dominates(np.array([1.0, 2.0, 3.0]), np.array([1.0, 2.0, 3.0]))  # equal: no
    assert not dominates(np.array([0.0, 5.0, 0.0]), np.array([1.0, 2.0, 3.0]))  # trade-off: no


def route(k: int) -> np.ndarray:
    return np.array([k], dtype=np.int64)


def test_archive_keeps_only_non_dominated_routes():
    archive = ParetoArchive(capacity=10)
    assert archive.add(route(0), np.array([2.0, 2.0, 2.0]))
    assert archive.add(route(1), np.array([1.0, 3.0, 2.0]))  # trade-off: both stay
    assert not archive.add(route(2), np.array([2.0, 2.0, 2.0]))  # equal to a member
    assert not archive.add(route(3), np.array([3.0, 3.0, 3.0]))  # dominated
    assert archive.add(route(4), np.array([1.0, 2.0, 2.0]))  # dominates both
    assert len(archive) == 1 and int(archive.routes[0][0]) == 4
    np.testing.assert_array_equal(archive.objectives, [[1.0, 2.0, 2.0]])


def test_archive_truncation_drops_the_most_crowded_and_keeps_the_extremes():
    archive = ParetoArchive(capacity=4)
    points = [(0.0, 10.0), (10.0, 0.0), (5.0, 5.0), (5.1, 4.9), (2.0, 8.0)]
    for k, (a, b) in enumerate(points):
        assert archive.add(route(k), np.array([a, b, 0.0]))
    kept = sorted(int(r[0]) for r in archive.routes)
    assert len(kept) == 4
    assert 0 in kept and 1 in kept  # extremes have infinite crowding distance
    assert not (2 in kept and 3 in kept)  # one of the two crowded neighbours left


def test_rank_and_crowding_order():
    F = np.array([
        [3.0, 3.0, 0.0],  # front 1 (dominated by index 2)
        [0.0, 4.0, 0.0],  # front 0, extreme
        [2.0, 2.0, 0.0],  # front 0, interior
        [4.0, 0.0, 0.0],  # front 0, extreme
        [5.0, 5.0, 0.0],  # front 2
    ])
    order = list(rank_and_crowding_order(F))
    assert set(order[:3]) == {1, 2, 3} and order[2] == 2  # boundary points before the interior one
    assert order[3:] == [0, 4]
