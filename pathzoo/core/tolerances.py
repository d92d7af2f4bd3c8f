"""The stated tolerances of the validity rules, all of which make the judge stricter.

Every rule in :mod:`pathzoo.rules` compares floating-point numbers. Where it
needs a tolerance, the tolerance only ever *rejects more*: a point that comes
within :data:`TOUCH_EPS_CELLS` of a forbidden set counts as inside it, and no
coordinate is ever snapped towards a blocked cell. ``docs/corner-rule.md``
explains each value.
"""

from __future__ import annotations

__all__ = ["TOUCH_EPS_CELLS", "ENDPOINT_TOLERANCE_CELLS", "SPEED_ROUNDING"]

TOUCH_EPS_CELLS = 1e-9
"""A point within this distance (per axis, in cells) of a blocked cell's closed square touches it.

The same margin, times the cell size, is added to every moving obstacle's
radius, and lattice coordinates are compared with it when terrain heights are
interpolated. It is far above the rounding error of world-to-cell conversion
(about 1e-12 cells on a 10,000-cell map) and far below any distance a planner
could gain from.
"""

ENDPOINT_TOLERANCE_CELLS = 1e-6
"""A path may start and end this close (per axis, in cells) to the scenario's start and goal.

The short connectors from the start to the first point and from the last
point to the goal are still checked against blocked cells, so the tolerance
cannot hide a collision.
"""

SPEED_ROUNDING = 1e-9
"""Relative rounding allowed when a timed segment is compared with cruise speed.

Times computed as cumulative distance over speed round either way; this
allowance changes no position and no obstacle check (those use the times as
given), only the speed comparison.
"""
