"""Box plots of one metric per scenario and configuration, with success rates shown beside the boxes."""

from __future__ import annotations

import warnings
import math
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd
import seaborn as sns
from matplotlib import MatplotlibDeprecationWarning
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from pathzoo.analysis.frame import Direction, MetricInfo, metric_info, with_config
from pathzoo.analysis.formatting import format_number, format_percent
from pathzoo.core.errors import InvalidParameterError
from pathzoo.plotting.figure import new_axes, new_figure, palette_for

__all__ = ["plot_metric_boxes", "plot_metric_panels", "plot_relative_medians", "clip_outliers", "SQUASH_FACTOR"]


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
    configs: Sequence[str] | None = None,
) -> Figure:
    """One box-plot panel per scenario, each with its own y axis, planners named on its x axis.

    A 60 m grid map and a 400 m terrain stay readable side by side, which a
    shared axis (:func:`plot_metric_boxes`) does not allow. Success rates
    below 100 % are printed above the boxes. A panel's y axis spans the
    whiskers (1.5 IQR) of its boxes, so one far outlier cannot squash the
    others flat: points beyond are drawn as triangles on the panel's edge and
    counted there with their extreme value (:func:`clip_outliers`).

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
        As in :func:`plot_metric_boxes`, decided per panel (a log axis is not clipped).
    configs : sequence of str, optional
        The configurations the figure makes room for and colours (default:
        those of ``runs``), e.g. every configuration of an experiment when
        ``runs`` holds only the scenarios shown.
    """
    info = metric_info(metric)
    df = with_config(runs, metric)
    order = sorted(df["scenario"].unique()) if scenarios is None else list(scenarios)
    configs = sorted(df["config"].unique()) if configs is None else sorted(configs)
    palette = palette_for(configs, palette)
    ncols = max(1, min(ncols, len(order)))
    nrows = max(1, math.ceil(len(order) / ncols))
    label_room = 0.09 * max(len(c) for c in configs)  # inches for the rotated planner names
    fig = new_figure((max(4.2 * ncols, 6.0), (3.0 + label_room) * nrows + 0.4))
    axes = fig.subplots(nrows, ncols, squeeze=False).ravel()
    for ax, sc in zip(axes, order):
        _planner_panel(ax, df[df["scenario"] == sc], metric, info, palette, log)
        ax.set_title(sc, fontsize="medium")
    for ax in axes[len(order):]:
        ax.set_visible(False)
    fig.suptitle(f"{info.label} over successful runs ({info.better})", fontsize="medium")
    return fig


def plot_relative_medians(runs: pd.DataFrame | None, metric: str = "length", *,
                          palette: Mapping[str, Any] | None = None, summary: pd.DataFrame | None = None) -> Figure:
    """One panel for all scenarios: each planner's median on a scenario over the best planner's median there.

    A box per configuration holds one value per scenario, its
    :func:`~pathzoo.analysis.summary.relative_medians` ratio (1 is the best
    on that scenario); scenarios without a ratio are left out. The number above a box is
    the share of scenarios on which the configuration had a successful run,
    when below 100 %. The figure's cost does not grow with the number of
    scenarios beyond its one table of medians.

    Parameters
    ----------
    runs : DataFrame or None
        One row per run (not read when ``summary`` is given).
    metric : str
        Metric id.
    palette : mapping, optional
        Colour per configuration.
    summary : DataFrame, optional
        The :func:`~pathzoo.analysis.summary.summarize` table of ``runs`` and
        ``metric``, when already at hand (e.g. gathered a chunk of scenarios
        at a time).
    """
    from pathzoo.analysis.summary import relative_to_best, summarize

    if summary is None:
        if runs is None:
            raise InvalidParameterError("plot_relative_medians needs runs or their summary")
        summary = summarize(runs, metric)
    table = relative_to_best(summary)
    info = table.attrs["metric"]
    frame = pd.DataFrame({"config": table["config"], metric: table["ratio"], "success": table["median"].notna()})
    configs = sorted(frame["config"].unique())
    palette = palette_for(configs, palette)
    label_room = 0.09 * max((len(c) for c in configs), default=1)
    fig = new_figure((max(1.0 + 0.7 * len(configs), 5.0), 3.4 + label_room))
    ax = fig.subplots()
    _planner_panel(ax, frame, metric, info, palette, False)
    ax.set_ylabel(f"{info.label} / best median")
    n = table["scenario"].nunique()
    fig.suptitle(f"{info.label}: median over the best median, {n} scenarios ({info.better})", fontsize="medium")
    return fig


def _planner_panel(ax: Axes, df: pd.DataFrame, metric: str, info: MetricInfo, palette: Mapping[str, Any],
                   log: bool | None) -> None:
    """Boxes of one scenario, one per configuration that ran there, named on the x axis."""
    shown = sorted(df["config"].unique())
    values = pd.to_numeric(df[metric], errors="coerce").to_numpy(float)
    keep = df["success"].to_numpy(bool) & np.isfinite(values)
    good = df.loc[keep, ["config"]].assign(**{metric: values[keep]})
    ax.set_ylabel(info.label)
    ax.set_xlabel("planner")
    if good.empty:  # e.g. length_ratio on a scenario with no reference length
        ax.text(0.5, 0.5, f"no {metric} value in any successful run", transform=ax.transAxes, ha="center",
                va="center", color="#888888")
        ax.set_xticks([])
        return
    with warnings.catch_warnings():  # seaborn 0.13 still passes matplotlib's deprecated ``vert``
        warnings.simplefilter("ignore", MatplotlibDeprecationWarning)
        sns.boxplot(data=good, x="config", y=metric, hue="config", order=shown, hue_order=shown, ax=ax,
                    palette={c: palette[c] for c in shown}, fliersize=2.5, linewidth=1.0, legend=False)
    positive = good.loc[good[metric] > 0, metric]
    if log is None:
        log = info.unit == "s" and len(positive) > 0 and positive.max() > 30 * positive.min()
    if log:
        ax.set_yscale("log")
    else:
        clip_outliers(ax, [good.loc[good["config"] == c, metric].to_numpy(float) for c in shown])
    rate = df.groupby("config")["success"].mean()
    top = ax.get_ylim()[1]
    for i, cfg in enumerate(shown):
        if rate.get(cfg, 1.0) < 1.0:
            ax.annotate(format_percent(rate[cfg]), (i, top), xytext=(0, 2), textcoords="offset points", ha="center",
                        va="bottom", fontsize="x-small", color="#b00000", annotation_clip=False)
    ax.set_xlabel("planner")
    ax.tick_params(axis="x", labelsize="x-small")
    for label in ax.get_xticklabels():
        label.set_rotation(60)
        label.set_horizontalalignment("right")
        label.set_rotation_mode("anchor")


SQUASH_FACTOR = 3.0
"""An axis is clipped to the whiskers when the full data range is more than this times the whiskers' range."""


def clip_outliers(ax: Axes, boxes: Sequence[np.ndarray]) -> int:
    """Limit ``ax``'s y axis to the boxes' whiskers when outliers would squash them; return the points clipped.

    The whiskers are Tukey's (1.5 IQR beyond the quartiles, as the box plot
    draws them). When the data reach more than :data:`SQUASH_FACTOR` times
    as far, the axis spans the whiskers (plus a margin) and each box's points
    beyond are drawn as one triangle on the edge, labelled with their count
    and the extreme value.
    """
    lows, highs = [], []
    for v in boxes:
        if len(v) == 0:
            continue
        q1, q3 = np.percentile(v, [25, 75])
        fence_lo, fence_hi = q1 - 1.5 * (q3 - q1), q3 + 1.5 * (q3 - q1)
        lows.append(v[v >= fence_lo].min())
        highs.append(v[v <= fence_hi].max())
    data = np.concatenate([v for v in boxes if len(v)])
    lo, hi = min(lows), max(highs)
    span = max(hi - lo, 1e-12 * max(abs(hi), 1.0))
    if data.max() - data.min() <= SQUASH_FACTOR * span:
        return 0
    margin = 0.12 * span
    ymin, ymax = lo - margin, hi + margin
    ax.set_ylim(ymin, ymax)
    clipped = 0
    for i, v in enumerate(boxes):
        for beyond, edge, marker, va, extreme in ((v[v > ymax], ymax, "^", "top", np.max),
                                                  (v[v < ymin], ymin, "v", "bottom", np.min)):
            if len(beyond) == 0:
                continue
            clipped += len(beyond)
            ax.plot([i], [edge], marker=marker, color="#444444", markersize=5, clip_on=False, zorder=5)
            ax.annotate(f"{len(beyond)} at {format_number(extreme(beyond), 3)}", (i, edge),
                        xytext=(4, -2 if va == "top" else 2), textcoords="offset points", fontsize="xx-small",
                        va=va, ha="left", color="#444444", annotation_clip=False)
    return clipped
