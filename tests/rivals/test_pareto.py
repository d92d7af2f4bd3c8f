"""Dominance, the Pareto archive and NSGA-II order of the multi-objective rivals, on hand-made vectors."""

from __future__ import annotations

import numpy as np
import pytest

from pathzoo_rivals.pareto import ParetoArchive, crowding_distances, dominates, rank_and_crowding_order


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


def pymoo_order(objectives: np.ndarray) -> np.ndarray:
    """NSGA-II's order by pymoo's own functions (the definition the compiled one follows)."""
    from pymoo.operators.survival.rank_and_crowding.metrics import calc_crowding_distance
    from pymoo.util.nds.non_dominated_sorting import NonDominatedSorting

    rank = np.empty(len(objectives), dtype=np.int64)
    crowd = np.empty(len(objectives))
    for r, members in enumerate(NonDominatedSorting().do(objectives)):
        rank[members] = r
        front = objectives[members]
        crowd[members] = np.inf if len(front) <= 2 else calc_crowding_distance(front)
    return np.lexsort((np.arange(len(objectives)), -crowd, rank))


@pytest.mark.parametrize("values", ["continuous", "ties"])
def test_compiled_order_and_crowding_are_pymoos(values):
    # continuous values tell apart any other order of the sums; small integers make ties, duplicates and flat objectives
    from pymoo.operators.survival.rank_and_crowding.metrics import calc_crowding_distance

    rng = np.random.default_rng(11)
    for _ in range(3000):
        n = int(rng.integers(1, 26))
        f = rng.normal(size=(n, 3)) * rng.uniform(0.1, 1e4, 3) if values == "continuous" else \
            rng.integers(0, 4, size=(n, 3)).astype(np.float64)
        if values == "ties" and rng.uniform() < 0.2:
            f[:, int(rng.integers(3))] = 1.0
        assert rank_and_crowding_order(f).tolist() == pymoo_order(f).tolist()
        expected = np.full(n, np.inf) if n <= 2 else calc_crowding_distance(f)
        assert crowding_distances(f).tobytes() == expected.tobytes()
