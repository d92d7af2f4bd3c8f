"""Join result databases of one experiment: shards run on other machines, or resumed runs (``pathzoo merge``).

Every database must hold the *same* experiment under each name it shares
with the others: the same seed, budget, hard limit, planner configurations
(id, version, parameters, label) and scenarios (id, kind and
:meth:`~pathzoo.harness.specs.ScenarioSpec.content_digest`: a file
scenario is compared by its content, not by where it lay on each machine).
Only the seed indices may differ (a resume with more seeds). Anything else
is refused before the output is touched.

Runs are copied with ``INSERT OR IGNORE`` on the ``(experiment, run_key)``
key, so a run in two inputs (or already in the output) is stored once, from
the first database that has it, and its convergence history is copied with
it and only then. The output may exist: it is checked like an input and
added to, never rewritten. Run keys and seeds depend on the experiment alone
(:mod:`pathzoo.harness.shard`), so the shards of one experiment merge into
exactly what one machine running it all would have stored.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

from pathzoo.harness.store import read_experiments
from pathzoo.harness.store_file import ResultsDatabaseError
from pathzoo.harness.store_writer import ResultStore

__all__ = ["MergedExperiment", "merge_databases"]


@dataclass(frozen=True)
class MergedExperiment:
    """What :func:`merge_databases` did for one experiment."""

    name: str
    added: int
    """Runs copied into the output."""
    duplicates: int
    """Runs of the inputs not copied, their key being stored already (earlier input, or the output)."""
    total: int
    """Runs of the experiment in the output afterwards."""


def _identity(row: Any) -> dict[str, Any]:
    """The parts of a stored experiment that must agree for its runs to merge."""
    config = row["config"]
    scenarios = {s["id"]: {"kind": s.get("kind"), "source": s.get("source"),
                           # databases written before digests were stored: compared by where the scenario was
                           "digest": s.get("digest") or s.get("location")}
                 for s in config.get("scenarios", [])}
    planners = sorted(json.dumps(p, sort_keys=True) for p in config.get("planners", []))
    return {"seed": row["seed"], "budget": row["budget"], "timeout_s": row["timeout_s"],
            "planner configurations": planners, "scenarios": scenarios}


def _unversioned(planners: list[str]) -> list[str]:
    """Planner configurations without their versions (for a database written before versions were stored)."""
    return sorted(json.dumps({k: v for k, v in json.loads(p).items() if k != "version"}, sort_keys=True)
                  for p in planners)


def _same(field: str, first: Any, second: Any) -> bool:
    if field == "planner configurations" and not all("version" in json.loads(p) for p in [*first, *second]):
        return _unversioned(first) == _unversioned(second)
    return bool(first == second)


def _difference(field: str, first: Any, second: Any) -> str:
    """A short account of how two values of ``field`` differ."""
    if field == "planner configurations":
        only = sorted(set(first) ^ set(second))
        return f"planner configurations differ ({only[0]}{' ...' if len(only) > 1 else ''})"
    if field == "scenarios":
        ids = sorted(set(first) ^ set(second))
        if ids:
            return f"scenario '{ids[0]}' is in one only"
        key = next(k for k in sorted(first) if first[k] != second[k])
        what = next(f for f in first[key] if first[key][f] != second[key][f])
        return f"scenario '{key}' differs in {what}"
    return f"{field} {first!r} != {second!r}"


def merge_databases(inputs: Sequence[str | Path], output: str | Path) -> list[MergedExperiment]:
    """Copy every run of ``inputs`` into ``output`` (created when missing); see the module docstring.

    Parameters
    ----------
    inputs : sequence of path
        Result databases written by ``pathzoo run`` (shards, resumes, other merges).
    output : path
        The database to write; it may already hold runs of the same experiments.

    Returns
    -------
    list of MergedExperiment
        One per experiment name, in the order first seen.

    Raises
    ------
    ResultsDatabaseError
        An input is missing, not a results database, or the output itself; or
        two databases hold different experiments under one name (one line
        naming both files and the first difference). Nothing is written then.
    """
    out = Path(output)
    paths = [Path(p) for p in inputs]
    if not paths:
        raise ResultsDatabaseError("nothing to merge: give at least one input database")
    for path in paths:
        if out.exists() and path.exists() and os.path.samefile(path, out):
            raise ResultsDatabaseError(f"{path}: the output is also an input; write the merge to a new file")
    sources = [(path, read_experiments(path)) for path in paths]
    known: dict[str, tuple[Path, dict[str, Any], dict[str, Any]]] = {}  # name: (file, identity, config)
    if out.exists():
        for _, row in read_experiments(out).iterrows():
            known[row["name"]] = (out, _identity(row), row["config"])
    seeds: dict[str, set[int]] = {}
    for path, frame in sources:
        for _, row in frame.iterrows():
            name = row["name"]
            identity = _identity(row)
            if name in known:
                where, first, _ = known[name]
                for field, value in first.items():
                    if not _same(field, value, identity[field]):
                        raise ResultsDatabaseError(
                            f"{path}: experiment '{name}' is not the one in {where}: "
                            f"{_difference(field, value, identity[field])}; refusing to merge")
            else:
                known[name] = (path, identity, row["config"])
            seeds.setdefault(name, set()).update(int(s) for s in row["config"].get("seeds", []))
    merged: dict[str, list[int]] = {}
    with ResultStore(out) as store:
        conn = store.conn
        for path, frame in sources:
            conn.execute("ATTACH DATABASE ? AS src", (str(path),))
            try:
                columns = {str(r[1]) for r in conn.execute("PRAGMA src.table_info(runs)")}
                store._ensure_metric_columns([c[len("metric:"):] for c in sorted(columns) if c.startswith("metric:")])
                shared = ", ".join(f'"{c}"' for c in sorted(columns & store._run_columns - {"id"}))
                for name in frame["name"]:
                    _, _, config = known[name]
                    config = {**config, "seeds": sorted(seeds[name])}
                    counts = merged.setdefault(name, [0, 0])
                    conn.execute("BEGIN IMMEDIATE")
                    try:
                        conn.execute(
                            "INSERT OR IGNORE INTO experiments SELECT name, seed, budget, timeout_s, ?, created "
                            "FROM src.experiments WHERE name = ?", (json.dumps(config, sort_keys=True), name))
                        conn.execute("CREATE TEMP TABLE new_keys AS SELECT run_key FROM src.runs "
                                     "WHERE experiment = ? AND run_key NOT IN "
                                     "(SELECT run_key FROM main.runs WHERE experiment = ?)", (name, name))
                        added = conn.execute(
                            f"INSERT OR IGNORE INTO main.runs ({shared}) SELECT {shared} FROM src.runs "
                            "WHERE experiment = ? AND run_key IN (SELECT run_key FROM new_keys) ORDER BY id",
                            (name,)).rowcount
                        conn.execute("INSERT INTO main.history SELECT * FROM src.history WHERE experiment = ? "
                                     "AND run_key IN (SELECT run_key FROM new_keys) ORDER BY rowid", (name,))
                        total = conn.execute("SELECT COUNT(*) FROM src.runs WHERE experiment = ?",
                                             (name,)).fetchone()[0]
                        conn.execute("DROP TABLE temp.new_keys")
                    except BaseException:
                        conn.execute("ROLLBACK")
                        raise
                    conn.execute("COMMIT")
                    counts[0] += added
                    counts[1] += int(total) - added
            finally:
                conn.execute("DETACH DATABASE src")
        return [MergedExperiment(name, added, dups, store.count_runs(name))
                for name, (added, dups) in merged.items()]
