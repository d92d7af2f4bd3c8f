"""``pathzoo compare A B``: check that two result databases store the same results for an experiment, times aside."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["EXIT_DIFFERENT", "add_parser"]

EXIT_DIFFERENT = 1
"""Exit code when the databases differ (2 stays the code of a bad input, as for every command)."""


def _run(args: argparse.Namespace) -> int:
    from pathzoo.analysis.repeatability import compare_results

    comparison = compare_results(args.first, args.second, args.experiment)
    print(comparison.summary(args.limit))
    return 0 if comparison.identical else EXIT_DIFFERENT


def add_parser(subparsers: Any) -> None:
    """Register the ``compare`` subcommand."""
    parser = subparsers.add_parser(
        "compare",
        help="check that two result databases hold the same results (times aside)",
        description="Compare every run of an experiment stored in two databases: status, validity, counts, "
        "stopped_by, path, history and every metric except measured times must be identical. "
        "Exit code 0 when they are, 1 when they differ, 2 on a bad input.",
    )
    parser.add_argument("first", metavar="A", help="SQLite results file written by 'pathzoo run'")
    parser.add_argument("second", metavar="B", help="another results file with the same experiment")
    parser.add_argument("--experiment", metavar="NAME", help="experiment to compare (needed when A holds several)")
    parser.add_argument("--limit", type=int, default=20, metavar="N", help="differences to print (default: 20)")
    parser.set_defaults(handler=_run)
