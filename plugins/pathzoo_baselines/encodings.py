"""The encoding interface the metaheuristics search over, and the factory that builds one from parameters."""

from __future__ import annotations

from typing import Any, Mapping, Protocol

import numpy as np

from pathzoo.core import Scenario, UnsupportedScenarioError
from pathzoo_baselines.params import waypoint_count

__all__ = ["Encoding", "FEASIBLE_ENCODINGS", "make_encoding"]


class Encoding(Protocol):
    """What a metaheuristic needs to know about candidate paths.

    Attributes
    ----------
    n_genes : int
        Length of a candidate vector.
    low, high : ndarray of shape (n_genes,)
        Inclusive bounds of each gene.
    integer : bool
        True when genes are integers (the grid-move and cell-chain encodings).

    Encodings with ``variable_length = True`` (the cell chains) take and give
    candidates as a list of int64 arrays of different lengths instead of an
    ``(n, n_genes)`` array, and bring their own ``crossover`` and ``mutate``.
    """

    n_genes: int
    low: np.ndarray
    high: np.ndarray
    integer: bool

    def initial(self, rng: np.random.Generator, n: int) -> Any:
        """``n`` random candidates from ``rng``: shape (n, n_genes), or a list of arrays when ``variable_length``."""

    def evaluate(self, genes: Any) -> tuple[np.ndarray, np.ndarray]:
        """Penalised cost and violation (0 when feasible) of candidates of shape (n, n_genes) (or a list of arrays)."""

    def path(self, genes: np.ndarray) -> np.ndarray:
        """The world path (N, 2) of one candidate, from ``scenario.start`` to ``scenario.goal``."""


FEASIBLE_ENCODINGS: tuple[str, ...] = ("cells", "routed")
"""Encodings whose every candidate decodes to a path that keeps clear of obstacles (see their modules)."""


def make_encoding(scenario: Scenario, params: Mapping[str, Any]) -> Encoding:
    """Build the encoding a planner's parameters ask for.

    ``params`` holds the entries of
    :data:`~pathzoo_baselines.params.ENCODING_PARAMS` and, for
    ``encoding='grid'``, ``moves_factor``; for ``encoding='cells'``,
    ``reroute_fraction`` and ``shortcut_rate``.

    - ``cells``: :class:`~pathzoo_baselines.cellpath.CellPathEncoding`
      (variable-length feasible chains of cells; GA only);
    - ``routed``: :class:`~pathzoo_baselines.routed.RoutedWaypointEncoding`
      (K waypoints, repairing decoder);
    - ``grid``: :class:`~pathzoo_baselines.gridpath.MoveEncoding` (compass moves);
    - ``waypoints``, ``spline``: :class:`~pathzoo_baselines.waypoints.WaypointEncoding`
      (penalised straight or spline paths).

    ``cells``, ``routed`` and ``grid`` walk the static 2-D neighbourhood
    graph, so they refuse ``dynamic`` and ``air3d`` scenarios.

    Raises
    ------
    UnsupportedScenarioError
        A graph encoding on a ``dynamic`` or ``air3d`` scenario.
    """
    if params["encoding"] in ("cells", "routed", "grid") and scenario.kind not in ("grid2d", "terrain"):
        raise UnsupportedScenarioError(
            f"encoding '{params['encoding']}' walks the static 2-D grid graph and does not support scenario kind "
            f"'{scenario.kind}'; use 'waypoints' or 'spline'"
        )
    if params["encoding"] == "cells":
        from pathzoo_baselines.cellpath import CellPathEncoding

        return CellPathEncoding(
            scenario,
            reroute_fraction=params["reroute_fraction"],
            shortcut_rate=params["shortcut_rate"],
            penalty=params["penalty"],
        )
    if params["encoding"] == "routed":
        from pathzoo_baselines.routed import RoutedWaypointEncoding

        return RoutedWaypointEncoding(scenario, waypoints=params["waypoints"], penalty=params["penalty"])
    if params["encoding"] == "grid":
        from pathzoo_baselines.gridpath import MoveEncoding

        return MoveEncoding(scenario, moves_factor=params["moves_factor"], penalty=params["penalty"])
    from pathzoo_baselines.waypoints import WaypointEncoding

    return WaypointEncoding(
        scenario,
        waypoints=waypoint_count(params["waypoints"], scenario.kind),
        spline=params["encoding"] == "spline",
        spline_samples=params["spline_samples"],
        penalty=params["penalty"],
        repair_window=params.get("repair_window", 0),
        smoothing=params.get("smoothing", 0),
        init=params.get("init", "uniform"),
        walk_bias=params.get("walk_bias", 0.5),
    )
