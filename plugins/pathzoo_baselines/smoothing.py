"""Local smoothing of straight-segment paths: a point is joined to the farthest of the next few points it sees.

:func:`smooth_polylines` walks each polyline from its start; from the
current point it looks at most ``lookahead`` points ahead along the same
polyline and jumps to the farthest one joined by a clear segment (one that
keeps ``margin`` cells from every blocked closed square,
:func:`~pathzoo_baselines.margin.segment_clear`), dropping the points in
between. When none of them is seen clearly it keeps the next point, so a
blocked segment stays (and the cost still penalises it) unless a later
point can be reached around it in a straight line.

This is the corner-cutting ("smooth") operator of the knowledge-based GA of
Hu & Yang (ICRA 2004) and the "line-of-sight shortcut" of waypoint PSO
planners, applied to every decoded path. Its reach is ``lookahead`` points
of the candidate's own path, and it tests only straight segments: no search,
no distances over the map. It runs on the 2-D occupancy grids (``grid2d``,
``dynamic``; moving obstacles are left to the cost's time-of-passage check).
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_baselines.margin import segment_clear

__all__ = ["smooth_polylines"]


@numba.njit(cache=True)
def smooth_polylines(blocked, paths, lengths, lookahead, margin):
    """Smooth every polyline of ``paths`` (shape (n, m, 2), cell units; ``lengths`` real points) in place.

    Returns the new lengths; the rest of each row repeats its last point.
    The first and last points of each polyline are kept.
    """
    n = paths.shape[0]
    out = lengths.copy()
    for i in range(n):
        m = lengths[i]
        k = 1
        cur = 0
        while cur < m - 1:
            nxt = cur + 1
            for j in range(min(m - 1, cur + lookahead), cur + 1, -1):
                if segment_clear(blocked, paths[i, cur, 0], paths[i, cur, 1], paths[i, j, 0], paths[i, j, 1], margin):
                    nxt = j
                    break
            paths[i, k, 0] = paths[i, nxt, 0]
            paths[i, k, 1] = paths[i, nxt, 1]
            k += 1
            cur = nxt
        for t in range(k, paths.shape[1]):
            paths[i, t, 0] = paths[i, k - 1, 0]
            paths[i, t, 1] = paths[i, k - 1, 1]
        out[i] = k
    return out


def _compile() -> None:
    """Compile for read-only maps at import, not inside a timed ``plan()``."""
    blocked = np.zeros((2, 2), dtype=bool)
    blocked.setflags(write=False)
    smooth_polylines(blocked, np.full((1, 3, 2), 0.5), np.array([3], dtype=np.int64), 8, 1e-6)


_compile()
