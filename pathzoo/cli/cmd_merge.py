"""``pathzoo merge A B ... -o OUT``: join the result databases of one experiment's shards (or resumes)."""

from __future__ import annotations

import argparse
import sys
from typing import Any

__all__ = ["add_parser"]


def _run(args: argparse.Namespace) -> int:
    from pathzoo.harness.merge import merge_databases

    for merged in merge_databases(args.inputs, args.output):
        already = f", {merged.duplicates} already stored and not copied again" if merged.duplicates else ""
        print(f"experiment '{merged.name}': {merged.added} runs added{already}; "
              f"{merged.total} runs in {args.output}", file=sys.stderr)
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``merge`` subcommand."""
    parser = subparsers.add_parser(
        "merge",
        help="join result databases of one experiment (shards from 'pathzoo run --shard', or resumes)",
        description="Copy every run of the input databases into OUT (created when missing, added to when it "
        "exists). Each experiment name must stand for the same experiment in every file: seed, budget, hard "
        "limit, planner configurations and scenario contents; anything else is refused with exit code 2 before "
        "OUT is written. A run stored twice is copied once.",
    )
    parser.add_argument("inputs", nargs="+", metavar="DB", help="SQLite results files written by 'pathzoo run'")
    parser.add_argument("-o", "--output", required=True, metavar="OUT", help="the merged results file")
    parser.set_defaults(handler=_run)
