"""Hyperparameters shared by the metaheuristic baselines (encoding and penalty), pure and hybrid."""

from __future__ import annotations

from typing import Mapping

from pathzoo.core import Param

__all__ = [
    "waypoint_count", "ENCODING_PARAMS", "PURE_ENCODINGS", "HYBRID_ENCODINGS", "ALL_KINDS", "HYBRID_KINDS",
    "hybrid_encoding",
]

PURE_ENCODINGS: tuple[str, ...] = ("waypoints", "spline")
"""Real-valued encodings that run no graph search (every pure planner supports them); the first is the default."""

HYBRID_ENCODINGS: tuple[str, ...] = ("routed", "cells")
"""Encodings whose decoder or operators route between cells with A* (:class:`~pathzoo_baselines.routing.CellRouter`)."""

ALL_KINDS: frozenset[str] = frozenset({"grid2d", "terrain", "dynamic", "air3d"})
"""Kinds of the pure configurations: straight segments judged by the same rules on every kind."""

HYBRID_KINDS: frozenset[str] = frozenset({"grid2d", "terrain"})
"""Kinds of the A*-routed hybrids: their routes follow the static 2-D neighbourhood graph."""

def waypoint_count(requested: int, kind: str) -> int:
    """K for a scenario kind: ``requested``, or for 0 the default (16 on ``grid2d`` and ``dynamic``, else 8)."""
    if requested:
        return requested
    return 16 if kind in ("grid2d", "dynamic") else 8


ENCODING_PARAMS: Mapping[str, Param] = {
    "encoding": Param(
        "waypoints",
        "candidate encoding: 'waypoints' (K free points joined by straight segments, penalised) or 'spline' "
        "(K control points of a clamped cubic B-spline, sampled into a polyline, penalised); neither runs a graph "
        "search (the A*-routed decoders are the '_astar' hybrid planners)",
        choices=PURE_ENCODINGS,
    ),
    "waypoints": Param(
        0,
        "K, the number of intermediate waypoints or spline control points; 0: 16 on grid2d and dynamic maps (where "
        "the initial walk and the local operators keep many points feasible), 8 on terrain and in air volumes",
        low=0, high=256,
    ),
    "spline_samples": Param(40, "points the spline is sampled at (encoding='spline')", low=4, high=4096),
    "repair_window": Param(
        8,
        "local repair: a segment that touches a blocked cell between two points at most this many cells apart is "
        "routed around it inside a small box (grid2d and dynamic maps; 0 turns the repair off)",
        low=0, high=16,
    ),
    "smoothing": Param(
        8,
        "local smoothing: each point of a decoded path is joined to the farthest of the next this many points that "
        "a clear straight segment reaches (grid2d and dynamic maps; 0 turns it off)",
        low=0, high=64,
    ),
    "init": Param(
        "walk",
        "initial candidates: 'walk' (points spread along goal-biased random walks over free cells, grid2d and "
        "dynamic maps; uniform elsewhere) or 'uniform' (uniform points sorted along the start-goal axis)",
        choices=("walk", "uniform"),
    ),
    "walk_bias": Param(
        0.5, "init='walk': probability that a walk step goes to the free neighbour nearest the goal in straight "
        "line (otherwise to a uniformly drawn free neighbour)", low=0.0, high=1.0,
    ),
    "penalty": Param(
        1.0,
        "cost of one unit of constraint violation, in map diagonals (see docs/planners/swarm.pso.md)",
        low=0.0,
        low_open=True,
    ),
}
"""Parameters of :func:`pathzoo_baselines.encodings.make_encoding`, merged into each pure planner's ``params``."""


def hybrid_encoding(default: str, choices: tuple[str, ...]) -> Param:
    """The ``encoding`` parameter of a hybrid planner: the A*-routed decoders ``choices``, ``default`` first."""
    return Param(
        default,
        "candidate encoding: 'routed' (K free points decoded into a feasible path: straight where clear, A* "
        "routes around obstacles) or 'cells' (a variable-length feasible chain of cells with A*-rerouting "
        "operators, evo.ga_astar only); see docs/planners/metaheuristics.md",
        choices=choices,
    )
