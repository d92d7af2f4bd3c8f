"""Read a text data file (``.map``, ``.scen``, ``.asc``) as lines, with one-line errors naming the file."""

from __future__ import annotations

from pathlib import Path

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["read_lines"]


def read_lines(path: Path) -> list[str]:
    """The file's lines (UTF-8).

    Raises
    ------
    InvalidScenarioError
        The file cannot be read, or is not UTF-8 text (a binary file given
        where a text format is expected), naming the file and the byte offset.
    """
    try:
        return path.read_text(encoding="utf-8").splitlines()
    except OSError as exc:
        raise InvalidScenarioError(f"cannot read: {exc.strerror or exc}", source=str(path)) from None
    except UnicodeDecodeError as exc:
        raise InvalidScenarioError(f"not UTF-8 text (byte {exc.start} is 0x{exc.object[exc.start]:02x})",
                                   source=str(path)) from None
