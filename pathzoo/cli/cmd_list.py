"""``pathzoo list planners|scenarios|metrics``: what the installed plugins provide, and where it comes from.

It reads the plugins' declarations only: no planner or metric class is
imported, and neither are numba, pandas or scipy, so it answers at once.
"""

from __future__ import annotations

import argparse
import fnmatch
import sys
from typing import Any, Callable

from pathzoo.plugins.entries import HYBRID_MARK, PluginEntry
from pathzoo.text_table import aligned_text

__all__ = ["add_parser", "list_table", "matches"]

KINDS = ("planners", "scenarios", "metrics")


def _planner_detail(entry: PluginEntry) -> str:
    return ",".join(sorted(entry.declared("kinds", ())))


def _scenario_detail(entry: PluginEntry) -> str:
    return str(entry.declared("kind", ""))


def _metric_detail(entry: PluginEntry) -> str:
    return f"{entry.declared('unit', '')}, {entry.declared('direction', '')}"


_DETAIL: dict[str, tuple[str, Callable[[PluginEntry], str]]] = {
    "planners": ("kinds", _planner_detail),
    "scenarios": ("kind", _scenario_detail),
    "metrics": ("unit, better", _metric_detail),
}


def _summary(entry: PluginEntry, kind: str) -> str:
    unavailable = entry.unavailable if kind == "planners" else ""
    summary = f"{HYBRID_MARK} {entry.summary}" if kind == "planners" and entry.declared("hybrid", False) else entry.summary
    return f"[unavailable, {unavailable}] {summary}" if unavailable else summary


def matches(entry_id: str, patterns: list[str]) -> bool:
    """Whether ``entry_id`` matches any of the shell-style ``patterns`` (case-sensitive; all match when empty)."""
    return not patterns or any(fnmatch.fnmatchcase(entry_id, p) for p in patterns)


def list_table(entries: list[PluginEntry], kind: str) -> str:
    """An aligned text table of registry entries: id, detail, distribution, version and summary."""
    detail_name, detail = _DETAIL[kind]
    columns = ["id", detail_name, "distribution", "version", "summary"]
    rows = [[e.id, detail(e), e.distribution or "-", e.version or "-", _summary(e, kind)] for e in entries]
    return aligned_text(columns, rows, left=columns)


def _run(args: argparse.Namespace) -> int:
    from pathzoo.plugins.manager import discover

    # a fresh discovery (not the cached registry) so import failures are reported here, once, at the end;
    # only the entry-point groups of this kind are imported
    registry = discover(kinds=(args.kind,))
    table = registry.table(args.kind)
    entries = [table[k] for k in sorted(table) if matches(k, args.patterns)]
    if entries:
        sys.stdout.write(list_table(entries, args.kind))
    else:
        print(f"no {args.kind} match {' '.join(args.patterns)}" if args.patterns else f"no {args.kind} registered")
    for failure in registry.failures:
        print(f"skipped: {failure.plugin}: {failure.error}", file=sys.stderr)
    return 0


def add_parser(subparsers: Any) -> None:
    """Register the ``list`` subcommand."""
    parser = subparsers.add_parser(
        "list",
        help="list registered planners, scenarios or metrics",
        description="List what the installed plugins register: id, details, providing distribution "
        "and its version, and a one-line summary. Plugins that failed to load are reported on stderr "
        "as 'skipped: <plugin>: <error>'.",
    )
    parser.add_argument("kind", choices=KINDS, help="what to list")
    parser.add_argument("patterns", nargs="*", metavar="PATTERN",
                        help="only ids matching any of these shell-style patterns, e.g. 'fgdaco.*' (quote them)")
    parser.set_defaults(handler=_run)
