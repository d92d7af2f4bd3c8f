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

Objectives, all minimised (the three of Hidalgo-Paniagua et al.):

- **length**: 3-D length in metres (:func:`pathzoo.metrics.geometry.path_pieces`);
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
from pathzoo.grid.segments import first_blocked_cell_2d, to_cell_units
from pathzoo.grid.terrain import segment_profile
from pathzoo.rules import segment_problem
from pathzoo.grid.paths import path_pieces
from pathzoo.metrics.geometry import travel_time_energy, turn_angles
from pathzoo_exact.problem import H_OCTILE, search_problem
from pathzoo_exact.search_loop import astar_batch
from pathzoo_exact.search_state import FOUND, HEAP_FULL, RUNNING, SearchState, run_batch
from pathzoo_exact.waypoints import trace_path

__all__ = ["RouteProblem", "SLOPE_MARGIN_DEG", "N_OBJECTIVES", "OBJECTIVES"]

SLOPE_MARGIN_DEG = 1e-6
"""How far inside the climb and descent limits every segment of a route must stay, degrees."""

OBJECTIVES = ("length_m", "risk_m", "turning_rad")
"""Names of the three objectives, in the order of :meth:`RouteProblem.objectives`."""

N_OBJECTIVES = len(OBJECTIVES)


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
        self.clearance = scenario.clearance
        self._segment_ok: dict[tuple[int, int], bool] = {}
        self._weights: np.ndarray | None = None  # random_route's noisy edge weights, one array reused
        vehicle = scenario.vehicle
        self._slopes_matter = scenario.kind == "terrain" and (
            min(vehicle.max_climb_deg, vehicle.max_descent_deg) < 90.0
            or (scenario.elevation is not None and bool(np.isnan(scenario.elevation).any()))
        )

    # ------------------------------------------------------------ feasibility
    def segment_ok(self, u: int, v: int) -> bool:
        """Whether the straight segment between the centres of cells ``u`` and ``v`` is allowed (see module)."""
        key = (u, v)
        known = self._segment_ok.get(key)
        if known is not None:
            return known
        s = self.scenario
        p0, p1 = s.point_of(np.array([u, v]))
        ok = u != v and bool(self.free.flat[u] and self.free.flat[v])
        if ok and not self._slopes_matter:
            a, b = to_cell_units(p0, s.cell_size), to_cell_units(p1, s.cell_size)
            ok = first_blocked_cell_2d(s.blocked, a[0], a[1], b[0], b[1])[0] == -2
        elif ok:
            ok = segment_problem(s, p0, p1) is None
        if ok and self._slopes_matter:
            _, slopes = segment_profile(s.elevation, p0, p1, s.cell_size)
            deg = np.degrees(slopes)
            ok = bool(deg.max() <= s.vehicle.max_climb_deg - SLOPE_MARGIN_DEG
                      and -deg.min() <= s.vehicle.max_descent_deg - SLOPE_MARGIN_DEG)
        self._segment_ok[key] = ok
        return ok

    def route_ok(self, route: np.ndarray) -> bool:
        """Whether a route runs from the start cell to the goal cell through allowed segments only."""
        if len(route) < 2 or int(route[0]) != self.start or int(route[-1]) != self.goal:
            return False
        return all(self.segment_ok(int(a), int(b)) for a, b in zip(route[:-1], route[1:]))

    def reachable(self) -> bool:
        """Whether the goal cell can be reached from the start cell in the neighbourhood graph."""
        return self.shortest_nodes(self.scenario.graph.length) is not None

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

    def random_route(self, rng: np.random.Generator, noise: float = 2.0) -> np.ndarray | None:
        """A feasible route: the shortest path under edge lengths scaled by ``U(1, 1 + noise)``, string-pulled.

        Returns ``None`` when the goal cell is unreachable.
        """
        graph = self.scenario.graph
        if self._weights is None:
            self._weights = np.empty(graph.n_edges)
        weights = self._weights
        # rng.uniform(1, 1 + noise, n) written into one reused array: uniform draws 1 + ((1 + noise) - 1) * U
        # from the same stream as rng.random, so the weights are bit for bit the same without two temporaries
        rng.random(out=weights)
        weights *= (1.0 + noise) - 1.0
        weights += 1.0
        weights *= graph.length
        nodes = self.shortest_nodes(weights)
        return None if nodes is None else self.pull_string(nodes)

    def pull_string(self, nodes: np.ndarray) -> np.ndarray:
        """Drop waypoints greedily: from each kept waypoint, go straight to the last node still in reach.

        ``nodes`` must be a feasible route (every consecutive pair allowed);
        the result is one too, with the same first and last node.
        """
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

    def objectives(self, route: np.ndarray) -> np.ndarray:
        """``(length, risk, turning)`` of a route, all to be minimised (see module)."""
        pts = self.polyline(route)
        lengths, _ = path_pieces(self.scenario, pts)
        return np.array([float(lengths.sum()), -self.mean_clearance(pts), float(turn_angles(pts).sum())])

    def mean_clearance(self, pts: np.ndarray) -> float:
        """Mean clearance (m) of the cells under points sampled every half cell along a polyline."""
        cs = self.scenario.cell_size
        seg = np.diff(pts, axis=0)
        steps = np.maximum(1, np.ceil(np.hypot(seg[:, 0], seg[:, 1]) / (0.5 * cs)).astype(np.int64))
        which = np.repeat(np.arange(len(seg)), steps)
        frac = (np.arange(len(which)) - np.repeat(np.cumsum(steps) - steps, steps)) / steps[which]
        samples = np.vstack([pts[:-1][which] + frac[:, None] * seg[which], pts[-1:]])
        cols = np.clip((samples[:, 0] / cs).astype(np.int64), 0, self.shape[1] - 1)
        rows = np.clip((samples[:, 1] / cs).astype(np.int64), 0, self.shape[0] - 1)
        return float(self.clearance[rows, cols].mean())

    def world_path(self, route: np.ndarray) -> np.ndarray:
        """The route as a world path from exactly ``scenario.start`` to exactly ``scenario.goal``."""
        return centre_path(self.scenario, route)

    def criterion(self, route: np.ndarray, rule: str) -> float:
        """Selection criterion of a route: its 3-D length (m) or the harness's energy metric (J)."""
        if rule == "length":
            return float(self.objectives(route)[0])
        return travel_time_energy(self.scenario, self.world_path(route))[1]
