"""The page a report is assembled on: headings, notes, tables and figures, rendered by one template."""

from __future__ import annotations

import base64
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

__all__ = ["ReportPage", "VECTOR_FORMATS"]

VECTOR_FORMATS: tuple[str, ...] = ("svg", "pdf")
"""Formats every report figure is also written in, to ``figures/`` beside ``index.html``."""


@dataclass
class ReportPage:
    """An HTML page being assembled as a list of blocks, rendered by the ``report.html.j2`` template.

    Blocks are dicts with a ``kind`` (``heading``, ``note``, ``meta``, ``nav``,
    ``table``, ``figure``, ``grid``, ``details``); ``grid`` and ``details``
    hold ``children``. Every text is escaped by the template; only tables
    rendered by :func:`~pathzoo.analysis.formatting.render_table` (themselves
    from an autoescaping template) are inserted as HTML.
    """

    embed: bool = True
    blocks: list[dict[str, Any]] = field(default_factory=list)
    files: dict[str, bytes] = field(default_factory=dict)
    n_figures: int = 0
    _open: list[list[dict[str, Any]]] = field(default_factory=list, repr=False)

    def _add(self, kind: str, **fields: Any) -> dict[str, Any]:
        block = dict(kind=kind, **fields)
        (self._open[-1] if self._open else self.blocks).append(block)
        return block

    def heading(self, level: int, text: str, anchor: str | None = None) -> None:
        """Add ``<hN>`` (with an id for the navigation bar)."""
        self._add("heading", level=level, text=text, anchor=anchor)

    def note(self, text: str, cls: str = "pz-note") -> None:
        """Add a paragraph (``cls="warn"`` for a warning box)."""
        self._add("note", text=text, cls=cls)

    def meta(self, lines: Mapping[str, str]) -> None:
        """Add the header lines (label to value)."""
        self._add("meta", lines=list(lines.items()))

    def nav(self, links: Sequence[tuple[str, str]]) -> None:
        """Add the navigation bar: ``(anchor, text)`` pairs."""
        self._add("nav", links=list(links))

    def table(self, rendered_html: str) -> None:
        """Add a table from :func:`~pathzoo.analysis.formatting.render_table` (``fmt="html"``)."""
        from markupsafe import Markup

        self._add("table", html=Markup(rendered_html))

    def begin(self, kind: str, summary: str = "") -> None:
        """Open a ``grid`` (figures side by side) or a ``details`` block (collapsed, with ``summary``)."""
        self._open.append(self._add(kind, summary=summary, children=[])["children"])

    def end(self) -> None:
        """Close the innermost open ``grid`` or ``details`` block."""
        self._open.pop()

    def figure(self, ax_or_fig: Any, name: str, caption: str) -> None:
        """Render a matplotlib Axes or Figure and add it with a caption.

        The page shows a PNG (embedded, or in ``figures/``); the same figure
        is also kept as SVG and PDF (:data:`VECTOR_FORMATS`) for
        ``figures/``, linked from the caption, so it can go into a paper.
        """
        from pathzoo.plotting.figure import figure_bytes

        fig = getattr(ax_or_fig, "figure", ax_or_fig)
        stem = f"{self.n_figures:02d}-{_slug(name)}"
        self.n_figures += 1
        data = figure_bytes(fig, "png")
        if self.embed:
            src = "data:image/png;base64," + base64.b64encode(data).decode("ascii")
        else:
            self.files[f"{stem}.png"] = data
            src = f"figures/{stem}.png"
        links = []
        for fmt in VECTOR_FORMATS:
            self.files[f"{stem}.{fmt}"] = figure_bytes(fig, fmt)
            links.append((fmt.upper(), f"figures/{stem}.{fmt}"))
        self._add("figure", src=src, caption=caption, files=links)

    def html(self, title: str) -> str:
        """The complete document."""
        from pathzoo.analysis.templates import environment

        return environment().get_template("report.html.j2").render(title=title, blocks=self.blocks)


def _slug(text: str) -> str:
    keep = "".join(c if c.isalnum() or c in "-_." else "-" for c in text)
    return keep.strip("-")[:60] or "figure"
