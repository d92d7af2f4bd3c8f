"""The optimality metrics: path length relative to the graph and any-angle optima, arrival relative to the earliest."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pathzoo.grid.reference import anyangle_bound_3d, anyangle_length, earliest_arrival_s, reference_length
from pathzoo.metrics.base import PathMetric
from pathzoo.metrics.geometry import driven_pieces
from pathzoo.rules.timing import path_times

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord
    from pathzoo.core.scenario import Scenario

__all__ = ["LengthRatio", "LengthRatioAnyAngle", "LengthRatioAnyAngleBound", "ArrivalRatio"]


class _LengthOverReference(PathMetric):
    """A path's length (3-D pieces, as the judge cuts them) over a reference length of the scenario."""

    @staticmethod
    def reference(scenario: "Scenario") -> float:
        """The reference length (NaN where there is none)."""
        raise NotImplementedError

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """``length / reference``; 1 when both are 0, NaN without a reference."""
        return _ratio(float(driven_pieces(scenario, path)[0].sum()), self.reference(scenario))


class LengthRatio(_LengthOverReference):
    """Path length divided by the reference length (1 = as short as the graph optimum).

    The reference is :func:`pathzoo.grid.reference.reference_length`: the
    scenario's ``reference_length`` when set, else the Dijkstra optimum on the
    8-connected (terrain: 3-D; air: ``max_step``) graph. Any-angle paths are
    not bound to the graph and may score below 1. NaN when there is no
    reference (``dynamic`` scenarios without ``reference_length``).
    """

    id = "length_ratio"
    unit = "1"
    direction = "min"
    summary = "length / exact graph optimum (any-angle paths may be < 1)"
    reference = staticmethod(reference_length)


class LengthRatioAnyAngle(_LengthOverReference):
    """Path length divided by the exact any-angle optimum (1 = as short as any valid path can be).

    The reference is :func:`pathzoo.grid.reference.anyangle_length`, the
    infimum of the lengths of all valid paths, so no valid path scores
    below 1. NaN where it is not computed: kinds other than ``grid2d`` and
    maps larger than :data:`pathzoo.grid.anyangle.MAX_EXACT_CELLS` cells
    (``docs/metrics.md`` says which ratio suits which planner).
    """

    id = "length_ratio_anyangle"
    unit = "1"
    direction = "min"
    summary = "length / exact any-angle optimum (grid2d up to 4096x4096; never below 1)"
    reference = staticmethod(anyangle_length)


class LengthRatioAnyAngleBound(_LengthOverReference):
    """Path length divided by the Lazy Theta* length in air volumes (an upper bound on the any-angle optimum).

    The reference is :func:`pathzoo.grid.reference.anyangle_bound_3d`. It is
    not the optimum, so a valid path may score below 1, by at most the gap
    between the bound and the straight-line distance. NaN on other kinds.
    """

    id = "length_ratio_anyangle_bound"
    unit = "1"
    direction = "min"
    summary = "length / Lazy Theta* length (air3d; an upper bound on the any-angle optimum, may be < 1)"
    reference = staticmethod(anyangle_bound_3d)


class ArrivalRatio(PathMetric):
    """Arrival time divided by the earliest arrival of SIPP (1 = as early as any timed grid path can be).

    The arrival is the last of the path's ``times`` or, without times, its
    length over the cruise speed (how the judge times it). The reference is
    :func:`pathzoo.grid.reference.earliest_arrival_s`: the earliest arrival
    among the moving obstacles of a vehicle that moves between 8-neighbouring
    cell centres at cruise speed and may wait. A grid planner's valid path
    never scores below 1; a path with segments in other directions can.
    NaN on kinds other than ``dynamic``.
    """

    id = "arrival_ratio"
    unit = "1"
    direction = "min"
    summary = "arrival time / earliest arrival of SIPP (dynamic; grid paths never below 1)"

    def measure(self, scenario: "Scenario", path: np.ndarray, record: "RunRecord") -> float:
        """``arrival / earliest arrival``; NaN without a reference."""
        if scenario.kind != "dynamic":
            return math.nan
        arrival = float(record.times[-1]) if record.times is not None else float(path_times(scenario, path)[-1])
        return _ratio(arrival, earliest_arrival_s(scenario))


def _ratio(length: float, ref: float) -> float:
    if math.isnan(ref):
        return math.nan
    if ref == 0.0:
        return 1.0 if length == 0.0 else math.inf
    return length / ref
