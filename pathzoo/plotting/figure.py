"""Creating and saving figures without pyplot (no global state, no GUI backend)."""

from __future__ import annotations

import io
from pathlib import Path

from typing import Any, Iterable, Mapping

from matplotlib import rc_context
from matplotlib.axes import Axes
from matplotlib.colors import to_rgb
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["new_figure", "new_axes", "save_figure", "png_bytes", "figure_bytes", "legend_below", "planner_colors",
           "palette_for", "PLANNER_PALETTE"]


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
    return figure_bytes(fig, "png", dpi=dpi)


def figure_bytes(fig: Figure, fmt: str, *, dpi: int = 110) -> bytes:
    """``fig`` rendered in ``fmt`` (``"png"``, ``"svg"``, ``"pdf"``).

    SVG keeps text as text and PDF embeds TrueType fonts, so a figure's
    labels stay editable in a paper; neither records a creation date, so
    the same figure gives the same bytes.
    """
    buf = io.BytesIO()
    metadata = {"Date": None} if fmt == "svg" else {"CreationDate": None} if fmt == "pdf" else None
    with rc_context({"svg.fonttype": "none", "pdf.fonttype": 42}):
        fig.savefig(buf, format=fmt, dpi=dpi, metadata=metadata)
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


PLANNER_PALETTE: tuple[str, ...] = (
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf",
    "#ff00ff", "#ff1493", "#f99379", "#c2b280", "#008856", "#a1caf1", "#b3446c", "#800000", "#f6a600", "#008080",
)
"""Twenty planner colours, any two at least 25 apart in CIELAB (ΔE76; 27.7 among the first twelve).

matplotlib's ``tab10`` first, then, one by one, the candidate farthest in
CIELAB from those already chosen (candidates: Kelly's colours of maximum
contrast and a few web colours, of lightness 25-80 so that lines show on
white and on maps).
"""


def planner_colors(labels: Iterable[str]) -> dict[str, Any]:
    """One distinct colour per label, assigned in sorted order from :data:`PLANNER_PALETTE`.

    Labels past the twentieth get the same colours darkened (up to 40; beyond
    that colours repeat and the legend is the only guide). The report builds
    one mapping from *all* configurations of an experiment and passes it to
    every figure (their ``palette`` argument), so a planner keeps its colour
    across figures.
    """
    names = sorted(set(labels))
    base = [to_rgb(c) for c in PLANNER_PALETTE]
    shades = [*base, *(tuple(0.6 * c for c in rgb) for rgb in base)]
    return {name: shades[i % len(shades)] for i, name in enumerate(names)}


def palette_for(labels: Iterable[str], palette: Mapping[str, Any] | None) -> Mapping[str, Any]:
    """``palette`` when the caller gave one (an experiment-wide mapping), else :func:`planner_colors` of ``labels``."""
    return planner_colors(labels) if palette is None else palette
