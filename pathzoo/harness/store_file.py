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

import os
import re
import sqlite3
import time
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import Any, Iterator

from pathzoo.core.errors import PathzooError

__all__ = [
    "SCHEMA_VERSION",
    "METRIC_ID",
    "ResultsDatabaseError",
    "metric_column",
    "connect",
    "transaction",
    "experiment_filter",
    "reading",
    "present_columns",
]

SCHEMA_VERSION = 1

METRIC_ID = re.compile(r"^[A-Za-z0-9_.\-]+$")
"""Metric ids that get a ``REAL`` column of their own (``"metric:<id>"``); every id is in the metrics JSON."""
"""Metric ids that get a ``REAL`` column of their own (``"metric:<id>"``); every id is in the metrics JSON."""

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
"""The tables of a new database; every statement is a no-op on a database that has them (see :func:`connect`)."""


class ResultsDatabaseError(PathzooError, RuntimeError):
    """A result database is missing, not a pathzoo database, of another schema version, conflicts, or its disk is full."""


def metric_column(metric_id: str) -> str:
    """The quoted name of a metric's column."""
    return f'"metric:{metric_id}"'


def connect(path: Path, *, create: bool) -> sqlite3.Connection:
    """A connection to the results database ``path`` (made, with the schema, when ``create`` and it is new).

    Raises
    ------
    ResultsDatabaseError
        Missing (without ``create``), not a pathzoo database, or of another schema version.
    """
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
def transaction(conn: sqlite3.Connection, path: Path) -> Iterator[sqlite3.Connection]:
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


@contextmanager
def reading(db: str | Path, experiment: str | None) -> Iterator[tuple[sqlite3.Connection, str, tuple[Any, ...]]]:
    """An existing database opened for reading: ``(connection, where, args)``, closed on leaving.

    ``where`` and ``args`` filter the ``runs`` or ``history`` table on
    ``experiment`` (checked to exist; no filter for ``None``).

    Raises
    ------
    ResultsDatabaseError
        Missing or foreign file, or unknown experiment.
    """
    path = Path(db)
    conn = connect(path, create=False)
    try:
        where, args = experiment_filter(conn, path, experiment)
        yield conn, where, args
    finally:
        conn.close()


def present_columns(conn: sqlite3.Connection) -> set[str]:
    """The columns of the file's ``runs`` table (an older file lacks some: see :mod:`pathzoo.harness.store`)."""
    return {str(r[1]) for r in conn.execute("PRAGMA table_info(runs)")}


def experiment_filter(conn: sqlite3.Connection, path: Path, experiment: str | None) -> tuple[str, tuple[Any, ...]]:
    """``(" WHERE experiment = ?", (experiment,))``, or none for ``None``; an unknown experiment is an error."""
    if experiment is None:
        return "", ()
    known = [r[0] for r in conn.execute("SELECT name FROM experiments ORDER BY name")]
    if experiment not in known:
        raise ResultsDatabaseError(
            f"{path}: no experiment named '{experiment}' (stored: {', '.join(known) or 'none'})"
        )
    return " WHERE experiment = ?", (experiment,)
