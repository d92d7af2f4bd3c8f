"""Safe Interval Path Planning (Phillips & Likhachev, ICRA 2011): the earliest arrival among moving obstacles.

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
(:func:`~pathzoo.grid.safe_intervals.stationary_unsafe_times`, closed form).
A search state is a (cell, safe interval) pair, reached at the earliest time
found so far; arriving earlier in the same interval is never worse, because
the vehicle can wait there. A* (heuristic: octile distance over ``v``, which
is consistent) expands states in order of ``arrival + heuristic``; from a
state it tries, for each neighbour and each safe interval of that neighbour,
the earliest departure whose drive is clear
(:func:`~pathzoo.grid.safe_intervals.earliest_free_departure`, which asks
the judge's own distance function). The first goal state taken from the queue
gives the earliest arrival.

Stated tolerances (they make SIPP stricter than the judge, never looser):

- safe intervals of a waiting vehicle use a radius larger by
  :data:`WAIT_SLACK_CELLS` cells than the judge's, so a wait the search
  allows is one the judge accepts whatever the rounding;
- departure windows shorter than :data:`MIN_STEP_S` seconds can be stepped
  over, so the arrival is the earliest up to that much per move;
- times after ``horizon_s`` count as unsafe everywhere: no arrival later
  than the horizon is found.

The path holds a repeated point for each wait (same position, two times),
and ``times`` gives the time of every point. Scenarios whose start or goal is
off its cell centre add one straight connector between that point and its
cell's centre, driven and checked like any move (the start point and the goal
point have safe intervals of their own). A vehicle with a turn limit is
outside this model (:class:`OutsideModel`).

The search is :func:`earliest_arrival`; ``exact.sipp`` runs it under a
budget, and :func:`pathzoo.grid.reference.earliest_arrival_s` uses it as the
reference of the ``arrival_ratio`` metric.
"""

from __future__ import annotations

import heapq
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Callable

import numpy as np

from pathzoo.core.tolerances import TOUCH_EPS_CELLS
from pathzoo.grid.paths import on_centre
from pathzoo.grid.safe_intervals import earliest_free_departure, obstacle_arrays, safe_intervals

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["TimedPath", "OutsideModel", "SearchStopped", "earliest_arrival", "WAIT_SLACK_CELLS", "MIN_STEP_S",
           "DEFAULT_HORIZON_S"]

DEFAULT_HORIZON_S = 3600.0
"""Latest time considered unless told otherwise (seconds)."""

WAIT_SLACK_CELLS = 1e-6
"""Extra clearance (cells) a waiting vehicle keeps beyond the judge's radius plus margin."""

MIN_STEP_S = 1e-6
"""Smallest step (s) of the departure sweep: the arrival is the earliest to this much per move."""

_MAX_SWEEP_STEPS = 1_000_000
"""Looks at one edge and one window before the window is given up: a bound on the work per edge."""

_START_POINT = -1
_GOAL_POINT = -2
"""Search nodes of a start or goal that lies off its cell centre; each is joined to its centre by a connector."""


class OutsideModel(ValueError):
    """The scenario is not one SIPP's model covers (a turn limit)."""


class SearchStopped(RuntimeError):
    """The caller's ``stop`` callback ended the search; the message says why."""


@dataclass(frozen=True, eq=False)
class TimedPath:
    """The result of :func:`earliest_arrival`.

    Attributes
    ----------
    path : ndarray (N, 2)
        World points from exactly the start to exactly the goal; a wait repeats a point.
    times : ndarray (N,)
        Time at each point, from 0.
    expanded : int
        Search states expanded.
    """

    path: np.ndarray
    times: np.ndarray
    expanded: int

    @property
    def arrival_s(self) -> float:
        """Arrival time at the goal, seconds."""
        return float(self.times[-1])


def earliest_arrival(scenario: "Scenario", horizon_s: float = DEFAULT_HORIZON_S,
                     stop: Callable[[int], str | None] | None = None) -> TimedPath | None:
    """The earliest-arriving timed path of SIPP's model, or ``None`` when none arrives by ``horizon_s``.

    Parameters
    ----------
    scenario : Scenario
        A 2-D scenario; its moving obstacles are the known ones.
    horizon_s : float
        Latest time considered (seconds).
    stop : callable, optional
        ``stop(expanded)`` is called after every expansion; a non-empty
        string ends the search with :class:`SearchStopped` carrying it.

    Raises
    ------
    OutsideModel
        The vehicle has a turn limit.
    SearchStopped
        ``stop`` asked for it.
    """
    if scenario.vehicle.max_turn_deg < 180.0:
        raise OutsideModel("outside SIPP's model: the vehicle has a turn limit")
    graph = scenario.graph
    speed = scenario.vehicle.cruise_speed
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
            found = intervals[node] = safe_intervals(obs, point(node), slack, horizon_s)
        return found

    start_safe = cell_intervals(first)
    if len(start_safe) == 0 or start_safe[0, 0] > 0.0:
        return None  # an obstacle covers the start at time 0: no timed path exists
    cell = scenario.cell_size

    def h(node: int) -> float:
        """Octile distance to the goal cell's centre over the speed (0 at the off-centre endpoints)."""
        if node < 0:
            return 0.0
        d = np.abs(point(node) - centres[1]) / cell
        return float(cell * (d.max() + (math.sqrt(2.0) - 1.0) * d.min()) / speed)

    State = tuple[int, int]
    best: dict[State, float] = {(first, 0): 0.0}
    parent: dict[State, tuple[State, float, float]] = {}
    heap: list[tuple[float, float, int, int]] = [(h(first), 0.0, first, 0)]
    closed: set[State] = set()
    expanded = 0
    while heap:
        _, g, u, iu = heapq.heappop(heap)
        if (u, iu) in closed:
            continue
        closed.add((u, iu))
        if u == last:
            return _timed_path(scenario, parent, (u, iu), point, expanded)
        expanded += 1
        if stop is not None:
            reason = stop(expanded)
            if reason:
                raise SearchStopped(reason)
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
    return None


def _timed_path(scenario: "Scenario", parent: dict[tuple[int, int], tuple[tuple[int, int], float, float]],
                state: tuple[int, int], point: Callable[[int], np.ndarray], expanded: int) -> TimedPath:
    """The timed path to ``state``: one point per cell reached, and a repeated point wherever the vehicle waits."""
    steps: list[tuple[int, float, float]] = []  # (node, departure from the previous node, arrival here)
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
    path.setflags(write=False)
    t.setflags(write=False)
    return TimedPath(path, t, expanded)
