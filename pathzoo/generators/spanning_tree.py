"""Random spanning trees of a rectangular lattice, the skeleton of mazes and of room layouts."""

from __future__ import annotations

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import minimum_spanning_tree

__all__ = ["lattice_edges", "random_spanning_tree"]


def lattice_edges(n_rows: int, n_cols: int) -> tuple[np.ndarray, np.ndarray]:
    """Endpoints (flat row-major ids) of every 4-neighbour edge of an ``n_rows x n_cols`` lattice.

    Returns
    -------
    u, v : ndarray of int64
        Edge ``k`` joins ``u[k]`` and ``v[k]``; horizontal edges come first
        (row-major), then vertical ones.
    """
    ids = np.arange(n_rows * n_cols, dtype=np.int64).reshape(n_rows, n_cols)
    u = np.concatenate([ids[:, :-1].ravel(), ids[:-1, :].ravel()])
    v = np.concatenate([ids[:, 1:].ravel(), ids[1:, :].ravel()])
    return u, v


def random_spanning_tree(n_rows: int, n_cols: int, rng: np.random.Generator) -> np.ndarray:
    """Which lattice edges (in :func:`lattice_edges` order) belong to a random spanning tree.

    The tree is the minimum spanning tree under independent uniform edge
    weights, i.e. randomised Kruskal: every cell is reachable from every other
    by exactly one route through tree edges.
    """
    u, v = lattice_edges(n_rows, n_cols)
    n = n_rows * n_cols
    if n == 1:
        return np.zeros(0, dtype=bool)
    weights = 1.0 + rng.random(len(u))  # strictly positive: a zero weight would read as "no edge"
    tree = minimum_spanning_tree(coo_matrix((weights, (u, v)), shape=(n, n)).tocsr()).tocoo()
    lo, hi = np.minimum(tree.row, tree.col).astype(np.int64), np.maximum(tree.row, tree.col).astype(np.int64)
    return np.isin(u * n + v, lo * n + hi)
