"""Rooms with doors: a grid of square rooms separated by one-cell walls, every room reachable."""

from __future__ import annotations

import numpy as np

from pathzoo.generators.checks import check_number, check_seed, check_shape
from pathzoo.generators.spanning_tree import lattice_edges, random_spanning_tree

__all__ = ["GENERATOR_VERSION", "rooms"]

GENERATOR_VERSION = 1
"""Bumped whenever the same arguments would give a different array."""


def _bands(length: int, room_size: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wall lines and the (start, stop) of the room bands between them along one axis.

    Walls sit at indices ``room_size, 2 room_size + 1, ...``; a wall on the
    last line would only thicken the map border, so it is left out and the
    last band is up to one cell wider.
    """
    walls = np.arange(room_size, length - 1, room_size + 1)
    starts = np.concatenate([[0], walls + 1])
    stops = np.concatenate([walls, [length]])
    return walls, starts, stops


def rooms(
    shape: tuple[int, int],
    seed: int,
    *,
    room_size: int = 8,
    door_width: int = 1,
    extra_door_probability: float = 0.5,
) -> np.ndarray:
    """Square rooms of ``room_size`` cells separated by one-cell walls, joined by doors.

    The doors on a random spanning tree of the room adjacency make every room
    reachable; each other wall between two rooms gets a door with probability
    ``extra_door_probability``, which adds loops. Each door sits at a uniformly
    random place along its wall. Rooms on the far edges are cut by the map
    size. This is the layout of MovingAI's ``room-*`` and ``8room_*`` maps.

    Parameters
    ----------
    shape : tuple of int
        ``(rows, cols)``.
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    room_size : int
        Inner side of a room in cells (>= 1).
    door_width : int
        Door width in cells (>= 1; a door never exceeds its wall).
    extra_door_probability : float
        In ``[0, 1]``; 0 gives a tree of rooms (one route between any two).

    Returns
    -------
    ndarray of bool
        ``True`` for wall cells.
    """
    n_rows, n_cols = check_shape(shape)
    room_size = int(check_number(room_size, "room_size", low=1, integer=True))
    door_width = int(check_number(door_width, "door_width", low=1, integer=True))
    extra = check_number(extra_door_probability, "extra_door_probability", low=0.0, high=1.0)
    rng = np.random.default_rng(check_seed(seed))

    wall_rows, row_starts, row_stops = _bands(n_rows, room_size)
    wall_cols, col_starts, col_stops = _bands(n_cols, room_size)
    occ = np.zeros((n_rows, n_cols), dtype=bool)
    occ[wall_rows, :] = True
    occ[:, wall_cols] = True

    nr, nc = len(row_starts), len(col_starts)
    u, v = lattice_edges(nr, nc)
    doors = random_spanning_tree(nr, nc, rng) | (rng.random(len(u)) < extra)
    place = rng.random(len(u))  # where along its wall each door goes
    ur, uc = np.divmod(u, nc)
    across = ur == v // nc  # rooms side by side: the wall between them is a column
    lo = np.where(across, row_starts[ur], col_starts[uc])  # the band the wall segment spans
    hi = np.where(across, row_stops[ur], col_stops[uc])
    width = np.minimum(door_width, hi - lo)
    first = lo + np.floor(place * (hi - lo - width + 1)).astype(np.int64)
    for k in np.flatnonzero(doors):
        span = slice(first[k], first[k] + width[k])
        if across[k]:
            occ[span, wall_cols[uc[k]]] = False
        else:
            occ[wall_rows[ur[k]], span] = False
    return occ
