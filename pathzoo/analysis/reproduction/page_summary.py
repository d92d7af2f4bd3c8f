"""The summary table of a page's generated paper sections: per paper, the rerun's setting, its verdicts and CPU-hours.

``pathzoo reproduce PAPER --markdown FILE`` writes the paper's section (see
:mod:`pathzoo.cli.cmd_reproduce`), whose generated lines say how it relates
to the paper's setting, count its claims per verdict and give the CPU-hours of
its stored runs. The summary is read back from those lines of every paper's
section on the page, so it is never typed by hand; it is rewritten between
the markers ``<!-- reproduce:summary:begin/end -->`` when the page has them.
"""

from __future__ import annotations

import re
from pathlib import Path

import pandas as pd

from pathzoo.analysis.formatting import format_number, render_table
from pathzoo.analysis.reproduction.sections import replace_section
from pathzoo.analysis.reproduction.verdicts import VERDICTS

__all__ = ["SUMMARY", "CPU_SENTENCE", "cpu_sentence", "summary_rows", "summary_table", "write_summary"]

SUMMARY = "summary"
"""The name of the summary's block on the page (``<!-- reproduce:summary:begin -->``)."""

CPU_SENTENCE = "Its {runs} stored runs took {hours} CPU-hours (the sum of their CPU times)."
"""The sentence of a section's header that gives the CPU time of its runs."""

_CPU = re.compile(r"Its (\d+) stored runs took ([0-9.eE+-]+) CPU-hours")
_SEEDS = re.compile(r"from (\d+) run\(s\) per planner and scenario \(the paper: (\d+)\)")
_REDUCED = re.compile(r"\*\*Reduced rerun:\*\* (.*?)\. Its verdicts")
_CLAIMS = re.compile(r"Claims: (\d+); " + ", ".join(rf"{v} (\d+)" for v in VERDICTS) + r"\.")


def cpu_sentence(runs: int, cpu_s: float) -> str:
    """The header's sentence on the CPU time of a section's ``runs`` stored runs, ``cpu_s`` seconds in all."""
    return CPU_SENTENCE.format(runs=runs, hours=format_number(cpu_s / 3600.0, 3))


def _blocks(page: str) -> list[tuple[str, str]]:
    """The generated sections of the page as (name, text), in page order."""
    return re.findall(r"<!-- reproduce:([A-Za-z0-9_.-]+):begin -->\n(.*?)<!-- reproduce:\1:end -->", page,
                      flags=re.S)


def summary_rows(page: str, papers: list[str] | tuple[str, ...]) -> pd.DataFrame:
    """One row per section of the page named in ``papers``: heading, setting, claims per verdict, CPU-hours.

    A section without a claims line is skipped; one written before its
    header gave the CPU time shows ``not recorded`` there.
    """
    rows = []
    for name, text in _blocks(page):
        claims = _CLAIMS.search(text)
        if name not in papers or not claims:
            continue
        heading = next((line[4:] for line in text.splitlines() if line.startswith("### ")), name)
        seeds, reduced, cpu = _SEEDS.search(text), _REDUCED.search(text), _CPU.search(text)
        runs = f"{seeds.group(1)} runs" if seeds else ""
        setting = f"reduced: {reduced.group(1)}" if reduced else f"paper's setting ({runs})" if runs else ""
        row = {"paper, table": heading, "rerun": setting, "claims": claims.group(1)}
        row.update({v: claims.group(i + 2) for i, v in enumerate(VERDICTS)})
        row["CPU-hours"] = cpu.group(2) if cpu else "not recorded"
        rows.append(row)
    return pd.DataFrame(rows, columns=["paper, table", "rerun", "claims", *VERDICTS, "CPU-hours"])


def summary_table(page: str, papers: list[str] | tuple[str, ...]) -> str:
    """The summary of the page's paper sections as a Markdown table, with a line on where it comes from."""
    table = render_table(summary_rows(page, papers), "markdown", left=("paper, table", "rerun"))
    return ("Generated from the paper sections below each time one is written (`pathzoo reproduce PAPER "
            "--markdown`); CPU-hours: the sum of the CPU times of the runs a section was computed from. "
            "Do not edit by hand.\n\n" + table.rstrip("\n") + "\n")


def write_summary(path: str | Path, papers: list[str] | tuple[str, ...]) -> bool:
    """Rewrite the summary block of the page ``path`` from its paper sections; False when it has no summary block."""
    page = Path(path).read_text(encoding="utf-8")
    if f"<!-- reproduce:{SUMMARY}:begin -->" not in page:
        return False
    replace_section(path, SUMMARY, summary_table(page, papers))
    return True
