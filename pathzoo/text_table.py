"""Aligned plain-text tables, without pandas: the text format of the analysis tables and of ``pathzoo list``."""

from __future__ import annotations

from typing import Sequence

__all__ = ["aligned_text"]


def aligned_text(header: Sequence[str], rows: Sequence[Sequence[str]], *, left: Sequence[str] = (), title: str = "",
                 notes: Sequence[str] = ()) -> str:
    """A table of strings with columns two spaces apart, a rule of dashes under the header, and trailing spaces cut.

    Parameters
    ----------
    header : sequence of str
        Column names.
    rows : sequence of sequence of str
        The cells, one row per item.
    left : sequence of str
        Columns aligned left (the others are right-aligned).
    title : str
        First line, followed by a blank line.
    notes : sequence of str
        Lines under the table, after a blank line.
    """
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    lefts = set(left)

    def line(cells: Sequence[str]) -> str:
        out = [c.ljust(w) if h in lefts else c.rjust(w) for c, w, h in zip(cells, widths, header)]
        return "  ".join(out).rstrip()

    rule = "  ".join("-" * w for w in widths)
    lines = [line(header), rule, *(line(r) for r in rows)]
    head = [title, ""] if title else []
    tail = ["", *notes] if notes else []
    return "\n".join([*head, *lines, *tail]) + "\n"
