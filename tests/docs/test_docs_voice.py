"""``docs/`` is reference for users: no lab notebook, and every speed table comes from its benchmark script.

How a figure was reached (numbered rounds, sessions, A/B tables, the load
of the machine it was measured on) belongs in the git log. A speed table
sits between the markers of ``benchmarks/doc_table.py`` and names the
script that rewrites it with ``--write-docs``.
"""

from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
DOCS = REPO_ROOT / "docs"
BENCHMARKS = REPO_ROOT / "benchmarks"

NARRATION = re.compile(
    r"\bround [0-9]"  # "round 3", "the third round" below
    r"|\b(third|fourth|fifth|sixth|first|second|previous|last|this|next) (round|session)s?\b"
    r"|\b(fourth|fifth)\b"
    r"|\bsessions?\b"
    r"|\bload (average )?[0-9]"
    r"|\bload average\b"
    r"|\bA/B\b"
    r"|\bidle (machine|run|rerun)\b"
    r"|\bthe machine was\b"
    r"|\bearlier versions?\b"
    r"|\bno longer\b"
    r"|\bused to be\b"
    r"|\bit was\b"
    r"|\bthe issue\b"
    r"|\bDESIGN\.md\b",
    re.IGNORECASE,
)
"""Words that narrate how a figure was reached; the issue's ``grep -riE`` and a few more."""

BEGIN = re.compile(r"<!-- benchmark: python benchmarks/(?P<script>[\w.]+\.py) -->")


def doc_pages() -> list[Path]:
    return sorted(p for p in DOCS.rglob("*") if p.suffix in (".md", ".rst") and "_build" not in p.parts)


def test_the_docs_narrate_no_history() -> None:
    found = []
    for page in doc_pages():
        for number, line in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
            match = NARRATION.search(line)
            if match:
                found.append(f"{page.relative_to(REPO_ROOT)}:{number}: {match.group(0)!r} in {line.strip()[:100]}")
    assert not found, "lab-notebook narration in docs/ (it belongs in the commit message):\n" + "\n".join(found)


@pytest.mark.parametrize("line", [
    "Fifth round (issue 12, measured at load 4.5-8 from the other sessions)",
    "**The machine was slower this time.**",
    "| row | fourth session's code | fifth session's code |",
    "figures below were taken under a load average of 5-20",
    "could not be measured on an idle machine",
    "An earlier version of the pack put the goal inside a C-shaped obstacle.",
    "graph lives (it was a pass over every edge in every plan())",
    "so two configurations of one planner no longer collide.",
    "including the issue's reproduction (problem 136).",
    "Scalars and arrays used to be stored as JSON.",
    "the architecture of DESIGN.md",
])
def test_the_narration_pattern_catches_what_the_docs_used_to_say(line: str) -> None:
    assert NARRATION.search(line)


@pytest.mark.parametrize("line", [
    "Tuning proceeds in rounds: in each round every planner gets one new trial",
    "the ants move in lock step, one step each per round",
    "ground heights; a path bending round an obstacle",
    "| ggaco.case1, 1000 x 20: DEM 2.6 s + graph 4.4 s |",
])
def test_the_narration_pattern_leaves_reference_text_alone(line: str) -> None:
    assert not NARRATION.search(line)


def test_every_speed_table_names_the_script_that_regenerates_it() -> None:
    blocks = {}
    for page in doc_pages():
        text = page.read_text(encoding="utf-8")
        for match in BEGIN.finditer(text):
            script = BENCHMARKS / match.group("script")
            where = f"{page.relative_to(REPO_ROOT)}: {match.group(0)}"
            assert script.is_file(), f"{where}: no such script"
            source = script.read_text(encoding="utf-8")
            assert "add_write_docs_option" in source and page.relative_to(DOCS).as_posix() in source, (
                f"{where}: the script cannot rewrite this page (--write-docs)")
            assert text.find("<!-- end benchmark -->", match.end()) > 0, f"{where}: no end marker"
            blocks[script.name] = page
    assert {"speed.py", "harness.py", "exact.py"} <= set(blocks)


def test_write_docs_replaces_only_the_marked_block(tmp_path: Path) -> None:
    spec = importlib.util.spec_from_file_location("doc_table", BENCHMARKS / "doc_table.py")
    assert spec and spec.loader
    doc_table = importlib.util.module_from_spec(spec)
    sys.modules["doc_table"] = doc_table
    spec.loader.exec_module(doc_table)
    page = tmp_path / "page.md"
    page.write_text("# Title\n\nbefore\n\n<!-- benchmark: python benchmarks/x.py -->\n\n| old |\n\n"
                    "<!-- end benchmark -->\n\nafter\n", encoding="utf-8")
    doc_table.replace_table(page, "x.py", "| a | b |\n|---|---|\n| 1 | 2 |\n")
    assert page.read_text(encoding="utf-8") == (
        "# Title\n\nbefore\n\n<!-- benchmark: python benchmarks/x.py -->\n\n| a | b |\n|---|---|\n| 1 | 2 |\n\n"
        "<!-- end benchmark -->\n\nafter\n")
    with pytest.raises(SystemExit, match="no '<!-- benchmark: python benchmarks/y.py -->'"):
        doc_table.replace_table(page, "y.py", "| c |")
