"""``pathzoo leaderboard DB``: rank the planners of a stored experiment within each scenario."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

from pathzoo.cli.errors import CommandError

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["add_parser", "add_table_options", "experiment_name", "render_leaderboard", "experiment_facts",
           "stored_experiment_facts"]

FORMATS = ("text", "markdown", "csv", "json", "latex", "html")


def experiment_name(db: str | Path, experiment: str | None) -> str:
    """``experiment``, or the name of the one experiment ``db`` holds.

    Raises
    ------
    ResultsDatabaseError
        ``db`` is missing or not a results database.
    CommandError
        ``db`` holds no experiment, or several and none was chosen.
    """
    from pathzoo.harness.store import read_experiments

    if experiment is not None:
        return experiment
    names = [str(n) for n in read_experiments(db)["name"]]
    if len(names) > 1:
        raise CommandError(f"{db} holds experiments {', '.join(sorted(names))}; choose one with --experiment")
    if not names:
        raise CommandError(f"{db}: no experiment stored yet")
    return names[0]


def render_leaderboard(runs: "pd.DataFrame", args: argparse.Namespace, db: str | Path | None = None) -> str:
    """The leaderboard of ``runs`` in ``args.format``; JSON also carries the facts of :func:`experiment_facts`."""
    from pathzoo.analysis.leaderboard import leaderboard

    table = leaderboard(runs, args.metric, reference=args.reference)
    facts = experiment_facts(db, runs) if args.format == "json" and db is not None else None
    return _rendered(table, args.format, facts)


def _rendered(table: "pd.DataFrame", fmt: str, facts: dict[str, Any] | None) -> str:
    from pathzoo.analysis.leaderboard import format_leaderboard

    text = format_leaderboard(table, fmt)
    if facts is None:
        return text
    document = json.loads(text)
    document["experiment"] = facts
    return json.dumps(document, ensure_ascii=False, indent=1) + "\n"


def experiment_facts(db: str | Path, runs: "pd.DataFrame") -> dict[str, Any]:
    """What a result depends on: the experiment's seed, seed indices, budget and hard limit, and the versions.

    ``versions`` gives each planner configuration's version and, for each
    library (pathzoo, Python, numpy, ...), the version the runs used, or the
    sorted list of versions when the runs used several.
    """
    from pathzoo.harness.store import read_versions

    name = str(runs["experiment"].iloc[0]) if len(runs) else ""
    libraries: dict[str, set[str]] = {}
    keys = set(runs["run_key"])
    for key, versions in read_versions(db, name).items():
        if key in keys:
            for lib, version in versions.items():
                if lib not in _MACHINE_FACTS:
                    libraries.setdefault(lib, set()).add(str(version))
    labels = runs["label"].where(runs["label"].astype(str) != "", runs["planner"]) if "label" in runs else runs["planner"]
    planners = dict(sorted(zip(labels.astype(str), runs["planner_version"].astype(str))))
    return _facts(db, name, planners, {lib: sorted(v) for lib, v in libraries.items()},
                  lambda: sorted(set(int(i) for i in runs["seed_index"])))


def stored_experiment_facts(db: str | Path, name: str) -> dict[str, Any]:
    """:func:`experiment_facts` of every stored run of an experiment, aggregated by SQLite (no runs frame)."""
    from pathzoo.harness.store_scan import configurations, library_versions

    configs = configurations(db, name)
    labels = configs["label"].where(configs["label"].astype(str) != "", configs["planner"])
    planners = dict(sorted(zip(labels.astype(str), configs["planner_version"].astype(str))))
    return _facts(db, name, planners, library_versions(db, name, skip=sorted(_MACHINE_FACTS)), list)


def _facts(db: str | Path, name: str, planners: dict[str, str], libraries: dict[str, list[str]],
           seeds: "Callable[[], list[int]]") -> dict[str, Any]:
    """The JSON facts; ``seeds`` gives the seed indices of a stored configuration that lists none."""
    from pathzoo.harness.store import read_experiments

    stored = read_experiments(db)
    row = stored[stored["name"] == name].iloc[0]
    return {
        "name": name,
        "seed": int(row["seed"]),
        "seeds": list(row["config"]["seeds"]) if "seeds" in row["config"] else seeds(),
        "budget": row["budget"],
        "timeout_s": float(row["timeout_s"]),
        "versions": {"planners": planners,
                     **{lib: (v[0] if len(v) == 1 else v) for lib, v in sorted(libraries.items())}},
    }


_MACHINE_FACTS = frozenset({"cpu", "cpu_count", "peak_rss_mb"})
"""Per-run facts of the stored ``versions`` that describe the machine or the run, not a version."""


def isolation_note(runs: "pd.DataFrame") -> str:
    """A warning line when some runs were not isolated (``inline`` executor), else ``""``."""
    if "isolated" not in runs.columns:
        return ""
    return _isolation_text(len(runs), int((~runs["isolated"].astype(bool)).sum()))


def _isolation_text(n_runs: int, n_inline: int) -> str:
    if not n_inline:
        return ""
    return (f"pathzoo: note: {n_inline} of {n_runs} runs ran inline, in the harness's own process (not isolated, "
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
    from pathzoo.analysis.leaderboard import leaderboard_from_db
    from pathzoo.harness.store_scan import isolation_counts

    name = experiment_name(args.db, args.experiment)
    table = leaderboard_from_db(args.db, name, args.metric, reference=args.reference)  # memory bounded
    facts = stored_experiment_facts(args.db, name) if args.format == "json" else None
    sys.stdout.write(_rendered(table, args.format, facts))
    note = _isolation_text(*isolation_counts(args.db, name))
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
