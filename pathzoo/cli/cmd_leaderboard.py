"""``pathzoo leaderboard DB``: rank the planners of a stored experiment within each scenario."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pathzoo.cli.errors import CommandError

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["add_parser", "add_table_options", "load_runs", "render_leaderboard"]

FORMATS = ("text", "markdown", "csv", "json", "latex", "html")


def load_runs(db: str | Path, experiment: str | None) -> "pd.DataFrame":
    """The stored runs of one experiment.

    Raises
    ------
    ResultsDatabaseError
        ``db`` is missing or not a results database, or holds no experiment ``experiment``.
    CommandError
        ``db`` holds no experiment, or several and none was chosen.
    """
    from pathzoo.harness.store import read_experiments, read_runs

    if experiment is None:
        names = [str(n) for n in read_experiments(db)["name"]]
        if len(names) > 1:
            raise CommandError(f"{db} holds experiments {', '.join(sorted(names))}; choose one with --experiment")
        if not names:
            raise CommandError(f"{db}: no experiment stored yet")
        experiment = names[0]
    return read_runs(db, experiment)


def render_leaderboard(runs: "pd.DataFrame", args: argparse.Namespace) -> str:
    """The leaderboard of ``runs`` as text, Markdown, CSV or HTML, per the table options in ``args``."""
    from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard

    table = leaderboard(runs, args.metric, reference=args.reference)
    return format_leaderboard(table, args.format)


def isolation_note(runs: "pd.DataFrame") -> str:
    """A warning line when some runs were not isolated (``inline`` executor), else ``""``."""
    if "isolated" not in runs.columns or runs["isolated"].all():
        return ""
    n = int((~runs["isolated"].astype(bool)).sum())
    return (f"pathzoo: note: {n} of {len(runs)} runs ran inline, in the harness's own process (not isolated, "
            "for debugging only); use --executor process for results")


def add_table_options(parser: argparse.ArgumentParser) -> None:
    """The options that shape a printed leaderboard (shared with ``pathzoo run``)."""
    parser.add_argument(
        "--metric", default="length", help="metric to rank by (default: length; see 'pathzoo list metrics'), "
        "or model_ratio: each planner against the optimum of its own path model, named in an 'optimum' column"
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
    note = isolation_note(runs)
    if note:
        print(note, file=sys.stderr)
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
