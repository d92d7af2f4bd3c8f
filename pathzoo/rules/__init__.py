"""The validity rules every path is judged by, below both the planners and the harness.

One module per rule:

- :mod:`pathzoo.rules.collision`: the map's bounds and the closed-cell rule
  (no segment touches a blocked cell or voxel, not even at a corner);
- :mod:`pathzoo.rules.slope`: the climb and descent limits on terrain (exact
  ground slope along every segment) and the pitch limit in air volumes;
- :mod:`pathzoo.rules.turns`: the turn limit as heading change per distance;
- :mod:`pathzoo.rules.timing`: timed paths, cruise speed and moving obstacles,
  from time 0 (the vehicle waits at the start until its first time);
- :mod:`pathzoo.rules.validation`: :func:`validate_path`, the whole check, and
  :func:`segment_problem`, the check of one segment that planners share.

Every tolerance makes a rule stricter (:mod:`pathzoo.core.tolerances`,
``docs/corner-rule.md``). This package imports only :mod:`pathzoo.core` and
:mod:`pathzoo.grid` (whose kernels the graph builder shares); the harness and the
planners import it.
"""

from __future__ import annotations

from pathzoo.rules.timing import path_times
from pathzoo.rules.validation import Validation, segment_problem, validate_path

__all__ = ["Validation", "validate_path", "segment_problem", "path_times"]
