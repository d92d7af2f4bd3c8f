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

import numpy as np
import scipy.sparse as sp

from pathzoo.grid.segments import touched_cells_2d, touched_cells_3d
from pathzoo.grid.terrain import lattice_slope_range, slope_exceeds

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.core.vehicle import VehicleModel

__all__ = ["GridGraph", "build_graph", "neighbour_offsets"]


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


def _move_edges(scenario: "Scenario", off: np.ndarray, free_padded: np.ndarray, pad: int
                ) -> tuple[np.ndarray, np.ndarray | float, np.ndarray | float]:
    """For one move: which cells may make it (flat bool), and the 3-D length and slope of each such edge.

    Length and slope are flat arrays over all cells on terrain, else one number for every cell.
    """
    shape = scenario.blocked.shape
    ndim = len(shape)
    vehicle = scenario.vehicle
    ok = np.ones(shape, dtype=bool)
    for rel in _touched(off):
        ok &= free_padded[tuple(slice(pad + r, pad + r + s) for r, s in zip(rel, shape))]
    step = off * scenario.cell_sizes[::-1]  # array-axis order
    horiz = float(np.hypot(step[-1], step[-2]))
    if ndim == 3:
        vert = float(step[0])
        pitch = math.degrees(math.atan2(abs(vert), horiz))
        if pitch > vehicle.max_pitch_deg:
            ok[:] = False
        return ok.ravel(), math.sqrt(horiz**2 + vert**2), math.atan2(vert, horiz)
    if scenario.elevation is not None and scenario.kind == "terrain":
        elev = scenario.elevation
        target = np.full(shape, np.nan)
        dr, dc = off
        src = (slice(max(0, -dr), shape[0] - max(0, dr)), slice(max(0, -dc), shape[1] - max(0, dc)))
        dst = (slice(max(0, dr), shape[0] - max(0, -dr)), slice(max(0, dc), shape[1] - max(0, -dc)))
        target[src] = elev[dst]
        dz = target - elev
        theta = np.arctan2(dz, horiz)
        # validity: the exact ground-slope range along the move, the validator's own rule
        grad_lo, grad_hi = lattice_slope_range(elev, (int(dr), int(dc)))
        with np.errstate(invalid="ignore"):
            ok &= ~slope_exceeds(grad_lo, grad_hi, float(scenario.cell_sizes[0]), vehicle)
        ok &= np.isfinite(dz)
        return ok.ravel(), np.sqrt(horiz**2 + np.nan_to_num(dz) ** 2).ravel(), np.nan_to_num(theta).ravel()
    return ok.ravel(), horiz, 0.0


def build_graph(scenario: "Scenario") -> GridGraph:
    """Build the neighbourhood graph of a scenario (vectorised over cells, one move at a time).

    Runs once per scenario; :attr:`Scenario.graph` caches it (large graphs
    on disk, :mod:`pathzoo.grid.graph_cache`). A first pass over the moves
    finds the edges, a second fills the CSR arrays in place, so the only
    graph-sized arrays are the results (a 2569 x 1919 terrain peaks at about
    half the memory of building an (cells x moves) table of every value).
    """
    blocked = scenario.blocked
    shape = blocked.shape
    ndim = blocked.ndim
    offsets = neighbour_offsets(ndim, scenario.max_step)
    pad = int(np.abs(offsets).max())
    free_padded = np.pad(~blocked, pad, constant_values=False)
    n = blocked.size
    k = len(offsets)
    valid = np.zeros((n, k), dtype=bool)
    for j, off in enumerate(offsets):
        valid[:, j] = _move_edges(scenario, off, free_padded, pad)[0]
    degree = valid.sum(axis=1)
    indptr = np.zeros(n + 1, dtype=np.int64)
    np.cumsum(degree, out=indptr[1:])
    n_edges = int(indptr[-1])
    indices = np.empty(n_edges, dtype=np.int64)
    length = np.empty(n_edges)
    slope = np.empty(n_edges)
    offset_id = np.empty(n_edges, dtype=np.int16)
    # the target cell is always among the touched cells, so ``valid`` already
    # excludes moves that leave the grid and a flat shift gives the target id
    strides = np.array([int(np.prod(shape[i + 1 :])) for i in range(ndim)], dtype=np.int64)
    filled = indptr[:-1].copy()  # next free edge slot of every node: edges are in move order within a node
    for j, off in enumerate(offsets):
        ok, move_length, move_slope = _move_edges(scenario, off, free_padded, pad)
        cells = np.flatnonzero(ok)
        slots = filled[cells]
        filled[cells] += 1
        indices[slots] = cells + int(off @ strides)
        length[slots] = move_length[cells] if isinstance(move_length, np.ndarray) else move_length
        slope[slots] = move_slope[cells] if isinstance(move_slope, np.ndarray) else move_slope
        offset_id[slots] = j
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
