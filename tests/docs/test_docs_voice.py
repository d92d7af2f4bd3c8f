"""``docs/`` is reference for users: no lab notebook, and every speed table comes from its benchmark script.

How a figure was reached (numbered rounds, sessions, A/B tables, the load
of the machine it was measured on) belongs in the git log. A speed table
sits between the markers of ``benchmarks/doc_table.py`` and names the
script that rewrites it with ``--write-docs``; prose gives no speed figure
of pathzoo's own code, it says what dominates and links to the table.
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


_NUMBER = r"(?<![\w.])\d[\d,.]*(?:\s*[-–]\s*\d[\d,.]*)?"
_SECONDS = r"(?:s|secs?|seconds?)\b(?!/)"
HAND_TIMING = re.compile(
    r"(?:\babout|\baround|\broughly|~|≈|\bnearly|\balmost)\s*" + _NUMBER
    + r"\s*(?:CPU\s*)?(?:ns|µs|μs|us|ms|" + _SECONDS + r")"  # "about 0.1 s"
    r"|" + _NUMBER + r"\s*(?:ns|µs|μs|us|ms)\b(?!/)"  # "1.4 ms", "6 ns"
    r"|" + _NUMBER + r"\s*CPU\s*(?:ms|" + _SECONDS + r")"  # "4-5 CPU s"
    r"|" + _NUMBER + r"\s*(?:ms|" + _SECONDS + r")\s*(?:of\s+)?CPU\b"  # "0.03 s CPU", "7.7 s of CPU"
    r"|" + _NUMBER + r"\s*(?:x|×|times|%)\s+(?:faster|slower|quicker)\b"  # "150x faster"
    r"|" + _NUMBER + r"\s*(?-i:[kM])?\s*(?:[a-z-]{2,})?\s*/\s*s\b"  # "1,100 writes/s", "3.1 M/s", not "2 m/s"
    r"|" + _NUMBER + r"\s*(?-i:[kM])?\s*(?:[a-z-]{2,}\s+)?per\s+(?:CPU\s+)?second\b"
    r"|\b(?:takes?|took|costs?|loads?\s+in|builds?\s+in|runs?\s+in)\s+" + _NUMBER + r"\s*" + _SECONDS,
    re.IGNORECASE)
"""A speed figure typed into prose: an approximate or sub-second time, CPU seconds, a rate, "Nx faster"."""

KEPT_TIMING = re.compile(
    r"target|budget|limit|timeout|killed|toleran|paper|sized to|more than about|\bat (?:least|most)\b"
    r"|\bevery \d+ ms\b",
    re.IGNORECASE)
"""A line with a time that is a setting, not a measurement: a target, a budget or limit, a paper's figure."""

GENERATED = re.compile(r"<!-- (?:benchmark: python benchmarks/[\w.]+\.py|reproduce:\w+:begin) -->")
GENERATED_END = re.compile(r"<!-- (?:end benchmark|reproduce:\w+:end) -->")


def hand_typed_timings(text: str) -> list[tuple[int, str]]:
    """Line numbers and matches of :data:`HAND_TIMING` outside generated blocks, on lines not :data:`KEPT_TIMING`."""
    found, generated = [], False
    for number, line in enumerate(text.splitlines(), 1):
        if GENERATED.search(line) or GENERATED_END.search(line):
            generated = bool(GENERATED.search(line))
            continue
        match = None if generated or KEPT_TIMING.search(line) else HAND_TIMING.search(line)
        if match:
            found.append((number, match.group(0)))
    return found


def test_the_docs_type_no_timing_by_hand() -> None:
    found = []
    for page in [*doc_pages(), REPO_ROOT / "README.md"]:
        for number, figure in hand_typed_timings(page.read_text(encoding="utf-8")):
            found.append(f"{page.relative_to(REPO_ROOT)}:{number}: {figure!r}")
    assert not found, ("a timing typed by hand (it belongs in a benchmark's generated block, "
                       "see benchmarks/doc_table.py; link to it instead):\n" + "\n".join(found))


@pytest.mark.parametrize("line", [
    "(2569 x 1919 cells, 29.6 million edges) the graph loads in about 0.1 s instead",
    "On ggaco.case1 a build and store takes about 4-5 CPU s in a fresh process",
    "the CPU time of the 100 x 100 setting is about 0.06 s, 150x faster than the",
    "`8room_000` this is about 1.5 times faster than an indexed heap with",
    "0.5-1 ms per run with every plugin loaded (4,400 namespaces, 75,000",
    "inserts at about 1,100 writes/s, under 1 % of the sweep's time; judging",
    "Python-to-C++ call per motion that planning never makes): 1.10-1.13 M/s.",
    "the hardest problems (roughly 11 M expansions per CPU second against",
    "- **GGACO.** No claim can be decided. MOSFLA needs 66-91 s CPU per plan with only 5",
    "1.56-2.93 M steps and 7.7-26.0 s of CPU (median 14.4 s):",
    "optimum took 20-50 s here, and 1.3 GB of memory for case 3 (the largest case has",
    "| `ggaco.hugo` | 90° | 14 964.2 | 1 388 / 2 054 | 1 ms |",
])
def test_the_timing_pattern_catches_hand_typed_figures(line: str) -> None:
    assert hand_typed_timings(line)


@pytest.mark.parametrize("line", [
    "| `check_budget_time` | with `Budget(time_s=0.3)` `plan()` returns within 0.3 s + 1 s tolerance |",
    "from the test process, killed after 60 s (`pathzoo.testing.checks.CHECK_LIMIT_S`),",
    "**Time.** The paper reports 21 s (MATLAB) for its setting; the CPU time",
    "at most 20 ms, slowest at most 500 ms, every problem solved), beside Theta*",
    "  reads the CPU clock every 10 ms, so a planner that checks its clock often",
    "| cruise speed `v` | `cruise_speed` | 2 m/s | G-Ant Table 3 |",
    "With the defaults a right angle adds 0.5 s and 45 J, a U-turn 2 s and 60 J.",
    "cells are the slowest of the rerun even at 5 iterations, so a rerun within 10 min of CPU",
    "<!-- benchmark: python benchmarks/x.py -->\n| plan() | 0.2 s CPU |\n<!-- end benchmark -->",
    "<!-- reproduce:gant_bound:begin -->\nThe exact Dijkstra took 0.62 s CPU.\n<!-- reproduce:gant_bound:end -->",
])
def test_the_timing_pattern_leaves_settings_and_generated_blocks_alone(line: str) -> None:
    assert not hand_typed_timings(line)


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
