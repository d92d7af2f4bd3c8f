"""Reading a large result database in bounded memory: runs a scenario chunk at a time, facts aggregated in SQL.

:func:`~pathzoo.harness.store.read_runs` builds one frame of every run,
parameters and all metrics; at a million runs that is gigabytes. The
leaderboard needs much less: per run the configuration, the scenario, the
outcome and one metric, and only the runs of one scenario at a time (a
configuration is ranked within each scenario). :func:`scenario_chunks`
streams exactly that, sorted by scenario, in frames of whole scenarios of
about ``chunk_runs`` runs; SQLite's sorter spills to a temporary file, so
the peak memory is set by the chunk, not by the database. The facts that
describe a whole experiment (its configurations, library versions, how
many runs were isolated) are aggregated by SQLite itself.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterator, Sequence

from pathzoo.harness.store import RUN_NUMBERS, column_sql, decode_runs
from pathzoo.harness.store_file import present_columns, reading

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["CHUNK_COLUMNS", "scenario_chunks", "configurations", "first_runs", "scenario_ids", "has_metric",
           "metrics_with_values", "has_history", "library_versions", "isolation_counts"]

CHUNK_COLUMNS: tuple[str, ...] = (
    "run_key", "experiment", "planner", "planner_version", "params_hash", "scenario", "seed_index", "seed",
    "status", "valid", "wall_time_s", "cpu_time_s", "iterations", "evaluations", "label", "isolated", "sandboxed",
    "stopped_by",
)
"""The columns of :data:`~pathzoo.harness.store.RUN_COLUMNS` a chunk holds (not the parameters or messages)."""

def _metric_expression(metric: str, present: set[str]) -> str:
    """SQL for one metric's value: its own REAL column, else the value in the run's metrics JSON."""
    if f"metric:{metric}" in present:
        return f'"metric:{metric}"'
    return "json_extract(metrics, '$.' || json_quote(?))"


def scenario_chunks(db: str | Path, experiment: str, metrics: Sequence[str], *,
                    chunk_runs: int = 20_000, columns: Sequence[str] = ()) -> "Iterator[pd.DataFrame]":
    """The runs of one experiment as frames of whole scenarios, in scenario order.

    Parameters
    ----------
    db : path
        Results database.
    experiment : str
        Experiment name (checked to exist).
    metrics : sequence of str
        Metric ids to include as float columns (NaN where a run has none).
    chunk_runs : int
        A frame is handed out once it holds at least this many runs and the
        next run is of another scenario; a scenario is never split.
    columns : sequence of str
        Further columns of :data:`~pathzoo.harness.store.RUN_COLUMNS` (as
        stored: ``params`` as JSON text), e.g. ``invalid_reason``, ``message``.

    Yields
    ------
    DataFrame
        :data:`CHUNK_COLUMNS` (``valid``, ``isolated``, ``sandboxed`` as bool),
        ``columns``, and one column per metric, rows ordered by scenario, then
        as stored.

    Raises
    ------
    ResultsDatabaseError
        Missing or foreign file, or unknown experiment.
    """
    import pandas as pd

    with reading(db, experiment) as (conn, where, args):
        present = present_columns(conn)
        extra = [c for c in dict.fromkeys(columns) if c not in CHUNK_COLUMNS]
        wanted = [m for m in dict.fromkeys(metrics) if m not in CHUNK_COLUMNS and m not in extra]
        exprs: list[str] = []
        metric_args: list[str] = []
        for m in wanted:
            expr = _metric_expression(m, present)
            exprs.append(f"{expr} AS \"m:{len(exprs)}\"")
            if "?" in expr:
                metric_args.append(m)
        base = column_sql((*CHUNK_COLUMNS, *extra), present)
        cursor = conn.execute(f"SELECT {', '.join(base + exprs)} FROM runs{where} ORDER BY scenario, id",
                              (*metric_args, *args))

        def frame(rows: list[tuple[Any, ...]]) -> pd.DataFrame:
            return decode_runs(pd.DataFrame(rows, columns=[*CHUNK_COLUMNS, *extra, *wanted]), (*RUN_NUMBERS, *wanted))

        scenario_at = CHUNK_COLUMNS.index("scenario")
        buffer: list[tuple[Any, ...]] = []
        while batch := cursor.fetchmany(4096):
            for row in batch:
                if len(buffer) >= chunk_runs and row[scenario_at] != buffer[-1][scenario_at]:
                    yield frame(buffer)
                    buffer = []
                buffer.append(row)
        if buffer:
            yield frame(buffer)


def configurations(db: str | Path, experiment: str) -> "pd.DataFrame":
    """``planner, params_hash, label, planner_version``: each distinct combination the experiment's runs hold."""
    import pandas as pd

    with reading(db, experiment) as (conn, where, args):
        label = column_sql(["label"], present_columns(conn))[0]
        rows = conn.execute(f"SELECT DISTINCT planner, params_hash, {label}, planner_version FROM runs{where} "
                            "ORDER BY planner, params_hash, label, planner_version", args).fetchall()
    return pd.DataFrame(rows, columns=["planner", "params_hash", "label", "planner_version"])


def first_runs(db: str | Path, experiment: str) -> "pd.DataFrame":
    """``planner, params_hash, label, planner_version, params``: the first stored run of each configuration.

    A configuration is a distinct ``(planner, params_hash, label)``; ``params``
    is the stored JSON text. Rows are in the order the runs were stored.
    """
    import pandas as pd

    with reading(db, experiment) as (conn, where, args):
        label = column_sql(["label"], present_columns(conn))[0]
        rows = conn.execute(
            f"SELECT planner, params_hash, {label}, planner_version, params FROM runs WHERE id IN "
            f"(SELECT MIN(id) FROM runs{where} GROUP BY planner, params_hash, {label}) ORDER BY id", args).fetchall()
    return pd.DataFrame(rows, columns=["planner", "params_hash", "label", "planner_version", "params"])


def scenario_ids(db: str | Path, experiment: str) -> list[str]:
    """The distinct scenarios of one experiment's runs, sorted."""
    with reading(db, experiment) as (conn, where, args):
        rows = conn.execute(f"SELECT DISTINCT scenario FROM runs{where} ORDER BY scenario", args).fetchall()
    return [str(s) for (s,) in rows]


def has_metric(db: str | Path, experiment: str, metric: str) -> bool:
    """Whether a run of the experiment stored ``metric`` (its value may be NaN); the scan ends at the first."""
    with reading(db, experiment) as (conn, where, args):
        cond = (" AND " if where else " WHERE ") + "json_type(metrics, '$.' || json_quote(?)) IS NOT NULL"
        row = conn.execute(f"SELECT 1 FROM runs{where}{cond} LIMIT 1", (*args, metric)).fetchone()
    return row is not None


def metrics_with_values(db: str | Path, experiment: str, metrics: Sequence[str]) -> set[str]:
    """The ids of ``metrics`` of which some run of the experiment has a value (not NaN), in one scan."""
    wanted = list(dict.fromkeys(metrics))
    if not wanted:
        return set()
    with reading(db, experiment) as (conn, where, args):
        present = present_columns(conn)
        exprs = [_metric_expression(m, present) for m in wanted]
        metric_args = [m for m, e in zip(wanted, exprs) if "?" in e]
        found = conn.execute(f"SELECT {', '.join(f'MAX({e} IS NOT NULL)' for e in exprs)} FROM runs{where}",
                             (*metric_args, *args)).fetchone()
    return {m for m, hit in zip(wanted, found) if hit}


def has_history(db: str | Path, experiment: str) -> bool:
    """Whether a run of the experiment stored convergence points."""
    with reading(db, experiment) as (conn, where, args):
        return conn.execute(f"SELECT 1 FROM history{where} LIMIT 1", args).fetchone() is not None


def library_versions(db: str | Path, experiment: str, skip: Sequence[str] = ()) -> dict[str, list[str]]:
    """Each key of the runs' stored ``versions`` (but ``skip``) with the sorted distinct values the runs hold."""
    with reading(db, experiment) as (conn, where, args):
        rows = conn.execute(
            f"SELECT DISTINCT j.key, CAST(j.value AS TEXT) FROM (SELECT versions FROM runs{where}) r, "
            "json_each(r.versions) j WHERE j.key NOT IN (SELECT value FROM json_each(?))",
            (*args, json.dumps(list(skip))),
        ).fetchall()
    out: dict[str, set[str]] = {}
    for key, value in rows:
        out.setdefault(str(key), set()).add(str(value))
    return {key: sorted(values) for key, values in sorted(out.items())}


def isolation_counts(db: str | Path, experiment: str) -> tuple[int, int]:
    """``(runs, runs not isolated)`` of one experiment (runs of the ``inline`` executor are not isolated)."""
    with reading(db, experiment) as (conn, where, args):
        inline = "SUM(isolated = 0)" if "isolated" in present_columns(conn) else "0"
        total, not_isolated = conn.execute(f"SELECT COUNT(*), {inline} FROM runs{where}", args).fetchone()
    return int(total), int(not_isolated or 0)
