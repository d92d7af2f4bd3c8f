"""``pathzoo report DB -o DIR``: a self-contained HTML report of a stored experiment."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_parser"]


def _run(args: argparse.Namespace) -> int:
    from pathzoo.analysis.report import write_report

    index = write_report(args.db, args.output, args.experiment, metric=args.metric, reference=args.reference,
                         detail=args.scenario or ())
    print(index)
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``report`` subcommand."""
    parser = subparsers.add_parser(
        "report",
        help="write a self-contained HTML report of a stored experiment",
        description="Write DIR/index.html: leaderboard, paper-style comparison table, critical-difference "
        "diagram, box plots, maps with paths, convergence curves and time-to-target ECDFs. Figures are "
        "embedded, so the file opens offline in any browser.",
    )
    parser.add_argument("db", metavar="DB", help="SQLite results file written by 'pathzoo run'")
    parser.add_argument("-o", "--output", metavar="DIR", required=True, help="directory to write index.html into")
    parser.add_argument("--experiment", metavar="NAME", help="experiment to report (needed when DB holds several)")
    parser.add_argument("--metric", default="length", help="metric to rank by (default: length)")
    parser.add_argument("--reference", metavar="PLANNER", help="planner the others are tested against")
    parser.add_argument("--scenario", metavar="ID", action="append",
                        help="draw this scenario's own figures (repeatable); with at most 12 scenarios every one "
                        "gets them, with more the figures summarise across scenarios and only these are drawn alone")
    parser.set_defaults(handler=_run)
