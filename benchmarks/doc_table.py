"""Put a benchmark's printed Markdown into its docs page, between two marker comments.

A speed page holds one current table, written by the script that measures it.
The page marks the table's place with::

    <!-- benchmark: python benchmarks/speed.py -->
    ...the script's output...
    <!-- end benchmark -->

and ``python benchmarks/speed.py --write-docs`` prints as usual and then
replaces what lies between the markers with what it printed to stdout
(notes about the machine go to stderr and stay out of the page).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import TextIO

DOCS = Path(__file__).resolve().parents[1] / "docs"
END = "<!-- end benchmark -->"


def begin_marker(script: str) -> str:
    """The comment that opens the table written by ``benchmarks/<script>``."""
    return f"<!-- benchmark: python benchmarks/{script} -->"


def add_write_docs_option(parser: argparse.ArgumentParser, page: str) -> None:
    """Give a benchmark script the ``--write-docs`` flag that rewrites its table in ``docs/<page>``."""
    parser.add_argument("--write-docs", action="store_true",
                        help=f"also replace the table in docs/{page} with this run's output")


def replace_table(page: Path, script: str, table: str) -> None:
    """Replace the text between ``script``'s markers in ``page`` with ``table``."""
    text = page.read_text(encoding="utf-8")
    begin = begin_marker(script)
    start = text.find(begin)
    end = text.find(END, start)
    if start < 0 or end < 0:
        raise SystemExit(f"{page}: no '{begin}' ... '{END}' block to replace")
    head = text[:start + len(begin)]
    page.write_text(f"{head}\n\n{table.strip()}\n\n{text[end:]}", encoding="utf-8")


class _Tee(io.TextIOBase):
    """Write to the terminal and keep a copy."""

    def __init__(self, out: TextIO) -> None:
        self.out, self.copy = out, io.StringIO()

    def write(self, text: str) -> int:
        self.copy.write(text)
        return self.out.write(text)

    def flush(self) -> None:
        self.out.flush()


@contextlib.contextmanager
def docs_table(write: bool, page: str, script: str) -> Iterator[None]:
    """Print as usual; with ``write``, put what was printed into ``docs/<page>`` once the block ends without error."""
    if not write:
        yield
        return
    tee = _Tee(sys.stdout)
    with contextlib.redirect_stdout(tee):
        yield
    replace_table(DOCS / page, script, tee.copy.getvalue())
    print(f"wrote the table into docs/{page}", file=sys.stderr)
