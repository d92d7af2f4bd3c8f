"""Generated sections of a Markdown page, rewritten in place between their markers."""

from __future__ import annotations

from pathlib import Path

__all__ = ["replace_section"]


def replace_section(path: str | Path, name: str, text: str) -> None:
    """Put ``text`` between the markers ``<!-- reproduce:NAME:begin/end -->`` of the page ``path``.

    The block is replaced where the markers exist and appended otherwise,
    so a generated section can be rewritten any number of times while the
    hand-written text around it stays.
    """
    page = Path(path)
    begin, end = f"<!-- reproduce:{name}:begin -->", f"<!-- reproduce:{name}:end -->"
    old = page.read_text(encoding="utf-8") if page.exists() else ""
    block = f"{begin}\n{text}{end}"
    if begin in old and end in old:
        new = old[: old.index(begin)] + block + old[old.index(end) + len(end):]
    else:
        new = old + ("\n" if old and not old.endswith("\n") else "") + block + "\n"
    page.write_text(new, encoding="utf-8")
