"""Creating and saving figures without pyplot (no global state, no GUI backend)."""

from __future__ import annotations

import io
from pathlib import Path

from typing import Any, Iterable, Mapping

import seaborn as sns
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["new_figure", "new_axes", "save_figure", "png_bytes", "legend_below", "planner_colors", "palette_for"]


def new_figure(figsize: tuple[float, float] = (6.0, 5.0)) -> Figure:
    """A new Agg-backed figure of ``figsize`` inches with constrained layout (not known to pyplot)."""
    fig = Figure(figsize=figsize, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def new_axes(ax: Axes | None = None, figsize: tuple[float, float] = (6.0, 5.0)) -> Axes:
    """Return ``ax``, or the Axes of a :func:`new_figure` of ``figsize`` inches."""
    return ax if ax is not None else new_figure(figsize).add_subplot()


def save_figure(fig: Figure, path: str | Path, *, dpi: int = 120) -> Path:
    """Write ``fig`` to ``path`` (format from the suffix) and return the path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    return path


def png_bytes(fig: Figure, *, dpi: int = 110) -> bytes:
    """``fig`` rendered as PNG bytes (for embedding in HTML)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()


def legend_below(ax: Axes, ncol: int | None = None) -> None:
    """Put ``ax``'s legend under it, centred and frameless.

    When ``ax`` is the only plot of its figure (colour bars aside) the
    legend becomes a figure legend placed "outside lower center", so the
    constrained layout makes room for it; otherwise it is anchored below the
    axes. ``ncol`` defaults to as many columns as long labels allow.
    """
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return
    if ncol is None:
        ncol = int(min(4, max(1, 64 // (max(len(t) for t in labels) + 8))))
    fig = ax.figure
    plots = [a for a in fig.axes if not hasattr(a, "_colorbar")]
    if plots == [ax] and hasattr(fig, "legend"):
        fig.legend(handles, labels, loc="outside lower center", ncol=ncol, fontsize="small", frameon=False)
    else:
        ax.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=ncol, fontsize="small",
                  frameon=False)


def planner_colors(labels: Iterable[str]) -> dict[str, Any]:
    """One distinct colour per label, assigned in sorted order.

    The first ten labels get seaborn's colour-blind-safe ``colorblind``
    palette; further labels get the same ten hues darkened, then lightened,
    so no two labels share a colour (up to 30; beyond that colours repeat and
    the legend is the only guide). Pass the mapping built from *all*
    configurations of an experiment to every plotting function (their
    ``palette`` argument) so a planner keeps its colour across figures.
    """
    names = sorted(set(labels))
    base = sns.color_palette("colorblind", 10)
    shades = [*base, *(tuple(0.62 * c for c in rgb) for rgb in base), *(tuple(c + 0.5 * (1 - c) for c in rgb) for rgb in base)]
    return {name: shades[i % len(shades)] for i, name in enumerate(names)}


def palette_for(labels: Iterable[str], palette: Mapping[str, Any] | None) -> Mapping[str, Any]:
    """``palette`` when the caller gave one (an experiment-wide mapping), else :func:`planner_colors` of ``labels``."""
    return planner_colors(labels) if palette is None else palette
