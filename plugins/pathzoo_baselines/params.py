"""Hyperparameters shared by the metaheuristic baselines (encoding and penalty), pure and hybrid."""

from __future__ import annotations

from typing import Mapping

from pathzoo.core import Param

__all__ = ["ENCODING_PARAMS", "PURE_ENCODINGS", "HYBRID_ENCODINGS", "ALL_KINDS", "HYBRID_KINDS", "hybrid_encoding"]

PURE_ENCODINGS: tuple[str, ...] = ("waypoints", "spline")
"""Real-valued encodings that run no graph search (every pure planner supports them); the first is the default."""

HYBRID_ENCODINGS: tuple[str, ...] = ("routed", "cells")
"""Encodings whose decoder or operators route between cells with A* (:class:`~pathzoo_baselines.routing.CellRouter`)."""

ALL_KINDS: frozenset[str] = frozenset({"grid2d", "terrain", "dynamic", "air3d"})
"""Kinds of the pure configurations: straight segments judged by the same rules on every kind."""

HYBRID_KINDS: frozenset[str] = frozenset({"grid2d", "terrain"})
"""Kinds of the A*-routed hybrids: their routes follow the static 2-D neighbourhood graph."""

ENCODING_PARAMS: Mapping[str, Param] = {
    "encoding": Param(
        "waypoints",
        "candidate encoding: 'waypoints' (K free points joined by straight segments, penalised) or 'spline' "
        "(K control points of a clamped cubic B-spline, sampled into a polyline, penalised); neither runs a graph "
        "search (the A*-routed decoders are the '_astar' hybrid planners)",
        choices=PURE_ENCODINGS,
    ),
    "waypoints": Param(8, "K, the number of intermediate waypoints or spline control points", low=1, high=256),
    "spline_samples": Param(40, "points the spline is sampled at (encoding='spline')", low=4, high=4096),
    "repair_window": Param(
        8,
        "local repair: a segment that touches a blocked cell between two points at most this many cells apart is "
        "routed around it inside a small box (grid2d and dynamic maps; 0 turns the repair off)",
        low=0, high=16,
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
