"""Polyanya (Cui, Harabor & Grastien, IJCAI 2017): exact any-angle search over a navigation mesh, exact arithmetic.

A search node is an *interval* on a polygon edge together with a *root*:
every point of the interval is reached by the shortest path to the root
followed by a straight segment, and the node stands for all paths that go on
from the interval into the polygon beyond it (its *next* polygon). Expanding
a node projects the interval through that polygon (a convex polygon, so
every point of it is visible from the interval): the parts of the far edges
inside the cone from the root through the interval are *observable*
successors with the same root; the parts outside are reached by turning at
an interval endpoint, and become *non-observable* successors rooted there,
but only when that endpoint is a mesh vertex and a corner (the only places
a shortest path bends). ``f = g(root) + h``, where ``h`` is the shortest
distance from the root through the interval to the goal (the goal reflected
across the interval's line when it lies on the root's side). Root-level
pruning keeps, for each vertex, the best ``g`` with which it became a root,
and drops nodes whose root was reached more cheaply.

Exactness. Coordinates are integers on a lattice of ``scale`` units per cell
(vertices are grid points; the start and goal must lie on the lattice). The
two sides of every cone are stored as integer direction vectors from the root
(towards a vertex, or along the line through two earlier roots), so every
decision (which side of a cone a vertex lies on, whether an interval ends at
a vertex, where a piece of an edge begins) is an exact integer cross product
or a comparison of two such rationals, with no tolerance. Distances are
floats. Intervals are closed, and only pieces of positive length become
nodes: a ray through a single vertex is the limit of the rays of a piece on
one side of it, so it is covered by the closed piece.

The goal is reached when a node's next polygon contains it: the node's
best path is then the straight line through the interval, or a turn at the
interval's endpoint if that endpoint is a corner; it is pushed as a final
node with its exact length, and the search ends when a final node is popped.
"""

from __future__ import annotations

import heapq
import math

import numba
import numpy as np

from pathzoo.grid.navmesh import NavMesh, polygons_at

__all__ = ["polyanya_search", "MAX_LATTICE_EXTENT"]

MAX_LATTICE_EXTENT = 2**15
"""Largest map side times lattice scale: products of two cross products then stay below 2**62."""

_EPS = 1e-9
"""Tolerance (in lattice units) of root-level pruning: a root reached more expensively by more than this is dropped."""

# node columns (int64)
_ROOT, _POLY, _EDGE, _RX, _RY, _LX, _LY, _FINAL = range(8)
_NI = 8
# root record columns (int64): vertex (-1 = start), x, y, parent record
_RV, _RPX, _RPY, _RPAR = range(4)


@numba.njit(cache=True)
def _cross(ax: int, ay: int, bx: int, by: int) -> int:
    return ax * by - ay * bx


@numba.njit(cache=True)
def _on_segment(px: int, py: int, ax: int, ay: int, bx: int, by: int) -> bool:
    # the point lies on the closed segment [a, b]
    if _cross(bx - ax, by - ay, px - ax, py - ay) != 0:
        return False
    return (px - ax) * (bx - ax) + (py - ay) * (by - ay) >= 0 and (px - bx) * (ax - bx) + (py - by) * (ay - by) >= 0


@numba.njit(cache=True)
def _h(rx: float, ry: float, ax: float, ay: float, bx: float, by: float, gx: float, gy: float) -> float:
    # shortest |r - p| + |p - g| over p on the segment [a, b], with g reflected to the far side of its line
    ex, ey = bx - ax, by - ay
    sr = ex * (ry - ay) - ey * (rx - ax)
    if sr == 0.0:
        return math.hypot(gx - rx, gy - ry)
    sg = ex * (gy - ay) - ey * (gx - ax)
    if sg != 0.0 and (sg > 0.0) == (sr > 0.0):
        t = ((gx - ax) * ex + (gy - ay) * ey) / (ex * ex + ey * ey)
        gx, gy = 2.0 * (ax + t * ex) - gx, 2.0 * (ay + t * ey) - gy
    dx, dy = gx - rx, gy - ry
    den = ex * dy - ey * dx
    if den != 0.0:
        s = ((rx - ax) * dy - (ry - ay) * dx) / den
        if 0.0 <= s <= 1.0:
            return math.hypot(dx, dy)
    return min(math.hypot(ax - rx, ay - ry) + math.hypot(gx - ax, gy - ay),
               math.hypot(bx - rx, by - ry) + math.hypot(gx - bx, gy - by))


@numba.njit(cache=True)
def _less(n1: int, d1: int, n2: int, d2: int) -> bool:
    # n1 / d1 < n2 / d2 for positive denominators
    return n1 * d2 < n2 * d1


@numba.njit(cache=True)
def _grow_int(a: np.ndarray, need: int) -> np.ndarray:
    if need <= len(a):
        return a
    out = np.empty((max(need, 2 * len(a)), a.shape[1]), dtype=a.dtype)
    out[: len(a)] = a
    return out


@numba.njit(cache=True)
def _grow_float(a: np.ndarray, need: int) -> np.ndarray:
    if need <= len(a):
        return a
    out = np.empty(max(need, 2 * len(a)), dtype=a.dtype)
    out[: len(a)] = a
    return out


@numba.njit(cache=True)
def _edge(vertex: np.ndarray, lo: int, n: int, j: int, w1: int, scale: int) -> tuple[int, int, int, int]:
    # the ends a, b (lattice units) of edge j of the polygon whose vertices are vertex[lo:lo + n]
    a = vertex[lo + j % n]
    b = vertex[lo + (j + 1) % n]
    return (a % w1) * scale, (a // w1) * scale, (b % w1) * scale, (b // w1) * scale


@numba.njit(cache=True)
def _push(
    nodes: np.ndarray, n_nodes: int, heap: list[tuple[float, np.int64]], f: float, root: int, final: int,
    poly: int, edge: int, rx: int, ry: int, lx: int, ly: int,
) -> np.ndarray:
    # store node n_nodes (growing the table) and put it on the open list with priority f
    nodes = _grow_int(nodes, n_nodes + 1)
    s = nodes[n_nodes]
    s[_ROOT], s[_FINAL], s[_POLY], s[_EDGE], s[_RX], s[_RY], s[_LX], s[_LY] = root, final, poly, edge, rx, ry, lx, ly
    heapq.heappush(heap, (f, np.int64(n_nodes)))
    return nodes


@numba.njit(cache=True)
def _turn_at(
    roots: np.ndarray, root_g: np.ndarray, n_roots: int, best: np.ndarray, corner_id: int,
    v: int, x: int, y: int, parent: int, g: float,
) -> tuple[np.ndarray, np.ndarray, int]:
    # a new root record for the corner v reached with g, or -1 when v was a root more cheaply before
    if g > best[corner_id] + _EPS:
        return roots, root_g, -1
    best[corner_id] = min(best[corner_id], g)
    roots = _grow_int(roots, n_roots + 1)
    root_g = _grow_float(root_g, n_roots + 1)
    roots[n_roots, _RV], roots[n_roots, _RPX], roots[n_roots, _RPY], roots[n_roots, _RPAR] = v, x, y, parent
    root_g[n_roots] = g
    return roots, root_g, n_roots


@numba.njit(cache=True)
def _outside_piece(pieces: np.ndarray, m: int, root: int, oa: int, ob: int, ray: int) -> None:
    # row m: the part of a -> b where the cross product with the cone's side `ray` (2 right, 3 left) is negative
    pieces[m, 0] = root
    if oa < 0 and ob < 0:
        pieces[m, 1], pieces[m, 2], pieces[m, 3], pieces[m, 4], pieces[m, 5], pieces[m, 6] = 0, 1, 0, 1, 1, 1
    elif oa < 0:
        pieces[m, 1], pieces[m, 2], pieces[m, 3], pieces[m, 4], pieces[m, 5], pieces[m, 6] = 0, ray, 0, 1, -oa, ob - oa
    else:
        pieces[m, 1], pieces[m, 2], pieces[m, 3], pieces[m, 4], pieces[m, 5], pieces[m, 6] = ray, 1, oa, oa - ob, 1, 1


@numba.njit(cache=True)
def _search(
    offsets: np.ndarray,
    vertex: np.ndarray,
    neighbour: np.ndarray,
    twin: np.ndarray,
    corner: np.ndarray,
    n_corners: int,
    w1: int,
    scale: int,
    start_polys: np.ndarray,
    goal_polys: np.ndarray,
    sx: int,
    sy: int,
    gx: int,
    gy: int,
    max_expansions: int,
) -> tuple[np.ndarray, np.ndarray, int, float, int, int]:
    # Returns (root records, their g, the last root record of the shortest path or -1 (unreachable), its length,
    # expansions, finished flag).
    n_poly = len(offsets) - 1
    is_goal = np.zeros(n_poly, dtype=np.bool_)
    for p in goal_polys:
        is_goal[p] = True
    best = np.full(n_corners, np.inf)
    roots = np.empty((64, 4), dtype=np.int64)
    root_g = np.empty(64, dtype=np.float64)
    nodes = np.empty((256, _NI), dtype=np.int64)
    n_roots = 1
    roots[0, _RV], roots[0, _RPX], roots[0, _RPY], roots[0, _RPAR] = -1, sx, sy, -1
    root_g[0] = 0.0
    n_nodes = 0
    fgx, fgy = float(gx), float(gy)
    heap = [(0.0, np.int64(0))]
    heap.pop()
    # the start: every polygon containing it; one that also contains the goal gives the straight line
    for p in start_polys:
        if is_goal[p]:
            return roots[:1], root_g[:1], 0, math.hypot(gx - sx, gy - sy), 0, 1
    for p in start_polys:
        lo, hi = offsets[p], offsets[p + 1]
        for j in range(hi - lo):
            q = neighbour[lo + j]
            if q < 0:
                continue
            ax, ay, bx, by = _edge(vertex, lo, hi - lo, j, w1, scale)
            if _on_segment(sx, sy, ax, ay, bx, by):
                continue  # the start lies on this edge: the polygon beyond also contains it and is expanded here
            f = _h(float(sx), float(sy), float(ax), float(ay), float(bx), float(by), fgx, fgy)
            nodes = _push(nodes, n_nodes, heap, f, 0, 0, q, twin[lo + j], ax - sx, ay - sy, bx - sx, by - sy)
            n_nodes += 1
    expansions = 0
    pieces = np.empty((3, 7), dtype=np.int64)  # root record, the two ends' kinds, their fractions of a -> b
    ends = np.empty((2, 2), dtype=np.int64)
    while heap:
        f, ni = heapq.heappop(heap)
        nd = nodes[ni].copy()
        rr = nd[_ROOT]
        g = root_g[rr]
        if nd[_FINAL] == 1:
            return roots[:n_roots], root_g[:n_roots], rr, f, expansions, 1
        rv = roots[rr, _RV]
        if rv >= 0 and g > best[corner[rv]] + _EPS:
            continue  # the root was reached more cheaply by another path
        if expansions >= max_expansions:
            return roots[:n_roots], root_g[:n_roots], -1, np.inf, expansions, 0
        expansions += 1
        rx, ry = roots[rr, _RPX], roots[rr, _RPY]
        p = nd[_POLY]
        lo, hi = offsets[p], offsets[p + 1]
        n = hi - lo
        k = nd[_EDGE]
        u = vertex[lo + k]
        w = vertex[lo + (k + 1) % n]
        ux, uy = (u % w1) * scale, (u // w1) * scale
        wx, wy = (w % w1) * scale, (w // w1) * scale
        ori = _cross(wx - ux, wy - uy, rx - ux, ry - uy)
        fr = float(rx)
        fry = float(ry)
        if ori > 0:
            continue  # cannot happen: the root is never inside the polygon it looks into
        croot = rr
        if ori == 0:
            # the root lies on the interval's line: the path slides along it to the nearer endpoint and turns there
            du = (ux - rx) ** 2 + (uy - ry) ** 2
            dw = (wx - rx) ** 2 + (wy - ry) ** 2
            c = u if du <= dw else w
            cx, cy = (c % w1) * scale, (c // w1) * scale
            if cx != rx or cy != ry:
                if corner[c] < 0:
                    continue
                cg = g + math.hypot(cx - fr, cy - fry)
                roots, root_g, croot = _turn_at(roots, root_g, n_roots, best, corner[c], c, cx, cy, rr, cg)
                if croot < 0:
                    continue
                n_roots += 1
            if is_goal[p]:
                # the root is now a vertex of the goal's polygon: straight to the goal
                cost = root_g[croot] + math.hypot(gx - float(cx), gy - float(cy))
                nodes = _push(nodes, n_nodes, heap, cost, croot, 1, -1, -1, 0, 0, 0, 0)
                n_nodes += 1
                continue
        drx, dry, dlx, dly = nd[_RX], nd[_RY], nd[_LX], nd[_LY]
        right_turn = ori < 0 and _cross(drx, dry, wx - rx, wy - ry) == 0 and corner[w] >= 0
        left_turn = ori < 0 and _cross(dlx, dly, ux - rx, uy - ry) == 0 and corner[u] >= 0
        if ori < 0 and is_goal[p]:
            # the goal's polygon: straight through the interval, or round a corner at one of its ends
            ogr = _cross(drx, dry, gx - rx, gy - ry)
            ogl = _cross(gx - rx, gy - ry, dlx, dly)
            via = -1
            cost = np.inf
            if ogr >= 0 and ogl >= 0:
                cost = g + math.hypot(gx - fr, gy - fry)
            elif ogr < 0 and right_turn:
                via = w
                cost = g + math.hypot(wx - fr, wy - fry) + math.hypot(gx - float(wx), gy - float(wy))
            elif ogl < 0 and left_turn:
                via = u
                cost = g + math.hypot(ux - fr, uy - fry) + math.hypot(gx - float(ux), gy - float(uy))
            if via >= 0:
                vx, vy = (via % w1) * scale, (via // w1) * scale
                vg = g + math.hypot(vx - fr, vy - fry)
                roots, root_g, rr = _turn_at(roots, root_g, n_roots, best, corner[via], via, vx, vy, rr, vg)
                if rr < 0:
                    continue
                n_roots += 1
            if cost < np.inf:
                nodes = _push(nodes, n_nodes, heap, cost, rr, 1, -1, -1, 0, 0, 0, 0)
                n_nodes += 1
            continue
        right_root = -1
        left_root = -1
        if right_turn:
            cg = g + math.hypot(wx - fr, wy - fry)
            roots, root_g, right_root = _turn_at(roots, root_g, n_roots, best, corner[w], w, wx, wy, rr, cg)
            if right_root >= 0:
                n_roots += 1
        if left_turn:
            cg = g + math.hypot(ux - fr, uy - fry)
            roots, root_g, left_root = _turn_at(roots, root_g, n_roots, best, corner[u], u, ux, uy, rr, cg)
            if left_root >= 0:
                n_roots += 1
        for j in range(k + 1, k + n):
            i = lo + j % n
            q = neighbour[i]
            if q < 0:
                continue
            ax, ay, bx, by = _edge(vertex, lo, n, j, w1, scale)
            if ori == 0:  # every far edge, whole, seen from the corner the path turned at
                pieces[0, 0], pieces[0, 1], pieces[0, 2], pieces[0, 3] = croot, 0, 1, 0
                pieces[0, 4], pieces[0, 5], pieces[0, 6] = 1, 1, 1
                m = 1
            else:
                oar = _cross(drx, dry, ax - rx, ay - ry)
                obr = _cross(drx, dry, bx - rx, by - ry)
                oal = _cross(ax - rx, ay - ry, dlx, dly)
                obl = _cross(bx - rx, by - ry, dlx, dly)
                m = 0
                # observable piece: t in [lo_t, hi_t] (fractions of a->b) with both cross products >= 0;
                # an end is 0: vertex a, 1: vertex b, 2: on the right ray, 3: on the left ray
                lon, lod, loe = 0, 1, 0
                hin, hid, hie = 1, 1, 1
                empty = False
                for side in range(2):
                    oa, ob, e = (oar, obr, 2) if side == 0 else (oal, obl, 3)
                    if oa < 0 and ob < 0:
                        empty = True
                    elif oa < 0:  # t >= -oa / (ob - oa)
                        if _less(lon, lod, -oa, ob - oa):
                            lon, lod, loe = -oa, ob - oa, e
                    elif ob < 0:  # t <= oa / (oa - ob)
                        if _less(oa, oa - ob, hin, hid):
                            hin, hid, hie = oa, oa - ob, e
                if not empty and _less(lon, lod, hin, hid):
                    pieces[m, 0], pieces[m, 1], pieces[m, 2] = rr, loe, hie
                    pieces[m, 3], pieces[m, 4], pieces[m, 5], pieces[m, 6] = lon, lod, hin, hid
                    m += 1
                if right_root >= 0 and (oar < 0 or obr < 0):
                    _outside_piece(pieces, m, right_root, oar, obr, 2)  # seen from the interval's right end
                    m += 1
                if left_root >= 0 and (oal < 0 or obl < 0):
                    _outside_piece(pieces, m, left_root, oal, obl, 3)  # seen from its left end
                    m += 1
            for t in range(m):
                sr = pieces[t, 0]
                srx, sry = roots[sr, _RPX], roots[sr, _RPY]
                if roots[sr, _RV] == -1 and _on_segment(srx, sry, ax, ay, bx, by):
                    continue  # an edge through the start: the polygons around it are expanded from the start
                for end in range(2):  # each end's direction from the root: to a, to b, or along a side
                    kind = pieces[t, 1 + end]
                    if kind == 0:
                        ends[end, 0], ends[end, 1] = ax - srx, ay - sry
                    elif kind == 1:
                        ends[end, 0], ends[end, 1] = bx - srx, by - sry
                    elif kind == 2:
                        ends[end, 0], ends[end, 1] = drx, dry
                    else:
                        ends[end, 0], ends[end, 1] = dlx, dly
                t0 = pieces[t, 3] / pieces[t, 4]
                t1 = pieces[t, 5] / pieces[t, 6]
                pax, pay = ax + t0 * (bx - ax), ay + t0 * (by - ay)
                pbx, pby = ax + t1 * (bx - ax), ay + t1 * (by - ay)
                f = root_g[sr] + _h(float(srx), float(sry), pax, pay, pbx, pby, fgx, fgy)
                nodes = _push(nodes, n_nodes, heap, f, sr, 0, q, twin[i], ends[0, 0], ends[0, 1], ends[1, 0], ends[1, 1])
                n_nodes += 1
    return roots[:n_roots], root_g[:n_roots], -1, np.inf, expansions, 1


def polyanya_search(
    mesh: NavMesh, scale: int, start: tuple[int, int], goal: tuple[int, int], max_expansions: int
) -> tuple[list[tuple[int, int]] | None, float, int, bool]:
    """Search from ``start`` to ``goal`` (integers, ``scale`` units per cell, inside the map).

    Returns the path's points (lattice units, from the start to the goal;
    the inner ones are mesh vertices), its length in lattice units, the
    expanded nodes, and whether the search finished. The path is None when
    the goal is unreachable, or when the search stopped at
    ``max_expansions`` expansions (then ``finished`` is False).
    """
    start_polys = polygons_at(mesh, start[0], start[1], scale)
    goal_polys = polygons_at(mesh, goal[0], goal[1], scale)
    if not np.isin(mesh.component[start_polys], mesh.component[goal_polys]).any():
        return None, math.inf, 0, True  # no polygon path joins them: nothing to search
    roots, _, final, length, expansions, finished = _search(
        mesh.offsets, mesh.vertex, mesh.neighbour, mesh.twin, mesh.corner, mesh.n_corners, mesh.shape[1] + 1,
        scale, start_polys, goal_polys,
        int(start[0]), int(start[1]), int(goal[0]), int(goal[1]), int(max_expansions),
    )
    if final < 0:
        return None, math.inf, int(expansions), bool(finished)
    points = [(int(goal[0]), int(goal[1]))]
    r = int(final)
    while r >= 0:
        points.append((int(roots[r, _RPX]), int(roots[r, _RPY])))
        r = int(roots[r, _RPAR])
    return points[::-1], float(length), int(expansions), True
