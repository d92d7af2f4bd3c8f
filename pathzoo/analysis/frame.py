"""The runs DataFrame as analysis sees it: column checks, success, configurations and metric facts.

Every analysis function takes the frame returned by
``pathzoo.harness.store.read_runs`` (one row per run). This module holds the
few rules they share:

- a run **succeeded** when ``status == "solved"`` and the harness found the
  path ``valid`` (the same rule as :attr:`pathzoo.core.RunRecord.success`);
- a **configuration** is a planner id plus a parameter hash; it is named by
  its stored ``label`` (the experiment's ``label``, else
  ``id(param=value, ...)`` for the parameters off their defaults, see
  :attr:`pathzoo.harness.specs.PlannerSpec.name`). Runs without a label
  (databases written before labels existed) are named by the planner id
  alone unless the frame holds several parameter sets of the same planner,
  then ``"<planner>@<first 7 hash characters>"``; a name that two
  configurations share gets the ``@hash`` suffix too;
- a metric's unit and direction come from the metric registry
  (``pathzoo list metrics``, looked up by :func:`metric_info` of
  :mod:`pathzoo.plugins.metric_lookup`); the harness's own numeric columns
  (``wall_time_s``, ``cpu_time_s``, ``iterations``, ``evaluations``) are known
  there too, all to be minimised;
- for rank-based comparisons a failed run is **worse than every successful
  run** and tied with the other failures: :func:`loss_values` turns a metric
  into a "loss" (smaller is better, the sign flipped for ``max`` metrics) in
  which every failed run is ``+inf``.
"""

from __future__ import annotations

from typing import Iterable

import numpy as np
import pandas as pd

from pathzoo.plugins.metric_lookup import DERIVED_COLUMNS, RUN_COLUMNS, Direction, MetricInfo, metric_info
from pathzoo.core.errors import InvalidParameterError

__all__ = [
    "MetricInfo",
    "RUN_COLUMNS",
    "DERIVED_COLUMNS",
    "metric_info",
    "require_columns",
    "success_mask",
    "config_labels",
    "loss_values",
    "MEASUREMENT_DIGITS",
    "round_measurements",
    "with_config",
]

_REQUIRED = ("planner", "params_hash", "scenario", "seed_index", "status", "valid")


def require_columns(runs: pd.DataFrame, columns: Iterable[str], name: str = "runs") -> None:
    """Raise :class:`InvalidParameterError` naming the first missing column."""
    if not isinstance(runs, pd.DataFrame):
        raise InvalidParameterError(f"{name} must be a pandas DataFrame, got {type(runs).__name__}")
    for col in columns:
        if col not in runs.columns:
            raise InvalidParameterError(f"{name}: missing column '{col}'")


def success_mask(runs: pd.DataFrame) -> pd.Series:
    """Boolean Series: the harness validated a solved path."""
    return (runs["status"].astype(str) == "solved") & runs["valid"].fillna(False).astype(bool)


def config_labels(runs: pd.DataFrame) -> pd.Series:
    """One label per run naming its configuration (planner, parameter hash); rules in the module docstring."""
    planner = runs["planner"].astype(str)
    phash = runs["params_hash"].astype(str)
    n_sets = phash.groupby(planner).transform("nunique")
    fallback = planner.where(n_sets <= 1, planner + "@" + phash.str[:7])
    if "label" not in runs.columns:
        return fallback
    stored = runs["label"].fillna("").astype(str)
    names = stored.where(stored != "", fallback)
    config = planner + "|" + phash
    shared = config.groupby(names).transform("nunique") > 1
    return names.where(~shared, names + "@" + phash.str[:7])


MEASUREMENT_DIGITS = 12
"""Significant digits a metric value is compared to in every table and test.

Two paths of equal length can differ in the last bits of their summed
lengths (summation order); without rounding, a rank test would call one of
them better every time.
"""


def round_measurements(values: pd.Series) -> pd.Series:
    """Metric values rounded to :data:`MEASUREMENT_DIGITS` significant digits (NaN and inf kept)."""
    v = values.astype(float).to_numpy()
    finite = np.isfinite(v) & (v != 0)
    out = v.copy()
    scale = 10.0 ** (MEASUREMENT_DIGITS - 1 - np.floor(np.log10(np.abs(v[finite]))))
    out[finite] = np.round(v[finite] * scale) / scale
    return pd.Series(out, index=values.index, name=values.name)


def with_config(runs: pd.DataFrame, metric: str | None = None) -> pd.DataFrame:
    """A copy with ``config`` and ``success`` columns added and ``status`` as plain strings (columns checked first).

    With ``metric``, that column is rounded by :func:`round_measurements`.
    """
    require_columns(runs, (*_REQUIRED, metric) if metric else _REQUIRED)
    out = runs.copy()
    if metric:
        out[metric] = round_measurements(out[metric])
    out["status"] = [str(getattr(s, "value", s)) for s in out["status"]]  # RunStatus members or their values
    out["config"] = config_labels(out)
    out["success"] = success_mask(out)
    return out


def loss_values(values: pd.Series | np.ndarray, success: pd.Series | np.ndarray, direction: Direction) -> np.ndarray:
    """Metric values as losses (smaller is better) with every failed run at ``+inf``.

    A successful run whose metric is NaN stays NaN (no value to rank) and is
    dropped by the callers.
    """
    v = np.asarray(values, dtype=np.float64)
    ok = np.asarray(success, dtype=bool)
    loss = v if direction == "min" else -v
    return np.where(ok, loss, np.inf)
