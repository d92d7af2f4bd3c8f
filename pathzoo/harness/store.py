"""The SQLite result database: one transaction per run, resumable, never destructive.

Layout (schema version 1; ``sqlite3 results.sqlite .schema`` shows it):

- ``pathzoo_schema(version)``: one row; files with another version are refused
  with a clear error rather than read wrongly or modified;
- ``experiments``: name (primary key), seed, budget (JSON), timeout_s, the
  whole configuration (JSON) and the creation time;
- ``runs``: one row per run, ``UNIQUE(experiment, run_key)``: every
  :class:`~pathzoo.core.results.RunRecord` field, parameters and versions as
  JSON, path and times as float64 bytes (C order) with the path's shape as
  JSON, the metrics as JSON *and* as one ``REAL`` column per metric, named
  ``"metric:<id>"`` (added with ``ALTER TABLE`` when a new metric appears,
  by whichever harness sees it first: concurrent harnesses on one file are
  fine), ``label``, the configuration's name in tables and plots (runs of
  databases written before it existed read with an empty label, so analysis
  falls back to ``id`` / ``id@hash``), and ``isolated`` (0 for runs of the
  ``inline`` executor, whose planner shared the harness's process),
  ``sandboxed`` (1 when the planner ran in the OS sandbox,
  :mod:`pathzoo.harness.sandbox`) and ``stopped_by``, the limit that ended
  the run (``docs/timing.md``); all are added to older files when they are
  opened for writing (``sandboxed`` as 0: no run was sandboxed then;
  ``stopped_by`` empty: unknown), and read as their defaults from files not
  opened for writing since;
- ``history``: the convergence points of every run (experiment, run_key,
  iteration, evaluations, best_cost, time_s).

The file runs in WAL mode, so readers (analysis, ``pathzoo show``) never
block the harness. A run and its history are written in one transaction
with ``INSERT OR IGNORE``: a run is either fully stored or not at all, and is
never stored twice, even if two harnesses race on the same experiment.
Opening an existing file never drops or rewrites anything.
"""

from __future__ import annotations

import json
import math
import os
import re
import sqlite3
import time
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import TYPE_CHECKING, Any, Collection, Iterator, Mapping, Sequence

import numpy as np

from pathzoo.core.errors import PathzooError
from pathzoo.core.results import HistoryPoint, RunRecord
from pathzoo.core.status import RunStatus
from pathzoo.harness.outcome import utc_now
from pathzoo.metrics.outcome import RETURNED

if TYPE_CHECKING:
    import pandas as pd

    from pathzoo.harness.experiment import Experiment

__all__ = [
    "SCHEMA_VERSION",
    "ResultsDatabaseError",
    "ResultStore",
    "RUN_COLUMNS",
    "read_runs",
    "read_history",
    "read_versions",
    "read_path",
    "read_record",
    "read_experiments",
]

SCHEMA_VERSION = 1

RUN_COLUMNS: tuple[str, ...] = (
    "run_key", "experiment", "planner", "planner_version", "params_hash", "params", "scenario", "seed_index",
    "seed", "status", "valid", "invalid_reason", "message", "wall_time_s", "cpu_time_s", "iterations", "evaluations",
    "label",
    "isolated",
    "sandboxed",
    "stopped_by",
)
"""The leading columns of :func:`read_runs`; one column per metric id follows."""

_METRIC_ID = re.compile(r"^[A-Za-z0-9_.\-]+$")

_SCHEMA = """
CREATE TABLE IF NOT EXISTS pathzoo_schema (version INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS experiments (
    name TEXT PRIMARY KEY,
    seed INTEGER NOT NULL,
    budget TEXT NOT NULL,
    timeout_s REAL NOT NULL,
    config TEXT NOT NULL,
    created TEXT NOT NULL
);
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY,
    experiment TEXT NOT NULL REFERENCES experiments(name),
    run_key TEXT NOT NULL,
    planner TEXT NOT NULL,
    planner_version TEXT NOT NULL,
    params_hash TEXT NOT NULL,
    params TEXT NOT NULL,
    scenario TEXT NOT NULL,
    seed_index INTEGER NOT NULL,
    seed INTEGER NOT NULL,
    status TEXT NOT NULL,
    valid INTEGER NOT NULL,
    invalid_reason TEXT NOT NULL,
    message TEXT NOT NULL,
    wall_time_s REAL,
    cpu_time_s REAL,
    iterations INTEGER,
    evaluations INTEGER,
    path BLOB,
    path_shape TEXT,
    times BLOB,
    versions TEXT NOT NULL,
    started_at TEXT NOT NULL,
    finished_at TEXT NOT NULL,
    metrics TEXT NOT NULL,
    label TEXT NOT NULL DEFAULT '',
    isolated INTEGER NOT NULL DEFAULT 1,
    sandboxed INTEGER NOT NULL DEFAULT 0,
    stopped_by TEXT NOT NULL DEFAULT '',
    UNIQUE (experiment, run_key)
);
CREATE TABLE IF NOT EXISTS history (
    experiment TEXT NOT NULL,
    run_key TEXT NOT NULL,
    iteration INTEGER NOT NULL,
    evaluations INTEGER NOT NULL,
    best_cost REAL,
    time_s REAL NOT NULL
);
CREATE INDEX IF NOT EXISTS history_run ON history (experiment, run_key);
"""
"""The tables of a new database; every statement is a no-op on a database that has them (see :func:`_connect`)."""


class ResultsDatabaseError(PathzooError, RuntimeError):
    """A result database is missing, not a pathzoo database, of another schema version, conflicts, or its disk is full."""


def _metric_column(metric_id: str) -> str:
    return f'"metric:{metric_id}"'


def _connect(path: Path, *, create: bool) -> sqlite3.Connection:
    if not create and not path.is_file():
        raise ResultsDatabaseError(f"{path}: no such results database")
    if create and not path.parent.is_dir():
        raise ResultsDatabaseError(f"{path}: directory {path.parent} does not exist")
    try:
        conn = sqlite3.connect(str(path), timeout=60.0, isolation_level=None)
        tables = {r[0] for r in conn.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
    except sqlite3.DatabaseError as exc:
        raise ResultsDatabaseError(f"{path}: not a results database ({exc})") from None
    if not tables:
        if not create:
            conn.close()
            raise ResultsDatabaseError(f"{path}: empty database, no pathzoo results in it")
        # Two harnesses may start on one new file together: both can find it empty here. The write lock
        # (BEGIN IMMEDIATE) puts their schema scripts one after the other, and the second one, finding
        # the tables and the version row there, changes nothing.
        conn.executescript(
            "BEGIN IMMEDIATE;" + _SCHEMA
            + f"INSERT INTO pathzoo_schema SELECT {SCHEMA_VERSION} WHERE NOT EXISTS (SELECT 1 FROM pathzoo_schema);"
            + "COMMIT;"
        )
        _use_wal(conn)
    elif "pathzoo_schema" not in tables:
        conn.close()
        raise ResultsDatabaseError(f"{path}: not a pathzoo results database (it has no pathzoo_schema table)")
    else:
        row = conn.execute("SELECT version FROM pathzoo_schema").fetchone()
        version = None if row is None else row[0]
        if version != SCHEMA_VERSION:
            conn.close()
            raise ResultsDatabaseError(
                f"{path}: written with result schema version {version}; this pathzoo reads version {SCHEMA_VERSION} "
                "(use the matching pathzoo version, or another database file)"
            )
    conn.execute("PRAGMA synchronous = NORMAL")
    return conn


def _use_wal(conn: sqlite3.Connection, timeout_s: float = 60.0) -> None:
    """Put the file in WAL mode (kept in the file), retrying while another connection holds it.

    SQLite answers "database is locked" at once, without its busy timeout,
    when the journal mode changes while another harness has the new file
    open, so the change is retried for up to ``timeout_s``.
    """
    deadline = time.monotonic() + timeout_s
    while conn.execute("PRAGMA journal_mode").fetchone()[0] != "wal":
        try:
            conn.execute("PRAGMA journal_mode = WAL")
        except sqlite3.OperationalError as exc:
            if "locked" not in str(exc) or time.monotonic() > deadline:
                raise
            time.sleep(0.01)


def _disk_full(exc: sqlite3.Error, path: Path) -> bool:
    """Whether SQLite's error means that the disk holding ``path`` is full.

    SQLite says "database or disk is full" when a write finds no space, but
    "disk I/O error" when the write-ahead log cannot grow; the second is read
    as a full disk when the file system has no block left for the user.
    """
    text = str(exc).lower()
    if "disk is full" in text:
        return True
    if "disk i/o error" not in text:
        return False
    try:
        stat = os.statvfs(path.parent)
    except OSError:
        return False
    return stat.f_bavail * stat.f_frsize < _FULL_BYTES


_FULL_BYTES = 1 << 20
"""Free space below which a "disk I/O error" is reported as a full disk."""


@contextmanager
def _transaction(conn: sqlite3.Connection, path: Path) -> Iterator[sqlite3.Connection]:
    """One write transaction; a full disk raises :class:`ResultsDatabaseError` saying so (the transaction is undone,
    nothing stored before is lost)."""
    try:
        conn.execute("BEGIN IMMEDIATE")
        try:
            yield conn
        except BaseException:
            with suppress(sqlite3.Error):
                conn.execute("ROLLBACK")
            raise
        conn.execute("COMMIT")
    except sqlite3.OperationalError as exc:
        if not _disk_full(exc, path):
            raise
        with suppress(sqlite3.Error):
            conn.execute("ROLLBACK")
        raise ResultsDatabaseError(
            f"{path}: the disk is full (SQLite: {exc}); the runs stored so far are kept: free some space and run the "
            "same command again to resume"
        ) from None


def _blob(arr: np.ndarray | None) -> bytes | None:
    return None if arr is None else np.ascontiguousarray(arr, dtype=np.float64).tobytes()


def _metrics_json(metrics: Mapping[str, float]) -> str:
    """The metrics as a JSON object, NaN (not computed, not solved) as ``null``: standard JSON that SQLite reads."""
    return json.dumps({k: None if math.isnan(float(v)) else float(v) for k, v in metrics.items()})


def _metrics_of(text: str) -> dict[str, float]:
    """The metrics of :func:`_metrics_json` (and of older files, which wrote NaN), ``null`` read as NaN."""
    return {k: math.nan if v is None else float(v) for k, v in json.loads(text).items()}


def _real(value: float) -> float | None:
    return None if value is None or math.isnan(value) else float(value)


class ResultStore:
    """Writes runs of experiments to one SQLite file (created when missing).

    Use as a context manager; see the module docstring for the layout.

    Raises
    ------
    ResultsDatabaseError
        The file is not a pathzoo database or has another schema version.
    """

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.conn = _connect(self.path, create=True)
        self._run_columns = self._columns()
        if "label" not in self._run_columns:  # a file written before labels: add the column, keep every row
            self._add_column("label TEXT NOT NULL DEFAULT ''")
        if "isolated" not in self._run_columns:  # a file written before the column existed
            self._add_column("isolated INTEGER NOT NULL DEFAULT 1")
        if "sandboxed" not in self._run_columns:  # a file written before the sandbox existed
            self._add_column("sandboxed INTEGER NOT NULL DEFAULT 0")
        if "stopped_by" not in self._run_columns:  # a file written before the column existed: unknown ('')
            self._add_column("stopped_by TEXT NOT NULL DEFAULT ''")

    def _columns(self) -> set[str]:
        return {str(r[1]) for r in self.conn.execute("PRAGMA table_info(runs)")}

    def _add_column(self, definition: str) -> None:
        """``ALTER TABLE runs ADD COLUMN``; another harness adding the same column first is fine."""
        try:
            self.conn.execute(f"ALTER TABLE runs ADD COLUMN {definition}")
        except sqlite3.OperationalError as exc:
            if "duplicate column name" not in str(exc):
                raise
        self._run_columns = self._columns()

    def __enter__(self) -> "ResultStore":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def close(self) -> None:
        """Close the connection."""
        self.conn.close()

    def add_experiment(self, experiment: "Experiment") -> None:
        """Record an experiment, or check that a stored one with its name is compatible.

        The seed, budget and hard limit determine every run's result, so a
        stored experiment with the same name must have the same ones; planners,
        scenarios and seeds may grow (their runs get new keys).

        Raises
        ------
        ResultsDatabaseError
            The stored experiment differs in seed, budget or timeout.
        """
        budget = json.dumps(experiment.budget.to_dict(), sort_keys=True)
        row = self.conn.execute(
            "SELECT seed, budget, timeout_s FROM experiments WHERE name = ?", (experiment.name,)
        ).fetchone()
        if row is None:
            with _transaction(self.conn, self.path):
                self.conn.execute(
                    "INSERT OR IGNORE INTO experiments VALUES (?, ?, ?, ?, ?, ?)",
                    (experiment.name, experiment.seed, budget, experiment.timeout_s,
                     json.dumps(experiment.config(), sort_keys=True), utc_now()),
                )
            return
        stored = {"seed": row[0], "budget": json.loads(row[1]), "timeout_s": row[2]}
        given = {"seed": experiment.seed, "budget": experiment.budget.to_dict(), "timeout_s": experiment.timeout_s}
        for name, value in given.items():
            if stored[name] != value:
                raise ResultsDatabaseError(
                    f"{self.path}: experiment '{experiment.name}' is stored with {name} = {stored[name]!r}, "
                    f"not {value!r}; use another experiment name (or database) for different settings"
                )

    def finished_keys(self, experiment: str, exclude_statuses: tuple[str, ...] = ()) -> set[str]:
        """Run keys already stored for an experiment, except those stored with one of ``exclude_statuses``."""
        rows = self.conn.execute("SELECT run_key, status FROM runs WHERE experiment = ?", (experiment,))
        return {key for key, status in rows if status not in exclude_statuses}

    def count_runs(self, experiment: str) -> int:
        """Number of stored runs of an experiment."""
        return int(self.conn.execute("SELECT COUNT(*) FROM runs WHERE experiment = ?", (experiment,)).fetchone()[0])

    def _ensure_metric_columns(self, ids: list[str]) -> None:
        for mid in ids:
            col = f"metric:{mid}"
            if col not in self._run_columns and _METRIC_ID.match(mid):
                self._add_column(f"{_metric_column(mid)} REAL")

    def insert(self, record: RunRecord, replace_statuses: tuple[str, ...] = (), label: str = "") -> bool:
        """Store one run and its history in one transaction; False if the key was already stored.

        A stored run of the same key whose status is in ``replace_statuses``
        (``pathzoo run --retry``) is deleted in the same transaction, so an
        interrupted retry never loses the old row. ``label`` is the
        configuration's name (:attr:`PlannerSpec.name`).
        """
        return self.insert_batch([record], replace_statuses, [label]) == 1

    def insert_batch(self, records: Sequence[RunRecord], replace_statuses: tuple[str, ...] = (),
                     labels: Sequence[str] | None = None) -> int:
        """Store several runs and their histories in one transaction; the number newly stored.

        Each run is stored as :meth:`insert` stores it (keys already stored
        are skipped); one transaction for all of them is what makes building
        a large database (``benchmarks/scale.py``) fast. ``labels`` gives each
        record's configuration name (empty by default).
        """
        names = [""] * len(records) if labels is None else list(labels)
        if len(names) != len(records):
            raise ValueError(f"insert_batch: {len(records)} records but {len(names)} labels")
        self._ensure_metric_columns(list(dict.fromkeys(m for r in records for m in r.metrics if _METRIC_ID.match(m))))
        stored = 0
        with _transaction(self.conn, self.path):
            for record, label in zip(records, names):
                stored += self._insert_one(record, replace_statuses, label)
        return stored

    def _insert_one(self, record: RunRecord, replace_statuses: tuple[str, ...], label: str) -> bool:
        """The statements of one run, inside the caller's transaction (metric columns already there)."""
        metric_ids = [m for m in record.metrics if _METRIC_ID.match(m)]
        returned = record.status in RETURNED
        values: dict[str, Any] = {
            "experiment": record.experiment,
            "run_key": record.run_key,
            "planner": record.planner_id,
            "planner_version": record.planner_version,
            "params_hash": record.params_hash,
            "params": json.dumps(dict(record.params), sort_keys=True, default=str),
            "scenario": record.scenario_id,
            "seed_index": record.seed_index,
            "seed": record.seed,
            "status": record.status.value,
            "valid": int(record.valid),
            "invalid_reason": record.invalid_reason,
            "message": record.message,
            "wall_time_s": _real(record.wall_time_s),
            "cpu_time_s": _real(record.cpu_time_s),
            "iterations": record.iterations if returned else None,
            "evaluations": record.evaluations if returned else None,
            "path": _blob(record.path),
            "path_shape": None if record.path is None else json.dumps(list(np.shape(record.path))),
            "times": _blob(record.times),
            "versions": json.dumps(dict(record.versions), sort_keys=True),
            "started_at": record.started_at,
            "finished_at": utc_now(),
            "metrics": _metrics_json(record.metrics),
            "label": label,
            "isolated": int(bool(record.isolated)),
            "sandboxed": int(bool(record.sandboxed)),
            "stopped_by": record.stopped_by,
        }
        for mid in metric_ids:
            values[f"metric:{mid}"] = _real(record.metrics[mid])
        cols = ", ".join(f'"{c}"' for c in values)
        marks = ", ".join("?" for _ in values)
        if replace_statuses:
            marks_ = ", ".join("?" for _ in replace_statuses)
            old = self.conn.execute(
                f"DELETE FROM runs WHERE experiment = ? AND run_key = ? AND status IN ({marks_})",
                (record.experiment, record.run_key, *replace_statuses),
            )
            if old.rowcount:
                self.conn.execute("DELETE FROM history WHERE experiment = ? AND run_key = ?",
                                  (record.experiment, record.run_key))
        cur = self.conn.execute(f"INSERT OR IGNORE INTO runs ({cols}) VALUES ({marks})", tuple(values.values()))
        if cur.rowcount == 0:
            return False
        self.conn.executemany(
            "INSERT INTO history VALUES (?, ?, ?, ?, ?, ?)",
            [(record.experiment, record.run_key, p.iteration, p.evaluations, _real(p.best_cost), p.time_s)
             for p in record.history],
        )
        return True


# ------------------------------------------------------------------ readers
def _experiment_filter(conn: sqlite3.Connection, path: Path, experiment: str | None) -> tuple[str, tuple[Any, ...]]:
    if experiment is None:
        return "", ()
    known = [r[0] for r in conn.execute("SELECT name FROM experiments ORDER BY name")]
    if experiment not in known:
        raise ResultsDatabaseError(
            f"{path}: no experiment named '{experiment}' (stored: {', '.join(known) or 'none'})"
        )
    return " WHERE experiment = ?", (experiment,)


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

    path = Path(db)
    conn = _connect(path, create=False)
    try:
        where, args = _experiment_filter(conn, path, experiment)
        present = {str(r[1]) for r in conn.execute("PRAGMA table_info(runs)")}
        defaults = {"label": "''", "isolated": "1", "sandboxed": "0", "stopped_by": "''"}
        base = ", ".join(f'"{c}"' if c in present else f'{defaults.get(c, "NULL")} AS "{c}"' for c in RUN_COLUMNS)
        if run_keys is not None:  # the keys go to SQLite as one JSON array: no row outside them is read
            where += (" AND" if where else " WHERE") + " run_key IN (SELECT value FROM json_each(?))"
            args = (*args, json.dumps(list(run_keys)))
        rows = conn.execute(f"SELECT {base}, metrics FROM runs{where} ORDER BY id", args).fetchall()
    finally:
        conn.close()
    frame = pd.DataFrame([r[: len(RUN_COLUMNS)] for r in rows], columns=list(RUN_COLUMNS))
    frame["params"] = [json.loads(p) for p in frame["params"]]
    frame["valid"] = frame["valid"].astype(bool)
    frame["isolated"] = frame["isolated"].astype(bool)
    frame["sandboxed"] = frame["sandboxed"].astype(bool)
    for col in ("wall_time_s", "cpu_time_s", "iterations", "evaluations"):
        frame[col] = pd.to_numeric(frame[col], errors="coerce").astype(float)
    metrics = [_metrics_of(r[-1]) for r in rows]
    ids: dict[str, None] = {}
    for m in metrics:
        ids.update(dict.fromkeys(m))
    for mid in ids:
        if mid in frame.columns:  # iterations, evaluations: same numbers as the base columns
            continue
        frame[mid] = np.array([m.get(mid, math.nan) for m in metrics], dtype=np.float64)
    return frame


def read_history(db: str | Path, experiment: str | None = None) -> "pd.DataFrame":
    """Convergence points: experiment, run_key, iteration, evaluations, best_cost, time_s."""
    import pandas as pd

    rows = _select(db, experiment, "SELECT * FROM history{where} ORDER BY rowid")
    frame = pd.DataFrame(rows, columns=["experiment", "run_key", "iteration", "evaluations", "best_cost", "time_s"])
    frame["best_cost"] = pd.to_numeric(frame["best_cost"], errors="coerce").astype(float)
    return frame


def read_versions(db: str | Path, experiment: str | None = None) -> dict[str, dict[str, str]]:
    """``{run_key: versions}``: each run's library versions, CPU, core count and peak RSS (see RunRecord)."""
    rows = _select(db, experiment, "SELECT run_key, versions FROM runs{where} ORDER BY id")
    return {key: json.loads(text) for key, text in rows}


def _select(db: str | Path, experiment: str | None, sql: str) -> list[Any]:
    """The rows of ``sql``, whose ``{where}`` becomes the filter on ``experiment`` (checked to exist)."""
    path = Path(db)
    conn = _connect(path, create=False)
    try:
        where, args = _experiment_filter(conn, path, experiment)
        return conn.execute(sql.format(where=where), args).fetchall()
    finally:
        conn.close()


def _run_row(db: str | Path, experiment: str, run_key: str, columns: str) -> tuple[Any, ...]:
    path = Path(db)
    conn = _connect(path, create=False)
    try:
        _experiment_filter(conn, path, experiment)
        row = conn.execute(
            f"SELECT {columns} FROM runs WHERE experiment = ? AND run_key = ?", (experiment, run_key)
        ).fetchone()
        if row is None:
            raise ResultsDatabaseError(f"{path}: experiment '{experiment}' has no run '{run_key}'")
        if columns == "*":
            names = [d[0] for d in conn.execute("SELECT * FROM runs LIMIT 0").description]
            hist = conn.execute(
                "SELECT iteration, evaluations, best_cost, time_s FROM history "
                "WHERE experiment = ? AND run_key = ? ORDER BY rowid", (experiment, run_key)
            ).fetchall()
            return (dict(zip(names, row)), hist)
        return tuple(row)
    finally:
        conn.close()


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

    path = Path(db)
    conn = _connect(path, create=False)
    try:
        rows = conn.execute(
            "SELECT e.name, e.seed, e.budget, e.timeout_s, e.created, "
            "(SELECT COUNT(*) FROM runs r WHERE r.experiment = e.name), e.config FROM experiments e ORDER BY e.created"
        ).fetchall()
    finally:
        conn.close()
    frame = pd.DataFrame(rows, columns=["name", "seed", "budget", "timeout_s", "created", "n_runs", "config"])
    frame["budget"] = [json.loads(b) for b in frame["budget"]]
    frame["config"] = [json.loads(c) for c in frame["config"]]
    return frame
