"""The turn limit, read as a bound on heading change per distance travelled.

The papers that limit turns (DSACO, FGDACO) do so per waypoint of a grid path,
whose waypoints are at least one cell apart: the vehicle may change heading by
at most ``max_turn_deg`` per cell it drives, which is a minimum turning radius
of about ``cell_size / max_turn`` (radians). A waypoint path can place its
waypoints anywhere, so the rule here is the same bound for any spacing: the
heading changes made within **any stretch of the path shorter than one cell**
(horizontal distance) add up to at most ``max_turn_deg``. Three 60° turns 1e-6 m
apart are a 180° turn in 2e-6 m and break a 60° limit; two 45° turns one cell
apart (a grid path) do not break a 45° limit.

For air paths the horizontal heading is used; a vertical segment has no
heading and no horizontal length, so turns on either side of it count
together. No angle tolerance is allowed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["TURN_WINDOW_CELLS", "heading_changes", "turn_problem"]

TURN_WINDOW_CELLS = 1.0 - 1e-6
"""Length of the stretch (in cells) within which heading changes add up.

One cell, less a 1e-6 allowance so that turns exactly one cell apart (grid
paths) are never joined by the rounding of cumulative distances.
"""


def heading_changes(path: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Horizontal heading changes (degrees, ``[0, 180]``) and the distance along the path where each is made.

    Segments without horizontal length are skipped. The angle between
    directions ``a`` and ``b`` is ``atan2(|a x b|, a . b)`` on the unnormalised
    vectors, which is exact for the 45° multiples of grid moves.
    """
    d = np.diff(np.asarray(path, dtype=np.float64)[:, :2], axis=0)
    horiz = np.hypot(d[:, 0], d[:, 1])
    at = np.concatenate([[0.0], np.cumsum(horiz)])[1:]  # distance at the end of each segment
    moving = horiz > 0
    d, at = d[moving], at[moving]
    if len(d) < 2:
        return np.zeros(0), np.zeros(0)
    a, b = d[:-1], d[1:]
    cross = np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    dot = a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]
    return np.degrees(np.arctan2(cross, dot)), at[:-1]


def turn_problem(scenario: "Scenario", path: np.ndarray) -> str | None:
    """Why the path turns more than the vehicle can, or ``None`` (vectorised over the path)."""
    limit = scenario.vehicle.max_turn_deg
    if limit >= 180.0:
        return None
    turns, at = heading_changes(path)
    if not len(turns):
        return None
    window = TURN_WINDOW_CELLS * scenario.cell_size
    last = np.searchsorted(at, at + window, side="left")  # turns i..last-1 lie within the window from turn i
    first = np.arange(len(turns))
    cum = np.concatenate([[0.0], np.cumsum(turns)])
    total = np.where(last - first == 1, turns, cum[last] - cum[first])
    worst = int(np.argmax(total))
    if total[worst] <= limit:
        return None
    count = int(last[worst] - first[worst])
    span = float(at[last[worst] - 1] - at[worst])
    if count == 1:
        return f"a heading change of {total[worst]:.3f} deg exceeds the turn limit {limit} deg"
    return (
        f"{count} heading changes within {span:.3g} m add up to {total[worst]:.3f} deg, more than the turn limit "
        f"{limit} deg per cell ({scenario.cell_size} m) of travel"
    )
