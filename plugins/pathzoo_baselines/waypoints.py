"""Continuous path encodings: K free waypoints, or K control points of a clamped cubic B-spline.

A candidate is a vector of ``dK`` reals ``(x1, y1, ..., xK, yK)`` in world
coordinates (``d = 3``, with ``z``, in air volumes), bounded by the map
(``0 <= x < width``, ``0 <= y < height``, ``0 <= z < ceiling``).

This encoding runs no graph search of any kind: it is the one the pure
configurations of the metaheuristics use (``docs/planners/metaheuristics.md``).

- ``waypoints``: the path is ``start, p1, ..., pK, goal`` joined by straight
  segments.
- ``spline``: ``start, p1, ..., pK, goal`` are the control points of a clamped
  B-spline of degree ``min(3, K + 1)`` with uniform interior knots, sampled
  at ``spline_samples`` evenly spaced parameters into a polyline. A clamped
  spline starts at the first and ends at the last control point, and the
  curve stays in the control points' convex hull, hence inside the map.

Initial candidates draw their points uniformly over the map and then sort
them along the start-goal axis, so a first path moves roughly towards the goal
instead of zig-zagging across the map (our choice; the baselines' papers do
not say how they initialise).
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import BSpline

from pathzoo.core import Scenario
from pathzoo_baselines.cost import PathCost

__all__ = ["WaypointEncoding", "spline_basis"]


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
    """

    integer = False

    def __init__(self, scenario: Scenario, *, waypoints: int, spline: bool, spline_samples: int, penalty: float):
        self.scenario = scenario
        self.k = int(waypoints)
        self.dim = scenario.dim
        self.n_genes = self.dim * self.k
        inside = np.nextafter(scenario.extent, 0.0)  # points stay in [0, extent)
        self.low = np.zeros(self.n_genes)
        self.high = np.tile(inside, self.k)
        self._basis = spline_basis(self.k + 2, spline_samples) if spline else None
        self._cost = PathCost(scenario, penalty)

    def polylines(self, genes: np.ndarray) -> np.ndarray:
        """Paths of shape (n, m, d) for candidates of shape (n, dK), clipped to the map."""
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
        """``n`` random candidates, points sorted along the start-goal axis."""
        sc = self.scenario
        pts = rng.uniform(0.0, 1.0, size=(n, self.k, self.dim)) * self.high[: self.dim]
        along = (pts - sc.start) @ (sc.goal - sc.start)
        order = np.argsort(along, axis=1, kind="stable")
        return np.take_along_axis(pts, order[..., None], axis=1).reshape(n, self.n_genes)

    def evaluate(self, genes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(cost, violation)`` of candidates of shape (n, dK)."""
        return self._cost(self.polylines(genes))

    def path(self, genes: np.ndarray) -> np.ndarray:
        """World path of one candidate."""
        return self.polylines(genes)[0]
