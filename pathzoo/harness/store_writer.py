"""Writing runs to the results database: :class:`ResultStore`, one transaction per run or batch.

The layout of the file is in :mod:`pathzoo.harness.store_file`. A run and
its history are written in one transaction with ``INSERT OR IGNORE``: a run
is either fully stored or not at all, and is never stored twice, even if two
harnesses race on the same experiment. Opening an existing file never drops
or rewrites anything; columns a file lacks are added to it.
"""

from __future__ import annotations

import json
import math
import sqlite3
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping, Sequence

import numpy as np

from pathzoo.core.results import RunRecord
from pathzoo.harness.outcome import utc_now
from pathzoo.harness.store_file import METRIC_ID, ResultsDatabaseError, connect, metric_column, transaction
from pathzoo.metrics.outcome import RETURNED

if TYPE_CHECKING:
    from pathzoo.harness.experiment import Experiment

__all__ = ["ResultStore"]


def _blob(arr: np.ndarray | None) -> bytes | None:
    return None if arr is None else np.ascontiguousarray(arr, dtype=np.float64).tobytes()


def _metrics_json(metrics: Mapping[str, float]) -> str:
    """The metrics as a JSON object, NaN (not computed, not solved) as ``null``: standard JSON that SQLite reads."""
    return json.dumps({k: None if math.isnan(float(v)) else float(v) for k, v in metrics.items()})


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
        self.conn = connect(self.path, create=True)
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
            with transaction(self.conn, self.path):
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
            if col not in self._run_columns and METRIC_ID.match(mid):
                self._add_column(f"{metric_column(mid)} REAL")

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
        self._ensure_metric_columns(list(dict.fromkeys(m for r in records for m in r.metrics if METRIC_ID.match(m))))
        stored = 0
        with transaction(self.conn, self.path):
            for record, label in zip(records, names):
                stored += self._insert_one(record, replace_statuses, label)
        return stored

    def _insert_one(self, record: RunRecord, replace_statuses: tuple[str, ...], label: str) -> bool:
        """The statements of one run, inside the caller's transaction (metric columns already there)."""
        metric_ids = [m for m in record.metrics if METRIC_ID.match(m)]
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
