"""Reading the results database: runs, histories, versions, paths, records and experiments.

The file's layout is in :mod:`pathzoo.harness.store_file`; :class:`ResultStore`
(:mod:`pathzoo.harness.store_writer`) writes it. A file written before a
column of :data:`RUN_COLUMNS` existed reads with the column's default
(:data:`RUN_DEFAULTS`). :mod:`pathzoo.harness.store_scan` reads large files
in bounded memory.
"""

from __future__ import annotations

import json
import math
import sqlite3
from pathlib import Path
from typing import TYPE_CHECKING, Any, Collection, Iterable

import numpy as np

from pathzoo.core.results import HistoryPoint, RunRecord
from pathzoo.core.status import RunStatus
from pathzoo.harness.store_file import SCHEMA_VERSION, ResultsDatabaseError, present_columns, reading
from pathzoo.harness.store_writer import ResultStore

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "SCHEMA_VERSION",
    "ResultsDatabaseError",
    "ResultStore",
    "RUN_COLUMNS",
    "RUN_DEFAULTS",
    "column_sql",
    "decode_runs",
    "read_runs",
    "read_history",
    "read_versions",
    "read_path",
    "read_record",
    "read_experiments",
]

RUN_COLUMNS: tuple[str, ...] = (
    "run_key", "experiment", "planner", "planner_version", "params_hash", "params", "scenario", "seed_index",
    "seed", "status", "valid", "invalid_reason", "message", "wall_time_s", "cpu_time_s", "iterations", "evaluations",
    "label",
    "isolated",
    "sandboxed",
    "stopped_by",
)
"""The leading columns of :func:`read_runs`; one column per metric id follows."""
RUN_DEFAULTS: dict[str, str] = {"label": "''", "isolated": "1", "sandboxed": "0", "stopped_by": "''"}
"""SQL values of the columns added after the first files were written, for files that lack them."""

RUN_FLAGS = ("valid", "isolated", "sandboxed")
"""Columns read as bool."""

RUN_NUMBERS = ("wall_time_s", "cpu_time_s", "iterations", "evaluations")
"""Columns read as float (NaN where the file has NULL)."""


def column_sql(columns: Iterable[str], present: Collection[str]) -> list[str]:
    """Each column as a SELECT expression: its name, or its :data:`RUN_DEFAULTS` value (else NULL) where missing."""
    return [f'"{c}"' if c in present else f'{RUN_DEFAULTS.get(c, "NULL")} AS "{c}"' for c in columns]


def decode_runs(frame: "pd.DataFrame", numbers: Iterable[str] = RUN_NUMBERS) -> "pd.DataFrame":
    """``frame`` (rows of runs) with :data:`RUN_FLAGS` as bool and ``numbers`` as float64, in place."""
    import pandas as pd

    for col in RUN_FLAGS:
        frame[col] = frame[col].astype(bool)
    for col in numbers:
        frame[col] = pd.to_numeric(frame[col], errors="coerce").astype(np.float64)
    return frame


def _metrics_of(text: str) -> dict[str, float]:
    """The metrics of :func:`_metrics_json` (and of older files, which wrote NaN), ``null`` read as NaN."""
    return {k: math.nan if v is None else float(v) for k, v in json.loads(text).items()}


_SHARED_COLUMNS = frozenset(RUN_COLUMNS) - {"run_key", "seed_index", "seed", "wall_time_s", "cpu_time_s",
                                            "iterations", "evaluations"}
"""Columns whose values repeat over runs: :func:`_run_columns` keeps one object per distinct value."""


def _run_columns(cursor: sqlite3.Cursor, batch: int = 10_000) -> tuple[dict[str, list[Any]], dict[str, list[float]]]:
    """The :data:`RUN_COLUMNS` and the metrics (first seen first, NaN where a run has none) of ``cursor``'s rows.

    Rows are read ``batch`` at a time and spread into columns, so the rows are
    never all held as tuples beside the columns; the strings and parameter
    dicts that repeat over runs (planner, scenario, status, parameters, ...)
    are one object per distinct value, not one per run. The parameter dicts
    of equal configurations are the same object: do not modify one in place.
    """
    columns: dict[str, list[Any]] = {c: [] for c in RUN_COLUMNS}
    shared: dict[str, dict[Any, Any]] = {c: {} for c in _SHARED_COLUMNS}
    metrics: dict[str, list[float]] = {}
    n = 0
    while rows := cursor.fetchmany(batch):
        *values, texts = zip(*rows)
        del rows
        for name, column in zip(RUN_COLUMNS, values):
            seen = shared.get(name)
            if seen is None:
                columns[name].extend(column)
                continue
            for value in column:
                kept = seen.get(value, seen)
                if kept is seen:
                    kept = seen[value] = json.loads(value) if name == "params" else value
                columns[name].append(kept)
        for text in texts:
            run = _metrics_of(text)
            for mid in run:
                if mid not in metrics:
                    metrics[mid] = [math.nan] * n
            for mid, kept_values in metrics.items():
                kept_values.append(run.get(mid, math.nan))
            n += 1
    return columns, metrics


def _only_keys(where: str, args: tuple[Any, ...], run_keys: "Collection[str] | None") -> tuple[str, tuple[Any, ...]]:
    """``where`` and ``args`` narrowed to ``run_keys`` (sent as one JSON array: no row outside them is read)."""
    if run_keys is None:
        return where, args
    return where + (" AND" if where else " WHERE") + " run_key IN (SELECT value FROM json_each(?))", (
        *args, json.dumps(list(run_keys)))


def read_runs(db: str | Path, experiment: str | None = None, run_keys: "Collection[str] | None" = None
              ) -> "pd.DataFrame":
    """One row per run, in the order they were stored (only ``run_keys``, when given).

    Columns: :data:`RUN_COLUMNS` (``params`` as dicts, ``valid``, ``isolated`` and ``sandboxed`` as bool,
    ``status`` as the :class:`~pathzoo.core.status.RunStatus` value), then one
    float column per metric id. ``iterations`` and ``evaluations`` are NaN
    for crashed and timed-out runs, like the metrics of the same names.

    Raises
    ------
    ResultsDatabaseError
        Missing or foreign file, or unknown experiment.
    """
    import pandas as pd

    with reading(db, experiment) as (conn, where, args):
        base = ", ".join(column_sql(RUN_COLUMNS, present_columns(conn)))
        where, args = _only_keys(where, args, run_keys)
        columns, metrics = _run_columns(conn.execute(f"SELECT {base}, metrics FROM runs{where} ORDER BY id", args))
    frame = decode_runs(pd.DataFrame(columns))
    for mid, values in metrics.items():
        if mid not in frame.columns:  # iterations, evaluations: same numbers as the base columns
            frame[mid] = np.array(values, dtype=np.float64)
    return frame


def read_history(db: str | Path, experiment: str | None = None, run_keys: "Collection[str] | None" = None
                 ) -> "pd.DataFrame":
    """Convergence points: experiment, run_key, iteration, evaluations, best_cost, time_s (of ``run_keys``, when given).

    Rows are in the order they were stored.
    """
    import pandas as pd

    with reading(db, experiment) as (conn, where, args):
        where, args = _only_keys(where, args, run_keys)
        rows = conn.execute(f"SELECT * FROM history{where} ORDER BY rowid", args).fetchall()
    frame = pd.DataFrame(rows, columns=["experiment", "run_key", "iteration", "evaluations", "best_cost", "time_s"])
    frame["best_cost"] = pd.to_numeric(frame["best_cost"], errors="coerce").astype(float)
    return frame


def read_versions(db: str | Path, experiment: str | None = None) -> dict[str, dict[str, str]]:
    """``{run_key: versions}``: each run's library versions, CPU, core count and peak RSS (see RunRecord)."""
    rows = _select(db, experiment, "SELECT run_key, versions FROM runs{where} ORDER BY id")
    return {key: json.loads(text) for key, text in rows}


def _select(db: str | Path, experiment: str | None, sql: str) -> list[Any]:
    """The rows of ``sql``, whose ``{where}`` becomes the filter on ``experiment`` (checked to exist)."""
    with reading(db, experiment) as (conn, where, args):
        return conn.execute(sql.format(where=where), args).fetchall()


def _run_row(db: str | Path, experiment: str, run_key: str, columns: str) -> tuple[Any, ...]:
    with reading(db, experiment) as (conn, _, _):
        row = conn.execute(
            f"SELECT {columns} FROM runs WHERE experiment = ? AND run_key = ?", (experiment, run_key)
        ).fetchone()
        if row is None:
            raise ResultsDatabaseError(f"{Path(db)}: experiment '{experiment}' has no run '{run_key}'")
        if columns == "*":
            names = [d[0] for d in conn.execute("SELECT * FROM runs LIMIT 0").description]
            hist = conn.execute(
                "SELECT iteration, evaluations, best_cost, time_s FROM history "
                "WHERE experiment = ? AND run_key = ? ORDER BY rowid", (experiment, run_key)
            ).fetchall()
            return (dict(zip(names, row)), hist)
        return tuple(row)


def _arrays(blob: bytes | None, shape: str | None, times: bytes | None) -> tuple[np.ndarray | None, np.ndarray | None]:
    path = None if blob is None else np.frombuffer(blob, dtype=np.float64).reshape(json.loads(shape or "[-1]")).copy()
    t = None if times is None else np.frombuffer(times, dtype=np.float64).copy()
    return path, t


def read_path(db: str | Path, experiment: str, run_key: str) -> tuple[np.ndarray | None, np.ndarray | None]:
    """The stored ``(path, times)`` of one run (``None`` where the run has none)."""
    blob, shape, times = _run_row(db, experiment, run_key, "path, path_shape, times")
    return _arrays(blob, shape, times)


def read_record(db: str | Path, experiment: str, run_key: str) -> RunRecord:
    """The full stored :class:`RunRecord` of one run, history included."""
    row, hist = _run_row(db, experiment, run_key, "*")
    path, times = _arrays(row["path"], row["path_shape"], row["times"])
    nan = math.nan
    return RunRecord(
        run_key=row["run_key"],
        experiment=row["experiment"],
        planner_id=row["planner"],
        planner_version=row["planner_version"],
        params=json.loads(row["params"]),
        params_hash=row["params_hash"],
        scenario_id=row["scenario"],
        seed_index=row["seed_index"],
        seed=row["seed"],
        status=RunStatus(row["status"]),
        valid=bool(row["valid"]),
        invalid_reason=row["invalid_reason"],
        message=row["message"],
        wall_time_s=nan if row["wall_time_s"] is None else row["wall_time_s"],
        cpu_time_s=nan if row["cpu_time_s"] is None else row["cpu_time_s"],
        iterations=row["iterations"] or 0,
        evaluations=row["evaluations"] or 0,
        path=path,
        times=times,
        history=tuple(HistoryPoint(i, e, nan if c is None else c, t) for i, e, c, t in hist),
        metrics=_metrics_of(row["metrics"]),
        versions=json.loads(row["versions"]),
        started_at=row["started_at"],
        isolated=bool(row.get("isolated", 1)),
        sandboxed=bool(row.get("sandboxed", 0)),
        stopped_by=row.get("stopped_by", ""),
    )


def read_experiments(db: str | Path) -> "pd.DataFrame":
    """Stored experiments: name, seed, budget (dict), timeout_s, created, n_runs, config (dict)."""
    import pandas as pd

    with reading(db, None) as (conn, _, _):
        rows = conn.execute(
            "SELECT e.name, e.seed, e.budget, e.timeout_s, e.created, "
            "(SELECT COUNT(*) FROM runs r WHERE r.experiment = e.name), e.config FROM experiments e ORDER BY e.created"
        ).fetchall()
    frame = pd.DataFrame(rows, columns=["name", "seed", "budget", "timeout_s", "created", "n_runs", "config"])
    frame["budget"] = [json.loads(b) for b in frame["budget"]]
    frame["config"] = [json.loads(c) for c in frame["config"]]
    return frame
