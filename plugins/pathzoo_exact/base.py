"""The common ``plan()`` of the exact planners: batched search, clock checks and endpoint handling.

Endpoints
---------
The search runs between the *cells* of ``scenario.start`` and ``scenario.goal``,
so the node path goes from cell centre to cell centre. The returned path then
ends exactly at the start and goal points:

- when a point lies within 1e-9 cells of its cell centre it replaces that centre;
- otherwise it is prepended (start) or appended (goal) as an extra waypoint,
  joined to its own cell centre by a short *connector* segment.

A point lies inside its cell, so a connector stays inside one free cell and
touches a neighbouring cell only when the point lies exactly on the cell's
border, in which case every segment from that point touches it too. On
terrain and in air volumes a connector can still break a slope or pitch
limit the graph edges respect. Connectors are therefore checked with the
validator's own :func:`~pathzoo.rules.segment_problem`; a bad one
gives ``Status.FAILED`` with the reason, never an invalid "solved" path.
The reported cost is the graph cost plus the connectors' cost, measured like
the graph edges (3-D length from :func:`~pathzoo.grid.terrain.segment_profile`,
energy from eq. 4 of G-Ant through :meth:`VehicleModel.segment_energy`).

Collinear waypoints
-------------------
On ``grid2d`` scenarios, waypoints in the middle of a straight run of moves
are dropped: the polyline is the same set of points, so the closed-cell test
touches exactly the same cells, and the path is shorter to store and to
validate. On terrain every cell centre is kept, because the validator cuts a
long segment into pieces whose slopes differ from those of the graph edges;
in air volumes too, so that each segment is one checked graph edge.

Reused arrays
-------------
A search's state (:class:`~pathzoo_exact.search_state.SearchState`) has a cost,
a parent and a closed flag per node. Each thread keeps the state of its last
search as a spare, and the next search on a graph of the same size
restarts it (:meth:`~pathzoo_exact.search_state.SearchState.restart`) instead of
allocating: refilling warm arrays costs the same as filling fresh ones, but a
fresh allocation of a few megabytes often comes from memory the C allocator
has just handed back to the system, and then every page faults once. On
``8room_000`` (512 x 512) a fresh state took 0.07 ms or, when that happened,
1.25 ms; the searches themselves take 0.2 to 20 ms. Spares are kept only for
graphs of at most :data:`SPARE_MAX_NODES` nodes, so a worker never holds a
big map's arrays (17 bytes per node) after its search. A restarted state is
what a fresh one would be, so it gives the same search.

Kept per scenario
-----------------
What a search needs besides its state depends on the scenario and the
planner's parameters only: the batch function and its arrays, the start and
goal cells, whether the end points lie on their cell centres, the
connectors' verdicts and costs. :meth:`GraphSearchPlanner._prepared` works
them out on the first ``plan()`` of a configuration on a scenario and keeps
them beside the scenario (:class:`PreparedSearch`), so that a search on a
small map costs a few microseconds besides its expansions. The batch that
finds the target also builds the path, in the same compiled call
(:mod:`pathzoo_exact.answer`, :func:`~pathzoo_exact.waypoints.waypoints`).

Budgets
-------
Numba code cannot read the clock cheaply, so the search runs in batches of
:attr:`GraphSearchPlanner.batch_expansions` expansions (a few milliseconds
each) and the Python driver checks the clock limits (``cpu_s``, ``time_s``)
between batches: a clock stop overshoots by at most one batch. ``budget.evaluations`` caps the number
of expanded nodes exactly. ``budget.iterations`` is always met, since the
search is one iteration. With no limit at all the search runs to completion,
which is bounded by the size of the graph.
"""

from __future__ import annotations

import abc
import math
import threading
from functools import cached_property
from typing import Any, ClassVar, NamedTuple

import numpy as np

from pathzoo.core import Budget, Planner, PlanResult, ProgressCallback, Scenario, Status
from pathzoo.core.object_memo import ObjectMemo
from pathzoo.grid.paths import centre_path, on_centre
from pathzoo.grid.terrain import segment_profile
from pathzoo.rules import segment_problem
from pathzoo_exact.answer import Batch, answer_problem
from pathzoo_exact.problem import grid_dims
from pathzoo_exact.search_state import EXHAUSTED, FOUND, HEAP_FULL, RUNNING, SearchState
from pathzoo_exact.waypoints import path_ends, path_layout

__all__ = ["GraphSearchPlanner", "SPARE_MAX_NODES", "Endpoints", "endpoints", "connector_cost", "PreparedSearch"]

SPARE_MAX_NODES = 1 << 21
"""Largest graph (nodes) whose search state a thread keeps for its next search (about 36 MB)."""

_SPARE = threading.local()
"""``_SPARE.state``: this thread's spare :class:`SearchState`, if any."""


def _search_state(n_nodes: int, source: int, heap_capacity: int) -> SearchState:
    """This thread's spare state restarted at ``source`` if it has ``n_nodes`` nodes, else a fresh one."""
    state = getattr(_SPARE, "state", None)
    if state is None or state.g.shape[0] != n_nodes:
        return SearchState.start(n_nodes, source, heap_capacity)
    _SPARE.state = None  # taken: a nested search on this thread gets its own
    state.restart(source, heap_capacity)
    return state


def _keep_spare(state: SearchState) -> None:
    if state.g.shape[0] <= SPARE_MAX_NODES:
        _SPARE.state = state

class Endpoints(NamedTuple):
    """Where a scenario's search starts and ends, and whether the points sit on their cells' centres."""

    source: int
    target: int
    start_on_centre: bool
    goal_on_centre: bool


_ENDPOINTS: "ObjectMemo[Scenario, Endpoints]" = ObjectMemo()


def endpoints(scenario: Scenario) -> Endpoints:
    """The :class:`Endpoints` of ``scenario``, worked out on the first call and kept while the (frozen) scenario lives."""
    return _ENDPOINTS.value(scenario, lambda: _find_endpoints(scenario))


def _find_endpoints(scenario: Scenario) -> Endpoints:
    source, target = scenario.start_node, scenario.goal_node
    centres = scenario.point_of(np.array([source, target]))
    return Endpoints(source, target, on_centre(scenario, scenario.start, centres[0]),
                     on_centre(scenario, scenario.goal, centres[1]))


def connector_cost(scenario: Scenario, p0: np.ndarray, p1: np.ndarray, cost: str) -> float:
    """Cost of one straight segment, measured like the graph's edges.

    Parameters
    ----------
    scenario : Scenario
        Gives the DEM (terrain), the cell sizes and the vehicle.
    p0, p1 : ndarray
        World coordinates of the segment's ends.
    cost : {"length", "energy"}
        3-D length in metres, or energy in joules (eq. 4 of G-Ant at cruise speed).
    """
    if scenario.dim == 3:
        d = np.asarray(p1, dtype=np.float64) - np.asarray(p0, dtype=np.float64)
        lengths = np.array([math.sqrt(float(d @ d))])
        slopes = np.array([math.atan2(float(d[2]), math.hypot(float(d[0]), float(d[1])))])
    else:
        elevation = scenario.elevation if scenario.kind == "terrain" else None
        lengths, slopes = segment_profile(elevation, p0, p1, scenario.cell_size)
    if cost == "length":
        return float(lengths.sum())
    return float(scenario.vehicle.segment_energy(lengths, slopes).sum())


class PreparedSearch(NamedTuple):
    """What one planner configuration's searches on one scenario share, worked out on its first ``plan()``.

    Attributes
    ----------
    batch : Batch
        The kernel that advances a search by one batch and returns the answer
        when it finds the target (:mod:`pathzoo_exact.answer`), with its
        leading arguments: :meth:`GraphSearchPlanner._make_batch`'s, the
        path's ``layout`` and ``ends`` packed after the problem's ``ints, reals``.
    source, target : int
        The start and goal cells' node ids.
    n_nodes : int
        Nodes of the graph.
    layout : ndarray of int64, shape (6,)
        The grid's shape, the width of a grid whose straight runs lose their
        inner waypoints (``grid2d``, else 0) and whether each end point sits
        on its cell's centre (:func:`~pathzoo_exact.waypoints.path_layout`).
    ends : ndarray of float64, shape (3, d)
        Cell sizes, start and goal point (:func:`~pathzoo_exact.waypoints.path_ends`).
    cost_kind : str
        The edge cost minimised.
    connector_problem : str or None
        Why a connector is not allowed (the first one that is not), or None.
    connector_costs : tuple of float
        The connectors' costs, start first, when both are allowed.
    """

    batch: Batch
    source: int
    target: int
    n_nodes: int
    layout: np.ndarray
    ends: np.ndarray
    cost_kind: str
    connector_problem: str | None
    connector_costs: tuple[float, ...]


_SOLVED = Status.SOLVED

_PREPARED: "ObjectMemo[Scenario, dict[str, PreparedSearch]]" = ObjectMemo()


class GraphSearchPlanner(Planner, abc.ABC):
    """Base of the exact planners: a best-first search on ``scenario.graph``.

    Subclasses provide :meth:`_make_batch`, the numba search they run, and
    :meth:`_cost_kind`. Everything else (budgets, endpoints, the result) is here.
    """

    batch_expansions: ClassVar[int] = 16384
    """Expansions between two looks at the clock."""

    initial_heap_capacity: ClassVar[int] = 4096
    """Heap slots allocated up front; the heap doubles when full."""

    @abc.abstractmethod
    def _make_batch(self, scenario: Scenario, target: int) -> Batch:
        """The kernel of :mod:`pathzoo_exact.answer` that searches ``scenario``, with its graph and problem arguments.

        The arguments end with the problem's ``ints, reals`` (:func:`~pathzoo_exact.problem.search_problem`);
        :meth:`_prepare` packs the path's ``layout`` and ``ends`` into them.
        """

    def _cost_kind(self) -> str:
        """The edge cost minimised, ``"length"`` or ``"energy"``."""
        return "length"

    @cached_property
    def _search_key(self) -> str:
        """What tells this configuration's prepared searches from another's on the same scenario.

        A string, whose hash Python keeps: a tuple's is worked out again on every look-up.
        """
        values: dict[str, Any] = self._values
        return f"{type(self).__module__}.{type(self).__qualname__}{tuple(values.items())!r}"

    def _prepared(self, scenario: Scenario) -> PreparedSearch:
        """This configuration's :class:`PreparedSearch` on ``scenario``, built on the first call and then kept."""
        searches = _PREPARED.get(scenario)  # a plain look-up first
        if searches is None:
            searches = _PREPARED.value(scenario, dict)
        found = searches.get(self._search_key)
        if found is None:
            self.check_supports(scenario)
            found = searches.setdefault(self._search_key, self._prepare(scenario))
        return found

    def _prepare(self, scenario: Scenario) -> PreparedSearch:
        ends = endpoints(scenario)
        graph = scenario.graph
        kind = self._cost_kind()
        example = np.array([ends.source, ends.target] if ends.source != ends.target else [ends.source])
        path = centre_path(scenario, example)  # ends as those of every path found (the connectors depend on no more)
        connectors = ([(path[0], path[1])] if not ends.start_on_centre else []) + (
            [(path[-2], path[-1])] if not ends.goal_on_centre else [])
        problem, costs = None, []
        for p0, p1 in connectors:
            problem = segment_problem(scenario, p0, p1)
            if problem is not None:
                break
            costs.append(connector_cost(scenario, p0, p1, kind))
        layout = path_layout(grid_dims(graph.shape), scenario.shape[1] if scenario.kind == "grid2d" else 0,
                             ends.start_on_centre, ends.goal_on_centre)
        path_points = path_ends(scenario.cell_sizes, scenario.start, scenario.goal)
        kernel, args, degree = self._make_batch(scenario, ends.target)
        return PreparedSearch(
            batch=Batch(kernel, (*args[:-2], *answer_problem(args[-2], args[-1], layout, path_points)), degree),
            source=ends.source,
            target=ends.target,
            n_nodes=graph.n_nodes,
            layout=layout,
            ends=path_points,
            cost_kind=kind,
            connector_problem=problem,
            connector_costs=tuple(costs),
        )

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Search the cell graph from the start cell to the goal cell; see the module docstring."""
        clock = budget.start() if budget.timed or budget.stop is not None else None  # else no clock can end it
        search = self._prepared(scenario)
        state = _search_state(search.n_nodes, search.source, self.initial_heap_capacity)
        (kernel, args, degree), cap, step, expanded = search.batch, budget.evaluations, self.batch_expansions, 0
        try:  # batches until the search ends or the budget does; nothing returned refers to the state's arrays
            while True:
                if cap is not None:
                    step = min(self.batch_expansions, cap - expanded)
                status, expanded, graph_cost, path = kernel(*args, *state.arrays, step, degree)
                if status == FOUND:
                    return self._solved(scenario, search, expanded, graph_cost, path, progress)
                if status == HEAP_FULL:
                    state.grow_heap()
                    continue
                if status != RUNNING:
                    break
                if cap is not None and expanded >= cap:
                    return self._failed(expanded, f"evaluation budget of {cap} expansions exhausted before the goal")
                spent = None if clock is None else clock.time_up()
                if spent is not None:
                    return self._failed(expanded, f"{'CPU' if spent == 'cpu_time' else 'wall'} time budget "
                                        "exhausted before the goal")
            assert status == EXHAUSTED
            return PlanResult(
                Status.NO_PATH,
                iterations=1,
                evaluations=expanded,
                message="the goal cell is not reachable from the start cell in the neighbourhood graph",
            )
        finally:
            _keep_spare(state)

    def _failed(self, expanded: int, message: str) -> PlanResult:
        return PlanResult(Status.FAILED, iterations=1, evaluations=expanded, message=message)

    def _solved(
        self,
        scenario: Scenario,
        search: PreparedSearch,
        expanded: int,
        graph_cost: float,
        path: np.ndarray,
        progress: ProgressCallback | None,
    ) -> PlanResult:
        """The answer of a search that expanded ``search.target`` after ``expanded`` expansions.

        ``graph_cost`` is the target's ``g`` and ``path`` the path the kernel built (:mod:`pathzoo_exact.answer`).
        """
        if search.connector_problem is not None:
            return self._failed(expanded, "connector between an endpoint and its cell centre is not allowed: "
                                f"{search.connector_problem}")
        cost = graph_cost
        for connector in search.connector_costs:
            cost += connector
        if progress is not None:
            progress(1, expanded, cost)
        extras = {"cost": search.cost_kind, "best_cost": cost, "graph_cost": graph_cost}
        # positional, and the member read once at import: keywords and an enum look-up cost as much as a small search
        return PlanResult(_SOLVED, path, None, 1, expanded, "", extras)
