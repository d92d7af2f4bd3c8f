"""Render result tables as aligned text, Markdown, CSV, JSON, LaTeX or an HTML table."""

from __future__ import annotations

import json
import math
import re
from typing import Literal, Sequence

import pandas as pd

from pathzoo.core.errors import InvalidParameterError
from pathzoo.text_table import aligned_text

__all__ = ["TABLE_FORMATS", "TableFormat", "format_number", "format_percent", "render_table"]

TableFormat = Literal["text", "markdown", "csv", "json", "latex", "html"]
TABLE_FORMATS: tuple[str, ...] = ("text", "markdown", "csv", "json", "latex", "html")
MISSING = "–"
_NUM = r"(-?(\d[\d.]*(e[-+]?\d+)?|inf)%?|–)"
_NUMERIC = re.compile(rf"^{_NUM}( [↑↓≈]| n/s| \[{_NUM}\])?$|^\d+/\d+/\d+( \+\d+ n/s)?$")
"""Cells shown right-aligned in HTML (``class="num"``): numbers, percentages, marks, w/t/l counts."""


def format_number(x: float, digits: int = 5) -> str:
    """Show a number with ``digits`` significant figures, never in exponent form above 1e-3.

    NaN and missing values become ``"–"``; infinities ``"inf"``/``"-inf"``.
    """
    if x is None or (isinstance(x, float) and math.isnan(x)) or pd.isna(x):
        return MISSING
    x = float(x)
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if x == 0:
        return "0"
    x = float(f"{x:.{digits}g}")  # round first: 0.9999999 must count as 1.0, not as 0.xxxxx
    magnitude = math.floor(math.log10(abs(x)))
    if magnitude < -3:
        return f"{x:.{digits - 1}e}"
    decimals = max(digits - 1 - magnitude, 0)
    return f"{x:.{decimals}f}"


def format_percent(x: float) -> str:
    """A fraction in [0, 1] as a whole percentage (``"85%"``), ``"–"`` when missing."""
    if x is None or pd.isna(x):
        return MISSING
    return f"{100 * float(x):.0f}%"


def render_table(
    display: pd.DataFrame,
    fmt: str,
    *,
    raw: pd.DataFrame | None = None,
    title: str = "",
    notes: Sequence[str] = (),
    left: Sequence[str] = (),
) -> str:
    """Render a table of display strings.

    Parameters
    ----------
    display : DataFrame
        Cells already formatted as strings; column names are the headers.
    fmt : {"text", "markdown", "csv", "json", "latex", "html"}
        Output format. ``csv`` writes ``raw`` (full-precision numbers) when
        given, and never the title or notes. ``json`` writes an object with
        ``title``, ``notes`` and ``rows`` (the records of ``raw`` when given,
        full precision, non-finite numbers as ``null``). ``latex`` writes a
        ``booktabs`` ``table`` environment with the title as caption and the
        notes below it.
    raw : DataFrame, optional
        The unformatted table, for ``csv`` and ``json``.
    title : str
        First line (text/Markdown) or ``<caption>`` (HTML).
    notes : sequence of str
        Lines printed under the table (legends, the ranking rule).
    left : sequence of str
        Columns aligned left in text output (others are right-aligned).

    Raises
    ------
    InvalidParameterError
        ``fmt`` is not one of :data:`TABLE_FORMATS`.
    """
    if fmt not in TABLE_FORMATS:
        raise InvalidParameterError(f"fmt must be one of {', '.join(TABLE_FORMATS)}, got {fmt!r}")
    if fmt == "csv":
        return (raw if raw is not None else display).to_csv(index=False)
    if fmt == "json":
        records = json.loads((raw if raw is not None else display).to_json(orient="records", double_precision=15))
        return json.dumps({"title": title, "notes": list(notes), "rows": records}, ensure_ascii=False, indent=1) + "\n"
    if fmt == "latex":
        return _latex(display, title, notes, left)
    header = [str(c) for c in display.columns]
    rows = [[str(v) for v in row] for row in display.itertuples(index=False, name=None)]
    if fmt == "html":
        return _html(header, rows, title, notes)
    if fmt == "markdown":
        esc = [[c.replace("|", "\\|") for c in r] for r in [header, *rows]]
        lines = ["| " + " | ".join(esc[0]) + " |", "|" + "|".join("---" for _ in header) + "|"]
        lines += ["| " + " | ".join(r) + " |" for r in esc[1:]]
        head = [f"**{title}**", ""] if title else []
        tail = ["", *notes] if notes else []
        return "\n".join([*head, *lines, *tail]) + "\n"
    return aligned_text(header, rows, left=left, title=title, notes=notes)


def _latex(display: pd.DataFrame, title: str, notes: Sequence[str], left: Sequence[str]) -> str:
    """A booktabs table through pandas' Styler (special characters escaped, numbers right-aligned)."""
    align = "".join("l" if c in set(left) else "r" for c in display.columns)
    styler = display.style.hide(axis="index").format(escape="latex").format_index(escape="latex", axis=1)
    body = styler.to_latex(column_format=align, hrules=True, caption=_latex_escape(title) or None,
                           position_float="centering", environment="table")
    if notes:
        foot = "\n".join(f"\\par\\footnotesize {_latex_escape(n)}" for n in notes)
        body = body.replace("\\end{table}", foot + "\n\\end{table}")
    return body


_LATEX_SPECIAL = str.maketrans({
    "\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_",
    "{": r"\{", "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}",
})


def _latex_escape(text: str) -> str:
    """Escape LaTeX's ten special characters in free text (captions, notes)."""
    return text.translate(_LATEX_SPECIAL)


def _html(header: list[str], rows: list[list[str]], title: str, notes: Sequence[str]) -> str:
    """The table through the ``table.html.j2`` template (autoescaped)."""
    from pathzoo.analysis.templates import environment

    cells = [[(c, bool(_NUMERIC.match(c))) for c in r] for r in rows]
    return environment().get_template("table.html.j2").render(header=header, rows=cells, title=title, notes=notes)
