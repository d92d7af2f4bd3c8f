"""A :class:`~pathzoo.analysis.reproduction.verdicts.Reproduction` as text or Markdown tables, with its legend."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pathzoo.analysis.formatting import format_number, format_percent, render_table
from pathzoo.analysis.reproduction.paper_data import PaperPlanner
from pathzoo.analysis.reproduction.verdicts import RIVAL_FAILED, VERDICTS, Reproduction
from pathzoo.core.errors import InvalidParameterError

__all__ = ["format_reproduction"]


def _cell(value: float, digits: int = 5) -> str:
    return format_number(value, digits) if np.isfinite(value) else "–"


def _percent(value: float) -> str:
    return format_percent(value) if np.isfinite(value) else "–"


def _planner_cell(p: PaperPlanner) -> str:
    variant = f", on the {p.variant.strip('_')} variant" if p.variant else ""
    return f"{p.label} ({p.id}{variant})"


def format_reproduction(rep: Reproduction, fmt: str = "text") -> str:
    """Render a :class:`Reproduction`: one table per metric, the w/t/l counts, the notes.

    Parameters
    ----------
    rep : Reproduction
    fmt : {"text", "markdown"}
    """
    if fmt not in ("text", "markdown"):
        raise InvalidParameterError(f"format must be 'text' or 'markdown', got {fmt!r}")
    paper = rep.paper
    stat = paper.statistic
    parts = []
    ref_label = paper.planner(paper.reference).label
    for m in paper.metrics:
        t = rep.table[rep.table["metric"] == m.id]
        if not len(t):
            continue
        blank = t["status"] != ""
        display = pd.DataFrame({
            "scenario": t["scenario"].astype(str),
            "planner": [_planner_cell(paper.planner(k)) for k in t["planner"]],
            f"paper {stat}": [_cell(v) + (f" {k}" if k else "") for v, k in zip(t["paper_value"], t["paper_mark"])],
            "paper SD": t["paper_sd"].map(_cell),
            "ours median": [s if s else _cell(v) + (f" {k}" if k else "")
                            for s, v, k in zip(t["status"], t["median"], t["mark"])],
            "ours SD": [("" if b else _cell(v)) for b, v in zip(blank, t["sd"])],
        })
        if stat == "mean":
            display["ours mean"] = [("" if b else _cell(v)) for b, v in zip(blank, t["mean"])]
        display["success"] = [("" if b else format_percent(v) if np.isfinite(v) else "–")
                              for b, v in zip(blank, t["success_rate"])]
        display["runs"] = [("" if b else str(n)) for b, n in zip(blank, t["n_runs"])]
        display["success ref : this"] = [
            "" if b or not v else f"{_percent(r)} : {_percent(s)}"
            for b, v, r, s in zip(blank, t["verdict"], t["ref_success_rate"], t["success_rate"])
        ]
        display["verdict"] = t["verdict"].to_numpy()
        parts.append(render_table(display, fmt, title=f"{paper.table}, {m.label}",
                                  left=("scenario", "planner", "ours median", "verdict")))
    wtl = pd.DataFrame({"metric": rep.wtl["metric"], "rival": [paper.planner(k).label for k in rep.wtl["planner"]],
                        "paper w/t/l": rep.wtl["paper"], "ours w/t/l": rep.wtl["ours"]})
    claims = rep.table.loc[rep.table["verdict"].ne("") & rep.table["verdict"].ne("no claim"), "verdict"]
    counts = claims.str.split(":").str[0].value_counts()
    legend = [
        f"Claims: {len(claims)}; " + ", ".join(f"{k} {int(counts.get(k, 0))}" for k in VERDICTS) + ".",
        f"Source: {paper.title}, {paper.table} ({paper.statistic} of {paper.runs} runs). Ours: {rep.seeds} "
        f"run(s) per planner and scenario{'' if rep.seeds >= paper.runs else ' (fewer than the paper)'}.",
        f"Marks read from {ref_label}'s side: ↑ it is better, ↓ worse, ≈ no significant difference. Paper marks "
        "are the printed ones, else from its numbers; ours from two-sided rank tests "
        f"(Holm-corrected per scenario and metric, alpha={rep.alpha:g}; failed runs rank worst).",
        "Verdict per claim: holds (same mark), not shown (we find no significant difference), reversed, "
        "differs (the paper has ≈), not testable (rival not reconstructed or not run). "
        f"'{RIVAL_FAILED}': the rival solved at most half of its runs and fewer than {ref_label}; failed runs "
        "rank worst, so the claim says nothing about the paths the rival finds. "
        f"success ref : this: the success rates of {ref_label} and of the row's planner beside every verdict.",
        f"Claim: {paper.claim}",
        *paper.notes,
    ]
    if fmt == "markdown":
        legend = [f"- {line}" for line in legend]
    parts.append(render_table(wtl, fmt, title=f"w/t/l of {ref_label} over the scenarios", notes=legend,
                              left=("metric", "rival")))
    return "\n".join(parts)
