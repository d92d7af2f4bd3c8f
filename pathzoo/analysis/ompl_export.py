"""Export runs as OMPL benchmark log files, for ``ompl_benchmark_statistics.py`` and Planner Arena.

OMPL's ``ompl_benchmark_statistics.py`` (shipped with the ``ompl`` wheel)
turns ``.log`` files into the SQLite database that Planner Arena
(plannerarena.org) plots. One log file holds one OMPL "experiment", i.e. one
planning problem, so pathzoo writes **one file per scenario**; running the
script on all of them gives one database for the whole pathzoo experiment.

Mapping
-------
- OMPL experiment name: ``<experiment>.<scenario>`` (whitespace replaced by
  ``_``: OMPL reads the last token of the line); experiment properties
  ``pathzoo_experiment``, ``scenario`` and ``runs_stored``;
- planner: the configuration label (see :mod:`pathzoo.analysis.frame`), its
  parameters as OMPL "common properties" (``name = value``), plus
  ``pathzoo.planner``, ``pathzoo.version`` and ``pathzoo.params_hash``;
- per-run properties, named as OMPL names them where a counterpart exists:

  ===========================  ==========================================
  OMPL column                  pathzoo value
  ===========================  ==========================================
  ``time REAL``                ``planning_time`` metric (else wall time)
  ``solved BOOLEAN``           run succeeded (solved *and* validated)
  ``approximate solution``     always 0 (pathzoo has no approximate paths)
  ``correct solution``         the harness validated the path
  ``solution length``          ``length`` [m]
  ``solution clearance``       ``clearance_min`` [m]
  ``solution smoothness``      ``smoothness`` (pathzoo's definition, rad/m)
  ``status ENUM``              see :data:`OMPL_STATUS`
  ``iterations``, ...          every other metric under its own id
  ===========================  ==========================================

  plus ``seed``, ``seed_index``, ``cpu_time_s``, ``wall_time_s`` and
  ``pathzoo_status`` (the pathzoo outcome word);
- progress properties ``time REAL``, ``best cost REAL``, ``iterations
  INTEGER``, ``evaluations INTEGER`` from the run's history (the planner's
  own objective, as stored; points at an already-seen time keep the last
  one, since OMPL keys progress by (run, time)).

NaN becomes ``nan``, which the script stores as NULL. OMPL 2.x's own
``PlannerStatus::asString`` prints "Unknown status" for ABORT and
INFEASIBLE; the enum line written here names them "Abort" and "Infeasible".
"""

from __future__ import annotations

import datetime as _dt
import math
import re
from collections import Counter
from pathlib import Path
from typing import Any, Mapping

import numpy as np
import pandas as pd

from pathzoo.analysis.frame import with_config
from pathzoo.core.errors import InvalidParameterError
from pathzoo.harness.provenance import CORES_KEY, CPU_KEY, PEAK_RSS_KEY

__all__ = ["OMPL_STATUS_NAMES", "OMPL_STATUS", "write_ompl_logs", "export_ompl"]

OMPL_STATUS_NAMES: tuple[str, ...] = (
    "Unknown status", "Invalid start", "Invalid goal", "Unrecognized goal type", "Timeout",
    "Approximate solution", "Exact solution", "Crash", "Abort", "Infeasible",
)  # fmt: skip
"""OMPL's ``PlannerStatus`` values in enum order (0..9)."""

OMPL_STATUS: dict[str, int] = {
    "solved": 6,  # EXACT_SOLUTION
    "no_path": 9,  # INFEASIBLE: the planner proved the goal unreachable
    "failed": 4,  # TIMEOUT: the budget ran out without a path
    "timeout": 4,  # TIMEOUT: the harness stopped the run
    "crash": 7,  # CRASH
    "invalid": 0,  # UNKNOWN: a claimed path the harness rejected; OMPL has no such status
}
"""pathzoo run status to OMPL ``PlannerStatus`` value."""

_RENAMED = {
    "planning_time": "time",
    "length": "solution length",
    "clearance_min": "solution clearance",
    "smoothness": "solution smoothness",
}
_INTEGER = {"iterations", "evaluations", "turns", "seed", "seed_index"}
_RESERVED = {"id", "experimentid", "plannerid", "runid"}


def _token(text: str) -> str:
    return re.sub(r"\s+", "_", str(text).strip()) or "_"


def _column(name: str) -> str:
    col = re.sub(r"[^0-9A-Za-z_ ]", "_", name)
    return f"pathzoo_{col}" if col.replace(" ", "_") in _RESERVED else col


def _value(x: Any, kind: str = "") -> str:
    if kind == "INTEGER" and isinstance(x, (float, np.floating)) and math.isfinite(x) and float(x).is_integer():
        return str(int(x))
    if x is None:
        return "nan"
    if isinstance(x, (bool, np.bool_)):
        return "1" if x else "0"
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    if isinstance(x, (float, np.floating)):
        return "nan" if math.isnan(x) or math.isinf(x) else repr(float(x))
    return str(x).replace(";", ",").replace("\n", " ")


def _run_columns(df: pd.DataFrame, base: set[str]) -> list[tuple[str, str, str]]:
    """(log name, type, source column) of every per-run property."""
    cols: list[tuple[str, str, str]] = [
        ("time", "REAL", "planning_time" if "planning_time" in df.columns else "wall_time_s"),
        ("solved", "BOOLEAN", "success"),
        ("approximate solution", "BOOLEAN", "_approx"),
        ("correct solution", "BOOLEAN", "valid"),
        ("status", "ENUM", "_ompl_status"),
    ]
    metrics = [c for c in df.columns if c not in base and c not in ("success", "config", "_approx", "_ompl_status")
               and pd.api.types.is_numeric_dtype(df[c])]
    for m in metrics:
        if m == "planning_time":
            continue
        kind = "INTEGER" if m in _INTEGER else "REAL"
        cols.append((_RENAMED.get(m, _column(m)), kind, m))
    cols += [("seed", "INTEGER", "seed"), ("seed index", "INTEGER", "seed_index"),
             ("cpu time s", "REAL", "cpu_time_s"), ("wall time s", "REAL", "wall_time_s"),
             ("pathzoo status", "VARCHAR(16)", "status")]
    return cols


def _progress(hist: pd.DataFrame | None) -> str:
    if hist is None or hist.empty:
        return ""
    h = hist.drop_duplicates("time_s", keep="last")
    return "".join(
        f"{_value(float(t))},{_value(float(c))},{_value(i, 'INTEGER')},{_value(e, 'INTEGER')},;"
        for t, c, i, e in zip(h["time_s"], h["best_cost"], h["iteration"], h["evaluations"])
    )


def _versions_of(runs: pd.DataFrame) -> list[Mapping[str, str]]:
    if "versions" not in runs.columns:
        return []
    return [v for v in runs["versions"] if isinstance(v, Mapping)]


def _host(runs: pd.DataFrame) -> str:
    """The CPU and core count the runs recorded (the most frequent one), or ``unknown``."""
    hosts = Counter(f"{v[CPU_KEY]} ({v[CORES_KEY]} cores)" for v in _versions_of(runs)
                    if CPU_KEY in v and CORES_KEY in v)
    return _token(hosts.most_common(1)[0][0]) if hosts else "unknown"


def _memory_mb(runs: pd.DataFrame) -> int:
    """The largest peak RSS over the runs, in whole MiB rounded up (0 when no run recorded one)."""
    peaks = []
    for v in _versions_of(runs):
        try:
            peaks.append(float(v[PEAK_RSS_KEY]))
        except (KeyError, TypeError, ValueError):
            continue
    peaks = [p for p in peaks if math.isfinite(p)]
    return math.ceil(max(peaks)) if peaks else 0


def write_ompl_logs(
    runs: pd.DataFrame,
    out_dir: str | Path,
    *,
    history: pd.DataFrame | None = None,
    seed: int = 0,
    time_limit_s: float | None = None,
    setup: Mapping[str, str] | None = None,
) -> list[Path]:
    """Write one OMPL benchmark log per scenario of ``runs``.

    Parameters
    ----------
    runs : DataFrame
        One row per run (``read_runs``).
    out_dir : path
        Directory for the ``.log`` files (created).
    history : DataFrame, optional
        Convergence points (``read_history``), written as OMPL progress data.
    seed : int
        Experiment seed, written as OMPL's random seed.
    time_limit_s : float, optional
        Per-run time limit; by default the largest wall time observed.
    setup : mapping, optional
        Extra ``key: value`` lines for each file's setup block (budget, ...).

    Notes
    -----
    With a ``versions`` column (dicts, as :func:`export_ompl` adds from the
    database), "Running on" names the CPU and core count the runs recorded,
    and "MB per run" (OMPL's memory limit field) is the largest peak RSS of a
    run; without it they are ``unknown`` and 0.

    Returns
    -------
    list of Path
        The files written, sorted by scenario.
    """
    df = with_config(runs)
    if df.empty:
        raise InvalidParameterError("runs is empty: nothing to export")
    base = set(df.columns) & {
        "run_key", "experiment", "planner", "planner_version", "params_hash", "params", "scenario", "seed_index",
        "seed", "status", "valid", "invalid_reason", "message", "wall_time_s", "cpu_time_s",
    }
    df["_approx"] = False
    df["_ompl_status"] = df["status"].astype(str).map(OMPL_STATUS).fillna(0).astype(int)
    columns = _run_columns(df, base)
    hist_by_key = {k: g.sort_values("iteration", kind="stable") for k, g in history.groupby("run_key")} \
        if history is not None and len(history) else {}
    limit = float(df["wall_time_s"].max()) if time_limit_s is None else float(time_limit_s)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    from pathzoo.version import installed_version

    written = []
    for scenario, sdf in df.groupby("scenario", sort=True):
        experiment = str(sdf["experiment"].iloc[0]) if "experiment" in sdf.columns else "pathzoo"
        name = _token(f"{experiment}.{scenario}")
        now = _dt.datetime.now().strftime("%Y-%m-%d %H:%M:%S")
        lines = [
            f"pathzoo version {installed_version()}",
            f"Experiment {name}",
            "3 experiment properties",
            f"pathzoo_experiment VARCHAR(256) = {_value(experiment)}",
            f"scenario VARCHAR(256) = {_value(scenario)}",
            f"runs_stored INTEGER = {len(sdf)}",
            f"Running on {_host(sdf)}",
            f"Starting at {now}",
            "<<<|",
            f"pathzoo experiment {experiment}, scenario {scenario}",
            *(f"{k}: {v}" for k, v in (setup or {}).items()),
            "|>>>",
            f"{int(seed)} is the random seed",
            f"{_value(limit)} seconds per run",
            f"{_memory_mb(sdf)} MB per run",
            f"{int(sdf.groupby('config').size().max())} runs per planner",
            f"{_value(float(np.nansum(sdf['wall_time_s'].to_numpy(dtype=float))))} seconds spent to collect the data",
            "1 enum type",
            "status|" + "|".join(OMPL_STATUS_NAMES),
            f"{sdf['config'].nunique()} planners",
        ]
        for config, g in sdf.groupby("config", sort=True):
            g = g.sort_values("seed_index", kind="stable")
            params = g["params"].iloc[0]
            params = params if isinstance(params, Mapping) else {}
            common = [f"{k} = {_value(v)}" for k, v in sorted(params.items())]
            common += [f"pathzoo.planner = {g['planner'].iloc[0]}",
                       f"pathzoo.version = {_value(g['planner_version'].iloc[0])}",
                       f"pathzoo.params_hash = {g['params_hash'].iloc[0]}"]
            lines += [str(config), f"{len(common)} common properties", *common]
            lines.append(f"{len(columns)} properties for each run")
            lines += [f"{log_name} {kind}" for log_name, kind, _ in columns]
            lines.append(f"{len(g)} runs")
            for rec in g.to_dict("records"):
                lines.append("".join(f"{_value(rec[src], kind)}; " for _, kind, src in columns))
            if hist_by_key:
                lines += ["4 progress properties for each run", "time REAL", "best cost REAL", "iterations INTEGER",
                          "evaluations INTEGER", f"{len(g)} runs"]
                lines += [_progress(hist_by_key.get(k)) for k in g["run_key"]]
            lines.append(".")
        path = out / f"{re.sub(r'[^0-9A-Za-z_.-]', '_', name)}.log"
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
        written.append(path)
    return written


def export_ompl(db: str | Path, out_dir: str | Path, experiment: str | None = None) -> list[Path]:
    """Write OMPL benchmark logs of one stored experiment (see :func:`write_ompl_logs`).

    Then ``python -m ompl.ompl_benchmark_statistics`` (or the script of the
    same name) ``-d arena.db out_dir/*.log`` builds Planner Arena's database.

    Raises
    ------
    InvalidParameterError
        ``db`` holds several experiments and none was chosen, or none at all.
    """
    from pathzoo.analysis.database import load_experiment

    from pathzoo.harness.store import read_versions

    exp = load_experiment(db, experiment)
    limit = exp.budget.get("time_s")
    versions = read_versions(db, exp.name)
    runs = exp.runs.assign(versions=pd.Series([versions.get(k, {}) for k in exp.runs["run_key"]], index=exp.runs.index,
                                              dtype=object))
    return write_ompl_logs(
        runs, out_dir, history=exp.history, seed=exp.seed, time_limit_s=float(limit) if limit is not None else None,
        setup={"budget": exp.budget_text, "timeout_s": str(exp.timeout_s)},
    )
