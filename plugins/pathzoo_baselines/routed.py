"""Routed waypoint encoding: K free points decoded into a feasible path by a collision-aware decoder.

A candidate is ``2K`` reals ``(x1, y1, ..., xK, yK)`` in world coordinates,
as in :mod:`pathzoo_baselines.waypoints`, so any real-valued optimiser
(pyswarms, cuckoo search, DEAP's real operators) moves it freely. Decoding
(:meth:`RoutedWaypointEncoding.decode`) never produces a colliding path:

1. **Snap** each point to its cell, and a cell that is blocked or cut off
   from the start or the goal to the nearest usable cell
   (:attr:`CellRouter.nearest_usable`); the stops are ``start cell, c1, ...,
   cK, goal cell``.
2. **Connect** consecutive stops: on ``grid2d`` by the straight segment
   between their centres when it keeps :data:`~pathzoo_baselines.margin.MARGIN_CELLS`
   from every blocked closed square (:func:`~pathzoo_baselines.margin.segment_clear`),
   otherwise, and always on terrain (where a straight segment could break a
   slope limit), by the shortest grid route between them
   (:meth:`CellRouter.route`: graph edges only). A stop the path so far
   cannot reach (one-way slopes on terrain) is skipped; every usable cell
   reaches the goal.
3. **Cut loops** (:func:`~pathzoo_baselines.routing.remove_loops`).

The path is the decoded cells' centres, from exactly the start to exactly the
goal (:func:`pathzoo.grid.paths.centre_path`); the cost is its length (graph
length on terrain). So the optimiser searches over via-points of a path that
is straight where it can be and routed around obstacles where it must; the
violation is 0 except for heading changes beyond a turn limit.

This follows the waypoint formulation of PSO path planners (the particle is
a list of intermediate points joined into a polyline; e.g. Saska, Hess &
Schilling 2006; Liang et al., Math. Probl. Eng. 2014), with constraint
handling by a repairing decoder instead of a penalty. The repair (steps 1-2)
is our reconstruction, named on the planners' pages.

Initial candidates (:meth:`RoutedWaypointEncoding.initial`) are drawn from
random feasible paths (:meth:`CellRouter.random_path`): the K points are the
centres of K cells evenly spaced along one such path.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from pathzoo.core import Scenario
from pathzoo.grid.paths import centre_path
from pathzoo_baselines.cellpath import chain_lengths, turn_violations
from pathzoo_baselines.margin import MARGIN_CELLS, segment_clear
from pathzoo_baselines.routing import CellRouter, remove_loops

__all__ = ["RoutedWaypointEncoding"]


class RoutedWaypointEncoding:
    """Candidates as ``2K`` world coordinates with a repairing decoder; see the module docstring.

    Parameters
    ----------
    scenario : Scenario
        The problem (``grid2d`` or ``terrain``).
    waypoints : int
        K, the number of free points.
    penalty : float
        Cost of one unit of violation (turns), in map diagonals.
    """

    integer = False
    costly = True  # graph searches per candidate: the search looks at the clock between candidates

    def __init__(self, scenario: Scenario, *, waypoints: int, penalty: float) -> None:
        self.scenario = scenario
        self.router = CellRouter(scenario)
        self.k = int(waypoints)
        self.n_genes = 2 * self.k
        self.low = np.zeros(self.n_genes)
        self.high = np.tile(np.nextafter(scenario.extent, 0.0), self.k)
        self._straight = scenario.kind == "grid2d"
        self._weight = float(penalty) * float(np.hypot(*scenario.extent))

    def stops(self, genes: np.ndarray) -> np.ndarray:
        """The usable cells ``start, c1, ..., cK, goal`` of one candidate (step 1)."""
        sc = self.scenario
        pts = np.clip(np.asarray(genes, dtype=np.float64).reshape(self.k, 2), self.low[:2], self.high[:2])
        cells = self.router.nearest_usable[sc.node_of(pts)]
        return np.concatenate([[sc.start_node], cells, [sc.goal_node]]).astype(np.int64)

    def decode(self, genes: np.ndarray) -> np.ndarray:
        """The decoded cells of one candidate (steps 1-3); consecutive cells are joined by valid segments."""
        stops = self.stops(genes)
        router = self.router
        if not router.connected:
            return stops[[0]]
        w = router.width
        blocked = self.scenario.blocked
        out = [stops[:1]]
        a = stops[0]
        for b in stops[1:]:
            if a == b:
                continue
            if self._straight and segment_clear(
                blocked, a % w + 0.5, a // w + 0.5, b % w + 0.5, b // w + 0.5, MARGIN_CELLS
            ):
                out.append(np.array([b], dtype=np.int64))
            else:
                piece = router.route(a, b)
                if piece is None:  # one-way slopes on terrain: skip this stop (the goal is reachable from a)
                    continue
                out.append(piece[1:])
            a = b
        return remove_loops(np.concatenate(out), scratch=router.scratch)

    def initial(self, rng: np.random.Generator, n: int, stop: Callable[[], bool] | None = None) -> np.ndarray:
        """``n`` candidates whose points are evenly spaced cells of random feasible paths.

        When ``stop()`` turns true (the time limit), the candidates not yet
        drawn are copies of those drawn (at least one is).
        """
        out = np.empty((n, self.n_genes))
        if not self.router.connected:
            return np.tile(np.resize(self.scenario.start, self.n_genes), (n, 1))
        for i in range(n):
            if i > 0 and stop is not None and stop():
                out[i:] = out[np.arange(i, n) % i]
                break
            path = self.router.random_path(rng, vias=1)
            pick = np.rint(np.linspace(0, len(path) - 1, self.k + 2)[1:-1]).astype(np.int64)
            out[i] = self.scenario.point_of(path[pick]).ravel()
        return out

    def evaluate(self, genes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(cost, violation)`` of candidates of shape (n, 2K)."""
        genes = np.asarray(genes, dtype=np.float64).reshape(-1, self.n_genes)
        chains = [self.decode(x) for x in genes]
        if not self.router.connected:  # no feasible path exists: every candidate violates by one unit
            return np.full(len(chains), self._weight), np.ones(len(chains))
        if self._straight:
            length = np.empty(len(chains))
            for i, c in enumerate(chains):
                d = np.diff(self.scenario.point_of(c), axis=0)
                length[i] = np.hypot(d[:, 0], d[:, 1]).sum()
        else:
            g = self.scenario.graph
            bounds = np.concatenate([[0], np.cumsum([len(c) for c in chains])]).astype(np.int64)
            length = chain_lengths(g.indptr, g.indices, g.length, np.concatenate(chains), bounds)
        violation = turn_violations(self.scenario, chains)
        return length + self._weight * violation, violation

    def path(self, genes: np.ndarray) -> np.ndarray:
        """World path of one candidate: the decoded cells' centres with the exact start and goal."""
        return centre_path(self.scenario, self.decode(genes))
