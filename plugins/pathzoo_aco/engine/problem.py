"""The static view of a scenario that every ant colony walks on: graph arrays, geometry, turn table."""

from __future__ import annotations

import math
from collections import OrderedDict
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Callable, Hashable, Iterator, TypeVar

import numpy as np

from pathzoo.core.object_memo import ObjectMemo
from pathzoo.core.scenario import Scenario
from pathzoo.grid.graph import GridGraph, move_values
from pathzoo.grid.graph_cache import release_pages
from pathzoo.grid.paths import centre_path

__all__ = ["ColonyProblem"]

T = TypeVar("T")

_TABLES: "ObjectMemo[Scenario, dict[str, Any]]" = ObjectMemo()
"""Per live scenario object: its problem's computed arrays and memo. The values never refer to the
scenario, so an entry goes with its scenario."""


class _kept(cached_property):
    """A :func:`functools.cached_property` kept in the problem's shared tables rather than on the instance."""

    def __get__(self, instance, owner=None):  # noqa: ANN001, ANN204
        if instance is None:
            return self
        tables = instance._tables
        if self.attrname not in tables:
            tables[self.attrname] = self.func(instance)
        return tables[self.attrname]

MEMO_ENTRIES = 8
"""Per-configuration tables kept per scenario (least recently used dropped first)."""


@dataclass(frozen=True, eq=False)
class ColonyProblem:
    """One scenario as the colony sees it: its neighbourhood graph and a few derived arrays.

    Everything here depends only on the scenario, never on a planner's
    parameters, and is computed lazily (a 2569 x 1919 terrain has about 39
    million edges, so nothing is built that a variant does not ask for).

    Parameters
    ----------
    scenario : Scenario
        The planning problem (left unchanged).

    Attributes
    ----------
    graph : GridGraph
        ``scenario.graph`` (CSR: ``indptr``, ``indices``, ``length``, ``slope``, ``energy``, ``degree``).
    start, goal : int
        Start and goal node ids.
    """

    scenario: Scenario
    _tables: dict[str, Any] = field(default_factory=dict, init=False, repr=False)

    @classmethod
    def of(cls, scenario: Scenario) -> "ColonyProblem":
        """A problem that shares its computed arrays and :meth:`memo` tables with every other of this scenario.

        The tables are kept in a weak-keyed map beside the scenario (nothing is
        added to the scenario object), and live exactly as long as it does,
        like ``scenario.graph``.
        """
        problem = cls(scenario)
        object.__setattr__(problem, "_tables", _TABLES.value(scenario, dict))
        return problem

    def memo(self, key: Hashable, build: Callable[[], T]) -> T:
        """``build()``, computed once per ``key`` and kept for later calls (the :data:`MEMO_ENTRIES` latest keys).

        For tables that depend on the scenario and a planner's configuration
        only (heuristics, gains, walk rules). Callers must treat the result
        as read-only.
        """
        memo = self._tables.setdefault("_memo", OrderedDict())
        if key in memo:
            memo.move_to_end(key)
            return memo[key]
        value = build()
        memo[key] = value
        while len(memo) > MEMO_ENTRIES:
            memo.popitem(last=False)
        return value

    @_kept
    def indices32(self) -> np.ndarray:
        """``graph.indices`` as int32 (half the memory traffic of the int64 CSR array in the walks).

        Copied block by block; a memory-mapped graph's pages are released
        behind the copy (:func:`pathzoo.grid.graph_cache.release_pages`).
        """
        g = self.graph
        out = np.empty(g.n_edges, dtype=np.int32)
        block = 1 << 22
        for lo in range(0, g.n_edges, block):
            edges = slice(lo, min(lo + block, g.n_edges))
            out[edges] = g.indices[edges]
            release_pages(g, edges)
        return out

    @_kept
    def indptr32(self) -> np.ndarray:
        """``graph.indptr`` as int32 (half the cache lines per node in the walks); int64 for 2**31 edges or more."""
        indptr = self.graph.indptr
        return indptr.astype(np.int32) if self.graph.n_edges < 2**31 else indptr

    @_kept
    def offset_id_small(self) -> np.ndarray:
        """``graph.offset_id`` as int8 (int32 for neighbourhoods of more than 127 moves)."""
        g = self.graph
        return g.offset_id.astype(np.int8 if len(g.offsets) <= 127 else np.int32)

    @_kept
    def graph(self) -> GridGraph:
        """The scenario's shared neighbourhood graph."""
        return self.scenario.graph

    @_kept
    def start(self) -> int:
        """Node id of the start cell."""
        return self.scenario.start_node

    @_kept
    def goal(self) -> int:
        """Node id of the goal cell."""
        return self.scenario.goal_node

    @property
    def n_nodes(self) -> int:
        """Number of nodes (all cells)."""
        return self.graph.n_nodes

    @_kept
    def n_free(self) -> int:
        """Number of nodes with at least one edge: the longest simple walk has fewer edges."""
        return int(np.count_nonzero(self.graph.degree)) + 1

    @_kept
    def sources(self) -> np.ndarray:
        """Source node of each edge."""
        return self.graph.sources

    @_kept
    def node_xyz(self) -> np.ndarray:
        """World coordinates of every node centre, shape (N, 3); on terrain ``z`` is the cell's elevation."""
        return self.xyz_of(slice(0, self.n_nodes))

    def xyz_of(self, nodes: slice) -> np.ndarray:
        """:attr:`node_xyz` of a range of nodes (computed, not kept)."""
        s = self.scenario
        lo, hi, _ = nodes.indices(self.n_nodes)
        pts = s.point_of(np.arange(lo, hi))
        if pts.shape[1] == 3:
            return pts
        z = np.zeros((len(pts), 1)) if s.elevation is None else np.nan_to_num(s.elevation.ravel()[lo:hi]).reshape(-1, 1)
        return np.hstack([pts, z])

    @_kept
    def goal_distance(self) -> np.ndarray:
        """Straight-line (3-D on terrain) distance in metres from every node centre to the goal's centre.

        Computed block by block of nodes (no (N, 3) coordinate table is kept for it).
        """
        goal = self.xyz_of(slice(self.goal, self.goal + 1))
        out = np.empty(self.n_nodes)
        block = 1 << 20
        for lo in range(0, self.n_nodes, block):
            hi = min(lo + block, self.n_nodes)
            out[lo:hi] = np.sqrt(((self.xyz_of(slice(lo, hi)) - goal) ** 2).sum(axis=1))
        return out

    @property
    def tangent(self) -> np.ndarray:
        """Per edge ``|tan θ|``: the rise over run of eq. 3 of GGACO (0 on flat maps and in the air).

        Computed on every access, not kept: callers keep what they derive
        from it (a 39-million-edge terrain would hold 312 MB for it).
        """
        return self.tangent_of(slice(None))

    def tangent_of(self, edges: slice) -> np.ndarray:
        """:attr:`tangent` of a range of edges."""
        return self.tangent_from(self.graph.slope[edges])

    def tangent_from(self, slope: np.ndarray) -> np.ndarray:
        """:attr:`tangent` of edges of the given slopes."""
        if self.scenario.kind != "terrain":
            return np.zeros(len(slope))
        return np.abs(np.tan(slope))

    def walk_geometry(self, flat: np.ndarray, offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """3-D length and slope of every edge of walks from the start, equal to ``graph.length[flat]``, ``graph.slope[flat]``.

        ``flat`` and ``offsets`` as in :class:`~pathzoo_aco.engine.walk.Walks`.
        The values are computed at the walked cells by the graph builder's own
        :func:`pathzoo.grid.graph.move_values` rather than read from the graph,
        so the per-colony costs and deposits of a memory-mapped graph map none
        of its pages back in (a few thousand edges spread over the map would
        map most of them).
        """
        flat = np.asarray(flat, dtype=np.int64)
        targets = self.indices32[flat]
        sources = np.empty(len(flat), dtype=np.int64)
        sources[1:] = targets[:-1]
        sources[offsets[:-1][offsets[:-1] < offsets[1:]]] = self.start  # each walk's first edge leaves the start
        moves = self.offset_id_small[flat]
        length = np.empty(len(flat))
        slope = np.empty(len(flat))
        for move in np.unique(moves):
            at = np.flatnonzero(moves == move)
            length[at], slope[at] = move_values(self.scenario, self.graph.offsets[move], sources[at])
        return length, slope

    def node_blocks(self, max_edges: int = 1 << 21) -> Iterator[slice]:
        """Consecutive ranges of nodes with about ``max_edges`` edges each (at least one node), covering all nodes.

        Per-edge tables built block by block need temporaries of one block,
        not of the whole graph; elementwise results are the same.
        """
        indptr = self.graph.indptr
        n = self.n_nodes
        lo = 0
        while lo < n:
            hi = int(np.searchsorted(indptr, indptr[lo] + max_edges, side="right")) - 1
            hi = min(max(hi, lo + 1), n)
            yield slice(lo, hi)
            lo = hi

    @_kept
    def horizontal_offsets(self) -> np.ndarray:
        """Per neighbourhood move: True when it changes the horizontal position (heading matters)."""
        off = self.graph.offsets
        return np.any(off[:, -2:] != 0, axis=1)

    @_kept
    def turn_table(self) -> np.ndarray:
        """Allowed heading changes: ``table[prev, next]`` is 1.0 or 0.0, shape (K + 1, K).

        Row ``K`` stands for "no previous move" (at the start). The heading
        change is measured horizontally, as the validator does; vertical moves
        keep the previous heading. Empty (shape (0, 0)) when the vehicle has no
        turn limit, which switches the check off in the walk kernel.
        """
        limit = self.scenario.vehicle.max_turn_deg
        if limit >= 180.0:
            return np.zeros((0, 0))
        off = self.graph.offsets
        k = len(off)
        heading = np.arctan2(off[:, -2], off[:, -1])  # y = row axis, x = column axis
        turn = np.abs((heading[None, :] - heading[:, None] + math.pi) % (2 * math.pi) - math.pi)
        table = np.ones((k + 1, k))
        table[:k] = np.where(np.degrees(turn) <= limit + 1e-7, 1.0, 0.0)
        vertical = ~self.horizontal_offsets
        table[:, vertical] = 1.0
        return table

    def walk_points(self, edges: np.ndarray) -> np.ndarray:
        """World path of a walk given as edge ids: exact start, cell centres, exact goal.

        The exact start and goal replace the first and last centres when they
        coincide (to the validator's tolerance) and are added otherwise.
        """
        targets = self.indices32[np.asarray(edges, dtype=np.int64)]  # not the graph's: its pages may be mapped out
        nodes = np.concatenate([np.array([self.start], dtype=np.int64), targets.astype(np.int64)])
        return centre_path(self.scenario, nodes)
