"""Fuzz tests of the validity rules against exact rational geometry and single corruptions.

- Segments nudged by 1e-12 ... 1e-6 towards or away from a blocked cell are
  rejected exactly when an exact ``fractions.Fraction`` test says they touch
  the cell's closed square grown by the stated margin (and always when they
  touch the square itself).
- Random honest paths pass, and every random single corruption of one fails.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra

from pathzoo import Scenario, VehicleModel
from pathzoo.core.tolerances import TOUCH_EPS_CELLS
from pathzoo.rules import path_times, segment_problem, validate_path

CELL = 0.7  # not a power of two, so world-to-cell conversion rounds


def _touches(p0, p1, lo, hi) -> bool:
    """Exact: does the closed segment p0 -> p1 meet the closed box [lo, hi]? (Liang-Barsky on Fractions)."""
    t0, t1 = Fraction(0), Fraction(1)
    for k in range(2):
        d = p1[k] - p0[k]
        if d == 0:
            if p0[k] < lo[k] or p0[k] > hi[k]:
                return False
            continue
        a, b = (lo[k] - p0[k]) / d, (hi[k] - p0[k]) / d
        if a > b:
            a, b = b, a
        t0, t1 = max(t0, a), min(t1, b)
        if t0 > t1:
            return False
    return True


def _exact_hit(blocked: np.ndarray, p0: np.ndarray, p1: np.ndarray, margin_cells: Fraction) -> bool:
    """Does the segment (world coordinates) touch a blocked or outside cell grown by ``margin_cells``?"""
    h, w = blocked.shape
    cs = Fraction(CELL)
    q0, q1 = [Fraction(float(v)) for v in p0], [Fraction(float(v)) for v in p1]
    lo_c = int(min(p0[0], p1[0]) / CELL) - 2
    hi_c = int(max(p0[0], p1[0]) / CELL) + 2
    lo_r = int(min(p0[1], p1[1]) / CELL) - 2
    hi_r = int(max(p0[1], p1[1]) / CELL) + 2
    m = margin_cells * cs
    for r in range(lo_r, hi_r + 1):
        for c in range(lo_c, hi_c + 1):
            if 0 <= r < h and 0 <= c < w and not blocked[r, c]:
                continue
            if _touches(q0, q1, (c * cs - m, r * cs - m), ((c + 1) * cs + m, (r + 1) * cs + m)):
                return True
    return False


@pytest.fixture(scope="module")
def grid() -> Scenario:
    rng = np.random.default_rng(3)
    occ = rng.random((12, 12)) < 0.25
    occ[0, 0] = occ[11, 11] = False
    return Scenario(id="fuzz", kind="grid2d", occupancy=occ, cell_size=CELL, start=(0.35, 0.35), goal=(8.05, 8.05))


def test_nudged_segments_are_rejected_exactly_when_they_touch(grid):
    rng = np.random.default_rng(11)
    blocked = grid.blocked
    h, w = blocked.shape
    eps = Fraction(TOUCH_EPS_CELLS)
    # (blocked cell, free neighbour) pairs across a vertical edge, either side
    pairs = [(r, c, dc) for r in range(h) for c in range(w) for dc in (-1, 1)
             if blocked[r, c] and 0 <= c + dc < w and not blocked[r, c + dc]]
    counts = {"touch": 0, "margin": 0, "free": 0}
    for _ in range(400):
        r, c, dc = pairs[rng.integers(len(pairs))]
        edge_x = c + (1 if dc == 1 else 0)  # the blocked cell's edge facing the free neighbour
        delta = 10.0 ** rng.uniform(-12, -6) * rng.choice([-1.0, 1.0])  # > 0: into the blocked cell
        y_end = r + rng.choice([rng.uniform(0, 1), 0.0, 1.0])
        end = np.array([(edge_x - dc * delta) * CELL, y_end * CELL])
        if rng.random() < 0.5:  # from inside the free cell
            start = np.array([(c + dc + rng.uniform(0.05, 0.95)) * CELL, (r + rng.uniform(0.05, 0.95)) * CELL])
        else:  # sliding along the wall, like PSO
            start = np.array([(edge_x - dc * delta * rng.uniform(0.5, 2.0)) * CELL, (r + rng.uniform(0, 1)) * CELL])
        verdict = segment_problem(grid, start, end)
        if _exact_hit(blocked, start, end, Fraction(0)):
            counts["touch"] += 1
            assert verdict is not None, (start, end)
        elif _exact_hit(blocked, start, end, eps * Fraction(999, 1000)):
            counts["margin"] += 1
            assert verdict is not None, (start, end)
        elif not _exact_hit(blocked, start, end, eps * Fraction(1001, 1000)):
            counts["free"] += 1
            assert verdict is None, (start, end, verdict)
    assert min(counts.values()) >= 20, counts


def _graph_path(scenario: Scenario, a: int, b: int) -> np.ndarray | None:
    _, pred = dijkstra(scenario.graph.to_sparse(), indices=a, return_predecessors=True)
    if pred[b] < 0:
        return None
    nodes = [b]
    while nodes[-1] != a:
        nodes.append(pred[nodes[-1]])
    return scenario.point_of(nodes[::-1])


def _corruptions(s: Scenario, path: np.ndarray, rng: np.random.Generator) -> dict[str, tuple[np.ndarray, object]]:
    """Single corruptions of an honest path, each of which breaks one rule for sure."""
    n = len(path)
    k = int(rng.integers(1, n - 1))
    blocked_cells = np.argwhere(s.blocked)
    r, c = blocked_cells[rng.integers(len(blocked_cells))]
    out: dict[str, tuple[np.ndarray, object]] = {}
    p = path.copy()
    p[k] = (np.array([c, r]) + rng.uniform(0, 1, 2)) * s.cell_size  # into a blocked cell (closed square)
    out["into a blocked cell"] = (p, None)
    p = path.copy()
    p[k] = np.array([c + rng.choice([0.0, 1.0]), r + rng.uniform(0, 1)]) * s.cell_size  # onto its boundary
    out["onto a blocked cell's edge"] = (p, None)
    p = path.copy()
    p[-1] = p[-1] + np.array([0.0, 2e-6 * s.cell_size])
    out["beside the goal"] = (p, None)
    p = path.copy()
    p[k, rng.integers(2)] = np.nan
    out["NaN"] = (p, None)
    out["outside the map"] = (np.insert(path, k, [-1e-10, path[k, 1]], axis=0), None)
    out["reversal"] = (np.insert(path, k + 1, [path[k - 1], path[k]], axis=0), None)
    t = path_times(s, path)
    bad = t.copy()
    bad[k] = t[k + 1] + 1.0
    out["times going back"] = (path, bad)
    out["faster than cruise"] = (path, t * 0.5)
    return out


def test_honest_paths_pass_and_every_single_corruption_fails():
    rng = np.random.default_rng(7)
    checked = 0
    for trial in range(12):
        occ = rng.random((14, 14)) < 0.2
        kind = "terrain" if trial % 2 else "grid2d"
        extra = {}
        if kind == "terrain":
            rows, cols = np.mgrid[0:14, 0:14]
            extra = dict(elevation=3.0 * np.sin(rows / 3.0) * np.cos(cols / 4.0) + rng.uniform(0, 0.3, (14, 14)),
                         vehicle=VehicleModel(max_climb_deg=35.0, max_descent_deg=35.0, max_turn_deg=135.0))
        else:
            extra = dict(vehicle=VehicleModel(max_turn_deg=135.0))
        free = np.argwhere(~occ)
        a, b = free[rng.choice(len(free), 2, replace=False)]
        base = Scenario(id="f", kind=kind, occupancy=occ, cell_size=CELL, start=(a[::-1] + 0.5) * CELL,
                        goal=(b[::-1] + 0.5) * CELL, **extra)
        path = _graph_path(base, base.start_node, base.goal_node)
        if path is None or len(path) < 4:
            continue
        assert validate_path(base, path), validate_path(base, path).reason
        assert validate_path(base, path, times=path_times(base, path))
        for name, (bad_path, times) in _corruptions(base, path, rng).items():
            res = validate_path(base, bad_path, times=times)
            assert not res, (name, kind)
            checked += 1
    assert checked >= 40
