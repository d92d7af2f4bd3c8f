"""Continuous path encodings: K free waypoints, or K control points of a clamped cubic B-spline.

A candidate is a vector of ``dK`` reals ``(x1, y1, ..., xK, yK)`` in world
coordinates (``d = 3``, with ``z``, in air volumes), bounded by the map
(``0 <= x < width``, ``0 <= y < height``, ``0 <= z < ceiling``).

This encoding runs no global search of any kind: it is the one the pure
configurations of the metaheuristics use (``docs/planners/metaheuristics.md``).
On the 2-D occupancy grids (``grid2d``, ``dynamic``) every decoded path goes
through two local operators, each with a stated reach:

- repair (:mod:`pathzoo_baselines.local_repair`, ``repair_window``): a
  segment that touches a blocked cell between two points at most
  ``repair_window`` cells apart is routed around it inside a small box;
- smoothing (:mod:`pathzoo_baselines.smoothing`, ``smoothing``): each point
  is joined by a straight segment to the farthest of the next ``smoothing``
  points it sees.

``0`` turns either off.

- ``waypoints``: the path is ``start, p1, ..., pK, goal`` joined by straight
  segments.
- ``spline``: ``start, p1, ..., pK, goal`` are the control points of a clamped
  B-spline of degree ``min(3, K + 1)`` with uniform interior knots, sampled
  at ``spline_samples`` evenly spaced parameters into a polyline. A clamped
  spline starts at the first and ends at the last control point, and the
  curve stays in the control points' convex hull, hence inside the map.

Initial candidates (``init``): with ``'walk'`` (the default; ``grid2d`` and
``dynamic`` maps) each candidate's points are spread along a goal-biased
random walk over free cells (:mod:`pathzoo_baselines.walk_init`), so a first
path follows free space; with ``'uniform'``, and on the other kinds, points
are drawn uniformly over the map and sorted along the start-goal axis.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import BSpline

from pathzoo.core import Scenario
from pathzoo.grid.segments import to_cell_units
from pathzoo_baselines.cost import PathCost
from pathzoo_baselines.local_repair import repair_polylines
from pathzoo_baselines.margin import MARGIN_CELLS
from pathzoo_baselines.smoothing import smooth_polylines
from pathzoo_baselines.walk_init import walk_candidates

__all__ = ["WaypointEncoding", "spline_basis", "WALK_STEPS_PER_CELL"]

WALK_STEPS_PER_CELL = 20
"""Steps an initial walk may take per cell of the map before its candidate falls back to uniform points."""


def spline_basis(n_control: int, n_samples: int) -> np.ndarray:
    """Design matrix (n_samples, n_control) of a clamped uniform B-spline of degree ``min(3, n_control - 1)``."""
    degree = min(3, n_control - 1)
    knots = np.concatenate([np.zeros(degree), np.linspace(0.0, 1.0, n_control - degree + 1), np.ones(degree)])
    return BSpline.design_matrix(np.linspace(0.0, 1.0, n_samples), knots, degree).toarray()


class WaypointEncoding:
    """Candidates as ``dK`` world coordinates; see the module docstring.

    Parameters
    ----------
    scenario : Scenario
        The problem (any kind).
    waypoints : int
        K, the number of free points.
    spline : bool
        Read the points as spline control points instead of waypoints.
    spline_samples : int
        Polyline resolution of the spline.
    penalty : float
        Penalty weight of :class:`~pathzoo_baselines.cost.PathCost`.
    repair_window : int
        Largest distance in cells between the ends of a blocked segment that
        the local repair routes around (0: no repair). Used on ``grid2d``
        and ``dynamic`` maps only.
    smoothing : int
        How many points ahead the smoothing looks (0: no smoothing); ``grid2d``
        and ``dynamic`` maps only.
    init : {'uniform', 'walk'}
        Initial candidates: uniform points, or points along goal-biased walks
        (``grid2d`` and ``dynamic`` maps only; uniform elsewhere).
    walk_bias : float
        Probability that a walk step heads for the goal.
    """

    integer = False

    def __init__(
        self, scenario: Scenario, *, waypoints: int, spline: bool, spline_samples: int, penalty: float,
        repair_window: int = 0, smoothing: int = 0, init: str = "uniform", walk_bias: float = 0.5,
    ):
        self.scenario = scenario
        self.k = int(waypoints)
        self.dim = scenario.dim
        self.n_genes = self.dim * self.k
        inside = np.nextafter(scenario.extent, 0.0)  # points stay in [0, extent)
        self.low = np.zeros(self.n_genes)
        self.high = np.tile(inside, self.k)
        self._basis = spline_basis(self.k + 2, spline_samples) if spline else None
        self._cost = PathCost(scenario, penalty)
        grid = scenario.kind in ("grid2d", "dynamic")
        self._repair = int(repair_window) if grid else 0
        self._smoothing = int(smoothing) if grid else 0
        self._walk = init == "walk" and grid
        self._walk_bias = float(walk_bias)

    def polylines(self, genes: np.ndarray) -> np.ndarray:
        """Paths of shape (n, m, d) for candidates of shape (n, dK), clipped to the map and repaired.

        Repaired paths have different numbers of points; each row repeats
        its last point up to the longest (see :func:`decode`).
        """
        return self.decode(genes)[0]

    def decode(self, genes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(paths, lengths)``: :meth:`polylines` and the number of real points of each path."""
        pts = self._points(genes)
        if self._repair <= 0 and self._smoothing <= 0:
            return pts, np.full(len(pts), pts.shape[1], dtype=np.int64)
        cs = self.scenario.cell_size
        blocked = self.scenario.blocked
        out = to_cell_units(pts, cs)
        lengths = np.full(len(pts), pts.shape[1], dtype=np.int64)
        if self._repair > 0:
            out, lengths = repair_polylines(blocked, out, self._repair, MARGIN_CELLS)
        if self._smoothing > 0:
            lengths = smooth_polylines(blocked, out, lengths, self._smoothing, MARGIN_CELLS)
        out = out * cs
        out[:, 0] = pts[:, 0]  # the exact start and goal, not their round trip through cell units
        tail = np.arange(out.shape[1])[None, :] >= lengths[:, None] - 1
        out[tail] = np.repeat(pts[:, -1], out.shape[1] - lengths + 1, axis=0)
        return out, lengths

    def _points(self, genes: np.ndarray) -> np.ndarray:
        """The unrepaired paths (n, m, d): start, the K points (or the sampled spline), goal."""
        x = np.clip(np.asarray(genes, dtype=np.float64).reshape(-1, self.n_genes), self.low, self.high)
        n = len(x)
        sc = self.scenario
        d = self.dim
        ends = np.broadcast_to(sc.start, (n, 1, d)), np.broadcast_to(sc.goal, (n, 1, d))
        control = np.concatenate([ends[0], x.reshape(n, self.k, d), ends[1]], axis=1)
        if self._basis is None:
            return control
        pts = np.clip(np.einsum("mj,njd->nmd", self._basis, control), 0.0, self.high[:d])  # rounding at the border
        pts[:, 0] = sc.start
        pts[:, -1] = sc.goal
        return pts

    def initial(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """``n`` initial candidates: points along goal-biased walks (``init='walk'``), else uniform, sorted.

        Uniform points are sorted along the start-goal axis. A walk that does
        not reach the goal within :data:`WALK_STEPS_PER_CELL` steps per cell
        of the map leaves its candidate uniform.
        """
        sc = self.scenario
        pts = rng.uniform(0.0, 1.0, size=(n, self.k, self.dim)) * self.high[: self.dim]
        along = (pts - sc.start) @ (sc.goal - sc.start)
        order = np.argsort(along, axis=1, kind="stable")
        pts = np.take_along_axis(pts, order[..., None], axis=1)
        if self._walk:
            cs = sc.cell_size
            walks = walk_candidates(
                sc.blocked, to_cell_units(sc.start, cs), to_cell_units(sc.goal, cs), self.k, n, rng,
                self._walk_bias, WALK_STEPS_PER_CELL * sc.blocked.size,
            )
            for i, points in enumerate(walks):
                if points is not None:
                    pts[i] = np.clip(points * cs, self.low[:2], self.high[:2])
        return pts.reshape(n, self.n_genes)

    def evaluate(self, genes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(cost, violation)`` of candidates of shape (n, dK)."""
        return self._cost(self.polylines(genes))

    def path(self, genes: np.ndarray) -> np.ndarray:
        """World path of one candidate (without the repeated tail)."""
        paths, lengths = self.decode(genes)
        return paths[0, : lengths[0]]
