"""Random obstacle fields: every cell is blocked independently with a given probability."""

from __future__ import annotations

import numpy as np

from pathzoo.generators.checks import check_number, check_seed, check_shape

__all__ = ["GENERATOR_VERSION", "random_obstacles"]

GENERATOR_VERSION = 1
"""Bumped whenever the same arguments would give a different array."""


def random_obstacles(shape: tuple[int, ...], seed: int, *, density: float = 0.2) -> np.ndarray:
    """A Bernoulli obstacle field (the MovingAI ``random-*`` maps are of this kind).

    Parameters
    ----------
    shape : tuple of int
        ``(rows, cols)``, or ``(layers, rows, cols)`` for an air volume.
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    density : float
        Probability in ``[0, 1)`` that a cell is blocked.

    Returns
    -------
    ndarray of bool
        ``True`` for blocked cells.
    """
    shape = check_shape(shape, ndims=(2, 3))
    density = check_number(density, "density", low=0.0, high=1.0, high_open=True)
    rng = np.random.default_rng(check_seed(seed))
    return rng.random(shape) < density
