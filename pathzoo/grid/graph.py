"""The neighbourhood graph of a scenario, in compressed sparse row form.

Nodes are *all* cells, numbered row-major (``node = row * W + col``, or
``(layer * H + row) * W + col`` for air volumes); blocked cells simply have no
edges. An edge exists from a free cell to a free neighbour when the straight
segment between their centres touches no blocked cell (the closed-cell rule of
:mod:`pathzoo.grid.segments`, i.e. no corner cutting) and, on terrain, when its
slope is within the vehicle's climb and descent limits.

- ``grid2d``, ``dynamic``, ``terrain``: 8-connected; straight moves cost one
  cell, diagonals √2 cells (3-D length on terrain).
- ``air3d``: every offset up to ``max_step = (horizontal, vertical)`` cells,
  filtered by the vehicle's pitch limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numba
import numpy as np
import scipy.sparse as sp

from pathzoo.grid.segments import touched_cells_2d, touched_cells_3d
from pathzoo.grid.terrain import segments_slope_range, slope_exceeds

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.core.vehicle import VehicleModel

__all__ = ["GridGraph", "build_graph", "move_values", "neighbour_offsets"]


@dataclass(frozen=True, eq=False)
class GridGraph:
    """Directed neighbourhood graph in CSR form.

    Attributes
    ----------
    shape : tuple of int
        Grid shape the node ids refer to.
    indptr : ndarray of int64, shape (N + 1,)
        Edges of node ``u`` are ``indptr[u]:indptr[u + 1]``.
    indices : ndarray of int64, shape (E,)
        Target node of each edge.
    length : ndarray of float64, shape (E,)
        3-D edge length in metres.
    slope : ndarray of float64, shape (E,)
        Signed slope (radians, uphill positive) of each edge; pitch for air.
    offset_id : ndarray of int8, shape (E,)
        Index into ``offsets`` of the move each edge makes.
    offsets : ndarray of int64, shape (K, ndim)
        The neighbourhood moves in array-axis order.
    vehicle : VehicleModel
        Used for the energy edge costs.
    """

    shape: tuple[int, ...]
    indptr: np.ndarray
    indices: np.ndarray
    length: np.ndarray
    slope: np.ndarray
    offset_id: np.ndarray
    offsets: np.ndarray
    vehicle: "VehicleModel"

    @property
    def n_nodes(self) -> int:
        """Number of nodes (all cells, blocked ones included)."""
        return len(self.indptr) - 1

    @property
    def n_edges(self) -> int:
        """Number of directed edges."""
        return len(self.indices)

    @cached_property
    def degree(self) -> np.ndarray:
        """Out-degree of each node (number of traversable neighbours)."""
        return np.diff(self.indptr)

    @cached_property
    def energy(self) -> np.ndarray:
        """Energy in joules to drive each edge at cruise speed (eq. 4 of G-Ant, no turns)."""
        return self.vehicle.segment_energy(self.length, self.slope)

    @cached_property
    def sources(self) -> np.ndarray:
        """Source node of each edge."""
        return np.repeat(np.arange(self.n_nodes, dtype=np.int64), self.degree)

    def neighbours(self, node: int) -> np.ndarray:
        """Target nodes of ``node``'s edges."""
        return self.indices[self.indptr[node] : self.indptr[node + 1]]

    def weights(self, cost: str) -> np.ndarray:
        """Edge weights for ``cost`` in ``{"length", "energy"}``."""
        if cost == "length":
            return self.length
        if cost == "energy":
            return self.energy
        raise ValueError(f"unknown cost {cost!r}; allowed: length, energy")

    def to_sparse(self, cost: str = "length") -> sp.csr_matrix:
        """The graph as a SciPy CSR matrix (for :mod:`scipy.sparse.csgraph`)."""
        n = self.n_nodes
        return sp.csr_matrix((self.weights(cost), self.indices, self.indptr), shape=(n, n))


def neighbour_offsets(ndim: int, max_step: tuple[int, int] = (1, 1)) -> np.ndarray:
    """Neighbourhood moves in array-axis order.

    2-D: the 8 king moves. 3-D: every ``(dz, dy, dx)`` with
    ``|dx|, |dy| <= max_step[0]`` and ``|dz| <= max_step[1]``, except zero.
    """
    if ndim == 2:
        return np.array([(dr, dc) for dr in (-1, 0, 1) for dc in (-1, 0, 1) if (dr, dc) != (0, 0)], dtype=np.int64)
    sh, sv = max_step
    moves = [
        (dz, dy, dx)
        for dz in range(-sv, sv + 1)
        for dy in range(-sh, sh + 1)
        for dx in range(-sh, sh + 1)
        if (dz, dy, dx) != (0, 0, 0)
    ]
    return np.array(moves, dtype=np.int64)


def _touched(offset: np.ndarray) -> np.ndarray:
    """Cells (relative, array-axis order) the centre-to-centre move touches."""
    if len(offset) == 2:
        dr, dc = offset
        return touched_cells_2d(0.5, 0.5, 0.5 + dc, 0.5 + dr)
    dz, dy, dx = offset
    return touched_cells_3d(np.array([0.5, 0.5, 0.5]), np.array([0.5 + dx, 0.5 + dy, 0.5 + dz]))


def _move_cells(scenario: "Scenario", off: np.ndarray, free_padded: np.ndarray, pad: int) -> np.ndarray:
    """Flat ids of the cells that may make one move: every touched cell free and, on terrain, the slope allowed.

    On terrain the slope test (:func:`pathzoo.grid.terrain.segments_slope_range`,
    the validator's own rule and the costly part of the build) runs only for
    the cells that pass the geometric test, with the same segment end points
    :func:`pathzoo.grid.terrain.lattice_slope_range` would use for them.
    """
    shape = scenario.blocked.shape
    vehicle = scenario.vehicle
    ok = np.ones(shape, dtype=bool)
    for rel in _touched(off):
        ok &= free_padded[tuple(slice(pad + r, pad + r + s) for r, s in zip(rel, shape))]
    cells = np.flatnonzero(ok)
    if len(shape) == 3:
        step = off * scenario.cell_sizes[::-1]
        pitch = math.degrees(math.atan2(abs(float(step[0])), float(np.hypot(step[-1], step[-2]))))
        return cells[:0] if pitch > vehicle.max_pitch_deg else cells
    if scenario.elevation is None or scenario.kind != "terrain":
        return cells
    elev = scenario.elevation.ravel()
    cells = cells[np.isfinite(elev[cells + _shift(off, shape)] - elev[cells])]
    keep = np.empty(len(cells), dtype=bool)
    block = 1 << 20  # the slope test's coordinates and ranges for a block of cells at a time (bounded memory)
    for lo in range(0, len(cells), block):
        part = cells[lo : lo + block]
        src = np.empty((len(part), 2))
        src[:, 0] = part % shape[1]
        src[:, 1] = part // shape[1]
        src += 0.5
        dst = src + np.array([off[1], off[0]], dtype=np.float64)
        grad_lo, grad_hi = segments_slope_range(scenario.elevation, src, dst)
        with np.errstate(invalid="ignore"):
            keep[lo : lo + len(part)] = ~slope_exceeds(grad_lo, grad_hi, float(scenario.cell_sizes[0]), vehicle)
    return cells[keep]


def _shift(off: np.ndarray, shape: tuple[int, ...]) -> int:
    """Flat-id difference between a cell and its neighbour by move ``off`` (row-major)."""
    strides = [int(np.prod(shape[i + 1 :])) for i in range(len(shape))]
    return int(np.dot(off, strides))


def move_values(scenario: "Scenario", off: np.ndarray, cells: np.ndarray
                ) -> tuple[np.ndarray | float, np.ndarray | float]:
    """3-D length and signed slope of one move from each of ``cells`` (one number for every cell off terrain).

    The builder fills ``GridGraph.length`` and ``GridGraph.slope`` with it, so
    for an edge of the graph it gives exactly the stored values. The move must
    be allowed from every cell given (on terrain both heights are finite).
    """
    step = off * scenario.cell_sizes[::-1]  # array-axis order
    horiz = float(np.hypot(step[-1], step[-2]))
    if len(off) == 3:
        vert = float(step[0])
        return math.sqrt(horiz**2 + vert**2), math.atan2(vert, horiz)
    if scenario.elevation is not None and scenario.kind == "terrain":
        elev = scenario.elevation.ravel()
        dz = elev[cells + _shift(off, scenario.blocked.shape)] - elev[cells]  # finite: _move_cells checked it
        return np.sqrt(horiz**2 + dz**2), np.arctan2(dz, horiz)
    return horiz, 0.0


@numba.njit(cache=True)
def _place_edges(filled, cells, shift, move, move_length, move_slope, indices, length, slope, offset_id):
    """Write one move's edges into the next free slot of each of ``cells`` (one value or one per cell for length, slope)."""
    per_cell = move_length.size > 1
    for i in range(cells.size):
        c = cells[i]
        e = filled[c]
        filled[c] = e + 1
        indices[e] = c + shift
        length[e] = move_length[i if per_cell else 0]
        slope[e] = move_slope[i if per_cell else 0]
        offset_id[e] = move


def build_graph(scenario: "Scenario") -> GridGraph:
    """Build the neighbourhood graph of a scenario (vectorised over cells, one move at a time).

    Runs once per scenario; :attr:`Scenario.graph` caches it (large graphs
    on disk, :mod:`pathzoo.grid.graph_cache`). A first pass over the moves
    finds each move's cells (the slope test, the costly part, once per
    candidate edge) and keeps them as one boolean per cell and move; a
    second fills the CSR arrays in place, computing lengths and slopes for
    the edges only. No (cells x moves) table of values is ever held.
    """
    blocked = scenario.blocked
    shape = blocked.shape
    ndim = blocked.ndim
    offsets = neighbour_offsets(ndim, scenario.max_step)
    pad = int(np.abs(offsets).max())
    free_padded = np.pad(~blocked, pad, constant_values=False)
    n = blocked.size
    k = len(offsets)
    valid = np.zeros((k, n), dtype=bool)  # move-major: each move's row is contiguous
    for j, off in enumerate(offsets):
        valid[j, _move_cells(scenario, off, free_padded, pad)] = True
    del free_padded
    degree = valid.sum(axis=0)
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(degree, out=indptr[1:])
    del degree
    n_edges = int(indptr[-1])
    indices = np.empty(n_edges, dtype=np.int64)
    length = np.empty(n_edges)
    slope = np.empty(n_edges)
    offset_id = np.empty(n_edges, dtype=np.int16)
    # the target cell is always among the touched cells, so ``valid`` already
    # excludes moves that leave the grid and a flat shift gives the target id
    filled = indptr[:-1].copy()  # next free edge slot of every node: edges are in move order within a node
    for j, off in enumerate(offsets):
        cells = np.flatnonzero(valid[j])
        move_length, move_slope = move_values(scenario, off, cells)
        _place_edges(filled, cells, _shift(off, shape), j, np.atleast_1d(move_length), np.atleast_1d(move_slope),
                     indices, length, slope, offset_id)
    graph = GridGraph(
        shape=tuple(shape),
        indptr=indptr,
        indices=indices,
        length=length,
        slope=slope,
        offset_id=offset_id,
        offsets=offsets,
        vehicle=scenario.vehicle,
    )
    for arr in (graph.indptr, graph.indices, graph.length, graph.slope, graph.offset_id):
        arr.setflags(write=False)
    return graph
