"""Variable-length cell-path encoding: a chromosome is a feasible chain of free cells, with path-aware operators.

A candidate is the sequence of graph nodes (cells) of a path from the start
cell to the goal cell in which consecutive cells are neighbours in
:attr:`Scenario.graph` (8-connected, no corner cutting, slope limits on
terrain). This is the variable-length node representation of grid
path-planning GAs (Hu & Yang, ICRA 2004; Tuncer & Yildirim, Computers &
Electrical Engineering 2012; reviewed by Alsouly & Bennaceur, ICAART 2016):
every individual is feasible, and the operators keep it so.

Operators (all public, usable by other planners):

- :func:`random_individual` (initialisation): :meth:`CellRouter.random_path`,
  a route through one random usable cell;
- :func:`crossover_at_shared_node`: pick a cell both parents visit (not the
  start or goal, uniformly among the shared ones) and swap the tails after
  it; loops the swap creates are cut (:func:`~pathzoo_baselines.routing.remove_loops`).
  Parents with no shared inner cell are returned unchanged;
- :func:`reroute_mutation`: pick two positions ``i < j`` at most
  ``max(2, ceil(reroute_fraction * steps))`` steps apart (a share of the
  chain, so the operator scales with the map) and replace the piece between
  them. With probability ``shortcut_rate`` (default 1/2) the new piece is the
  shortest route between the two cells (the "shortcut" local step, the grid
  analogue of Hu & Yang's deletion/improvement operators); otherwise it goes
  through a random usable cell near the piece (a detour that explores).
  Loops are cut.

The cost is the graph length of the chain (3-D on terrain); the violation is
0, except for heading changes beyond ``vehicle.max_turn_deg`` when that
limit is below 180 degrees, and 1 for the start-cell-only chains used when
the goal cell cannot be reached at all. The path is the chain's cell centres with the
exact start and goal (:func:`pathzoo.grid.paths.centre_path`): every segment
joins two 8-neighbouring centres along a graph edge, so it keeps at least
half a cell's distance from every blocked square it does not touch at a
corner, and a graph edge touches none.
"""

from __future__ import annotations

import math
from typing import Callable

import numba
import numpy as np

from pathzoo.core import Scenario
from pathzoo.grid.paths import centre_path
from pathzoo_baselines.routing import CellRouter, remove_loops

__all__ = [
    "CellPathEncoding",
    "random_individual",
    "crossover_at_shared_node",
    "reroute_mutation",
    "chain_lengths",
    "is_graph_chain",
    "turn_violations",
]


@numba.njit(cache=True)
def _edge_length(indptr, indices, weights, u, v):
    for e in range(indptr[u], indptr[u + 1]):
        if indices[e] == v:
            return weights[e]
    return np.inf


@numba.njit(cache=True)
def chain_lengths(indptr, indices, weights, flat, bounds):
    """Graph length of each chain ``flat[bounds[i]:bounds[i + 1]]``; ``inf`` when a step is not an edge."""
    n = bounds.shape[0] - 1
    out = np.zeros(n)
    for i in range(n):
        total = 0.0
        for k in range(bounds[i], bounds[i + 1] - 1):
            total += _edge_length(indptr, indices, weights, flat[k], flat[k + 1])
        out[i] = total
    return out


def is_graph_chain(scenario: Scenario, nodes: np.ndarray) -> bool:
    """Whether ``nodes`` runs from the start cell to the goal cell along graph edges."""
    nodes = np.asarray(nodes, dtype=np.int64)
    if len(nodes) == 0 or nodes[0] != scenario.start_node or nodes[-1] != scenario.goal_node:
        return False
    g = scenario.graph
    bounds = np.array([0, len(nodes)], dtype=np.int64)
    return bool(np.isfinite(chain_lengths(g.indptr, g.indices, g.length, nodes, bounds)[0]))


def turn_violations(scenario: Scenario, chains: list[np.ndarray]) -> np.ndarray:
    """Per chain of cells: heading changes beyond ``vehicle.max_turn_deg`` (all 0 when the limit is 180)."""
    out = np.zeros(len(chains))
    if scenario.vehicle.max_turn_deg >= 180.0:
        return out
    for k, c in enumerate(chains):
        d = np.diff(scenario.point_of(c), axis=0)
        heading = np.arctan2(d[:, 1], d[:, 0])
        turn = np.degrees(np.abs((np.diff(heading) + np.pi) % (2 * np.pi) - np.pi))
        out[k] = float((turn > scenario.vehicle.max_turn_deg).sum())
    return out


def random_individual(router: CellRouter, rng: np.random.Generator) -> np.ndarray:
    """A random feasible chain: the route through one random usable cell."""
    return router.random_path(rng, vias=1)


def crossover_at_shared_node(
    a: np.ndarray, b: np.ndarray, rng: np.random.Generator, scratch: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Swap the tails of ``a`` and ``b`` after a random inner cell they share; see the module docstring."""
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    shared = np.intersect1d(a[1:-1], b[1:-1])
    if len(shared) == 0:
        return a.copy(), b.copy()
    cell = shared[rng.integers(len(shared))]
    i = int(np.flatnonzero(a == cell)[0])
    j = int(np.flatnonzero(b == cell)[0])
    child_a = remove_loops(np.concatenate([a[:i], b[j:]]), scratch=scratch)
    child_b = remove_loops(np.concatenate([b[:j], a[i:]]), scratch=scratch)
    return child_a, child_b


def reroute_mutation(
    nodes: np.ndarray, router: CellRouter, rng: np.random.Generator, reroute_fraction: float, shortcut_rate: float
) -> np.ndarray:
    """Replace a piece of at most ``max(2, ceil(reroute_fraction * steps))`` steps by a detour or a shortcut.

    The piece becomes the shortest route between its ends with probability
    ``shortcut_rate``, otherwise a route through a random usable cell near it.
    See the module docstring.
    """
    nodes = np.asarray(nodes, dtype=np.int64)
    if len(nodes) < 2:
        return nodes.copy()
    reroute_span = max(2, math.ceil(reroute_fraction * (len(nodes) - 1)))
    i = int(rng.integers(len(nodes) - 1))
    j = int(rng.integers(i + 1, min(len(nodes), i + 1 + reroute_span)))
    if rng.random() >= shortcut_rate:
        w = router.width
        u, v = nodes[i], nodes[j]
        radius = max(2, int(math.ceil(0.5 * max(abs(u // w - v // w), abs(u % w - v % w)))) + 1)
        h = router.scenario.shape[0]
        row = int(np.clip((u // w + v // w) // 2 + rng.integers(-radius, radius + 1), 0, h - 1))
        col = int(np.clip((u % w + v % w) // 2 + rng.integers(-radius, radius + 1), 0, w - 1))
        stops = np.array([u, router.nearest_usable[row * w + col], v], dtype=np.int64)
    else:
        stops = np.array([nodes[i], nodes[j]], dtype=np.int64)
    piece = router.chain(stops)
    return remove_loops(np.concatenate([nodes[:i], piece, nodes[j + 1:]]), scratch=router.scratch)


class CellPathEncoding:
    """Feasible variable-length chains of cells; see the module docstring.

    Unlike the fixed-length encodings, candidates are a list of int64 arrays
    of different lengths, and the planner must use this encoding's operators.

    Parameters
    ----------
    scenario : Scenario
        The problem (``grid2d`` or ``terrain``).
    reroute_fraction : float
        Longest piece a mutation replaces, as a share of the chain's steps.
    shortcut_rate : float
        Probability that a mutation is the shortcut rather than a detour.
    penalty : float
        Cost of one unit of violation (turns), in map diagonals.
    """

    integer = True
    variable_length = True
    costly = True  # graph searches per candidate: the search looks at the clock between candidates

    def __init__(self, scenario: Scenario, *, reroute_fraction: float, shortcut_rate: float, penalty: float) -> None:
        self.scenario = scenario
        self.router = CellRouter(scenario)
        self.reroute_fraction = float(reroute_fraction)
        self.shortcut_rate = float(shortcut_rate)
        self.n_genes = 0  # variable
        self.low = np.zeros(0)
        self.high = np.zeros(0)
        self._weight = float(penalty) * float(np.hypot(*scenario.extent))

    def initial(self, rng: np.random.Generator, n: int, stop: Callable[[], bool] | None = None) -> list[np.ndarray]:
        """``n`` random feasible chains (the start cell alone when the goal cell is unreachable).

        When ``stop()`` turns true (the time limit), the chains not yet drawn
        are copies of those drawn (at least one is).
        """
        if not self.router.connected:
            return [np.array([self.scenario.start_node], dtype=np.int64) for _ in range(n)]
        out: list[np.ndarray] = []
        while len(out) < n and not (out and stop is not None and stop()):
            out.append(random_individual(self.router, rng))
        return [out[i % len(out)].copy() for i in range(n)]

    def crossover(self, a: np.ndarray, b: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
        """:func:`crossover_at_shared_node`."""
        return crossover_at_shared_node(a, b, rng, self.router.scratch)

    def mutate(self, nodes: np.ndarray, rng: np.random.Generator) -> np.ndarray:
        """:func:`reroute_mutation`."""
        return reroute_mutation(nodes, self.router, rng, self.reroute_fraction, self.shortcut_rate)

    def evaluate(self, genes: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        """``(cost, violation)`` of a list of chains."""
        chains = [np.asarray(c, dtype=np.int64) for c in genes]
        bounds = np.concatenate([[0], np.cumsum([len(c) for c in chains])]).astype(np.int64)
        g = self.scenario.graph
        length = chain_lengths(g.indptr, g.indices, g.length, np.concatenate(chains), bounds)
        violation = turn_violations(self.scenario, chains)
        violation += np.array([c[-1] != self.scenario.goal_node for c in chains], dtype=np.float64)
        return length + self._weight * violation, violation

    def diversity(self, genes: list[np.ndarray]) -> float:
        """Mean Jaccard distance between the cell sets of consecutive individuals, in ``[0, 1]``."""
        if len(genes) < 2:
            return 0.0
        sets = [np.unique(np.asarray(c)) for c in genes]
        d = []
        for a, b in zip(sets[:-1], sets[1:]):
            common = len(np.intersect1d(a, b, assume_unique=True))
            d.append(1.0 - common / (len(a) + len(b) - common))
        return float(np.mean(d))

    def path(self, genes: np.ndarray) -> np.ndarray:
        """World path of one chain: its cell centres, from exactly the start to exactly the goal."""
        return centre_path(self.scenario, np.asarray(genes, dtype=np.int64))
