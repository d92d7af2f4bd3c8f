"""Perfect mazes: corridors on a lattice joined along a random spanning tree."""

from __future__ import annotations

import numpy as np

from pathzoo.generators.checks import check_number, check_seed, check_shape
from pathzoo.generators.spanning_tree import lattice_edges, random_spanning_tree

__all__ = ["GENERATOR_VERSION", "maze"]

GENERATOR_VERSION = 1
"""Bumped whenever the same arguments would give a different array."""


def maze(shape: tuple[int, int], seed: int, *, corridor_width: int = 1, wall_width: int = 1) -> np.ndarray:
    """A perfect maze (exactly one route between any two corridor cells).

    Maze cell ``(i, j)`` is the square of side ``corridor_width`` whose top-left
    grid cell is ``(i p, j p)`` with ``p = corridor_width + wall_width``; the
    passages are the edges of a random spanning tree of the maze-cell lattice
    (randomised Kruskal, see :mod:`pathzoo.generators.spanning_tree`). The map
    edge serves as the outer wall; rows and columns left over when the shape
    is not a whole number of periods stay blocked.

    Parameters
    ----------
    shape : tuple of int
        ``(rows, cols)``, each at least ``corridor_width``.
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    corridor_width, wall_width : int
        Widths in cells (>= 1).

    Returns
    -------
    ndarray of bool
        ``True`` for wall cells.
    """
    cw = int(check_number(corridor_width, "corridor_width", low=1, integer=True))
    ww = int(check_number(wall_width, "wall_width", low=1, integer=True))
    n_rows, n_cols = check_shape(shape, minimum=cw)
    rng = np.random.default_rng(check_seed(seed))
    period = cw + ww
    nr, nc = (n_rows + ww) // period, (n_cols + ww) // period
    u, _ = lattice_edges(nr, nc)
    tree = random_spanning_tree(nr, nc, rng)
    horizontal = np.arange(len(u)) < nr * (nc - 1)  # lattice_edges lists horizontal edges first
    blocks = np.ones((nr * nc, period, period), dtype=bool)  # one block per maze cell, row-major
    blocks[:, :cw, :cw] = False
    blocks[u[tree & horizontal], :cw, cw:] = False  # passage to the right-hand neighbour
    blocks[u[tree & ~horizontal], cw:, :cw] = False  # passage to the neighbour below
    full = blocks.reshape(nr, nc, period, period).transpose(0, 2, 1, 3).reshape(nr * period, nc * period)
    occ = np.ones((n_rows, n_cols), dtype=bool)
    h, w = min(n_rows, full.shape[0]), min(n_cols, full.shape[1])
    occ[:h, :w] = full[:h, :w]
    return occ
