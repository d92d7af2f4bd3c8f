"""Analysis of stored runs: leaderboards, statistics, paper-style tables, reports and exports.

Every function works on the runs frame of ``pathzoo.harness.store.read_runs``
(one row per run); see :mod:`pathzoo.analysis.frame` for the shared rules
(success, configurations, how failed runs are ranked).
"""

from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard
from pathzoo.analysis.summary import summarize, summarize_metrics

__all__ = ["leaderboard", "format_leaderboard", "summarize", "summarize_metrics"]
