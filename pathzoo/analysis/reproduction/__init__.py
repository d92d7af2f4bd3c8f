"""A paper's comparison table rerun: the paper's numbers as data, our runs beside them, a verdict per claim.

One module per step:

- :mod:`~pathzoo.analysis.reproduction.paper_data`: a paper's data file
  (the schema, the plugins that provide it, its reader);
- :mod:`~pathzoo.analysis.reproduction.runs`: the rerun through the harness
  (which planners can run, the experiments, runs labelled by the paper's
  planner keys);
- :mod:`~pathzoo.analysis.reproduction.verdicts`: the paper's table beside
  ours and one verdict per claim;
- :mod:`~pathzoo.analysis.reproduction.rendering`: that table as text or
  Markdown;
- :mod:`~pathzoo.analysis.reproduction.sections`: a generated section of a
  page (``docs/reproduction.md``) rewritten in place;
- :mod:`~pathzoo.analysis.reproduction.page_summary`: the page's summary
  table, read back from its paper sections (verdicts, CPU-hours);
- :mod:`~pathzoo.analysis.reproduction.estimate`: the expected CPU time of a
  full rerun, from a short pilot (``--estimate``).

The package names the steps' main entry points (reading a paper, running
it, comparing, rendering, rewriting a page); the pieces they are built
from are in their modules.
"""

from __future__ import annotations

from pathzoo.analysis.reproduction.paper_data import (
    PAPERS,
    PaperData,
    PaperDataError,
    load_paper,
    paper_file,
    paper_tables,
)
from pathzoo.analysis.reproduction.rendering import format_reproduction
from pathzoo.analysis.reproduction.runs import NOT_AVAILABLE, RerunOptions, planner_status, run_paper
from pathzoo.analysis.reproduction.sections import replace_section
from pathzoo.analysis.reproduction.verdicts import RIVAL_FAILED, Reproduction, compare_paper

__all__ = [
    "PAPERS",
    "NOT_AVAILABLE",
    "RIVAL_FAILED",
    "PaperDataError",
    "PaperData",
    "Reproduction",
    "RerunOptions",
    "paper_file",
    "paper_tables",
    "load_paper",
    "planner_status",
    "run_paper",
    "compare_paper",
    "format_reproduction",
    "replace_section",
]
