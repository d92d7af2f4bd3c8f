"""Grid-path encoding: a chromosome of compass moves walked on the scenario's neighbourhood graph.

A candidate is ``L`` integer genes in ``0..7`` (E, NE, N, NW, W, SW, S, SE).
Decoding walks from the start cell:

- gene ``g`` asks for move ``g``; when that move is not an edge of
  :attr:`Scenario.graph` (blocked, corner-cutting, off the map or too steep),
  the nearest allowed direction is taken instead, trying ``g+1, g-1, g+2,
  g-2, ...`` (mod 8), so every gene moves the walker;
- revisiting a cell cuts the loop just walked (the path keeps the first visit);
- the walk stops at the goal cell; genes after it are unused.

Every decoded path therefore follows graph edges, which already respect the
collision rule and the slope limits. The only violations left are not
reaching the goal (the octile distance still to go, in cells) and, with a
turn limit, the number of heading changes beyond it. The cost is the graph
length of the walk (3-D on terrain) plus ``penalty * diagonal * violation``
as in :mod:`pathzoo_baselines.cost`.

``L = ceil(moves_factor * (H + W))``. Initial genes point towards the goal
with probability 1/2 and are uniform otherwise (our choice: a uniform random
walk almost never reaches the goal of a 100 x 100 map).

The path starts at ``scenario.start`` and ends at ``scenario.goal``: a point
within 1e-9 cells of its cell centre replaces the centre, otherwise it is
added as an extra waypoint inside its own cell.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from pathzoo.core import Scenario
from pathzoo.grid.paths import centre_path

__all__ = ["MoveEncoding", "COMPASS"]

COMPASS = np.array([(0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0), (1, 1)], dtype=np.int64)
"""The eight moves ``(d_row, d_col)`` in counter-clockwise order from east (y grows downwards)."""

_TRY_ORDER = np.array([0, 1, -1, 2, -2, 3, -3, 4], dtype=np.int64)


@numba.njit(cache=True)
def _walk(targets, lengths, start, goal, genes, pos, nodes, dirs):
    # returns (number of nodes, length); pos must be all -1 on entry and is reset on exit
    nodes[0] = start
    pos[start] = 0
    m = 1
    total = 0.0
    for g in genes:
        u = nodes[m - 1]
        if u == goal:
            break
        v = -1
        d = 0
        for t in _TRY_ORDER:
            d = (g + t) % 8
            if targets[u, d] >= 0:
                v = targets[u, d]
                break
        if v < 0:
            break  # an isolated cell: no move at all
        if pos[v] >= 0:
            keep = pos[v] + 1
            for q in range(keep, m):
                total -= lengths[nodes[q - 1], dirs[q]]
                pos[nodes[q]] = -1
            m = keep
        else:
            nodes[m] = v
            dirs[m] = d
            total += lengths[u, d]
            pos[v] = m
            m += 1
    for q in range(m):
        pos[nodes[q]] = -1
    return m, total


@numba.njit(cache=True)
def _batch_cost(targets, lengths, width, start, goal, genes, max_turn, weight, pos, nodes, dirs):
    n = genes.shape[0]
    cost = np.empty(n)
    violation = np.empty(n)
    gr, gc = goal // width, goal % width
    for i in range(n):
        m, total = _walk(targets, lengths, start, goal, genes[i], pos, nodes, dirs)
        last = nodes[m - 1]
        dr = abs(last // width - gr)
        dc = abs(last % width - gc)
        bad = max(dr, dc) + (math.sqrt(2.0) - 1.0) * min(dr, dc)
        if max_turn < 180.0:
            for q in range(2, m):
                diff = abs(dirs[q] - dirs[q - 1]) % 8
                if 45.0 * min(diff, 8 - diff) > max_turn:
                    bad += 1.0
        violation[i] = bad
        cost[i] = total + weight * bad
    return cost, violation


def _compile() -> None:
    """Compile the walk kernels now, at import, not inside a timed ``plan()``."""
    targets = np.full((1, 8), -1, dtype=np.int64)
    idx = np.zeros(2, dtype=np.int64)
    genes = np.zeros((1, 1), dtype=np.int64)
    _batch_cost(targets, np.zeros((1, 8)), 1, 0, 0, genes, 180.0, 1.0, np.full(1, -1), idx, idx)
    _walk(targets, np.zeros((1, 8)), 0, 0, np.zeros(1, dtype=np.int64), np.full(1, -1), idx, idx.copy())


_compile()


class MoveEncoding:
    """Candidates as ``L`` compass moves; see the module docstring.

    Parameters
    ----------
    scenario : Scenario
        The problem (``grid2d`` or ``terrain``); its graph is built if needed.
    moves_factor : float
        ``L = ceil(moves_factor * (H + W))``.
    penalty : float
        Cost of one unit of violation, in map diagonals.
    """

    integer = True

    def __init__(self, scenario: Scenario, *, moves_factor: float, penalty: float) -> None:
        self.scenario = scenario
        h, w = scenario.shape
        self.n_genes = max(1, math.ceil(moves_factor * (h + w)))
        self.low = np.zeros(self.n_genes)
        self.high = np.full(self.n_genes, 7.0)
        graph = scenario.graph
        n = graph.n_nodes
        compass_of_offset = np.array(
            [int(np.flatnonzero((COMPASS == off).all(axis=1))[0]) for off in graph.offsets], dtype=np.int64
        )
        self._targets = np.full((n, 8), -1, dtype=np.int64)
        self._lengths = np.zeros((n, 8))
        src, comp = graph.sources, compass_of_offset[graph.offset_id]
        self._targets[src, comp] = graph.indices
        self._lengths[src, comp] = graph.length
        self._weight = float(penalty) * float(np.hypot(*scenario.extent))
        self._pos = np.full(n, -1, dtype=np.int64)
        self._nodes = np.empty(self.n_genes + 1, dtype=np.int64)
        self._dirs = np.zeros(self.n_genes + 1, dtype=np.int64)
        start_rc, goal_rc = scenario.cell_of(np.stack([scenario.start, scenario.goal]))
        bearing = math.atan2(-(goal_rc[0] - start_rc[0]), goal_rc[1] - start_rc[1])
        self._towards_goal = int(round(bearing / (math.pi / 4))) % 8

    def initial(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """``n`` random move strings, each gene aimed at the goal with probability 1/2."""
        genes = rng.integers(0, 8, size=(n, self.n_genes))
        aimed = rng.random((n, self.n_genes)) < 0.5
        genes[aimed] = self._towards_goal
        return genes

    def evaluate(self, genes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(cost, violation)`` of candidates of shape (n, L)."""
        sc = self.scenario
        g = np.asarray(genes).reshape(-1, self.n_genes).astype(np.int64) % 8
        return _batch_cost(
            self._targets, self._lengths, sc.shape[1], sc.start_node, sc.goal_node, g,
            float(sc.vehicle.max_turn_deg), self._weight, self._pos, self._nodes, self._dirs,
        )

    def path(self, genes: np.ndarray) -> np.ndarray:
        """World path of one candidate: cell centres of the walk, with the exact start and goal."""
        sc = self.scenario
        g = np.asarray(genes).reshape(self.n_genes).astype(np.int64) % 8
        m, _ = _walk(self._targets, self._lengths, sc.start_node, sc.goal_node, g, self._pos, self._nodes, self._dirs)
        return centre_path(sc, self._nodes[:m])
