"""The verdicts of a rerun: the paper's table beside ours, one verdict per claim.

:func:`compare_paper` builds the table with
:func:`pathzoo.analysis.comparison_table.paper_table` (medians, SDs, marks
from Holm-corrected rank tests, w/t/l) and derives the verdicts:

- a **claim** is one (scenario, rival, metric) cell: the paper says the
  proposed method is better (``↑``), worse (``↓``) or equal (``≈``) than the
  rival there, by its printed mark or else by its numbers;
- its **verdict** compares our mark with the paper's: ``holds`` (same),
  ``not shown`` (the paper has ↑ or ↓, our test finds no significant
  difference), ``reversed`` (opposite), ``differs`` (the paper has ≈, our
  test finds a difference) or ``not testable`` (the rival is not available).

A planner id that is not registered is listed as "not available (not
reconstructed)" with the paper's numbers; it is never dropped.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import pandas as pd

from pathzoo.analysis.comparison_table import NOT_TESTABLE, paper_table
from pathzoo.analysis.frame import MetricInfo, success_mask
from pathzoo.analysis.reproduction.paper_data import PAPER_MARKS, PaperData
from pathzoo.analysis.reproduction.runs import NOT_AVAILABLE, planner_status

__all__ = ["VERDICTS", "RIVAL_FAILED", "Reproduction", "compare_paper"]

VERDICTS = ("holds", "not shown", "reversed", "differs", "not testable")
"""The verdicts of a claim (a ``not testable`` one says why after a colon)."""


@dataclass(frozen=True)
class Reproduction:
    """The paper's table with our numbers beside it.

    Attributes
    ----------
    paper : PaperData
    table : DataFrame
        One row per (metric, scenario, planner): the paper's ``paper_value,
        paper_sd, paper_mark`` and our ``median, sd, mean, success_rate,
        n_runs, mark`` (in the paper's unit), ``ref_success_rate`` (the
        reference's on that scenario), ``status`` (empty, or why the planner
        did not run) and ``verdict`` (rivals only; :data:`RIVAL_FAILED` for a
        claim that holds only because the rival failed most runs).
    wtl : DataFrame
        Per (metric, rival): the paper's and our wins/ties/losses of the
        reference over the scenarios.
    seeds : int
        Runs per planner and scenario behind our numbers.
    alpha : float
    """

    paper: PaperData
    table: pd.DataFrame
    wtl: pd.DataFrame
    seeds: int
    alpha: float


def _paper_direction(ref: float, other: float, mark: str) -> str:
    if mark:
        return mark
    if math.isnan(ref) or math.isnan(other):
        return ""
    return "↑" if ref < other else "↓" if ref > other else "≈"


def _verdict(paper_mark: str, ours: str, status: str, has_runs: bool) -> str:
    if status:
        return "not testable: " + ("rival not reconstructed" if status == NOT_AVAILABLE else "rival not run")
    if not paper_mark:
        return "no claim"
    if not has_runs or not ours:
        return "not testable: no runs"
    if ours == NOT_TESTABLE:
        return "not testable: too few runs"
    if ours == paper_mark:
        return "holds"
    if paper_mark == "≈":
        return "differs"
    return "not shown" if ours == "≈" else "reversed"


RIVAL_FAILED = "holds: only because the rival failed"
"""Verdict of a claim that holds while the rival solved at most half of its runs and fewer than the reference:
its failures rank worst, so the claim says nothing about the paths it finds."""


def _with_reference_success(table: pd.DataFrame, reference: str) -> pd.DataFrame:
    """Add ``ref_success_rate`` (the reference's on the same metric and scenario); mark a "holds" resting on failures."""
    if table.empty:
        return table.assign(ref_success_rate=pd.Series(dtype=float))
    ref = table[table["planner"] == reference].set_index(["metric", "scenario"])["success_rate"]
    keys = list(zip(table["metric"], table["scenario"]))
    table["ref_success_rate"] = [float(ref.get(k, math.nan)) for k in keys]
    rival_failed = ((table["verdict"] == "holds") & (table["paper_mark"] == "↑")
                    & (table["success_rate"] <= 0.5) & (table["success_rate"] < table["ref_success_rate"]))
    table.loc[rival_failed, "verdict"] = RIVAL_FAILED
    return table


def compare_paper(paper: PaperData, runs: pd.DataFrame, *, alpha: float = 0.05) -> Reproduction:
    """Build the side-by-side table and the verdicts from labelled runs (:func:`run_paper`)."""
    ours = None
    if len(runs):
        # derived metrics are columns the reproduction adds, not registered metrics: unit 1, lower is better
        metrics = [MetricInfo(m.id, "1", "min") if m.derived else m.id for m in paper.metrics]
        pt = paper_table(runs, paper.reference, metrics, alpha=alpha)
        ours = pt.table
    by_id = {v: k for k, v in paper.scenarios.items()}
    ran = set(runs["scenario"].unique()) if len(runs) else set()
    rows = []
    for m in paper.metrics:
        for skey, sid in paper.scenarios.items():
            if sid not in ran:
                continue
            pv = paper.values[(paper.values["scenario"] == skey) & (paper.values["metric"] == m.id)]
            ref_values = pv.loc[pv["planner"] == paper.reference, "value"]
            ref_val = float(ref_values.iloc[0]) if len(ref_values) else math.nan
            for p in paper.planners:
                status = planner_status(p)
                row = pv[pv["planner"] == p.key]
                paper_value = float(row["value"].iloc[0]) if len(row) else math.nan
                paper_sd = float(row["sd"].iloc[0]) if len(row) else math.nan
                is_ref = p.key == paper.reference
                paper_mark = "" if is_ref else _paper_direction(ref_val, paper_value,
                                                                str(row["mark"].iloc[0]) if len(row) else "")
                rec: dict[str, Any] = dict(
                           metric=m.id, scenario=by_id[sid], scenario_id=sid, planner=p.key, label=p.label,
                           planner_id=p.id, status=status, paper_value=paper_value, paper_sd=paper_sd,
                           paper_mark=paper_mark, median=math.nan, sd=math.nan, mean=math.nan,
                           success_rate=math.nan, n_runs=0, mark="")
                sub = runs[(runs["planner"] == p.key) & (runs["scenario"] == sid)] if len(runs) else runs
                if not status and len(sub) and ours is not None:
                    o = ours[(ours["config"] == p.key) & (ours["scenario"] == sid)]
                    if len(o):
                        vals = sub.loc[success_mask(sub), m.id].astype(float)
                        rec.update(median=float(o[f"{m.id}_median"].iloc[0]) * m.scale,
                                   sd=float(o[f"{m.id}_sd"].iloc[0]) * m.scale,
                                   mean=float(vals.mean()) * m.scale if len(vals) else math.nan,
                                   success_rate=float(o["success_rate"].iloc[0]), n_runs=len(sub),
                                   mark=str(o[f"{m.id}_mark"].iloc[0]))
                if not status and rec["n_runs"] == 0:
                    rec["status"] = status = "not run: the planner does not handle this scenario kind"
                rec["verdict"] = "" if is_ref else _verdict(paper_mark, rec["mark"], status, rec["n_runs"] > 0)
                rows.append(rec)
    table = _with_reference_success(pd.DataFrame(rows), paper.reference)
    wtl_rows = []
    for (metric, planner), g in table[table["planner"] != paper.reference].groupby(["metric", "planner"], sort=False):
        count = {k: (g["paper_mark"] == k).sum() for k in PAPER_MARKS}
        ours_count = {k: (g["mark"] == k).sum() for k in PAPER_MARKS}
        tested = bool(g["status"].eq("").all())
        wtl_rows.append(dict(metric=metric, planner=planner,
                             paper=f"{count['↑']}/{count['≈']}/{count['↓']}",
                             ours=f"{ours_count['↑']}/{ours_count['≈']}/{ours_count['↓']}" if tested else "–"))
    seeds = int(runs.groupby(["planner", "scenario"]).size().max()) if len(runs) else 0
    wtl = pd.DataFrame(wtl_rows, columns=["metric", "planner", "paper", "ours"])
    return Reproduction(paper=paper, table=table, wtl=wtl,
                        seeds=seeds, alpha=alpha)

