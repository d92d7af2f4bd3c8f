"""Pheromone trails on edges or nodes, with lazy evaporation and clamp-on-read bounds.

A colony on a 2569 x 1919 terrain has about 39 million edges, so nothing may
cost O(edges) per iteration. The trail therefore stores ``x`` and a global
scale ``s``: the true value of entry ``k`` is ``clip(s * x[k], lo, hi)``.

- Evaporating *every* entry, ``τ <- (1 - ρ) τ``, is ``s <- (1 - ρ) s``: O(1).
- Bounds (MMAS's ``τmin``/``τmax``, a floor) are applied when a value is read.
  Evaporation only lowers values, so ``clip((1-ρ) clip(v)) == clip((1-ρ) v)``
  and the lazy clamp gives exactly the eager result, also when the bounds
  rise over time (MMAS raises them as the best length falls).
- Every write (deposit, local update) reads the true value, changes it,
  clamps it and stores ``value / s``.

When ``s`` falls below 1e-150 it is folded back into ``x`` (one O(entries)
pass, every few hundred iterations at the most).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo_aco.engine.prefetch import AHEAD, prefetch

__all__ = ["Pheromone", "deposit_walks"]

_RENORMALISE_BELOW = 1e-150


class Pheromone:
    """A pheromone trail on the edges or on the nodes of a graph.

    Parameters
    ----------
    size : int
        Number of entries (edges or nodes).
    initial : float or ndarray
        Initial trail ``τ0`` (scalar or one value per entry).
    on_nodes : bool
        Whether entries are nodes (the trail of edge ``i -> j`` is ``τ[j]``)
        rather than edges.
    lo, hi : float
        Bounds applied on every read and write.
    """

    def __init__(self, size: int, initial: float | np.ndarray, *, on_nodes: bool = False,
                 lo: float = 0.0, hi: float = math.inf) -> None:
        self.x = np.empty(size, dtype=np.float64)
        self.x[:] = initial
        self.scale = 1.0
        self.on_nodes = bool(on_nodes)
        self.lo = float(lo)
        self.hi = float(hi)

    def values(self) -> np.ndarray:
        """True trail values (a new array, O(entries))."""
        return np.clip(self.scale * self.x, self.lo, self.hi)

    def set_bounds(self, lo: float, hi: float = math.inf) -> None:
        """Change the bounds; they apply lazily to every entry from now on."""
        self.lo = float(lo)
        self.hi = float(hi)

    def evaporate(self, rho: float) -> None:
        """Multiply every entry by ``1 - rho`` (O(1))."""
        self.scale *= 1.0 - rho
        if self.scale < _RENORMALISE_BELOW:  # in place: no trail-sized temporaries (2 x 237 MB on ggaco.case1)
            np.multiply(self.x, self.scale, out=self.x)
            np.clip(self.x, self.lo, self.hi, out=self.x)
            self.scale = 1.0


@numba.njit(cache=True)
def _deposit(x, scale, lo, hi, on_nodes, indices, flat, offsets, ants, keep, per_walk, per_edge, per_step):
    use_edge = per_edge.size > 0
    use_step = per_step.size > 0
    for i in range(ants.size):
        a = ants[i]
        end = offsets[a + 1]
        for p in range(offsets[a], end):
            ahead = flat[min(p + AHEAD, end - 1)]  # the walk's entries follow no stride: hint a few ahead
            if on_nodes:
                prefetch(indices, ahead)
            else:
                prefetch(x, ahead)
            e = flat[p]
            k = indices[e] if on_nodes else e
            t = min(max(scale * x[k], lo), hi)
            t = keep * t + per_walk[i]
            if use_edge:
                t += per_edge[e]
            if use_step:
                t += per_step[p]
            x[k] = min(max(t, lo), hi) / scale


def deposit_walks(trail: Pheromone, indices: np.ndarray, flat: np.ndarray, offsets: np.ndarray,
                  ants: np.ndarray, per_walk: np.ndarray | float, *, keep: float = 1.0,
                  per_edge: np.ndarray | None = None, per_step: np.ndarray | None = None) -> None:
    """Update the trail along the walks of the chosen ants: ``τ <- clip(keep τ + Δ)``.

    ``Δ`` on an edge ``e`` of ant ``ants[i]`` is ``per_walk[i] + per_edge[e]``.
    AS-style deposits use ``keep = 1``; ACS's global update
    ``τ <- (1-ρ) τ + ρ/L`` uses ``keep = 1 - ρ``. Walks are simple paths, so
    each entry is touched at most once per walk.

    Parameters
    ----------
    trail : Pheromone
        Updated in place.
    indices : ndarray
        ``graph.indices`` (edge -> target node, used for node trails).
    flat, offsets : ndarray
        The walks' edges (:class:`~pathzoo_aco.engine.walk.Walks`).
    ants : ndarray of int
        Which walks deposit.
    per_walk : float or ndarray
        Amount per walk (broadcast to ``len(ants)``).
    keep : float
        Factor on the old value.
    per_edge : ndarray, optional
        Extra amount per edge id.
    per_step : ndarray, optional
        Extra amount per entry of ``flat`` (the same as ``per_edge[flat]``
        without a graph-sized array; use one or the other).
    """
    ants = np.asarray(ants, dtype=np.int64)
    amounts = np.empty(ants.shape)
    amounts[:] = per_walk  # broadcast (np.broadcast_to costs more than the deposit of one short walk)
    extra = np.zeros(0) if per_edge is None else np.asarray(per_edge, dtype=np.float64)
    steps = np.zeros(0) if per_step is None else np.asarray(per_step, dtype=np.float64)
    _deposit(trail.x, trail.scale, trail.lo, trail.hi, trail.on_nodes, indices, flat, offsets, ants,
             float(keep), amounts, extra, steps)
