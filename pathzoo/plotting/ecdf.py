"""ECDF of the time each run needs to come within ε of the optimum."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
import pandas as pd
from matplotlib.axes import Axes
from matplotlib.ticker import NullFormatter

from pathzoo.analysis.anytime import AnytimeAxis, time_to_target
from pathzoo.core.errors import InvalidParameterError
from pathzoo.plotting.convergence import AXIS_LABELS
from pathzoo.plotting.figure import legend_below, new_axes, palette_for

__all__ = ["plot_time_to_target_ecdf"]


def plot_time_to_target_ecdf(
    history: pd.DataFrame | None,
    runs: pd.DataFrame | None,
    *,
    eps: float = 0.05,
    optimum: Mapping[str, float] | pd.Series | None = None,
    metric: str = "length",
    x: AnytimeAxis = "time_s",
    ax: Axes | None = None,
    log: bool = True,
    rtol: float = 1e-3,
    palette: Mapping[str, Any] | None = None,
    hits: pd.DataFrame | None = None,
) -> Axes:
    """Fraction of runs that reached ``(1 + eps) * optimum`` by each ``x``, per configuration, pooled over scenarios.

    Times come from :func:`pathzoo.analysis.anytime.time_to_target`. The
    denominator of each curve is the configuration's *comparable* runs
    (unsuccessful runs count, as never reaching the target); runs whose
    objective is not ``metric`` are left out and their number is given in
    the legend. A curve that stays below 1 shows the share of runs that
    never got there.

    Parameters
    ----------
    history, runs : DataFrame
        History rows and the runs frame.
    eps : float
        Relative tolerance.
    optimum : mapping, optional
        Optimal value per scenario (default: best known in ``runs``).
    metric : str
        Metric the target refers to.
    x : {"iteration", "evaluations", "time_s"}
        Horizontal axis.
    ax : Axes, optional
        Where to draw.
    log : bool
        Logarithmic x axis.
    rtol : float
        Tolerance deciding whether a run's objective is ``metric``.
    palette : mapping, optional
        Colour per configuration (default: :func:`~pathzoo.plotting.figure.planner_colors` of those shown).
    hits : DataFrame, optional
        The :func:`~pathzoo.analysis.anytime.time_to_target` rows (at least
        ``config, comparable, hit``) of ``history`` and ``runs`` with these
        settings, when already at hand (e.g. gathered a chunk of scenarios at
        a time); then ``history`` and ``runs`` are not read.
    """
    if hits is None:
        if history is None or runs is None:
            raise InvalidParameterError("plot_time_to_target_ecdf needs history and runs, or their hits")
        hits = time_to_target(history, runs, eps=eps, optimum=optimum, metric=metric, x=x, rtol=rtol)
    ax = new_axes(ax, (6.0, 4.0))
    configs = sorted(hits["config"].unique())
    colors = palette_for(configs, palette)
    finite = hits["hit"][np.isfinite(hits["hit"])]
    positive = finite[finite > 0]
    x_lo = float(positive.min()) if len(positive) else 1.0
    x_hi = float(finite.max()) if len(finite) else 1.0
    for cfg in configs:
        h = hits[hits["config"] == cfg]
        comp = h[h["comparable"]]
        n_out = len(h) - len(comp)
        note = f", {n_out} not comparable" if n_out else ""
        label = f"{cfg} (n={len(comp)}{note})"
        if comp.empty:
            ax.plot([], [], color=colors[cfg], label=label)
            continue
        t = np.sort(comp["hit"].to_numpy())
        t = t[np.isfinite(t)]
        frac = np.arange(1, len(t) + 1) / len(comp)
        xs = np.concatenate([[x_lo if log else 0.0], np.maximum(t, x_lo if log else t), [x_hi]])
        ys = np.concatenate([[0.0], frac, [frac[-1] if len(frac) else 0.0]])
        ax.step(xs, ys, where="post", color=colors[cfg], lw=1.8, label=label)
    if log and len(positive):
        ax.set_xscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel(AXIS_LABELS[x])
    ax.set_ylabel("fraction of runs")
    ref = "the best known value" if optimum is None else "the optimum"
    ax.set_title(f"{metric} within {eps:.0%} of {ref}")
    ax.grid(alpha=0.3)
    legend_below(ax)
    return ax
