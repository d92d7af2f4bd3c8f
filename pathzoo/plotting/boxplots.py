"""Box plots of one metric per scenario and configuration, with success rates shown beside the boxes."""

from __future__ import annotations

import warnings
import math
from typing import Any, Mapping, Sequence

import pandas as pd
import seaborn as sns
from matplotlib import MatplotlibDeprecationWarning
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from pathzoo.analysis.frame import Direction, metric_info, with_config
from pathzoo.analysis.formatting import format_percent
from pathzoo.plotting.figure import new_axes, new_figure, palette_for

__all__ = ["plot_metric_boxes", "plot_metric_panels"]


def plot_metric_boxes(
    runs: pd.DataFrame,
    metric: str = "length",
    ax: Axes | None = None,
    *,
    scenarios: Sequence[str] | None = None,
    direction: Direction | None = None,
    unit: str | None = None,
    log: bool | None = None,
    palette: Mapping[str, Any] | None = None,
) -> Axes:
    """Box plot of ``metric`` over successful runs: scenarios on the x axis, one box per configuration.

    A configuration's success rate is printed above its box when it is
    below 100 % (a box of 2 runs out of 20 must not look like a result), and
    "0%" marks a configuration with no successful run at all.

    Parameters
    ----------
    runs : DataFrame
        One row per run.
    metric : str
        Metric id.
    ax : Axes, optional
        Where to draw; a new figure by default.
    scenarios : sequence of str, optional
        Scenarios to show, in order (default: all, sorted).
    direction, unit : optional
        Overrides of the registered metric facts (used in the axis label).
    log : bool, optional
        Logarithmic y axis. By default only for times (unit ``s``) whose
        positive values span more than a factor of 30.
    palette : mapping, optional
        Colour per configuration (default: :func:`~pathzoo.plotting.figure.planner_colors` of those shown).

    See Also
    --------
    plot_metric_panels : one panel per scenario, each with its own axis.
    """
    info = metric_info(metric, direction, unit)
    df = with_config(runs, metric)
    order = sorted(df["scenario"].unique()) if scenarios is None else list(scenarios)
    df = df[df["scenario"].isin(order)]
    hue_order = sorted(df["config"].unique())
    ax = new_axes(ax, (max(5.0, 1.2 + 0.35 * len(order) * len(hue_order)), 4.2))
    good = df[df["success"] & pd.to_numeric(df[metric], errors="coerce").notna()]
    if good.empty:  # e.g. length_ratio on a scenario with no reference length: nothing to draw
        ax.text(0.5, 0.5, f"no {metric} value in any successful run", transform=ax.transAxes, ha="center",
                va="center", color="#888888")
        ax.set_ylabel(info.label)
        ax.set_xticks([])
        return ax
    with warnings.catch_warnings():  # seaborn 0.13 still passes matplotlib's deprecated ``vert``
        warnings.simplefilter("ignore", MatplotlibDeprecationWarning)
        sns.boxplot(data=good, x="scenario", y=metric, hue="config", order=order, hue_order=hue_order, ax=ax,
                    palette=palette_for(hue_order, palette), fliersize=2.5, linewidth=1.0)
    rate = df.groupby(["scenario", "config"])["success"].mean()
    width = 0.8 / max(len(hue_order), 1)
    ymax = good[metric].max() if len(good) else 1.0
    for i, sc in enumerate(order):
        for j, cfg in enumerate(hue_order):
            r = rate.get((sc, cfg))
            if r is None or r >= 1.0:
                continue
            top = good.loc[(good["scenario"] == sc) & (good["config"] == cfg), metric].max()
            y = ymax if pd.isna(top) else top
            ax.annotate(format_percent(r), (i - 0.4 + (j + 0.5) * width, y), xytext=(0, 3),
                        textcoords="offset points", ha="center", va="bottom", fontsize="x-small", color="#b00000")
    positive = good.loc[good[metric] > 0, metric]
    if log is None:
        log = info.unit == "s" and len(positive) > 0 and positive.max() > 30 * positive.min()
    if log:
        ax.set_yscale("log")
    ax.set_ylabel(info.label)
    ax.set_title(f"{info.id} over successful runs ({info.better})", fontsize="medium")
    ax.set_xlabel("scenario")
    if len(order) > 4 or max(len(str(s)) for s in order) > 10:
        for label in ax.get_xticklabels():
            label.set_rotation(25)
            label.set_horizontalalignment("right")
    if ax.get_legend() is not None:
        sns.move_legend(ax, "upper left", bbox_to_anchor=(1.01, 1.0), title="planner", fontsize="small", frameon=False)
    return ax


def plot_metric_panels(
    runs: pd.DataFrame,
    metric: str = "length",
    *,
    scenarios: Sequence[str] | None = None,
    palette: Mapping[str, Any] | None = None,
    ncols: int = 3,
    log: bool | None = None,
) -> Figure:
    """One box-plot panel per scenario, each with its own y axis, and one legend for the figure.

    A 60 m grid map and a 400 m terrain stay readable side by side, which a
    shared axis (:func:`plot_metric_boxes`) does not allow. Success rates
    below 100 % are printed above the boxes as there.

    Parameters
    ----------
    runs : DataFrame
        One row per run.
    metric : str
        Metric id.
    scenarios : sequence of str, optional
        Scenarios to show, in order (default: all, sorted).
    palette : mapping, optional
        Colour per configuration (default: :func:`~pathzoo.plotting.figure.planner_colors` of all configurations).
    ncols : int
        Panels per row.
    log : bool, optional
        As in :func:`plot_metric_boxes`, decided per panel.
    """
    df = with_config(runs, metric)
    order = sorted(df["scenario"].unique()) if scenarios is None else list(scenarios)
    configs = sorted(df["config"].unique())
    palette = palette_for(configs, palette)
    ncols = max(1, min(ncols, len(order)))
    nrows = max(1, math.ceil(len(order) / ncols))
    fig = new_figure((max(4.2 * ncols, 6.0), 3.3 * nrows + 0.5 + 0.22 * math.ceil(len(configs) / 4)))
    axes = fig.subplots(nrows, ncols, squeeze=False).ravel()
    for ax, sc in zip(axes, order):
        plot_metric_boxes(runs, metric, ax, scenarios=[sc], palette=palette, log=log)
        ax.set_title(sc, fontsize="medium")
        ax.set_xlabel("")
        ax.set_xticks([])
        if ax.get_legend() is not None:
            ax.get_legend().remove()
    for ax in axes[len(order):]:
        ax.set_visible(False)
    handles = [Patch(facecolor=palette[c], edgecolor="#333333", label=c) for c in configs]
    fig.legend(handles=handles, loc="outside lower center", ncol=min(4, len(configs)), fontsize="small",
               frameon=False)
    fig.suptitle(f"{metric_info(metric).label} over successful runs", fontsize="medium")
    return fig
