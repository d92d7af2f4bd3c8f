"""Feasibility-keeping moves on routes: relocate, insert and remove a waypoint, and the SFLA leap.

Every move returns a new route whose changed segments passed
:meth:`~pathzoo_rivals.routes.RouteProblem.segment_ok`, or ``None`` when
``tries`` random draws found no feasible one. Unchanged segments were
feasible before, so a feasible route stays feasible.
"""

from __future__ import annotations

import numpy as np

from pathzoo_rivals.route_kernels import blend_cells, bridge_corners_free
from pathzoo_rivals.routes import RouteProblem

__all__ = ["relocate", "insert", "remove", "leap"]


def _cell_near(problem: RouteProblem, node: int, radius: int, rng: np.random.Generator) -> int | None:
    """A free cell at Chebyshev distance 1..radius from ``node``; ``None`` if the draw leaves the map or is blocked."""
    h, w = problem.shape
    r, c = divmod(int(node), w)
    dr, dc = 0, 0
    while dr == 0 and dc == 0:
        dr, dc = (int(v) for v in rng.integers(-radius, radius + 1, size=2))
    rr, cc = r + dr, c + dc
    if not (0 <= rr < h and 0 <= cc < w) or not problem.free[rr, cc]:
        return None
    return rr * w + cc


def relocate(problem: RouteProblem, route: np.ndarray, rng: np.random.Generator, radius: int,
             tries: int = 8) -> np.ndarray | None:
    """Move one interior waypoint to a free cell within ``radius`` cells."""
    if len(route) < 3:
        return None
    for _ in range(tries):
        i = int(rng.integers(1, len(route) - 1))
        cell = _cell_near(problem, int(route[i]), radius, rng)
        before, after = int(route[i - 1]), int(route[i + 1])
        if cell is not None and problem.segment_ok(before, cell) and problem.segment_ok(cell, after):
            out = route.copy()
            out[i] = cell
            return out
    return None


def insert(problem: RouteProblem, route: np.ndarray, rng: np.random.Generator, radius: int,
           tries: int = 8) -> np.ndarray | None:
    """Split one segment with a new waypoint within ``radius`` cells of the segment's middle cell."""
    w = problem.shape[1]
    for _ in range(tries):
        i = int(rng.integers(0, len(route) - 1))
        a, b = int(route[i]), int(route[i + 1])
        middle = ((a // w + b // w) // 2) * w + (a % w + b % w) // 2
        cell = _cell_near(problem, middle, radius, rng)
        if cell is not None and problem.segment_ok(a, cell) and problem.segment_ok(cell, b):
            return np.concatenate([route[: i + 1], [cell], route[i + 1:]]).astype(np.int64)
    return None


def remove(problem: RouteProblem, route: np.ndarray, rng: np.random.Generator, tries: int = 8) -> np.ndarray | None:
    """Drop one interior waypoint whose neighbours see each other."""
    if len(route) < 3:
        return None
    for _ in range(tries):
        i = int(rng.integers(1, len(route) - 1))
        if problem.segment_ok(int(route[i - 1]), int(route[i + 1])):
            return np.delete(route, i)
    return None


def leap(problem: RouteProblem, worst: np.ndarray, best: np.ndarray, rng: np.random.Generator) -> np.ndarray | None:
    """SFLA's leap ``X_w + r (X_b - X_w)``, ``r ~ U(0, 1)``, on routes resampled to a common number of points.

    Both routes are resampled by arc length to one point per cell of the
    longer route, blended, and snapped to the cells under the blended points
    (start and goal cells forced), with repeated cells merged. A feasible
    result is string-pulled (:meth:`RouteProblem.pull_string`), the same
    simplification random routes get; otherwise returns ``None``.
    """
    (pa, length_a), (pb, length_b) = problem.outline(worst), problem.outline(best)
    longest = max(length_a, length_b)
    n = max(len(worst), len(best), int(np.ceil(longest / problem.scenario.cell_size)) + 1)
    h, w = problem.shape
    cells = blend_cells(pa, pb, n, rng.uniform(), problem.scenario.cell_size, h, w, problem.start, problem.goal)
    bridged = _bridge_corners(problem, cells)
    return problem.pull_string(bridged) if bridged is not None and problem.route_ok(bridged) else None


def _bridge_corners(problem: RouteProblem, cells: np.ndarray) -> np.ndarray | None:
    """Replace each diagonal step the corner rule forbids by two straight steps through a free side cell, if one works.

    Snapping a smooth blend to cells often produces a diagonal step past a
    blocked corner; the blend itself does not cross the obstacle, so going
    round the corner on the free side is the faithful cell route. Returns
    ``None`` as soon as a step is not allowed and cannot be bridged (the
    route is infeasible: the steps after it are not looked at).
    """
    if problem.collision_only:
        bridged = bridge_corners_free(problem.blocked, problem.cell_size, cells)
        return bridged if len(bridged) else None
    w = problem.shape[1]
    out = [int(cells[0])]
    for v in (int(c) for c in cells[1:]):
        u = out[-1]
        if not problem.segment_ok(u, v):
            (ru, cu), (rv, cv) = divmod(u, w), divmod(v, w)
            if abs(ru - rv) != 1 or abs(cu - cv) != 1:
                return None
            side = next((c for c in (ru * w + cv, rv * w + cu) if problem.segment_ok(u, c) and problem.segment_ok(c, v)),
                        None)
            if side is None:
                return None
            out.append(side)
        out.append(v)
    return np.array(out, dtype=np.int64)
