"""Routes as waypoint cells: the path encoding, feasibility rule, random routes and three objectives of the MO rivals.

A *route* is an ``int64`` array of node ids (cells), from the start cell to
the goal cell; the robot drives straight between the centres of consecutive
waypoints. This encoding is pathzoo's, written for the multi-objective rivals
(``swarm.mosfla``, ``search.movns``): their papers' own encodings were not
reachable (see their pages).

Feasibility is exact: a segment is allowed only when the judge's own
:func:`~pathzoo.rules.segment_problem` finds nothing wrong with
it (the closed-cell rule of ``docs/corner-rule.md``) and, on terrain, its
steepest piece is at least :data:`SLOPE_MARGIN_DEG` inside the vehicle's
climb and descent limits, so a route never depends on the judge's angle
tolerance. When no slope can break a limit (both limits 90° and no missing
height in the DEM), only the collision test is left, and the route calls
the judge's collision function :func:`~pathzoo.grid.segments.first_blocked_cell_2d`
directly: the same verdict without the slope profile (about 0.7 ms a
segment). Every route a planner keeps has passed this test segment by
segment; operators that would break it are rejected, never repaired silently
(the leap's corner bridging builds a different route and tests it too).

Random routes (:meth:`RouteProblem.random_route`) are shortest routes
through a random *via* cell, read off two shortest-path trees (from the
start, to the goal) built once per problem, so each costs the length of the
route, not a search of the map. Where only the collision test applies, the
segment test, string-pulling and corner bridging run compiled
(:mod:`pathzoo_rivals.route_kernels`), with the same verdicts.

Objectives of a route's world path (the start and goal connectors
included), all minimised (the three of Hidalgo-Paniagua et al.):

- **length**: 3-D length in metres (:func:`pathzoo.metrics.geometry.driven_pieces`);
- **risk** (path safety): minus the mean clearance, in metres, of the cells
  under points sampled every half cell along the route (clearance from
  :attr:`Scenario.clearance`), so routes that keep away from obstacles have
  lower risk. The mean, not the minimum: the minimum is often fixed by the
  start or goal cell and would then not separate any two routes;
- **turning** (path smoothness): the sum of the heading changes at the
  waypoints in radians (:func:`pathzoo.metrics.geometry.turn_angles`).
"""

from __future__ import annotations

import numpy as np

from pathzoo.core import Scenario
from pathzoo.grid.paths import centre_path
from pathzoo.grid.terrain import segment_profile
from pathzoo.rules import segment_problem
from pathzoo.metrics.geometry import drive_time_energy, turn_angles
from pathzoo_exact.problem import H_OCTILE, H_ZERO, search_problem
from pathzoo_exact.search_loop import astar_batch
from pathzoo_exact.search_state import FOUND, HEAP_FULL, RUNNING, SearchState, run_batch
from pathzoo_exact.waypoints import trace_path
from pathzoo_rivals.route_kernels import SEEN_BITS, pull_string_free, route_free, segment_free, via_route
from pathzoo_rivals.route_memo import RouteMemo
from pathzoo_rivals.route_segments import SegmentCache

__all__ = ["RouteProblem", "SLOPE_MARGIN_DEG", "N_OBJECTIVES", "OBJECTIVES", "DETOUR", "SEGMENT_CACHE_SIZE"]

SLOPE_MARGIN_DEG = 1e-6
"""How far inside the climb and descent limits every segment of a route must stay, degrees."""

OBJECTIVES = ("length_m", "risk_m", "turning_rad")
"""Names of the three objectives, in the order of :meth:`RouteProblem.objectives`."""

N_OBJECTIVES = len(OBJECTIVES)

DETOUR = 1.2
"""Longest random route's detour: the via cell of :meth:`RouteProblem.random_route` is drawn among the cells whose
shortest route through them is at most this multiple of the shortest route."""

SEGMENT_CACHE_SIZE = 1 << 20
"""Most segment verdicts :meth:`RouteProblem.segment_ok` keeps (slope-checked maps); the cache starts again when full."""


class RouteProblem:
    """Routes on one scenario: segment feasibility (cached), random routes, objectives and selection criteria.

    Parameters
    ----------
    scenario : Scenario
        A ``grid2d`` or ``terrain`` scenario.
    """

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario
        self.start = int(scenario.start_node)
        self.goal = int(scenario.goal_node)
        self.shape = scenario.shape
        self.free = ~scenario.blocked
        self._segments = SegmentCache(scenario)
        self._measured: dict[str, RouteMemo[tuple[np.ndarray, float]]] = {}  # measure()'s values per rule
        self._outlines: RouteMemo[tuple[np.ndarray, float]] = RouteMemo()  # outline()'s values
        self._segment_ok: dict[tuple[int, int], bool] = {}
        self._via: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None = None  # random_route's trees
        self._candidates: tuple[float, np.ndarray, np.ndarray] | None = None  # its via cells and scratch array
        self._seen: np.ndarray | None = None  # pull_string's segment verdicts (route_kernels.kept_segment_free)
        vehicle = scenario.vehicle
        self._slopes_matter = scenario.kind == "terrain" and (
            min(vehicle.max_climb_deg, vehicle.max_descent_deg) < 90.0
            or (scenario.elevation is not None and bool(np.isnan(scenario.elevation).any()))
        )
        self.collision_only = not self._slopes_matter
        """Whether a segment's only test is the collision test (no slope limit can be broken)."""
        self.blocked = np.ascontiguousarray(scenario.blocked)
        self.cell_size = float(scenario.cell_size)

    # ------------------------------------------------------------ feasibility
    def segment_ok(self, u: int, v: int) -> bool:
        """Whether the straight segment between the centres of cells ``u`` and ``v`` is allowed (see module)."""
        if self.collision_only:
            return bool(segment_free(self.blocked, self.cell_size, u, v))
        key = (u, v)
        known = self._segment_ok.get(key)
        if known is not None:
            return known
        s = self.scenario
        p0, p1 = s.point_of(np.array([u, v]))
        ok = u != v and bool(self.free.flat[u] and self.free.flat[v])
        if ok:
            ok = segment_problem(s, p0, p1) is None
        if ok:
            _, slopes = segment_profile(s.elevation, p0, p1, s.cell_size)
            deg = np.degrees(slopes)
            ok = bool(deg.max() <= s.vehicle.max_climb_deg - SLOPE_MARGIN_DEG
                      and -deg.min() <= s.vehicle.max_descent_deg - SLOPE_MARGIN_DEG)
        if len(self._segment_ok) >= SEGMENT_CACHE_SIZE:
            self._segment_ok.clear()
        self._segment_ok[key] = ok
        return ok

    def route_ok(self, route: np.ndarray) -> bool:
        """Whether a route runs from the start cell to the goal cell through allowed segments only."""
        if len(route) < 2 or int(route[0]) != self.start or int(route[-1]) != self.goal:
            return False
        if self.collision_only:
            return bool(route_free(self.blocked, self.cell_size, np.asarray(route, dtype=np.int64)))
        return all(self.segment_ok(int(a), int(b)) for a, b in zip(route[:-1], route[1:]))

    def reachable(self) -> bool:
        """Whether the goal cell can be reached from the start cell in the neighbourhood graph."""
        return bool(np.isfinite(self._trees()[2][self.goal]))

    # ------------------------------------------------------------ construction
    def shortest_nodes(self, weights: np.ndarray) -> np.ndarray | None:
        """Nodes of a least-``weights`` path from the start cell to the goal cell, ``None`` if there is none.

        A* of the exact family's numba kernel with the octile heuristic, which
        is consistent for any weights at least the edges' 3-D lengths.
        """
        graph = self.scenario.graph
        dims = np.array((1, *self.shape), dtype=np.int64)
        cs = self.scenario.cell_size
        problem = search_problem(self.goal, dims, np.array([cs, cs, 0.0]), H_OCTILE, 1.0)
        args = (graph.indptr, graph.indices, weights, *problem)
        state = SearchState.start(graph.n_nodes, self.start)
        status = RUNNING
        while status in (RUNNING, HEAP_FULL):
            if status == HEAP_FULL:
                state.grow_heap()
            status = run_batch(astar_batch, args, len(graph.offsets), state, 1 << 20)
        return trace_path(state.parent, self.goal) if status == FOUND else None

    def _trees(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Shortest-path trees by 3-D length: ``(from_start, to_goal, d_start, d_goal)``, built once.

        ``from_start[v]`` is ``v``'s predecessor on a shortest path from the
        start cell and ``d_start[v]`` its length; ``to_goal[v]`` is ``v``'s
        successor on a shortest path to the goal cell and ``d_goal[v]`` its
        length (a search from the goal over the reversed edges). Unreached
        cells have an infinite distance.
        """
        if self._via is None:
            graph = self.scenario.graph
            from_start, d_start = self._dijkstra(graph.indptr, graph.indices, graph.length, self.start)
            if self._symmetric():
                rev_indptr, rev_indices, rev_length = graph.indptr, graph.indices, graph.length
            else:
                rev = graph.to_sparse("length").T.tocsr()
                rev_indptr, rev_indices = rev.indptr.astype(np.int64), rev.indices.astype(np.int64)
                rev_length = np.asarray(rev.data, dtype=np.float64)
            to_goal, d_goal = self._dijkstra(rev_indptr, rev_indices, rev_length, self.goal)
            self._via = from_start, to_goal, d_start, d_goal
        return self._via

    def _symmetric(self) -> bool:
        """Whether every edge has its reverse with the same length (no climb limit differs from the descent's)."""
        vehicle = self.scenario.vehicle
        return self.scenario.kind != "terrain" or (
            vehicle.max_climb_deg == vehicle.max_descent_deg or min(vehicle.max_climb_deg, vehicle.max_descent_deg) >= 90.0)

    def _dijkstra(self, indptr: np.ndarray, indices: np.ndarray, weights: np.ndarray, source: int
                  ) -> tuple[np.ndarray, np.ndarray]:
        """Parents and distances of a whole-map search from ``source`` (the exact kernel, zero heuristic)."""
        dims = np.array((1, *self.shape), dtype=np.int64)
        cs = self.scenario.cell_size
        problem = search_problem(-1, dims, np.array([cs, cs, 0.0]), H_ZERO, 1.0)
        args = (indptr, indices, weights, *problem)
        state = SearchState.start(len(indptr) - 1, source)
        status = RUNNING
        while status in (RUNNING, HEAP_FULL):
            if status == HEAP_FULL:
                state.grow_heap()
            status = run_batch(astar_batch, args, len(self.scenario.graph.offsets), state, 1 << 22)
        unreached = ~state.closed
        np.putmask(state.parent, unreached, -1)  # in place: no second pair of node-sized arrays
        np.putmask(state.g, unreached, np.inf)
        return state.parent, state.g

    def random_route(self, rng: np.random.Generator, detour: float = DETOUR) -> np.ndarray | None:
        """A feasible route: the shortest route through a random *via* cell, string-pulled.

        The via cell is drawn uniformly among the cells whose shortest route
        through them is at most ``detour`` times the shortest route (the
        trees of :meth:`_trees`, built on the first call); the route is the
        start tree's path to it and the goal tree's path on, with any loop
        cut. Returns ``None`` when the goal cell is unreachable.
        """
        from_start, to_goal, d_start, d_goal = self._trees()
        best = float(d_goal[self.start])
        if not np.isfinite(best):
            return None
        if self._candidates is None or self._candidates[0] != detour:
            through = d_start + d_goal
            self._candidates = (detour, np.flatnonzero(through <= detour * best),
                                np.full(len(d_start), -1, dtype=np.int64))
        _, candidates, seen = self._candidates
        via = int(candidates[rng.integers(len(candidates))])
        nodes = via_route(from_start, to_goal, via, self.goal, seen)
        return self.pull_string(nodes)

    def pull_string(self, nodes: np.ndarray) -> np.ndarray:
        """Drop waypoints greedily: from each kept waypoint, go straight to the last node still in reach.

        ``nodes`` must be a feasible route (every consecutive pair allowed);
        the result is one too, with the same first and last node.
        """
        if self.collision_only:
            if self._seen is None:
                self._seen = np.full(1 << SEEN_BITS, -1, dtype=np.int64)
            return pull_string_free(self.blocked, self.cell_size, np.asarray(nodes, dtype=np.int64), self._seen)
        keep = [int(nodes[0])]
        anchor = 0
        i = 1
        while i < len(nodes):
            j = i
            while j + 1 < len(nodes) and self.segment_ok(int(nodes[anchor]), int(nodes[j + 1])):
                j += 1
            keep.append(int(nodes[j]))
            anchor = j
            i = j + 1
        return np.array(keep, dtype=np.int64)

    # ------------------------------------------------------------ objectives
    def polyline(self, route: np.ndarray) -> np.ndarray:
        """Cell-centre polyline of a route (world coordinates, no endpoint connectors)."""
        return self.scenario.point_of(route)

    def outline(self, route: np.ndarray) -> tuple[np.ndarray, float]:
        """A route's :meth:`polyline` and its length (NumPy's sum of the segments' ``hypot``), kept per route.

        The arrays are kept (:class:`~pathzoo_rivals.route_memo.RouteMemo`): callers must not modify them.
        """
        known = self._outlines.get(route)
        if known is None:
            points = self.polyline(route)
            known = points, float(np.hypot(*np.diff(points, axis=0).T).sum())
            self._outlines.keep(route, known)
        return known

    def objectives(self, route: np.ndarray) -> np.ndarray:
        """``(length, risk, turning)`` of a route's world path, all to be minimised (see module)."""
        return self.measure(route, "length")[0]

    def measure(self, route: np.ndarray, rule: str) -> tuple[np.ndarray, float]:
        """The objectives of a route (:meth:`objectives`) and its selection criterion under ``rule``.

        The criterion is the route's 3-D length (m, ``rule="length"``) or the
        harness's energy metric (J, ``"energy"``). Both come from the same
        driven pieces, the harness's (:func:`~pathzoo.metrics.geometry.driven_pieces`)
        kept per segment (:class:`~pathzoo_rivals.route_segments.SegmentCache`),
        and heading changes (:func:`~pathzoo.metrics.geometry.turn_angles`).
        A route measured before is answered from a :class:`~pathzoo_rivals.route_memo.RouteMemo`
        (the same values, to the last bit).
        """
        memo = self._measured.setdefault(rule, RouteMemo())
        known = memo.get(route)
        if known is None:
            known = self._measure_path(self.world_path(route), rule)
            memo.keep(route, known)
        return known[0].copy(), known[1]

    def _measure_path(self, pts: np.ndarray, rule: str) -> tuple[np.ndarray, float]:
        """:meth:`measure` of a route's world path, computed."""
        lengths, slopes = self._segments.pieces(pts)
        turns = turn_angles(pts)
        f = np.array([float(lengths.sum()), -self.mean_clearance(pts), float(turns.sum())])
        if rule == "length":
            return f, float(f[0])
        return f, drive_time_energy(self.scenario.vehicle, lengths, slopes, turns)[1]

    def mean_clearance(self, pts: np.ndarray) -> float:
        """Mean clearance (m) of the cells under points sampled every half cell along a polyline (kept per segment)."""
        return float(self._segments.clearances(np.asarray(pts, dtype=np.float64)).mean())

    def world_path(self, route: np.ndarray) -> np.ndarray:
        """The route as a world path from exactly ``scenario.start`` to exactly ``scenario.goal``."""
        return centre_path(self.scenario, route)
