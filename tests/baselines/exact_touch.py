"""An exact, independent test of the closed-cell rule: segment versus closed square in rational arithmetic.

Every float is converted to a :class:`fractions.Fraction` exactly, so no
tolerance is involved: a segment touches a blocked cell when it shares at
least one point with the cell's closed square ``[c, c+1] x [r, r+1]`` (cell
units; out-of-grid cells count as blocked). Used by the issue-15 regression
tests and by ``benchmarks/baselines.py`` to count valid paths that touch.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

__all__ = ["segment_touches_square", "touching_segments"]


def segment_touches_square(p0: tuple[Fraction, Fraction], p1: tuple[Fraction, Fraction], col: int, row: int) -> bool:
    """Whether the closed segment ``p0 p1`` meets the closed square of cell ``(row, col)`` (Liang-Barsky, exact)."""
    t0, t1 = Fraction(0), Fraction(1)
    for axis, lo in ((0, col), (1, row)):
        start, delta = p0[axis], p1[axis] - p0[axis]
        for p, q in ((-delta, start - lo), (delta, lo + 1 - start)):  # p t <= q
            if p == 0:
                if q < 0:
                    return False
            elif p < 0:
                t0 = max(t0, q / p)
            else:
                t1 = min(t1, q / p)
            if t0 > t1:
                return False
    return True


def touching_segments(blocked: np.ndarray, path: np.ndarray, cell_size: float) -> list[tuple[int, int, int]]:
    """``(segment index, row, col)`` of every segment of ``path`` (world ``x, y``) touching a blocked closed square.

    Candidate cells are those of the segment's bounding box grown by one cell
    that are blocked or outside the grid; a float distance bound only skips
    cells more than a tenth of a cell away, far beyond any rounding, and the
    verdict on the rest is exact.
    """
    h, w = blocked.shape
    size = Fraction(float(cell_size))
    pts = [(Fraction(float(x)) / size, Fraction(float(y)) / size) for x, y in np.asarray(path, dtype=np.float64)]
    hits = []
    for k, (a, b) in enumerate(zip(pts[:-1], pts[1:])):
        ax, ay, bx, by = (float(v) for v in (*a, *b))
        c_lo, c_hi = int(np.floor(min(ax, bx))) - 1, int(np.floor(max(ax, bx))) + 1
        r_lo, r_hi = int(np.floor(min(ay, by))) - 1, int(np.floor(max(ay, by))) + 1
        rows, cols = np.mgrid[r_lo : r_hi + 1, c_lo : c_hi + 1]
        rows, cols = rows.ravel(), cols.ravel()
        inside = (rows >= 0) & (rows < h) & (cols >= 0) & (cols < w)
        bad = ~inside
        bad[inside] = blocked[rows[inside], cols[inside]]
        rows, cols = rows[bad], cols[bad]
        # float prefilter: distance from the segment to the square's centre minus the half-diagonal
        d = np.array([bx - ax, by - ay])
        cx, cy = cols + 0.5 - ax, rows + 0.5 - ay
        t = np.clip((cx * d[0] + cy * d[1]) / max(float(d @ d), 1e-300), 0.0, 1.0)
        dist = np.hypot(cx - t * d[0], cy - t * d[1])
        near = dist <= np.sqrt(0.5) + 0.1
        for r, c in zip(rows[near], cols[near]):
            if segment_touches_square(a, b, int(c), int(r)):
                hits.append((k, int(r), int(c)))
    return hits
