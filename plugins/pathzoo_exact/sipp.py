"""``exact.sipp``: Safe Interval Path Planning (Phillips & Likhachev, ICRA 2011), the earliest arrival among moving obstacles.

The model
---------
The vehicle moves on the scenario's 8-connected cell graph (the graph of
:mod:`pathzoo.grid.graph`: no blocked cell touched, no corner cut), from cell
centre to cell centre, in a straight line at exactly its cruise speed ``v``
(an edge of length ``l`` takes ``l / v`` seconds), and it may wait at a cell
centre for any time. It is at the start at time 0. A timed path is allowed
when the judge accepts it (:mod:`pathzoo.rules.timing`): at no instant of
``[0, arrival]`` does the vehicle come within any moving obstacle's radius
plus the margin ``TOUCH_EPS_CELLS * cell_size``. Among the allowed paths of
this model, SIPP returns one with the earliest arrival at the goal.

How
---
Each cell's timeline splits into *safe intervals*, maximal times when a
vehicle waiting at its centre is clear of every obstacle
(:func:`~pathzoo_exact.safe_intervals.stationary_unsafe_times`, closed form).
A search state is a (cell, safe interval) pair, reached at the earliest time
found so far; arriving earlier in the same interval is never worse, because
the vehicle can wait there. A* (heuristic: octile distance over ``v``, which
is consistent) expands states in order of ``arrival + heuristic``; from a
state it tries, for each neighbour and each safe interval of that neighbour,
the earliest departure whose drive is clear
(:func:`~pathzoo_exact.safe_intervals.earliest_free_departure`, which asks
the judge's own distance function). The first goal state taken from the queue
gives the earliest arrival.

Stated tolerances (they make SIPP stricter than the judge, never looser):

- safe intervals of a waiting vehicle use a radius larger by
  :data:`WAIT_SLACK_CELLS` cells than the judge's, so a wait the search
  allows is one the judge accepts whatever the rounding;
- departure windows shorter than :data:`MIN_STEP_S` seconds can be stepped
  over, so the arrival is the earliest up to that much per move;
- times after ``horizon_s`` count as unsafe everywhere: an arrival later
  than the horizon is reported as a failure, not found.

The path holds a repeated point for each wait (same position, two times),
and ``times`` gives the time of every point. Scenarios whose start or goal is
off its cell centre add one straight connector between that point and its
cell's centre, driven and checked like any move (the start point and the goal
point have safe intervals of their own). A vehicle with a turn limit is
outside this model: the planner then returns ``Status.FAILED`` saying so.
"""

from __future__ import annotations

import heapq
import math
from typing import Callable, ClassVar

import numpy as np

from pathzoo.core import Budget, Param, Planner, PlanResult, ProgressCallback, Scenario, Status
from pathzoo.core.tolerances import TOUCH_EPS_CELLS
from pathzoo.grid.paths import on_centre
from pathzoo.rules import validate_path
from pathzoo_exact.safe_intervals import ObstacleArrays, earliest_free_departure, obstacle_arrays, stationary_unsafe_times

__all__ = ["SippPlanner", "WAIT_SLACK_CELLS", "MIN_STEP_S", "safe_intervals"]

WAIT_SLACK_CELLS = 1e-6
"""Extra clearance (cells) a waiting vehicle keeps beyond the judge's radius plus margin."""

MIN_STEP_S = 1e-6
"""Smallest step (s) of the departure sweep: the arrival is the earliest to this much per move."""

_MAX_SWEEP_STEPS = 1_000_000
"""Looks at one edge before its window is given up (never reached on the packs' scenarios)."""

_CLOCK_EVERY = 512
"""Expansions between two looks at the clock."""

_START_POINT = -1
_GOAL_POINT = -2
"""Search nodes of a start or goal that lies off its cell centre; each is joined to its centre by a connector."""


def safe_intervals(obs: ObstacleArrays, point: np.ndarray, slack: float, horizon: float) -> np.ndarray:
    """Maximal intervals of ``[0, horizon]`` when a vehicle waiting at ``point`` is clear of every obstacle.

    Returns ``(m, 2)`` closed intervals ``[start, end]`` in increasing order,
    computed with every radius increased by ``slack`` metres.
    """
    unsafe = [stationary_unsafe_times(obs.cycles[obs.bounds[k]:obs.bounds[k + 1]], obs.cums[obs.bounds[k]:obs.bounds[k + 1]],
                                      float(obs.speeds[k]), float(obs.phases[k]), float(point[0]), float(point[1]),
                                      float(obs.radii[k]) + slack, horizon)
              for k in range(len(obs.speeds))]
    bad = np.concatenate(unsafe) if unsafe else np.zeros((0, 2))
    if len(bad) == 0:
        return np.array([[0.0, horizon]])
    bad = bad[np.argsort(bad[:, 0], kind="stable")]
    out: list[tuple[float, float]] = []
    free_from = 0.0
    for lo, hi in bad:
        if lo > free_from:
            out.append((free_from, float(np.nextafter(lo, -math.inf))))
        free_from = max(free_from, float(np.nextafter(hi, math.inf)))
    if free_from <= horizon:
        out.append((free_from, horizon))
    return np.array(out, dtype=np.float64).reshape(-1, 2)


class SippPlanner(Planner):
    """Safe Interval Path Planning on the 8-connected graph; the earliest arrival (see the module docstring).

    Parameters
    ----------
    horizon_s : float
        Latest time considered (seconds); later times count as unsafe.
    """

    id: ClassVar[str] = "exact.sipp"
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = ("SIPP (Phillips & Likhachev 2011): earliest arrival on the 8-connected graph "
                              "among the moving obstacles, waiting allowed")
    kinds: ClassVar[frozenset[str]] = frozenset({"dynamic"})
    path_model: ClassVar[str] = "timed"
    params = {
        "horizon_s": Param(3600.0, "latest time considered (s); later arrivals are reported as failures",
                           low=0.0, low_open=True),
    }

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Search (cell, safe interval) states from the start at time 0; see the module docstring."""
        self.check_supports(scenario)
        clock = budget.start()
        if scenario.vehicle.max_turn_deg < 180.0:
            return PlanResult(Status.FAILED, message="outside SIPP's model: the vehicle has a turn limit")
        graph = scenario.graph
        speed = scenario.vehicle.cruise_speed
        horizon = float(self.horizon_s)
        obs = obstacle_arrays(scenario.moving_obstacles, TOUCH_EPS_CELLS * scenario.cell_size)
        slack = WAIT_SLACK_CELLS * scenario.cell_size
        source, target = scenario.start_node, scenario.goal_node
        centres = scenario.point_of(np.array([source, target]))
        start_off = not on_centre(scenario, scenario.start, centres[0])
        goal_off = not on_centre(scenario, scenario.goal, centres[1])
        first = _START_POINT if start_off else source
        last = _GOAL_POINT if goal_off else target

        def point(node: int) -> np.ndarray:
            if node == _START_POINT or (node == source and not start_off):
                return scenario.start
            if node == _GOAL_POINT or (node == target and not goal_off):
                return scenario.goal
            return scenario.point_of(np.array([node]))[0]

        def moves(node: int) -> list[tuple[int, float]]:
            """``(next node, driving time)``: the graph's edges, and the connectors to and from off-centre endpoints."""
            if node == _START_POINT:
                return [(source, float(np.linalg.norm(centres[0] - scenario.start)) / speed)]
            out = [(int(graph.indices[e]), float(graph.length[e]) / speed)
                   for e in range(graph.indptr[node], graph.indptr[node + 1])]
            if node == target and goal_off:
                out.append((_GOAL_POINT, float(np.linalg.norm(scenario.goal - centres[1])) / speed))
            return out

        intervals: dict[int, np.ndarray] = {}

        def cell_intervals(node: int) -> np.ndarray:
            found = intervals.get(node)
            if found is None:
                found = intervals[node] = safe_intervals(obs, point(node), slack, horizon)
            return found

        if cell_intervals(first)[0, 0] > 0.0:
            return PlanResult(Status.NO_PATH, message="a moving obstacle covers the start at time 0")
        goal_centre = centres[1]
        cell = scenario.cell_size

        def h(node: int) -> float:
            """Octile distance to the goal cell's centre over the speed (0 at the off-centre endpoints)."""
            if node < 0:
                return 0.0
            d = np.abs(point(node) - goal_centre) / cell
            return float(cell * (d.max() + (math.sqrt(2.0) - 1.0) * d.min()) / speed)

        best: dict[tuple[int, int], float] = {(first, 0): 0.0}
        parent: dict[tuple[int, int], tuple[tuple[int, int], float, float]] = {}
        heap: list[tuple[float, float, int, int]] = [(h(first), 0.0, first, 0)]
        closed: set[tuple[int, int]] = set()
        expanded = 0
        cap = budget.evaluations
        while heap:
            _, g, u, iu = heapq.heappop(heap)
            if (u, iu) in closed:
                continue
            closed.add((u, iu))
            if u == last:
                return self._solved(scenario, parent, (u, iu), point, expanded, progress)
            expanded += 1
            if cap is not None and expanded >= cap:
                return PlanResult(Status.FAILED, iterations=1, evaluations=expanded,
                                  message=f"evaluation budget of {cap} expansions exhausted before the goal")
            if expanded % _CLOCK_EVERY == 0 and clock.exhausted():
                return PlanResult(Status.FAILED, iterations=1, evaluations=expanded,
                                  message=f"time budget of {budget.time_s} s exhausted before the goal")
            end_u = float(cell_intervals(u)[iu, 1])
            pu = point(u)
            for v, tau in moves(u):
                pv = point(v)
                for iv, (a_v, b_v) in enumerate(cell_intervals(v)):
                    if a_v > end_u + tau:
                        break
                    if b_v < g + tau or (v, iv) in closed:
                        continue
                    lo, hi = max(g, a_v - tau), min(end_u, b_v - tau)
                    if lo > hi:
                        continue
                    t = earliest_free_departure(obs.cycles, obs.cums, obs.bounds, obs.speeds, obs.phases, obs.radii,
                                                float(pu[0]), float(pu[1]), float(pv[0]), float(pv[1]), tau,
                                                lo, hi, MIN_STEP_S, _MAX_SWEEP_STEPS)
                    if t < 0.0:
                        continue
                    arrival = t + tau
                    if arrival < best.get((v, iv), math.inf):
                        best[(v, iv)] = arrival
                        parent[(v, iv)] = ((u, iu), t, arrival)
                        heapq.heappush(heap, (arrival + h(v), arrival, v, iv))
        return PlanResult(Status.FAILED, iterations=1, evaluations=expanded,
                          message=f"no arrival at the goal before the horizon of {horizon} s")

    def _solved(self, scenario: Scenario, parent: dict[tuple[int, int], tuple[tuple[int, int], float, float]],
                state: tuple[int, int], point: Callable[[int], np.ndarray], expanded: int,
                progress: ProgressCallback | None) -> PlanResult:
        """The timed path to ``state``: one point per cell reached, and a repeated point wherever the vehicle waits."""
        steps: list[tuple[int, float, float]] = []  # (cell, departure from the previous cell, arrival here)
        while state in parent:
            prev, depart, arrival = parent[state]
            steps.append((state[0], depart, arrival))
            state = prev
        pts = [point(state[0])]
        times = [0.0]
        for node, depart, arrival in reversed(steps):
            if depart > times[-1]:
                pts.append(pts[-1])
                times.append(depart)
            pts.append(point(node))
            times.append(arrival)
        if len(pts) == 1:  # start and goal on one centre
            pts.append(scenario.goal)
            times.append(0.0)
        path = np.array(pts, dtype=np.float64)
        t = np.array(times, dtype=np.float64)
        check = validate_path(scenario, path, t)
        if not check:  # never seen; kept so that a rounding surprise is a failure, not an invalid "solved" path
            return PlanResult(Status.FAILED, iterations=1, evaluations=expanded,
                              message=f"SIPP's path was refused by the judge's rule: {check.reason}")
        if progress is not None:
            progress(1, expanded, float(t[-1]))
        return PlanResult(Status.SOLVED, path=path, times=t, iterations=1, evaluations=expanded,
                          extras={"cost": "arrival_s", "best_cost": float(t[-1]), "arrival_s": float(t[-1])})
