"""``pathzoo leaderboard DB``: rank the planners of a stored experiment within each scenario."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pathzoo.cli.errors import CommandError

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["add_parser", "add_table_options", "load_runs", "render_leaderboard", "experiment_facts"]

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


def render_leaderboard(runs: "pd.DataFrame", args: argparse.Namespace, db: str | Path | None = None) -> str:
    """The leaderboard of ``runs`` in ``args.format``; JSON also carries the facts of :func:`experiment_facts`."""
    from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard

    table = leaderboard(runs, args.metric, reference=args.reference)
    text = format_leaderboard(table, args.format)
    if args.format != "json" or db is None:
        return text
    document = json.loads(text)
    document["experiment"] = experiment_facts(db, runs)
    return json.dumps(document, ensure_ascii=False, indent=1) + "\n"


def experiment_facts(db: str | Path, runs: "pd.DataFrame") -> dict[str, Any]:
    """What a result depends on: the experiment's seed, seed indices, budget and hard limit, and the versions.

    ``versions`` gives each planner configuration's version and, for each
    library (pathzoo, Python, numpy, ...), the version the runs used, or the
    sorted list of versions when the runs used several.
    """
    from pathzoo.harness.store import read_experiments, read_versions

    name = str(runs["experiment"].iloc[0]) if len(runs) else ""
    stored = read_experiments(db)
    row = stored[stored["name"] == name].iloc[0]
    libraries: dict[str, set[str]] = {}
    keys = set(runs["run_key"])
    for key, versions in read_versions(db, name).items():
        if key in keys:
            for lib, version in versions.items():
                if lib not in _MACHINE_FACTS:
                    libraries.setdefault(lib, set()).add(str(version))
    labels = runs["label"].where(runs["label"].astype(str) != "", runs["planner"]) if "label" in runs else runs["planner"]
    planners = dict(sorted(zip(labels.astype(str), runs["planner_version"].astype(str))))
    return {
        "name": name,
        "seed": int(row["seed"]),
        "seeds": list(row["config"].get("seeds", sorted(set(int(i) for i in runs["seed_index"])))),
        "budget": row["budget"],
        "timeout_s": float(row["timeout_s"]),
        "versions": {"planners": planners,
                     **{lib: (v.pop() if len(v) == 1 else sorted(v)) for lib, v in sorted(libraries.items())}},
    }


_MACHINE_FACTS = frozenset({"cpu", "cpu_count", "peak_rss_mb"})
"""Per-run facts of the stored ``versions`` that describe the machine or the run, not a version."""


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
    sys.stdout.write(render_leaderboard(runs, args, args.db))
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
