"""The anytime view: convergence curves on a common grid, and times to reach within ε of the optimum.

History rows (``pathzoo.harness.store.read_history``) hold, for each run,
the planner's best cost after each reported iteration, with the evaluations
used and the harness's clock. A run's best cost is a step function of
iterations, evaluations or time: it holds its last reported value until the
next report (and after the last one).

What ``best_cost`` is
---------------------
Planners report their best cost **in their own objective** (length, energy,
a weighted sum, a penalised fitness...). Only the harness's metrics are
comparable across planners. So:

- convergence curves compare planners only in shape unless all of them
  optimise the same objective; the plot labels the y axis "best cost
  (planner's objective)";
- :func:`time_to_target` uses a run's history only when the run's final
  reported best cost agrees with the metric the harness measured on its
  path (``length`` by default) within ``rtol``, i.e. when the planner's
  objective *is* that metric. Other runs are marked not comparable and left
  out, and the count is reported, never silently hidden.

Runs that did not succeed count as never having a solution (``+inf``)
throughout, whatever they reported: the harness did not accept their answer.
"""

from __future__ import annotations

from typing import Any, Literal, Mapping

import numpy as np
import pandas as pd

from pathzoo.analysis.frame import require_columns, with_config
from pathzoo.core.errors import InvalidParameterError

__all__ = ["ANYTIME_AXES", "AnytimeAxis", "resample_history", "convergence_curves", "best_known", "time_to_target"]

AnytimeAxis = Literal["iteration", "evaluations", "time_s"]
ANYTIME_AXES: tuple[str, ...] = ("iteration", "evaluations", "time_s")
_HISTORY = ("run_key", "iteration", "evaluations", "best_cost", "time_s")


def _check_axis(x: str) -> None:
    if x not in ANYTIME_AXES:
        raise InvalidParameterError(f"x must be one of {', '.join(ANYTIME_AXES)}, got {x!r}")


def resample_history(xs: np.ndarray, costs: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Value of a best-cost step curve at each grid point (``+inf`` before its first report).

    Parameters
    ----------
    xs : ndarray
        Increasing (non-decreasing) report positions.
    costs : ndarray
        Best cost at each report.
    grid : ndarray
        Where to sample.
    """
    xs = np.asarray(xs, dtype=np.float64)
    costs = np.asarray(costs, dtype=np.float64)
    idx = np.searchsorted(xs, np.asarray(grid, dtype=np.float64), side="right") - 1
    out = np.full(len(idx), np.inf)
    ok = idx >= 0
    out[ok] = costs[idx[ok]]
    return out


def _merge(history: pd.DataFrame, runs: pd.DataFrame) -> tuple[pd.DataFrame, pd.DataFrame]:
    require_columns(history, _HISTORY, "history")
    df = with_config(runs)
    hist = history.merge(df[["run_key", "scenario", "config", "success"]], on="run_key", how="inner")
    return df, hist.sort_values(["run_key", "iteration"], kind="stable")


def convergence_curves(
    history: pd.DataFrame,
    runs: pd.DataFrame,
    *,
    x: AnytimeAxis = "iteration",
    n_points: int = 100,
    log: bool = False,
) -> pd.DataFrame:
    """Median and interquartile band of best cost against ``x``, per scenario and configuration.

    Every run of the configuration (successful or not) is sampled on a grid
    shared by all configurations of the scenario, from the smallest to the
    largest reported ``x``. A run has ``+inf`` before its first report and
    throughout if it did not succeed. Quantiles use the inverted-CDF rule
    (each is the value of one of the runs, no interpolation with ``inf``),
    so the median is finite where at least half of the runs hold a solution
    and the upper quartile where at least three quarters do; infinite values
    are returned as NaN (no curve drawn there).

    Parameters
    ----------
    history : DataFrame
        ``run_key, iteration, evaluations, best_cost, time_s`` rows.
    runs : DataFrame
        The runs frame (for scenario, configuration and success).
    x : {"iteration", "evaluations", "time_s"}
        Horizontal axis.
    n_points : int
        Grid size.
    log : bool
        Space the grid logarithmically (from the smallest positive ``x``).

    Returns
    -------
    DataFrame
        ``scenario, config, x, median, q25, q75, n_runs``.
    """
    _check_axis(x)
    if n_points < 2:
        raise InvalidParameterError(f"n_points must be >= 2, got {n_points}")
    df, hist = _merge(history, runs)
    parts = []
    for scenario, sh in hist.groupby("scenario", sort=True):
        lo, hi = float(sh[x].min()), float(sh[x].max())
        if log:
            pos = sh.loc[sh[x] > 0, x]
            lo = float(pos.min()) if len(pos) else 1.0
            grid = np.geomspace(lo, max(hi, lo * 1.0001), n_points)
        else:
            grid = np.linspace(lo, hi if hi > lo else lo + 1.0, n_points)
        curves = {k: g for k, g in sh.groupby("run_key")}
        for config, rdf in df[df["scenario"] == scenario].groupby("config", sort=True):
            mat = np.full((len(rdf), n_points), np.inf)
            for i, (key, ok) in enumerate(zip(rdf["run_key"], rdf["success"])):
                g = curves.get(key)
                if ok and g is not None:
                    mat[i] = resample_history(g[x].to_numpy(), g["best_cost"].to_numpy(), grid)
            q25, med, q75 = np.percentile(mat, [25, 50, 75], axis=0, method="inverted_cdf") \
                if len(mat) else (np.full(n_points, np.inf),) * 3
            parts.append(pd.DataFrame(dict(scenario=scenario, config=config, x=grid, median=med, q25=q25, q75=q75,
                                           n_runs=len(rdf))))
    cols = ["scenario", "config", "x", "median", "q25", "q75", "n_runs"]
    out = pd.concat(parts, ignore_index=True)[cols] if parts else pd.DataFrame(columns=cols)
    out[["median", "q25", "q75"]] = out[["median", "q25", "q75"]].replace([np.inf, -np.inf], np.nan)
    out.attrs["x"] = x
    return out


def best_known(runs: pd.DataFrame, metric: str = "length") -> pd.Series:
    """Best successful value of a (minimised) metric on each scenario: the default optimum."""
    df = with_config(runs, metric)
    return df[df["success"]].groupby("scenario")[metric].min()


def time_to_target(
    history: pd.DataFrame,
    runs: pd.DataFrame,
    *,
    eps: float = 0.05,
    optimum: Mapping[str, float] | pd.Series | None = None,
    metric: str = "length",
    x: AnytimeAxis = "time_s",
    rtol: float = 1e-3,
) -> pd.DataFrame:
    """Per run, when its best cost first came within ``(1 + eps)`` of the optimum.

    Parameters
    ----------
    history, runs : DataFrame
        As for :func:`convergence_curves`.
    eps : float
        Relative tolerance of the target ``(1 + eps) * optimum``.
    optimum : mapping, optional
        Optimal (or reference) value of ``metric`` per scenario, e.g. the
        scenarios' ``reference_length``. Default: :func:`best_known`, the best
        successful value any run reached (so "within ε of the best known").
    metric : str
        The harness metric the planners' objective must equal (minimised).
    x : {"iteration", "evaluations", "time_s"}
        What to measure the time in.
    rtol : float
        A successful run is *comparable* when its last reported best cost is
        within ``rtol`` (relative) of the measured ``metric``.

    Returns
    -------
    DataFrame
        One row per run: ``run_key, scenario, config, success, comparable,
        target, hit`` (the ``x`` at which the target was first reached;
        ``inf`` for comparable runs that never reached it, including
        unsuccessful runs; NaN for runs that are not comparable).
    """
    _check_axis(x)
    if not eps >= 0:
        raise InvalidParameterError(f"eps must be >= 0, got {eps!r}")
    require_columns(runs, [metric])
    df, hist = _merge(history, runs)
    opt = best_known(runs, metric) if optimum is None else pd.Series(optimum, dtype=float)
    curves = {k: g for k, g in hist.groupby("run_key")}
    rows = []
    r: Any  # a DataFrame row: its fields are whatever the columns hold
    for r in df.itertuples(index=False):
        target = float(opt.get(r.scenario, np.nan)) * (1.0 + eps)
        g = curves.get(r.run_key)
        measured = float(getattr(r, metric))
        comparable = not r.success or (
            g is not None and len(g) > 0 and np.isclose(g["best_cost"].iloc[-1], measured, rtol=rtol, atol=0.0)
        )
        hit = np.nan
        if comparable:
            hit = np.inf
            if r.success and np.isfinite(target):
                reached = g[g["best_cost"] <= target]  # type: ignore[index]
                if len(reached):
                    hit = float(reached[x].iloc[0])
        rows.append(dict(run_key=r.run_key, scenario=r.scenario, config=r.config, success=bool(r.success),
                         comparable=bool(comparable), target=target, hit=hit))
    out = pd.DataFrame(rows, columns=["run_key", "scenario", "config", "success", "comparable", "target", "hit"])
    out.attrs.update(x=x, eps=eps, metric=metric)
    return out
