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
from typing import TYPE_CHECKING, Callable

import numba
import numpy as np
import scipy.sparse as sp

from pathzoo.grid.segments import touched_cells_2d, touched_cells_3d
from pathzoo.grid.slope_limit import slope_exceeds, slope_limit_band
from pathzoo.grid.terrain import neighbour_slope_range, segments_slope_range

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


def _shift(off: np.ndarray, shape: tuple[int, ...]) -> int:
    """Flat-id difference between a cell and its neighbour by move ``off`` (row-major)."""
    return sum(int(d) * math.prod(shape[i + 1 :]) for i, d in enumerate(off))


def _on_terrain(scenario: "Scenario") -> bool:
    """Whether edges get the ground's heights (lengths, slopes and the slope limits)."""
    return scenario.elevation is not None and scenario.kind == "terrain"


def _move_run(scenario: "Scenario", off: np.ndarray) -> tuple[float, float]:
    """Horizontal and vertical run in metres of one move (vertical 0 on 2-D maps: the ground's rise is separate)."""
    step = off * scenario.cell_sizes[::-1]  # array-axis order
    return float(np.hypot(step[-1], step[-2])), float(step[0]) if len(off) == 3 else 0.0


def move_values(scenario: "Scenario", off: np.ndarray, cells: np.ndarray
                ) -> tuple[np.ndarray | float, np.ndarray | float]:
    """3-D length and signed slope of one move from each of ``cells`` (one number for every cell off terrain).

    :func:`build_graph` fills ``GridGraph.length`` and ``GridGraph.slope``
    with the same expressions, so for an edge of the graph it gives exactly
    the stored values. The move must be allowed from every cell given (on
    terrain both heights are finite).
    """
    horiz, vert = _move_run(scenario, off)
    if len(off) == 3:
        return math.sqrt(horiz**2 + vert**2), math.atan2(vert, horiz)
    if _on_terrain(scenario):
        assert scenario.elevation is not None  # _on_terrain: it has one
        elev = scenario.elevation.ravel()
        dz = elev[cells + _shift(off, scenario.blocked.shape)] - elev[cells]  # finite: the builder checked it
        return np.sqrt(horiz**2 + dz**2), _terrain_slope(dz, horiz)
    return horiz, 0.0


def _terrain_slope(dz: np.ndarray, horiz: float) -> np.ndarray:
    """Signed slope of terrain edges of one move from their rises (a contiguous array) and the move's run."""
    return np.arctan2(dz, horiz)


_UNDECIDED = 2
"""A move's verdict in :func:`_move_verdicts` when the slope limits need the angle expression itself."""


@numba.njit(cache=True)
def _move_verdicts(free_padded, dims, pads, touched_ptr, touched_shift, move_ok, shift, terrain, z, steps,
                   climb_band, descent_band, verdict):
    """Per cell and move: 1 an edge, 0 none, :data:`_UNDECIDED` when the slope verdict needs the angle expression.

    ``free_padded`` is the flat free-cell grid padded by ``pads`` cells
    (layers, rows, columns) on each side (``dims``: layers, rows, columns
    of the unpadded grid; 2-D maps are one layer, padded by none);
    ``touched_shift`` holds, for move ``j`` at
    ``touched_ptr[j]:touched_ptr[j + 1]``, the padded flat offsets of the
    cells its segment touches, all of which must be free. On terrain
    (``z``: the heights), the two heights must be finite and
    the gradient range of the move's segment from centre to centre
    (:func:`pathzoo.grid.terrain.neighbour_slope_range`, the validator's
    :func:`~pathzoo.grid.terrain.segment_slope_range` for these segments;
    ``steps[j]`` = rows, columns) must lie
    below both limits' bands (:func:`pathzoo.grid.slope_limit.slope_limit_band`):
    the climb limit's for the greatest gradient, the descent limit's for the
    negated least. Returns the number of undecided moves.
    """
    n_layers, h, w = dims[0], dims[1], dims[2]
    hp = h + 2 * pads[1]
    wp = w + 2 * pads[2]
    z_flat = z.ravel()
    k = move_ok.size
    undecided = 0
    c = 0
    for layer in range(n_layers):
        for r in range(h):
            q = ((layer + pads[0]) * hp + r + pads[1]) * wp + pads[2]
            for col in range(w):
                for j in range(k):
                    verdict[c, j] = 0
                    if not move_ok[j]:
                        continue
                    free = True
                    for m in range(touched_ptr[j], touched_ptr[j + 1]):
                        if not free_padded[q + touched_shift[m]]:
                            free = False
                            break
                    if not free:
                        continue
                    if not terrain:
                        verdict[c, j] = 1
                        continue
                    if not math.isfinite(z_flat[c + shift[j]] - z_flat[c]):
                        continue
                    lo, hi = neighbour_slope_range(z, r, col, steps[j, 0], steps[j, 1])
                    if hi < climb_band[0] and -lo < descent_band[0]:
                        verdict[c, j] = 1
                    elif hi <= climb_band[1] and -lo <= descent_band[1]:
                        verdict[c, j] = _UNDECIDED
                        undecided += 1
                q += 1
                c += 1
    return undecided


@numba.njit(cache=True)
def _count_edges(verdict, indptr):
    """``indptr`` of the CSR arrays from the verdicts (each 0 or 1)."""
    indptr[0] = 0
    total = 0
    for c in range(verdict.shape[0]):
        for j in range(verdict.shape[1]):
            total += verdict[c, j]
        indptr[c + 1] = total


@numba.njit(cache=True)
def _write_edges(verdict, lo, hi, first, shift, terrain, z_flat, run2, move_length, move_slope,
                 indices, length, slope, offset_id, rise, rise_at, rise_count):
    """Write the edges of cells ``lo:hi`` from slot ``first`` on, in cell order and move order within a cell.

    Off terrain each move's length and slope are ``move_length[j]``,
    ``move_slope[j]``. On terrain the length is ``sqrt(run2[j] + dz**2)``
    (``run2``: the squared horizontal run) and the rise ``dz`` of each edge
    is gathered per move into ``rise[j, :rise_count[j]]`` with its slot in
    ``rise_at``: the slopes are computed from them per move afterwards.
    Returns the slot after the last edge written.
    """
    e = first
    rise_count[:] = 0
    for c in range(lo, hi):
        for j in range(verdict.shape[1]):
            if verdict[c, j] == 0:
                continue
            t = c + shift[j]
            indices[e] = t
            offset_id[e] = j
            if terrain:
                dz = z_flat[t] - z_flat[c]
                length[e] = math.sqrt(run2[j] + dz * dz)
                m = rise_count[j]
                rise[j, m] = dz
                rise_at[j, m] = e
                rise_count[j] = m + 1
            else:
                length[e] = move_length[j]
                slope[e] = move_slope[j]
            e += 1
    return e


def build_graph(scenario: "Scenario", allocate: "Callable[[str, type, int], np.ndarray] | None" = None) -> GridGraph:
    """Build the neighbourhood graph of a scenario (two compiled passes over the cells).

    Runs once per scenario; :attr:`Scenario.graph` caches it (large graphs
    on disk, :mod:`pathzoo.grid.graph_cache`). The first pass decides every
    cell's moves (:func:`_move_verdicts`: free touched cells, and on terrain
    the validator's exact slope test, once per candidate edge), one byte per
    cell and move; the few slope verdicts a comparison cannot settle get
    :func:`pathzoo.grid.slope_limit.slope_exceeds` itself. The second writes the
    CSR arrays in order (:func:`_write_edges`), with lengths and slopes by
    :func:`move_values`'s expressions.

    Parameters
    ----------
    scenario : Scenario
        The map, its heights and the vehicle.
    allocate : callable, optional
        ``allocate(name, dtype, size)`` returns the writable one-dimensional
        array to fill for ``indptr``, ``indices``, ``length``, ``slope`` and
        ``offset_id`` (the graph cache hands out memory-mapped files);
        ``numpy.empty`` by default.
    """
    if allocate is None:
        allocate = _allocate_in_memory
    blocked = scenario.blocked
    shape = blocked.shape
    offsets = neighbour_offsets(blocked.ndim, scenario.max_step)
    pad = int(np.abs(offsets).max())
    free_padded = np.pad(~blocked, pad, constant_values=False)
    dims = np.array((1, *shape) if blocked.ndim == 2 else shape, dtype=np.int64)
    pads = np.array((0, pad, pad) if blocked.ndim == 2 else (pad, pad, pad), dtype=np.int64)
    padded_strides = np.array([int(np.prod(free_padded.shape[i + 1 :])) for i in range(blocked.ndim)], dtype=np.int64)
    touched = [_touched(off) @ padded_strides for off in offsets]
    touched_ptr = np.zeros(len(offsets) + 1, dtype=np.int64)
    np.cumsum([len(t) for t in touched], out=touched_ptr[1:])
    shift = np.array([_shift(off, shape) for off in offsets], dtype=np.int64)
    vehicle = scenario.vehicle
    runs = [_move_run(scenario, off) for off in offsets]
    move_ok = np.array([math.degrees(math.atan2(abs(vert), horiz)) <= vehicle.max_pitch_deg if len(shape) == 3 else True
                        for horiz, vert in runs], dtype=np.bool_)
    terrain = _on_terrain(scenario)
    z = np.ascontiguousarray(scenario.elevation, dtype=np.float64) if terrain else np.zeros((1, 1))
    steps = np.ascontiguousarray(offsets[:, -2:])  # rows, columns
    cell = float(scenario.cell_sizes[0])
    verdict = np.empty((blocked.size, len(offsets)), dtype=np.uint8)
    undecided = _move_verdicts(free_padded.ravel(), dims, pads, touched_ptr, np.concatenate(touched), move_ok, shift,
                               terrain, z, steps, np.array(slope_limit_band(cell, vehicle.max_climb_deg)),
                               np.array(slope_limit_band(cell, vehicle.max_descent_deg)), verdict)
    del free_padded
    if undecided:
        cells, moves = np.nonzero(verdict == _UNDECIDED)
        src = np.empty((len(cells), 2))
        src[:, 0] = cells % shape[1]
        src[:, 1] = cells // shape[1]
        src += 0.5
        grad_lo, grad_hi = segments_slope_range(z, src, src + steps[moves][:, ::-1])
        verdict[cells, moves] = ~slope_exceeds(grad_lo, grad_hi, cell, vehicle)
    indptr = allocate("indptr", np.int64, blocked.size + 1)
    _count_edges(verdict, indptr)
    n_edges = int(indptr[-1])
    indices = allocate("indices", np.int64, n_edges)
    length = allocate("length", np.float64, n_edges)
    slope = allocate("slope", np.float64, n_edges)
    offset_id = allocate("offset_id", np.int16, n_edges)
    if terrain:
        values = np.zeros((2, len(offsets)))
    else:
        values = np.array([move_values(scenario, off, shift[:0]) for off in offsets], dtype=np.float64).T
    run2 = np.array([horiz**2 for horiz, _ in runs])  # as move_values squares it
    block = _WRITE_BLOCK if terrain else blocked.size
    rise = np.empty((len(offsets), block if terrain else 0))
    rise_at = np.empty(rise.shape, dtype=np.int64)
    rise_count = np.zeros(len(offsets), dtype=np.int64)
    edge = 0
    for lo in range(0, blocked.size, block):
        edge = _write_edges(verdict, lo, min(lo + block, blocked.size), edge, shift, terrain, z.ravel(), run2,
                            values[0], values[1], indices, length, slope, offset_id, rise, rise_at, rise_count)
        for j in np.flatnonzero(rise_count):
            slope[rise_at[j, : rise_count[j]]] = _terrain_slope(rise[j, : rise_count[j]], runs[j][0])
    graph = GridGraph(
        shape=tuple(shape),
        indptr=indptr,
        indices=indices,
        length=length,
        slope=slope,
        offset_id=offset_id,
        offsets=offsets,
        vehicle=vehicle,
    )
    for arr in (graph.indptr, graph.indices, graph.length, graph.slope, graph.offset_id):
        arr.setflags(write=False)
    return graph


_WRITE_BLOCK = 1 << 16
"""Cells whose terrain edges :func:`build_graph` writes at a time (bounds the per-move rise buffers)."""


def _allocate_in_memory(name: str, dtype: type, size: int) -> np.ndarray:
    """:func:`build_graph`'s default allocator: an uninitialised array in memory."""
    return np.empty(size, dtype=dtype)
