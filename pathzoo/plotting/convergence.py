"""Convergence curves: median best cost with its interquartile band against iterations, evaluations or time."""

from __future__ import annotations

from typing import Any, Mapping

import pandas as pd
from matplotlib.axes import Axes
from matplotlib.ticker import NullFormatter

from pathzoo.analysis.anytime import AnytimeAxis, convergence_curves
from pathzoo.core.errors import InvalidParameterError
from pathzoo.plotting.figure import new_axes, palette_for

__all__ = ["plot_convergence", "AXIS_LABELS"]

AXIS_LABELS = {"iteration": "iteration", "evaluations": "evaluations", "time_s": "time [s]"}


def plot_convergence(
    history: pd.DataFrame,
    runs: pd.DataFrame,
    scenario: str | None = None,
    *,
    x: AnytimeAxis = "iteration",
    ax: Axes | None = None,
    log: bool | None = False,
    n_points: int = 100,
    palette: Mapping[str, Any] | None = None,
) -> Axes:
    """Median best cost (line) and interquartile band (shaded) of each configuration on one scenario.

    The curves come from :func:`pathzoo.analysis.anytime.convergence_curves`:
    each run's step curve sampled on a common grid, unsuccessful runs and
    times before a run's first solution counting as "no solution" (so a
    curve starts only once at least half of the runs hold a solution). The y
    axis is each planner's own objective; see that module for why curves of
    planners with different objectives compare only in shape.

    Parameters
    ----------
    history, runs : DataFrame
        History rows and the runs frame.
    scenario : str, optional
        Required when the runs cover several scenarios.
    x : {"iteration", "evaluations", "time_s"}
        Horizontal axis.
    ax : Axes, optional
        Where to draw.
    log : bool or None
        Logarithmic x axis (and grid); ignored when no run holds a solution.
        ``None`` chooses it when the positive ``x`` values span more than a
        factor of 20.
    n_points : int
        Grid size.
    palette : mapping, optional
        Colour per configuration (default: :func:`~pathzoo.plotting.figure.planner_colors` of those shown).
    """
    scenarios = sorted(runs["scenario"].unique())
    if scenario is None:
        if len(scenarios) != 1:
            raise InvalidParameterError(f"scenario is required when runs cover {len(scenarios)} scenarios")
        scenario = scenarios[0]
    elif scenario not in scenarios:
        raise InvalidParameterError(f"scenario '{scenario}' has no runs")
    sub = runs[runs["scenario"] == scenario]
    if log is None:
        xs = history.loc[history["run_key"].isin(sub["run_key"]), x]
        xs = xs[xs > 0]
        log = bool(len(xs)) and float(xs.max()) > 20.0 * float(xs.min())
    curves = convergence_curves(history[history["run_key"].isin(sub["run_key"])], sub, x=x, n_points=n_points,
                                log=log)
    ax = new_axes(ax, (6.0, 4.0))
    configs = sorted(curves["config"].unique())
    colors = palette_for(configs, palette)
    for cfg, c in curves.groupby("config", sort=True):
        ax.plot(c["x"], c["median"], color=colors[str(cfg)], lw=1.8, label=f"{cfg} (n={c['n_runs'].iloc[0]})")
        ax.fill_between(c["x"], c["q25"], c["q75"], color=colors[str(cfg)], alpha=0.2, lw=0)
    if curves["median"].notna().any() or curves["q25"].notna().any():
        if log:
            ax.set_xscale("log")
            ax.xaxis.set_minor_formatter(NullFormatter())
    else:
        ax.text(0.5, 0.5, "no run holds a solution", transform=ax.transAxes, ha="center", va="center",
                color="#888888")
    ax.set_xlabel(AXIS_LABELS[x])
    ax.set_ylabel("best cost (planner's objective)")
    ax.set_title(f"{scenario}: median and IQR of best cost")
    ax.grid(alpha=0.3)
    if configs:
        ax.legend(fontsize="small", frameon=False)
    return ax
