"""The exact reference optima of a scenario (graph optimum, any-angle optimum, earliest arrival), cached per scenario.

The references, for three path models (``docs/metrics.md``):

- the *graph optimum* (:func:`reference_path`, :func:`reference_length`):
  Dijkstra on the scenario's neighbourhood graph, the optimum of planners
  that move between neighbouring cells;
- the *any-angle optimum* (:func:`anyangle_reference`,
  :func:`anyangle_length`): the infimum of the lengths of all valid paths,
  whatever their vertices (:mod:`pathzoo.grid.anyangle`), the optimum of
  planners whose segments may take any direction;
- in air volumes, an *any-angle bound* (:func:`anyangle_bound_3d`): the
  length of the Lazy Theta* path (:mod:`pathzoo.grid.lazy_theta3d`) once the
  judge has accepted it, an upper bound on the any-angle optimum (which is
  at least the straight-line distance);
- the *earliest arrival* (:func:`earliest_arrival_s`) on ``dynamic``
  scenarios: SIPP on the 8-connected graph among the moving obstacles
  (:mod:`pathzoo.grid.sipp`), the optimum of timed grid paths.

The harness uses it twice: as the denominator of the ``length_ratio`` metric,
and as a witness when a planner claims that no path exists (the claim is
rejected when the reference path exists *and* passes the validator).

Endpoints are handled like the exact planners do: the search runs from the
start cell to the goal cell; a start or goal lying on its cell centre (to
1e-9 cells) replaces it, otherwise it is joined to it by a straight connector.
For cell-centre endpoints (every MovingAI problem) the length is therefore the
exact optimum of the graph; otherwise it is the optimum through the endpoint
cells' centres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from pathzoo.core.object_memo import ObjectMemo
from pathzoo.grid.anyangle import AnyAngleError, AnyAnglePath, anyangle_path
from pathzoo.grid.navmesh import scenario_mesh
from pathzoo.grid.paths import centre_path

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = [
    "ReferencePath",
    "reference_path",
    "reference_length",
    "GRAPH_REFERENCE_KINDS",
    "ANYANGLE_KINDS",
    "anyangle_reference",
    "anyangle_length",
    "earliest_arrival_s",
    "anyangle_bound_3d",
    "ARRIVAL_MAX_CELLS",
]

ARRIVAL_MAX_CELLS = 256 * 256
"""Largest map (cells) whose earliest arrival the metrics compute; SIPP's search runs in Python (about 1 s at 100 x 100)."""

GRAPH_REFERENCE_KINDS: frozenset[str] = frozenset({"grid2d", "terrain", "air3d"})
"""Kinds whose graph optimum is the right reference for path length.

``dynamic`` is excluded: the static graph ignores the moving obstacles, so
its optimum is only a lower bound there.
"""


@dataclass(frozen=True, eq=False)
class ReferencePath:
    """The graph-optimal path of a scenario.

    Attributes
    ----------
    path : ndarray of shape (N, d)
        World coordinates from exactly ``scenario.start`` to exactly ``scenario.goal``.
    length : float
        Its 3-D length in metres, measured like the ``length`` metric.
    nodes : ndarray of int64
        The graph nodes (cells) it visits.
    """

    path: np.ndarray
    length: float
    nodes: np.ndarray


ANYANGLE_KINDS: frozenset[str] = frozenset({"grid2d"})
"""Kinds with an any-angle optimum: static 2-D grids measured by plane length."""

_references: "ObjectMemo[Scenario, ReferencePath | None]" = ObjectMemo()
_arrivals: "ObjectMemo[Scenario, float]" = ObjectMemo()
_anyangle_bounds: "ObjectMemo[Scenario, float]" = ObjectMemo()
_anyangle_references: "ObjectMemo[Scenario, AnyAnglePath | None | AnyAngleError]" = ObjectMemo()


def _compute(scenario: "Scenario") -> ReferencePath | None:
    # imported here: registering the metrics (which import this module) must not pull in scipy
    from scipy.sparse.csgraph import dijkstra

    from pathzoo.grid.paths import path_pieces

    graph = scenario.graph
    source, target = scenario.start_node, scenario.goal_node
    dists, preds = dijkstra(graph.to_sparse("length"), directed=True, indices=[source], return_predecessors=True)
    dist, pred = dists[0], preds[0]
    if not math.isfinite(float(dist[target])):
        return None
    nodes = [target]
    while nodes[-1] != source:
        nodes.append(int(pred[nodes[-1]]))
    node_arr = np.array(nodes[::-1], dtype=np.int64)
    path = centre_path(scenario, node_arr)
    lengths, _ = path_pieces(scenario, path)
    path.setflags(write=False)
    node_arr.setflags(write=False)
    return ReferencePath(path=path, length=float(lengths.sum()), nodes=node_arr)


def reference_path(scenario: "Scenario") -> ReferencePath | None:
    """The shortest path on ``scenario.graph``, or ``None`` when the goal cell is unreachable.

    Computed once per scenario object (Dijkstra from the start cell with
    :func:`scipy.sparse.csgraph.dijkstra`) and cached while the scenario lives.
    """
    return _references.value(scenario, lambda: _compute(scenario))


def reference_length(scenario: "Scenario") -> float:
    """The reference length in metres for ``length_ratio``, or NaN when there is none.

    ``scenario.reference_length`` when set (e.g. from a MovingAI ``.scen``
    file); otherwise the graph optimum for the kinds in
    :data:`GRAPH_REFERENCE_KINDS`; NaN for other kinds and unreachable goals.
    """
    if scenario.reference_length is not None:
        return float(scenario.reference_length)
    if scenario.kind not in GRAPH_REFERENCE_KINDS:
        return math.nan
    ref = reference_path(scenario)
    return math.nan if ref is None else ref.length


def _compute_anyangle(scenario: "Scenario") -> AnyAnglePath | None | AnyAngleError:
    if scenario.kind not in ANYANGLE_KINDS:
        return AnyAngleError(f"no any-angle optimum for kind {scenario.kind!r} (only {sorted(ANYANGLE_KINDS)})")
    try:
        return anyangle_path(
            scenario.blocked, scenario.start, scenario.goal, scenario.cell_size, mesh=lambda: scenario_mesh(scenario)
        )
    except AnyAngleError as exc:
        return exc


def anyangle_reference(scenario: "Scenario") -> AnyAnglePath | None:
    """The exact any-angle optimum of ``scenario``, or ``None`` when the goal is unreachable.

    Computed once per scenario object and cached while it lives.

    Raises
    ------
    AnyAngleError
        For kinds outside :data:`ANYANGLE_KINDS`, maps larger than
        :data:`pathzoo.grid.anyangle.MAX_EXACT_CELLS` and endpoints too fine
        for the search's lattice on large maps: the optimum is then not
        computed, never approximated.
    """
    ref = _anyangle_references.value(scenario, lambda: _compute_anyangle(scenario))
    if isinstance(ref, AnyAngleError):
        raise ref
    return ref


def anyangle_length(scenario: "Scenario") -> float:
    """The any-angle optimum in metres, or NaN when it is not computed or the goal is unreachable."""
    try:
        ref = anyangle_reference(scenario)
    except AnyAngleError:
        return math.nan
    return math.nan if ref is None else ref.length


def _compute_arrival(scenario: "Scenario") -> float:
    from pathzoo.grid.sipp import OutsideModel, earliest_arrival

    if scenario.kind != "dynamic" or scenario.occupancy.size > ARRIVAL_MAX_CELLS:
        return math.nan
    try:
        found = earliest_arrival(scenario)
    except OutsideModel:
        return math.nan
    return math.nan if found is None else found.arrival_s


def earliest_arrival_s(scenario: "Scenario") -> float:
    """SIPP's earliest arrival at the goal in seconds (:func:`pathzoo.grid.sipp.earliest_arrival`), cached per scenario.

    NaN for kinds other than ``dynamic``, for maps larger than
    :data:`ARRIVAL_MAX_CELLS`, for vehicles with a turn limit (outside SIPP's
    model) and when no timed path arrives within the default horizon.
    """
    return _arrivals.value(scenario, lambda: _compute_arrival(scenario))


def _compute_anyangle_bound(scenario: "Scenario") -> float:
    from pathzoo.grid.lazy_theta3d import lazy_theta_path
    from pathzoo.grid.paths import path_pieces
    from pathzoo.rules import validate_path

    if scenario.kind != "air3d":
        return math.nan
    path = lazy_theta_path(scenario)
    if path is None or not validate_path(scenario, path):
        return math.nan
    return float(path_pieces(scenario, path)[0].sum())


def anyangle_bound_3d(scenario: "Scenario") -> float:
    """Length in metres of the judge-accepted Lazy Theta* path of an ``air3d`` scenario, cached per scenario.

    An upper bound on the any-angle optimum, not the optimum. NaN for other
    kinds, for an unreachable goal, and when the judge refuses the path (it
    ignores the turn limit).
    """
    return _anyangle_bounds.value(scenario, lambda: _compute_anyangle_bound(scenario))
