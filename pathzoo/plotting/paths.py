"""Several planners' paths drawn over one scenario's map or hillshaded terrain."""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np
from matplotlib import patheffects
from matplotlib.axes import Axes

from pathzoo.core.scenario import Scenario
from pathzoo.plotting.figure import legend_below, palette_for
from pathzoo.plotting.scenario import draw_path, plot_scenario

__all__ = ["plot_paths"]


def plot_paths(
    scenario: Scenario,
    paths: Mapping[str, np.ndarray],
    ax: Axes | None = None,
    *,
    title: str | None = None,
    colors: Mapping[str, Any] | None = None,
) -> Axes:
    """Draw each labelled path over :func:`~pathzoo.plotting.scenario.plot_scenario`'s view of ``scenario``.

    Paths get distinct colour-blind-safe colours with a white outline, so
    they stay visible on dark obstacles and on coloured terrain.

    Parameters
    ----------
    scenario : Scenario
        The map.
    paths : mapping of str to ndarray
        Label (usually the planner) to an ``(N, 2)`` or ``(N, 3)`` path.
    ax : Axes, optional
        Where to draw.
    title : str, optional
        Axes title (default: the scenario id).
    colors : mapping, optional
        Colour per label (default: :func:`~pathzoo.plotting.figure.planner_colors` of the labels).
    """
    ax = plot_scenario(scenario, ax=ax, title=title, legend=False)
    colors = palette_for(paths, colors)
    outline = [patheffects.withStroke(linewidth=4.0, foreground="white")]
    for label, path in paths.items():
        draw_path(ax, path, label=label, color=colors[label], path_effects=outline)
    legend_below(ax)
    return ax
