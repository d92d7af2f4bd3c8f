"""What a route's evaluation measures on each segment, kept per segment: the routes a search evaluates share most.

A route rival evaluates thousands of routes that differ from each other in a
few waypoints (a shaken or leaped route, a random route string-pulled through
the same corners). Each evaluation measures the route's world path on every
segment: the 3-D lengths and slopes of the pieces it is driven in
(:func:`pathzoo.metrics.geometry.driven_pieces`; on terrain
:func:`pathzoo.grid.terrain.path_profile`'s) and the clearances sampled along
it (:func:`pathzoo_rivals.route_kernels.clearance_samples`). Both are
computed segment by segment, element by element, so a segment's values do
not depend on the rest of the path. :class:`SegmentCache` keeps them per
segment (keyed by the segment's two world points) and joins them in path
order: a path's arrays are exactly those of the whole-path computation, to the
last bit, while only its new segments are measured. On the kinds other than
terrain a piece is a whole segment and pieces are not kept.
"""

from __future__ import annotations

import numpy as np

from pathzoo.core import Scenario
from pathzoo.grid.terrain import segments_profile
from pathzoo.metrics.geometry import driven_pieces
from pathzoo_rivals.route_kernels import clearance_samples

__all__ = ["SegmentCache", "SEGMENT_VALUES"]

SEGMENT_VALUES = 1 << 22
"""Most values a :class:`SegmentCache` keeps of each kind, pieces and clearance samples (a piece is two float64s,
a sample one: at most about 100 MB in all); a store starts again when full."""

_Key = tuple[float, ...]


class _Kept:
    """Arrays kept per segment key, at most :data:`SEGMENT_VALUES` values; a full store starts again."""

    def __init__(self) -> None:
        self.arrays: dict[_Key, tuple[np.ndarray, ...]] = {}
        self.values = 0

    def missing(self, keys: list[_Key]) -> list[int]:
        """Indices of the keys not kept (all of them after the store has started again)."""
        if self.values >= SEGMENT_VALUES:
            self.arrays.clear()
            self.values = 0
        return [i for i, key in enumerate(keys) if key not in self.arrays]

    def keep(self, keys: list[_Key], new: list[int], counts: np.ndarray, *columns: np.ndarray) -> None:
        """Keep ``columns`` split into consecutive runs of ``counts`` values, one run per key ``keys[new[i]]``."""
        bounds = np.cumsum(counts)[:-1]
        for i, parts in zip(new, zip(*(np.split(c, bounds) for c in columns))):
            self.arrays[keys[i]] = parts
        self.values += int(counts.sum())


class SegmentCache:
    """Driven pieces and clearance samples of world paths on one scenario, kept per segment.

    Parameters
    ----------
    scenario : Scenario
        The paths' scenario.
    """

    def __init__(self, scenario: Scenario) -> None:
        self.scenario = scenario
        self._pieces = _Kept()
        self._clearances = _Kept()

    @staticmethod
    def _keys(path: np.ndarray) -> list[_Key]:
        points = [tuple(p) for p in path.tolist()]
        return [a + b for a, b in zip(points[:-1], points[1:])]

    def pieces(self, path: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``driven_pieces(scenario, path)``: lengths (m) and slopes (rad) of a world path's pieces, in order."""
        s = self.scenario
        if s.kind != "terrain" or len(path) < 2:
            return driven_pieces(s, path)
        keys = self._keys(path)
        new = self._pieces.missing(keys)
        if new:
            at = np.array(new)
            lengths, slopes, segment = segments_profile(s.elevation, path[at], path[at + 1], s.cell_size)
            self._pieces.keep(keys, new, np.bincount(segment, minlength=len(new)), lengths, slopes)
        parts = [self._pieces.arrays[key] for key in keys]
        return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])

    def clearances(self, path: np.ndarray) -> np.ndarray:
        """Clearances (m) of the cells under points every half cell along a world path of two points or more.

        Segment ``i`` gives ``steps[i] = max(1, ceil(|p[i + 1] - p[i]| / (cs / 2)))``
        samples from its start on (horizontal length); the path's last point
        gives one more (:func:`~pathzoo_rivals.route_kernels.clearance_samples`).
        """
        cs = float(self.scenario.cell_size)
        keys = self._keys(path)
        new = self._clearances.missing(keys)
        if new:
            at = np.array(new)
            seg = path[at + 1] - path[at]
            steps = np.maximum(1, np.ceil(np.hypot(seg[:, 0], seg[:, 1]) / (0.5 * cs)).astype(np.int64))
            samples = [clearance_samples(self.scenario.clearance, np.ascontiguousarray(path[i:i + 2], dtype=np.float64),
                                         steps[j:j + 1], cs) for j, i in enumerate(new)]
            self._clearances.keep(keys, new, steps + 1, np.concatenate(samples))
        parts = [self._clearances.arrays[key][0] for key in keys]
        return np.concatenate([p[:-1] for p in parts] + [parts[-1][-1:]])
