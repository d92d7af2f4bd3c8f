"""Descriptive statistics per scenario and configuration: median, IQR, SD and success rate."""

from __future__ import annotations

from typing import Sequence

import numpy as np
import pandas as pd

from pathzoo.analysis.frame import Direction, loss_values, metric_info, with_config

__all__ = ["summarize", "summarize_metrics", "median_runs", "relative_medians", "relative_to_best",
           "SUMMARY_COLUMNS"]

SUMMARY_COLUMNS: tuple[str, ...] = (
    "scenario",
    "config",
    "planner",
    "params_hash",
    "n_runs",
    "n_success",
    "success_rate",
    "median",
    "q25",
    "q75",
    "iqr",
    "sd",
    "mean",
    "min",
    "max",
    "penalized_median",
)


def _describe(group: pd.DataFrame, metric: str, direction: Direction) -> pd.Series:
    ok = group["success"].to_numpy()
    vals = group[metric].to_numpy(dtype=np.float64)
    good = vals[ok & np.isfinite(vals)]
    loss = loss_values(vals, ok, direction)
    loss = loss[~np.isnan(loss)]
    n = len(good)
    q25, q50, q75 = np.percentile(good, [25, 50, 75]) if n else (np.nan,) * 3
    pen = float(np.median(loss)) if len(loss) else np.nan
    return pd.Series(
        {
            "planner": group["planner"].iloc[0],
            "params_hash": group["params_hash"].iloc[0],
            "n_runs": len(group),
            "n_success": int(ok.sum()),
            "success_rate": float(ok.mean()) if len(group) else np.nan,
            "median": q50,
            "q25": q25,
            "q75": q75,
            "iqr": q75 - q25,
            # shifted by one sample, so identical values give exactly 0 (the mean of
            # equal floats can differ from them in the last bit)
            "sd": float(np.std(good - good[0], ddof=1)) if n > 1 else np.nan,
            "mean": float(good.mean()) if n else np.nan,
            "min": float(good.min()) if n else np.nan,
            "max": float(good.max()) if n else np.nan,
            "penalized_median": pen if direction == "min" else -pen,
        }
    )


def summarize(runs: pd.DataFrame, metric: str = "length", *, direction: Direction | None = None) -> pd.DataFrame:
    """Median, quartiles, IQR, SD, mean, range and success rate of one metric.

    Statistics of the metric use successful runs only (status ``solved`` and
    a valid path); ``success_rate`` is reported beside them.
    ``penalized_median`` is the median over *all* runs with every failed run
    counted as the worst possible value (``+inf`` for ``min`` metrics,
    ``-inf`` for ``max`` metrics); it is finite only when more than half of the
    runs succeeded, and it is what the leaderboard ranks by.

    Parameters
    ----------
    runs : DataFrame
        One row per run (``pathzoo.harness.store.read_runs``).
    metric : str
        Metric column.
    direction : {"min", "max"}, optional
        Override the registered direction.

    Returns
    -------
    DataFrame
        One row per (scenario, configuration) with :data:`SUMMARY_COLUMNS`;
        ``attrs["metric"]`` holds the :class:`~pathzoo.analysis.frame.MetricInfo`.
    """
    info = metric_info(metric, direction)
    df = with_config(runs, metric)
    rows = [
        _describe(g, metric, info.direction).rename((sc, cfg))
        for (sc, cfg), g in df.groupby(["scenario", "config"], sort=True)
    ]
    out = pd.DataFrame(rows)
    if out.empty:
        out = pd.DataFrame(columns=list(SUMMARY_COLUMNS))
    else:
        out.index = pd.MultiIndex.from_tuples(out.index, names=["scenario", "config"])
        out = out.reset_index()[list(SUMMARY_COLUMNS)]
        out[["n_runs", "n_success"]] = out[["n_runs", "n_success"]].astype(int)
    out.attrs["metric"] = info
    return out


def summarize_metrics(runs: pd.DataFrame, metrics: Sequence[str] | None = None) -> pd.DataFrame:
    """:func:`summarize` for several metrics, stacked with a leading ``metric`` column.

    Parameters
    ----------
    runs : DataFrame
        One row per run.
    metrics : sequence of str, optional
        Metric ids; by default every registered metric that is a column of ``runs``.
    """
    if metrics is None:
        from pathzoo.plugins.manager import get_registry

        metrics = [m for m in sorted(get_registry().metrics) if m in runs.columns]
    parts = [summarize(runs, m).assign(metric=m) for m in metrics]
    if not parts:
        return pd.DataFrame(columns=["metric", *SUMMARY_COLUMNS])
    out = pd.concat(parts, ignore_index=True)
    return out[["metric", *SUMMARY_COLUMNS]]


def median_runs(runs: pd.DataFrame, metric: str = "length") -> pd.DataFrame:
    """The most typical successful run of each configuration on each scenario.

    For each (scenario, configuration) with a successful run, the run whose
    ``metric`` is closest to the median of the successful runs (the lowest
    seed index on ties). Used to pick which path to draw.

    Returns
    -------
    DataFrame
        ``scenario, config, run_key, seed_index`` and ``metric``.
    """
    df = with_config(runs, metric)
    good = df[df["success"] & np.isfinite(df[metric].astype(float))].copy()
    good["_gap"] = (good[metric] - good.groupby(["scenario", "config"])[metric].transform("median")).abs()
    good = good.sort_values(["scenario", "config", "_gap", "seed_index"], kind="stable")
    best = good.groupby(["scenario", "config"], sort=True).head(1)
    return best[["scenario", "config", "run_key", "seed_index", metric]].reset_index(drop=True)


def relative_medians(runs: pd.DataFrame, metric: str = "length") -> pd.DataFrame:
    """Each configuration's median on each scenario over the best configuration's median there.

    The median is over successful runs (:func:`summarize`); the best is the
    lowest median of a ``min`` metric, the highest of a ``max`` one, so the
    best configuration of a scenario has ratio 1 and scales of different
    maps do not mix. The ratio is NaN where the configuration has no
    successful run or the best median is not positive.

    Returns
    -------
    DataFrame
        ``scenario, config, median, ratio``; ``attrs["metric"]`` as in :func:`summarize`.
    """
    return relative_to_best(summarize(runs, metric))


def relative_to_best(table: pd.DataFrame) -> pd.DataFrame:
    """:func:`relative_medians` of the runs whose :func:`summarize` table is ``table``."""
    info = table.attrs["metric"]
    median = table["median"].astype(float)
    best = median.groupby(table["scenario"]).transform("min" if info.direction == "min" else "max")
    out = pd.DataFrame({"scenario": table["scenario"], "config": table["config"], "median": median,
                        "ratio": median / best.where(best > 0)})
    out.attrs["metric"] = info
    return out
