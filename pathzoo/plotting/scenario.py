"""Draw a scenario seen from above: occupancy, hillshaded terrain, air-volume heights, moving obstacles.

Images follow the scenario's world convention (``x`` = column to the right,
``y`` = row downwards, metres): every map is drawn with
``imshow(extent=(0, W * cs, H * cs, 0))`` so a path's world coordinates land
on the right cells without any flipping.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.collections import LineCollection
from matplotlib.colors import LightSource, ListedColormap, Normalize
from matplotlib.patches import Circle
from matplotlib.figure import Figure

from pathzoo.core.scenario import Scenario
from pathzoo.plotting.figure import legend_below, new_axes, save_figure

__all__ = ["plot_scenario", "save_scenario_png", "draw_path", "map_extent", "scenario_figsize"]

OCCUPANCY_CMAP = ListedColormap(["#ffffff", "#2b2b2b"])
BLOCKED_RGBA = (0.12, 0.12, 0.12, 0.85)
OBSTACLE_COLOR = "#e07b00"


def map_extent(scenario: Scenario) -> tuple[float, float, float, float]:
    """``imshow`` extent ``(0, W * cs, H * cs, 0)``: x right, y down, in metres."""
    h, w = scenario.shape[-2:]
    return (0.0, w * scenario.cell_size, h * scenario.cell_size, 0.0)


def scenario_figsize(scenario: Scenario, width: float = 6.0) -> tuple[float, float]:
    """A figure size that follows the map's aspect ratio (height clipped to 3.5-9 in)."""
    h, w = scenario.shape[-2:]
    return (width, float(np.clip(width * h / w + 1.2, 3.5, 9.0)))


def _blocked_overlay(blocked: np.ndarray) -> np.ndarray:
    rgba = np.zeros(blocked.shape + (4,))
    rgba[blocked] = BLOCKED_RGBA
    return rgba


def _draw_occupancy(ax: Axes, scenario: Scenario) -> None:
    ax.imshow(scenario.blocked, cmap=OCCUPANCY_CMAP, vmin=0, vmax=1, extent=map_extent(scenario),
              interpolation="nearest")


def _draw_terrain(ax: Axes, scenario: Scenario) -> None:
    elev = np.asarray(scenario.elevation, dtype=np.float64)
    finite = np.isfinite(elev)
    lo, hi = (float(elev[finite].min()), float(elev[finite].max())) if finite.any() else (0.0, 1.0)
    filled = np.where(finite, elev, lo)
    norm = Normalize(lo, hi if hi > lo else lo + 1.0)
    cmap = colormaps["terrain"]
    ls = LightSource(azdeg=315, altdeg=45)
    rgb = ls.shade(filled, cmap=cmap, norm=norm, blend_mode="soft",
                   dx=scenario.cell_size, dy=scenario.cell_size)
    ext = map_extent(scenario)
    ax.imshow(rgb, extent=ext, interpolation="nearest")
    ax.imshow(_blocked_overlay(scenario.blocked), extent=ext, interpolation="nearest")
    ax.figure.colorbar(ScalarMappable(norm, cmap), ax=ax, label="elevation [m]", shrink=0.85)


def _draw_air(ax: Axes, scenario: Scenario) -> None:
    occ = scenario.occupancy
    layers = occ.shape[0]
    vcs = float(scenario.vertical_cell_size)  # type: ignore[arg-type]
    any_blocked = occ.any(axis=0)
    top_layer = layers - 1 - np.argmax(occ[::-1], axis=0)
    top = np.where(any_blocked, (top_layer + 1) * vcs, 0.0)
    label = "max obstacle height [m]"
    if scenario.elevation is not None:
        top = np.maximum(top, np.nan_to_num(scenario.elevation, nan=0.0))
        label = "ground / obstacle top [m]"
    norm = Normalize(0.0, max(float(top.max()), layers * vcs * 1e-3, 1e-9))
    ax.imshow(top, cmap="viridis", norm=norm, extent=map_extent(scenario), interpolation="nearest")
    full = occ.all(axis=0)
    if full.any():
        ax.imshow(_blocked_overlay(np.asarray(full)), extent=map_extent(scenario), interpolation="nearest")
    ax.figure.colorbar(ScalarMappable(norm, "viridis"), ax=ax, label=label, shrink=0.85)


def _draw_moving(ax: Axes, scenario: Scenario) -> None:
    span = float(max(scenario.extent[:2]))
    for i, ob in enumerate(scenario.moving_obstacles):
        wp = np.asarray(ob.waypoints, dtype=np.float64)
        if ob.mode == "loop" and len(wp) > 1:
            wp = np.vstack([wp, wp[:1]])
        label = "obstacle path" if i == 0 else None
        ax.plot(wp[:, 0], wp[:, 1], ls="--", lw=1.2, color=OBSTACLE_COLOR, alpha=0.9, label=label)
        p0 = ob.position(0.0)
        ax.add_patch(Circle(tuple(p0), ob.radius, facecolor=OBSTACLE_COLOR, edgecolor="black", lw=0.8, alpha=0.75,
                            label="obstacle at t=0" if i == 0 else None, zorder=4))
        if ob.speed > 0 and np.isfinite(ob.period_s):
            dt = min(ob.period_s / 50.0, 0.05 * span / ob.speed)
            d = ob.position(dt) - p0
            norm = float(np.linalg.norm(d))
            if norm > 0:
                d = d / norm * max(1.5 * ob.radius, 0.04 * span)
                ax.annotate("", xy=tuple(p0 + d), xytext=tuple(p0), zorder=5,
                            arrowprops=dict(arrowstyle="->", color="black", lw=1.2))


def _draw_graph(ax: Axes, scenario: Scenario) -> None:
    g = scenario.graph
    src = np.repeat(np.arange(g.n_nodes), np.diff(g.indptr))
    keep = src < g.indices
    pts = scenario.point_of(np.arange(g.n_nodes))[:, :2]
    seg = np.stack([pts[src[keep]], pts[g.indices[keep]]], axis=1)
    seg = np.unique(np.round(seg, 9), axis=0)
    ax.add_collection(LineCollection(list(seg), colors="#4a90d9", linewidths=0.4, alpha=0.5, zorder=2))


def draw_path(ax: Axes, path: np.ndarray, *, label: str | None = None, color: Any = None, **kwargs: Any) -> None:
    """Draw a path's ``x, y`` (any extra columns, such as ``z``, are ignored)."""
    p = np.asarray(path, dtype=np.float64)
    if p.ndim != 2 or p.shape[1] < 2 or len(p) == 0:
        from pathzoo.core.errors import InvalidParameterError

        raise InvalidParameterError(f"path must be an (N, 2) or (N, 3) array, got shape {p.shape}")
    style: dict[str, Any] = dict(lw=2.0, zorder=6, solid_capstyle="round")
    style.update(kwargs)
    ax.plot(p[:, 0], p[:, 1], label=label, color=color, **style)


def plot_scenario(
    scenario: Scenario,
    path: np.ndarray | None = None,
    ax: Axes | None = None,
    *,
    show_graph: bool = False,
    title: str | None = None,
    legend: bool = True,
) -> Axes:
    """Draw a scenario from above, with its start, goal and optionally a path.

    - ``grid2d``: blocked cells dark, free cells white;
    - ``terrain``: hillshaded elevation (:class:`matplotlib.colors.LightSource`,
      light from the north-west) with blocked cells overlaid in dark grey and
      an elevation colour bar;
    - ``air3d``: top view of the highest obstacle voxel in each column (or the
      ground, when the volume has an elevation grid), columns blocked at every
      height overlaid in dark grey;
    - ``dynamic``: the occupancy map plus every moving obstacle as a disc at
      ``t = 0``, an arrow for its initial heading and its trajectory dashed.

    Parameters
    ----------
    scenario : Scenario
        What to draw.
    path : ndarray of shape (N, 2) or (N, 3), optional
        A path in world coordinates.
    ax : Axes, optional
        Where to draw; a new Agg-backed figure by default.
    show_graph : bool
        Also draw the neighbourhood graph's edges (small maps only; air
        volumes show the edges projected onto the ground plane).
    title : str, optional
        Axes title (default: the scenario id).
    legend : bool
        Add a legend.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = new_axes(ax, scenario_figsize(scenario))
    if scenario.kind == "terrain":
        _draw_terrain(ax, scenario)
    elif scenario.kind == "air3d":
        _draw_air(ax, scenario)
    else:
        _draw_occupancy(ax, scenario)
    if show_graph:
        _draw_graph(ax, scenario)
    if scenario.kind == "dynamic":
        _draw_moving(ax, scenario)
    if path is not None:
        draw_path(ax, path, label="path", color="#d62728")
    s, g = scenario.start, scenario.goal
    ax.plot(s[0], s[1], "o", ms=9, color="#2ca02c", mec="black", zorder=7, label="start")
    ax.plot(g[0], g[1], "*", ms=15, color="#ffd700", mec="black", zorder=7, label="goal")
    ext = map_extent(scenario)
    ax.set_xlim(ext[0], ext[1])
    ax.set_ylim(ext[2], ext[3])
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(scenario.id if title is None else title)
    if legend:
        legend_below(ax)
    return ax


def save_scenario_png(
    scenario: Scenario,
    path: str | Path,
    *,
    planned_path: np.ndarray | None = None,
    show_graph: bool = False,
    dpi: int = 120,
) -> Path:
    """Draw ``scenario`` with :func:`plot_scenario` and write it to the PNG file ``path``.

    ``planned_path`` is an optional planner path drawn on top (``path`` is the file).
    """
    ax = plot_scenario(scenario, planned_path, show_graph=show_graph)
    figure = ax.figure
    assert isinstance(figure, Figure)  # plot_scenario draws on a figure of its own, not a subfigure
    return save_figure(figure, path, dpi=dpi)
