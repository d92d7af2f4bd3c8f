"""Analysis of stored runs: leaderboards, statistics, paper-style tables, reports and exports.

Every function works on the runs frame of ``pathzoo.harness.store.read_runs``
(one row per run); see :mod:`pathzoo.analysis.frame` for the shared rules
(success, configurations, how failed runs are ranked) and
``docs/statistics.md`` for the statistics. Names other than the leaderboard
and summaries are imported on first use, so ``import pathzoo.analysis``
stays light (scipy.stats and matplotlib load only when needed).
"""

from __future__ import annotations

from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard
from pathzoo.analysis.summary import summarize, summarize_metrics
from pathzoo.lazy_names import lazy_getattr

_LAZY = {
    "pairwise_tests": "pathzoo.analysis.stats",
    "friedman": "pathzoo.analysis.ranks",
    "paper_table": "pathzoo.analysis.comparison_table",
    "format_paper_table": "pathzoo.analysis.comparison_table",
    "write_report": "pathzoo.analysis.report",
    "render_report": "pathzoo.analysis.report",
    "load_experiment": "pathzoo.analysis.database",
    "export_ompl": "pathzoo.analysis.ompl_export",
    "write_ompl_logs": "pathzoo.analysis.ompl_export",
    "compare_results": "pathzoo.analysis.repeatability",
}

__all__ = ["leaderboard", "format_leaderboard", "summarize", "summarize_metrics", *_LAZY]


__getattr__ = lazy_getattr(__name__, _LAZY)
