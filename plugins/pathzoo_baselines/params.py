"""Hyperparameters shared by the four metaheuristic baselines (encoding and penalty)."""

from __future__ import annotations

from typing import Mapping

from pathzoo.core import Param

__all__ = ["ENCODING_PARAMS", "CONTINUOUS_ENCODINGS"]

CONTINUOUS_ENCODINGS: tuple[str, ...] = ("routed", "waypoints", "spline")
"""Encodings whose genes are real coordinates (every baseline supports them); the first is the default."""

ENCODING_PARAMS: Mapping[str, Param] = {
    "encoding": Param(
        "routed",
        "candidate encoding: 'routed' (K free points, decoded into a feasible path: straight where clear, "
        "grid routes around obstacles), 'waypoints' (K free points joined by straight segments, penalised) or "
        "'spline' (K control points of a clamped cubic B-spline, sampled into a polyline, penalised)",
        choices=CONTINUOUS_ENCODINGS,
    ),
    "waypoints": Param(8, "K, the number of intermediate waypoints or spline control points", low=1, high=256),
    "spline_samples": Param(40, "points the spline is sampled at (encoding='spline')", low=4, high=4096),
    "penalty": Param(
        1.0,
        "cost of one unit of constraint violation, in map diagonals (see docs/planners/swarm.pso.md)",
        low=0.0,
        low_open=True,
    ),
}
"""Parameters of :func:`pathzoo_baselines.encodings.make_encoding`, merged into each planner's ``params``."""
