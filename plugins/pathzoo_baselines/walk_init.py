"""Obstacle-aware initial candidates: K waypoints spread along a goal-biased random walk from the start to the goal.

The knowledge-based GA of Hu & Yang (ICRA 2004) starts from feasible
paths built by a random walk over free space towards the goal; later
waypoint PSO and GA planners start likewise from random feasible paths
instead of uniform points. :func:`goal_biased_walk` is our form of it:

- the walk moves between 8-connected free cells without cutting a blocked
  corner (the MovingAI rule). At each step it moves, with probability
  ``bias``, to the allowed neighbour closest in straight line to the goal
  cell, and otherwise to an allowed neighbour drawn uniformly;
- a loop is erased as soon as it closes (the walk returns to a cell it
  holds, and everything after that cell is dropped), so the walk is a
  simple chain of cells;
- it stops on the goal cell, or after ``max_steps`` steps (then there is no
  walk and the caller falls back to uniform points).

The walk uses no distances over the map, no open list and no search tree:
one cell, its 8 neighbours and the straight-line direction to the goal. It
is not a local operator, though: it may wander over the whole map before it
reaches the goal, so the *initial* candidates can span the map (the pages
say so). :func:`walk_waypoints` places K points evenly by arc length along
the chain of cell centres, so every point lies in a free cell or on the
segment between two adjacent free cells.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["goal_biased_walk", "walk_waypoints", "walk_candidates"]

_DR = np.array([0, -1, -1, -1, 0, 1, 1, 1], dtype=np.int64)
_DC = np.array([1, 1, 0, -1, -1, -1, 0, 1], dtype=np.int64)


@numba.njit(cache=True)
def goal_biased_walk(blocked, r0, c0, r1, c1, bias, max_steps, seed):
    """Loop-erased goal-biased random walk ``(r0, c0) -> (r1, c1)``: its cells (k, 2) as ``(row, col)``.

    The walk draws from numba's own generator, seeded with ``seed`` (drawn by
    the caller from the run's generator; numba's state is not numpy's). Returns
    an empty array when either cell is blocked or the goal is not reached
    within ``max_steps`` steps.
    """
    np.random.seed(seed)
    h, w = blocked.shape
    none = np.empty((0, 2), dtype=np.int64)
    if blocked[r0, c0] or blocked[r1, c1]:
        return none
    on_walk = np.full(h * w, -1, dtype=np.int64)  # position of a cell in the walk, -1 when not on it
    walk = np.empty((h * w, 2), dtype=np.int64)
    walk[0, 0], walk[0, 1] = r0, c0
    on_walk[r0 * w + c0] = 0
    n = 1
    visits = np.zeros(h * w, dtype=np.int64)
    visits[r0 * w + c0] = 1
    allowed = np.empty(8, dtype=np.int64)
    for _ in range(max_steps):
        r, c = walk[n - 1, 0], walk[n - 1, 1]
        if r == r1 and c == c1:
            return walk[:n].copy()
        count = 0
        fewest = np.iinfo(np.int64).max
        for k in range(8):  # the allowed neighbours visited least often
            vr, vc = r + _DR[k], c + _DC[k]
            if vr < 0 or vc < 0 or vr >= h or vc >= w or blocked[vr, vc]:
                continue
            if _DR[k] != 0 and _DC[k] != 0 and (blocked[r, vc] or blocked[vr, c]):
                continue
            seen = visits[vr * w + vc]
            if seen < fewest:
                fewest = seen
                count = 0
            if seen == fewest:
                allowed[count] = k
                count += 1
        if count == 0:
            return none
        if np.random.random() < bias:
            k = allowed[0]
            best = np.inf
            for i in range(count):
                d = math.hypot(r + _DR[allowed[i]] - r1, c + _DC[allowed[i]] - c1)
                if d < best:
                    best = d
                    k = allowed[i]
        else:
            k = allowed[min(int(np.random.random() * count), count - 1)]
        vr, vc = r + _DR[k], c + _DC[k]
        visits[vr * w + vc] += 1
        seen = on_walk[vr * w + vc]
        if seen >= 0:  # erase the loop: back to where the walk held this cell
            for i in range(seen + 1, n):
                on_walk[walk[i, 0] * w + walk[i, 1]] = -1
            n = seen + 1
        else:
            walk[n, 0], walk[n, 1] = vr, vc
            on_walk[vr * w + vc] = n
            n += 1
    if walk[n - 1, 0] == r1 and walk[n - 1, 1] == c1:
        return walk[:n].copy()
    return none


def walk_waypoints(cells: np.ndarray, k: int) -> np.ndarray:
    """``k`` points (cell units ``x, y``) evenly spaced by arc length along the centres of a walk's cells.

    The walk's ends (the start and goal cells) are excluded: the points are
    at arc-length fractions ``1/(k+1), ..., k/(k+1)``.
    """
    centres = cells[:, ::-1].astype(np.float64) + 0.5
    if len(centres) == 1:
        return np.repeat(centres, k, axis=0)
    run = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(centres, axis=0).T))])
    at = run[-1] * np.arange(1, k + 1) / (k + 1)
    return np.column_stack([np.interp(at, run, centres[:, 0]), np.interp(at, run, centres[:, 1])])


def walk_candidates(
    blocked: np.ndarray, start: np.ndarray, goal: np.ndarray, k: int, n: int, rng: np.random.Generator,
    bias: float, max_steps: int,
) -> list[np.ndarray | None]:
    """``n`` candidates of ``k`` points (cell units, shape (k, 2)) from independent walks; None where a walk failed.

    ``start`` and ``goal`` are in cell units; the walks run between their cells.
    """
    r0, c0 = int(math.floor(start[1])), int(math.floor(start[0]))
    r1, c1 = int(math.floor(goal[1])), int(math.floor(goal[0]))
    out: list[np.ndarray | None] = []
    for _ in range(n):
        cells = goal_biased_walk(blocked, r0, c0, r1, c1, bias, max_steps, int(rng.integers(2**31)))
        out.append(walk_waypoints(cells, k) if len(cells) else None)
    return out


def _compile() -> None:
    """Compile for read-only maps at import, not inside a timed ``plan()``."""
    blocked = np.zeros((2, 2), dtype=bool)
    blocked.setflags(write=False)
    goal_biased_walk(blocked, 0, 0, 1, 1, 0.5, 4, 0)


_compile()
