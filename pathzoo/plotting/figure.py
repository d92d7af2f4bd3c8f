"""Creating and saving figures without pyplot (no global state, no GUI backend)."""

from __future__ import annotations

import io
from pathlib import Path

from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["new_axes", "save_figure", "png_bytes", "legend_below"]


def new_axes(ax: Axes | None = None, figsize: tuple[float, float] = (6.0, 5.0)) -> Axes:
    """Return ``ax``, or the Axes of a new Agg-backed figure of ``figsize`` inches."""
    if ax is not None:
        return ax
    fig = Figure(figsize=figsize, layout="constrained")
    FigureCanvasAgg(fig)
    return fig.add_subplot()


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


def legend_below(ax: Axes, ncol: int = 4) -> None:
    """Put ``ax``'s legend under the axes, centred, without a frame."""
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=ncol, fontsize="small", frameon=False)
