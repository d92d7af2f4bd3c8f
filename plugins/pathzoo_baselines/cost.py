"""Penalised cost of a batch of polylines: length plus penalty times constraint violation.

The metaheuristic baselines search over candidate paths that may collide, so
they minimise

``cost = length + penalty * diagonal * violation``

where ``diagonal`` is the map diagonal in metres and ``violation`` (unitless,
0 exactly for a path the harness would accept, up to the caveats below) adds:

- **collision**: the number of blocked or out-of-grid cells touched by the
  segments, under the closed-cell rule of :mod:`pathzoo.grid.segments`
  (:func:`~pathzoo.grid.segments.count_blocked_cells_2d`, on the same snapped
  cell units as the validator), plus one for each segment that touches none
  but passes within :data:`~pathzoo_baselines.margin.MARGIN_CELLS` of one;
  so it is 0 only when every segment passes with that margin;
- **slope** (terrain): the horizontal length, in cells, of the segments whose
  exact gradient range (:func:`pathzoo.grid.terrain.segments_slope_range`, the
  validator's own slope rule) breaks the vehicle's climb or descent limit
  (:func:`pathzoo.grid.slope_limit.slope_exceeds`), so a 0 here is never rejected
  there;
- **turns**: the number of heading changes beyond ``vehicle.max_turn_deg``
  (only when that limit is below 180 degrees; zero-length segments are not
  skipped here as the validator skips them, which is why the final path is
  still judged by :func:`~pathzoo.rules.validate_path`);
- **moving obstacles** (``dynamic``): the number of segments that come within
  an obstacle's radius (plus :data:`~pathzoo_baselines.margin.MARGIN_CELLS`,
  stricter than the judge's margin) while the vehicle drives
  them at cruise speed from time 0, with the exact distance of
  :meth:`pathzoo.core.MovingObstacle.min_distances`, the judge's own rule
  (:mod:`pathzoo.rules.timing`); the paths do not wait;
- **voxels and pitch** (``air3d``): the number of segments that touch a
  blocked voxel or leave the volume (:func:`pathzoo.grid.segments.blocked_segments`,
  the judge's rule) plus those that pitch beyond ``vehicle.max_pitch_deg``
  (:func:`pathzoo.rules.slope.steep_segments`).

``length`` is the horizontal length on ``grid2d`` and ``dynamic`` maps, the
3-D length (sum of the pieces' lengths) on ``terrain`` and the Euclidean 3-D
length in air volumes, i.e. the quantity the exact planners minimise on the
same maps.
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo.core import Scenario
from pathzoo.grid.segments import blocked_segments, count_blocked_cells_2d, to_cell_units
from pathzoo.grid.slope_limit import slope_exceeds
from pathzoo.grid.terrain import MAX_PIECE_CELLS, bilinear_elevation, segments_slope_range
from pathzoo_baselines.margin import MARGIN_CELLS, segment_clear

__all__ = ["PathCost", "collision_counts"]


@numba.njit(cache=True)
def collision_counts(blocked: np.ndarray, cells: np.ndarray, margin: float) -> np.ndarray:
    """Collision measure of each polyline; ``cells`` has shape (n, m, 2) in cell units (x, y).

    Per segment: the blocked cells it touches, or 1 when it touches none but
    comes within ``margin`` of one (:func:`~pathzoo_baselines.margin.segment_clear`),
    so an optimiser gains nothing by sliding along a wall.
    """
    n, m = cells.shape[0], cells.shape[1]
    out = np.zeros(n)
    for i in range(n):
        total = 0
        for k in range(m - 1):
            x0, y0, x1, y1 = cells[i, k, 0], cells[i, k, 1], cells[i, k + 1, 0], cells[i, k + 1, 1]
            touched = count_blocked_cells_2d(blocked, x0, y0, x1, y1)
            if touched == 0 and not segment_clear(blocked, x0, y0, x1, y1, margin):
                touched = 1
            total += touched
        out[i] = total
    return out


def _compile() -> None:
    """Compile :func:`collision_counts` for read-only maps now, at import, not inside a timed ``plan()``."""
    blocked = np.zeros((2, 2), dtype=bool)
    blocked.setflags(write=False)
    collision_counts(blocked, np.full((1, 2, 2), 0.5), MARGIN_CELLS)


_compile()


class PathCost:
    """Vectorised penalised cost of polylines on one scenario.

    Parameters
    ----------
    scenario : Scenario
        A scenario of any kind.
    penalty : float
        Cost of one unit of violation, in map diagonals.
    """

    def __init__(self, scenario: Scenario, penalty: float) -> None:
        self.scenario = scenario
        self.weight = float(penalty) * float(np.linalg.norm(scenario.extent))
        self._terrain = scenario.kind == "terrain"
        self._max_turn = float(scenario.vehicle.max_turn_deg)

    def __call__(self, paths: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Return ``(cost, violation)`` for polylines of shape (n, m, d) in world coordinates."""
        sc = self.scenario
        n = paths.shape[0]
        if sc.kind == "air3d":
            violation = self._air_violation(paths)
        else:
            violation = collision_counts(sc.blocked, to_cell_units(paths, sc.cell_size), MARGIN_CELLS)
        if self._terrain:
            length, slope_excess = self._terrain_terms(paths)
            violation = violation + slope_excess
        else:
            length = np.linalg.norm(np.diff(paths, axis=1), axis=-1).sum(axis=1)
        if sc.moving_obstacles:
            violation = violation + self._moving_hits(paths)
        if self._max_turn < 180.0 and paths.shape[1] > 2:
            d = np.diff(paths, axis=1)
            heading = np.arctan2(d[..., 1], d[..., 0])
            turn = np.degrees(np.abs((np.diff(heading, axis=1) + np.pi) % (2 * np.pi) - np.pi))
            violation = violation + (turn > self._max_turn).sum(axis=1)
        return length + self.weight * violation, violation.reshape(n)

    def _air_violation(self, paths: np.ndarray) -> np.ndarray:
        """Per polyline of an air volume: segments touching a blocked voxel plus segments beyond the pitch limit."""
        from pathzoo.rules.slope import steep_segments

        sc = self.scenario
        cells = to_cell_units(paths, sc.cell_sizes)
        return np.array(
            [blocked_segments(sc.blocked, c).sum() + steep_segments(sc, p).sum() for c, p in zip(cells, paths)],
            dtype=np.float64,
        )

    def _moving_hits(self, paths: np.ndarray) -> np.ndarray:
        """Per polyline: segments that meet a moving obstacle when driven at cruise speed from time 0."""
        sc = self.scenario
        n, m = paths.shape[0], paths.shape[1]
        step = np.linalg.norm(np.diff(paths, axis=1), axis=-1)
        times = np.concatenate([np.zeros((n, 1)), np.cumsum(step, axis=1)], axis=1) / sc.vehicle.cruise_speed
        p0 = paths[:, :-1, :2].reshape(-1, 2)
        p1 = paths[:, 1:, :2].reshape(-1, 2)
        t0, t1 = times[:, :-1].ravel(), times[:, 1:].ravel()
        hit = np.zeros(len(p0), dtype=bool)
        margin = MARGIN_CELLS * sc.cell_size  # stricter than the judge's margin (issue 15)
        for ob in sc.moving_obstacles:
            hit |= ob.min_distances(p0, p1, t0, t1) < ob.radius + margin
        return hit.reshape(n, m - 1).sum(axis=1).astype(np.float64)

    def _terrain_terms(self, paths: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """3-D length (pieces as ``segment_profile`` cuts them) and slope violation (cells of bad segments)."""
        sc = self.scenario
        assert sc.elevation is not None  # only terrain scenarios get here, and every one has an elevation
        n, m = paths.shape[0], paths.shape[1]
        cs = sc.cell_size
        p0 = paths[:, :-1].reshape(-1, 2)
        step = (paths[:, 1:] - paths[:, :-1]).reshape(-1, 2)
        horiz = np.hypot(step[:, 0], step[:, 1])
        pieces = np.maximum(1, np.ceil(horiz / cs / MAX_PIECE_CELLS - 1e-12)).astype(np.int64)
        n_seg = len(horiz)
        seg_of_point = np.repeat(np.arange(n_seg), pieces + 1)
        first = np.concatenate([[0], np.cumsum(pieces + 1)[:-1]])
        k = np.arange(len(seg_of_point)) - first[seg_of_point]
        frac = k * (1.0 / pieces[seg_of_point])  # what np.linspace(0, 1, n + 1) computes
        last = first + pieces
        frac[last] = 1.0
        pts = p0[seg_of_point] + frac[:, None] * step[seg_of_point]
        z = bilinear_elevation(sc.elevation, pts / cs)
        starts = np.ones(len(z), dtype=bool)
        starts[last] = False  # a piece starts at every point but a segment's last
        idx = np.flatnonzero(starts)
        seg = seg_of_point[idx]
        dz = z[idx + 1] - z[idx]
        dh = horiz[seg] / pieces[seg]
        piece_len = np.where(np.isfinite(dz), np.sqrt(dh * dh + np.nan_to_num(dz) ** 2), dh)
        length = np.bincount(seg // (m - 1), weights=piece_len, minlength=n)
        lo, hi = segments_slope_range(sc.elevation, p0 / cs, (p0 + step) / cs)
        bad = slope_exceeds(lo, hi, cs, sc.vehicle)
        excess = np.bincount(np.arange(n_seg) // (m - 1), weights=np.where(bad, horiz / cs, 0.0), minlength=n)
        return length, excess

