"""Lazy Theta* (Nash, Koenig & Tovey, AAAI 2010) in air volumes: a short any-angle path, an upper bound on the optimum.

The search runs on the scenario's air graph (:mod:`pathzoo.grid.graph`: voxel
centres, ``max_step`` moves within the pitch limit) with the Euclidean
distance in metres as edge cost and heuristic. Like Theta*, a node's parent
may be any earlier node it sees; Lazy Theta* assumes the grandparent is seen
when a node is generated and checks it only when the node is expanded,
falling back to the best expanded neighbour otherwise. "Seen" is the judge's
rule for one segment (:func:`pathzoo.grid.segments.segment_blocked_3d`, the
closed voxels grown by the margin, and the vehicle's pitch limit), so every
segment of the result passes the judge's collision and pitch checks.

Lazy Theta* is not optimal: the any-angle optimum can be shorter, so its
length is an **upper bound** on the optimum, not the optimum. It ignores the
turn limit; :func:`lazy_theta_path` leaves the whole-path judgement to the
caller (:func:`pathzoo.grid.reference.anyangle_bound_3d` runs the judge on it).
"""

from __future__ import annotations

import heapq
import math
from typing import TYPE_CHECKING

import numba
import numpy as np

from pathzoo.grid.segments import segment_blocked_3d

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["lazy_theta_path"]


@numba.njit(cache=True)
def _sees(blocked: np.ndarray, xyz: np.ndarray, sizes: np.ndarray, tan_pitch: float, a: int, b: int) -> bool:
    """Whether the straight segment between nodes ``a`` and ``b`` is free (voxels and pitch)."""
    dx, dy, dz = xyz[b, 0] - xyz[a, 0], xyz[b, 1] - xyz[a, 1], xyz[b, 2] - xyz[a, 2]
    if abs(dz) > tan_pitch * math.hypot(dx, dy) * (1.0 - 1e-12):  # stricter than the judge by rounding
        return False
    return not segment_blocked_3d(blocked, xyz[a] / sizes, xyz[b] / sizes)


@numba.njit(cache=True)
def _dist(xyz: np.ndarray, a: int, b: int) -> float:
    return math.sqrt((xyz[a, 0] - xyz[b, 0]) ** 2 + (xyz[a, 1] - xyz[b, 1]) ** 2 + (xyz[a, 2] - xyz[b, 2]) ** 2)


@numba.njit(cache=True)
def _lazy_theta(indptr: np.ndarray, indices: np.ndarray, blocked: np.ndarray, xyz: np.ndarray, sizes: np.ndarray,
                tan_pitch: float, source: int, target: int) -> np.ndarray:
    n = indptr.shape[0] - 1
    g = np.full(n, np.inf)
    parent = np.full(n, -1, dtype=np.int64)
    closed = np.zeros(n, dtype=np.bool_)
    g[source] = 0.0
    parent[source] = source
    heap = [(_dist(xyz, source, target), source)]
    while len(heap) > 0:
        f, s = heapq.heappop(heap)
        if closed[s] or f > g[s] + _dist(xyz, s, target) + 1e-9 * (1.0 + f):
            continue  # a stale entry
        # set the vertex: the assumed parent must be seen, else take the best expanded neighbour
        p = parent[s]
        if p != s and not _sees(blocked, xyz, sizes, tan_pitch, p, s):
            best, arg = np.inf, -1
            for e in range(indptr[s], indptr[s + 1]):
                v = indices[e]
                if closed[v] and g[v] + _dist(xyz, v, s) < best:
                    best, arg = g[v] + _dist(xyz, v, s), v
            g[s], parent[s] = best, arg
        closed[s] = True
        if s == target:
            break
        ps = parent[s]
        for e in range(indptr[s], indptr[s + 1]):
            v = indices[e]
            if closed[v]:
                continue
            cand = g[ps] + _dist(xyz, ps, v)  # path 2: through the parent, seen or not (checked on expansion)
            if cand < g[v]:
                g[v], parent[v] = cand, ps
                heapq.heappush(heap, (cand + _dist(xyz, v, target), v))
    if not closed[target]:
        return np.empty(0, dtype=np.int64)
    nodes = [target]
    while nodes[-1] != source:
        nodes.append(parent[nodes[-1]])
    out = np.empty(len(nodes), dtype=np.int64)
    for i in range(len(nodes)):
        out[i] = nodes[len(nodes) - 1 - i]
    return out


def lazy_theta_path(scenario: "Scenario") -> np.ndarray | None:
    """The Lazy Theta* path of an ``air3d`` scenario from exactly its start to exactly its goal, or ``None``.

    The start and goal points stand in for their voxels' centres, so the
    first and last segments are seen from the points themselves. ``None``
    when the goal voxel is not reachable.
    """
    graph = scenario.graph
    source, target = scenario.start_node, scenario.goal_node
    xyz = scenario.point_of(np.arange(graph.n_nodes))
    xyz[source] = scenario.start
    xyz[target] = scenario.goal
    tan_pitch = math.tan(math.radians(scenario.vehicle.max_pitch_deg)) if scenario.vehicle.max_pitch_deg < 90 else math.inf
    nodes = _lazy_theta(graph.indptr, graph.indices, np.ascontiguousarray(scenario.blocked), xyz,
                        np.ascontiguousarray(scenario.cell_sizes, dtype=np.float64), tan_pitch, source, target)
    if len(nodes) == 0:
        return None
    path = xyz[nodes]
    if len(path) == 1:
        path = np.stack([scenario.start, scenario.goal])
    return path
