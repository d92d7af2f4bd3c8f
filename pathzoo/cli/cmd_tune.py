"""``pathzoo tune EXPERIMENT.toml``: tune every planner with the same budget, then compare default and tuned on test scenarios."""

from __future__ import annotations

import argparse
import errno
import shutil
import sys
import textwrap
from pathlib import Path
from typing import Any

from pathzoo.cli.cmd_leaderboard import add_table_options, render_leaderboard
from pathzoo.cli.cmd_run import add_execution_options, executor_of, positive_int
from pathzoo.cli.errors import CommandError

__all__ = ["add_parser"]


def _run(args: argparse.Namespace) -> int:
    executor = executor_of(args)
    path = Path(args.experiment)
    if not path.is_file():
        raise FileNotFoundError(errno.ENOENT, "no such experiment file", str(path))
    from pathzoo.analysis.formatting import render_table
    from pathzoo.harness.runner import DEFAULT_DB
    from pathzoo.tuning import load_tuning, tune

    try:
        import optuna  # noqa: F401
    except ModuleNotFoundError:
        raise CommandError("pathzoo tune needs Optuna: pip install 'pathzoo[tune]'") from None
    setup = load_tuning(path, trials=args.trials)
    db = args.db or setup.experiment.db or DEFAULT_DB
    try:
        result = tune(setup, db=db, jobs=args.jobs, executor=executor, progress=not args.no_progress)
    except KeyboardInterrupt:
        raise CommandError(
            f"interrupted; finished trials and runs are stored in {db}, run the same command again to resume"
        ) from None
    print(f"tuned {len(result.planners)} planner(s) on {len(setup.train)} training scenario(s); trials in "
          f"{result.storage}, runs in {db} (experiments '{setup.experiment.name}.tune' and "
          f"'{setup.experiment.name}.test')", file=sys.stderr)
    sys.stdout.write(f"Tuning: {setup.trials} trials per planner, score = mean over training scenarios of the "
                     "median length ratio (failed runs count as worst); lower is better\n\n")
    table = result.table()
    display = table.astype(str)
    for col in ("default score", "tuned score"):
        display[col] = [f"{v:.4f}" if v == v else "n/a" for v in table[col]]
    sys.stdout.write(render_table(display, "text", left=("planner", "tuned parameters")))
    ids = ", ".join(s.id for s in setup.test)
    width = max(40, shutil.get_terminal_size().columns)
    sys.stdout.write("\n" + textwrap.fill(f"Test scenarios ({len(setup.test)}): {ids}", width, subsequent_indent="  ") + "\n\n")
    sys.stdout.write(render_leaderboard(result.test_runs, args))
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``tune`` subcommand."""
    parser = subparsers.add_parser(
        "tune",
        help="tune every planner with the same budget, then compare default and tuned",
        description="Give every planner of a tuning experiment file the same number of Optuna (seeded TPE) "
        "trials on its 'train' scenarios, then run each planner's default and tuned configurations on its "
        "'test' scenarios and print both rows per planner. Trials and runs are stored, so an interrupted "
        "tuning resumes with the same result. See docs/tuning.md.",
    )
    parser.add_argument("experiment", metavar="EXPERIMENT.toml", help="tuning experiment file (with train and test)")
    parser.add_argument("--trials", type=positive_int, metavar="N", help="trials per planner (default: the file's, else 20)")
    parser.add_argument(
        "--db", metavar="FILE", help="SQLite results file (default: the experiment's db, else pathzoo-results.sqlite); "
        "the Optuna trials go beside it in FILE-stem.optuna.sqlite"
    )
    add_execution_options(parser)
    add_table_options(parser)
    parser.set_defaults(handler=_run)
