"""``pathzoo export-ompl DB -o DIR``: OMPL benchmark logs for Planner Arena."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_parser"]


def _run(args: argparse.Namespace) -> int:
    from pathzoo.analysis.ompl_export import export_ompl

    for path in export_ompl(args.db, args.output, args.experiment):
        print(path)
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``export-ompl`` subcommand."""
    parser = subparsers.add_parser(
        "export-ompl",
        help="export a stored experiment as OMPL benchmark logs (Planner Arena)",
        description="Write one OMPL benchmark .log file per scenario. OMPL's own "
        "'python -m ompl.ompl_benchmark_statistics -d arena.db DIR/*.log' turns them into the "
        "SQLite database that Planner Arena reads.",
    )
    parser.add_argument("db", metavar="DB", help="SQLite results file written by 'pathzoo run'")
    parser.add_argument("-o", "--output", metavar="DIR", required=True, help="directory for the .log files")
    parser.add_argument("--experiment", metavar="NAME", help="experiment to export (needed when DB holds several)")
    parser.set_defaults(handler=_run)
