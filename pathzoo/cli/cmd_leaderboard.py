"""``pathzoo leaderboard DB``: rank the planners of a stored experiment within each scenario."""

from __future__ import annotations

import argparse
import errno
import sqlite3
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pathzoo.cli.errors import CommandError

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["add_parser", "add_table_options", "load_runs", "render_leaderboard"]

FORMATS = ("text", "markdown", "csv")


def load_runs(db: str | Path, experiment: str | None) -> "pd.DataFrame":
    """The stored runs of one experiment.

    Raises
    ------
    FileNotFoundError
        ``db`` does not exist (it is never created here).
    CommandError
        ``db`` is not a results database, holds no runs of ``experiment``, or
        holds several experiments and none was chosen.
    """
    path = Path(db)
    if not path.is_file():
        raise FileNotFoundError(errno.ENOENT, "no such results database", str(path))
    from pathzoo.harness.store import read_runs

    try:
        runs = read_runs(path)
    except sqlite3.DatabaseError as exc:
        raise CommandError(f"{path}: not a pathzoo results database ({exc})") from None
    names = sorted(str(n) for n in runs["experiment"].unique())
    if experiment is None:
        if len(names) > 1:
            raise CommandError(f"{path} holds experiments {', '.join(names)}; choose one with --experiment")
        if not names:
            raise CommandError(f"{path}: no runs stored yet")
        return runs
    if experiment not in names:
        held = ", ".join(names) if names else "none"
        raise CommandError(f"{path}: no runs of experiment '{experiment}' (experiments stored: {held})")
    return runs[runs["experiment"] == experiment]


def render_leaderboard(runs: "pd.DataFrame", args: argparse.Namespace) -> str:
    """The leaderboard of ``runs`` as text, Markdown or CSV, per the table options in ``args``."""
    from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard

    table = leaderboard(runs, args.metric, reference=args.reference)
    return format_leaderboard(table, args.format)


def add_table_options(parser: argparse.ArgumentParser) -> None:
    """The options that shape a printed leaderboard (shared with ``pathzoo run``)."""
    parser.add_argument(
        "--metric", default="length", help="metric to rank by (default: length; see 'pathzoo list metrics')"
    )
    parser.add_argument(
        "--reference",
        metavar="PLANNER",
        help="test every other planner against this one (Mann-Whitney U or Wilcoxon, Holm-corrected)",
    )
    parser.add_argument("--format", choices=FORMATS, default="text", help="output format (default: text)")


def _run(args: argparse.Namespace) -> int:
    runs = load_runs(args.db, args.experiment)
    sys.stdout.write(render_leaderboard(runs, args))
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``leaderboard`` subcommand."""
    parser = subparsers.add_parser(
        "leaderboard",
        help="rank the planners of a stored experiment",
        description="Rank configurations within each scenario: median, IQR and SD of the metric over "
        "successful runs, and the success rate. Failed runs count as worst when ranking.",
    )
    parser.add_argument("db", metavar="DB", help="SQLite results file written by 'pathzoo run'")
    parser.add_argument("--experiment", metavar="NAME", help="experiment to show (needed when DB holds several)")
    add_table_options(parser)
    parser.set_defaults(handler=_run)
