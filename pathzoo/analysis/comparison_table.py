"""A paper-style comparison table (after Table 2 of the GGACO paper): medians, SDs, marks and w/t/l counts.

For each metric and scenario the table gives every configuration's median
and SD over successful runs, with a mark against a reference configuration
taken from :func:`pathzoo.analysis.stats.pairwise_tests` (Holm-corrected per
scenario and metric). As in the paper, marks and counts read from the
reference's side:

- ``↑``: the reference is significantly better than this configuration;
- ``↓``: the reference is significantly worse;
- ``≈``: no significant difference;
- ``n/s`` (in :attr:`PaperTable.table`; shown as no mark at all): not
  testable: with this many runs no outcome could reach the level after
  Holm's correction (see :func:`pathzoo.analysis.stats.min_pvalue`).

The w/t/l counts give, per metric and configuration, on how many scenarios
the reference wins, ties and loses. Unlike the paper, the success rate is
shown beside the medians (failed runs enter the tests as worst, see
``docs/statistics.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import pandas as pd

from pathzoo.analysis.formatting import format_number, format_percent, render_table
from pathzoo.analysis.frame import MetricInfo, metric_info
from pathzoo.analysis.stats import pairwise_tests
from pathzoo.analysis.summary import summarize
from pathzoo.core.errors import InvalidParameterError

__all__ = ["PaperTable", "PaperPart", "paper_table", "paper_part", "combine_paper_tables", "format_paper_table",
           "MARKS", "NOT_TESTABLE"]

MARKS = {"a": "↑", "b": "↓", "tie": "≈"}
"""Winner of a reference-vs-other test (reference is side ``a``) to the mark shown."""

NOT_TESTABLE = "n/s"
"""The mark of a comparison the run count cannot decide (instead of ``≈``)."""


@dataclass(frozen=True)
class PaperTable:
    """The paper-style table and its w/t/l summary.

    Attributes
    ----------
    table : DataFrame
        One row per (scenario, configuration), reference first: ``scenario,
        config, success_rate`` and for each metric ``<m>_median, <m>_sd,
        <m>_mark`` (the reference's marks are empty).
    wtl : DataFrame
        One row per (metric, configuration other than the reference):
        ``wins, ties, losses`` of the reference over the scenarios where the
        comparison was testable, and ``untestable`` (the other scenarios).
    reference : str
        The reference configuration.
    metrics : tuple of MetricInfo
        The metrics, in column order.
    alpha : float
        Significance level of the marks.
    """

    table: pd.DataFrame
    wtl: pd.DataFrame
    reference: str
    metrics: tuple[MetricInfo, ...]
    alpha: float


def paper_table(
    runs: pd.DataFrame,
    reference: str,
    metrics: Sequence[str | MetricInfo] = ("length", "planning_time", "energy"),
    *,
    alpha: float = 0.05,
    paired: bool | str = "auto",
) -> PaperTable:
    """Build the paper-style table.

    Parameters
    ----------
    runs : DataFrame
        One row per run.
    reference : str
        Configuration every other one is compared with (the paper's "proposed method").
    metrics : sequence of str or MetricInfo
        Registered metric ids, in column order (default: length, planning
        time and energy, the columns of GGACO's Table 2). A column of ``runs``
        that is not a registered metric is given as a :class:`MetricInfo`
        (its unit and direction).
    alpha : float
        Level of the Holm-corrected tests behind the marks.
    paired : bool or "auto"
        See :func:`pathzoo.analysis.stats.pair_by_seed`.

    Raises
    ------
    InvalidParameterError
        ``metrics`` is empty or ``reference`` is unknown.
    """
    if not metrics:
        raise InvalidParameterError("metrics must name at least one metric")
    infos = tuple(m if isinstance(m, MetricInfo) else metric_info(m) for m in metrics)
    return combine_paper_tables([paper_part(runs, reference, infos, alpha=alpha, paired=paired)], reference, infos,
                                alpha=alpha)


PaperPart = tuple[pd.DataFrame, pd.DataFrame]
"""The rows of a :class:`PaperTable`'s ``table`` and ``wtl`` for some whole scenarios (:func:`paper_part`)."""


def paper_part(runs: pd.DataFrame, reference: str | None, infos: Sequence[MetricInfo], *, alpha: float = 0.05,
               paired: bool | str = "auto") -> PaperPart:
    """The rows of the paper-style table for the scenarios of ``runs`` (combined by :func:`combine_paper_tables`).

    Parameters
    ----------
    runs : DataFrame
        The runs of some whole scenarios.
    reference : str, optional
        The reference configuration; None when it ran on none of these
        scenarios (then no row has a mark and no w/t/l is counted).
    infos : sequence of MetricInfo
        The metrics, in column order.
    alpha, paired
        As for :func:`paper_table`.
    """
    table = None
    wtl_rows = []
    for info in infos:
        if reference is None:
            tests = pd.DataFrame(columns=["scenario", "b", "winner", "testable"])
        else:
            tests = pairwise_tests(runs, info.id, direction=info.direction, reference=reference, alpha=alpha,
                                   paired=paired)
        summ = summarize(runs, info.id, direction=info.direction)[["scenario", "config", "success_rate", "median", "sd"]]
        marks = tests.assign(mark=tests["winner"].map(MARKS).where(tests["testable"].astype(bool), NOT_TESTABLE))
        marks = marks[["scenario", "b", "mark"]]
        summ = summ.merge(marks.rename(columns={"b": "config"}), on=["scenario", "config"], how="left")
        summ["mark"] = summ["mark"].fillna("")
        summ = summ.rename(columns={"median": f"{info.id}_median", "sd": f"{info.id}_sd", "mark": f"{info.id}_mark"})
        table = summ if table is None else table.merge(summ.drop(columns="success_rate"), on=["scenario", "config"])
        for cfg, g in tests.groupby("b", sort=True):
            decided = g[g["testable"].astype(bool)]
            counts = decided["winner"].value_counts()
            wtl_rows.append(dict(metric=info.id, config=cfg, wins=int(counts.get("a", 0)),
                                 ties=int(counts.get("tie", 0)), losses=int(counts.get("b", 0)),
                                 untestable=len(g) - len(decided)))
    assert table is not None
    return table, pd.DataFrame(wtl_rows, columns=list(_WTL_COLUMNS))


_WTL_COLUMNS = ("metric", "config", "wins", "ties", "losses", "untestable")


def combine_paper_tables(parts: Sequence[PaperPart], reference: str, infos: Sequence[MetricInfo], *,
                         alpha: float = 0.05) -> PaperTable:
    """The :class:`PaperTable` of :func:`paper_part` results of disjoint sets of whole scenarios.

    Parameters
    ----------
    parts : sequence of (DataFrame, DataFrame)
        At least one :func:`paper_part`; the scenarios of the parts do not overlap.
    reference : str
        The reference configuration.
    infos : sequence of MetricInfo
        The metrics the parts were built with.
    alpha : float
        Their level.
    """
    table = pd.concat([t for t, _ in parts], ignore_index=True)
    order = table["config"].ne(reference).astype(int)
    table = (
        table.assign(_o=order).sort_values(["scenario", "_o", "config"], kind="stable").drop(columns="_o")
        .reset_index(drop=True)
    )
    rows = pd.concat([w for _, w in parts if len(w)] or [parts[0][1]], ignore_index=True)
    if len(parts) > 1 and len(rows):  # counts over every part, metrics in column order, then configurations
        rank = {info.id: i for i, info in enumerate(infos)}
        rows = rows.groupby(["metric", "config"], sort=True, as_index=False)[list(_WTL_COLUMNS[2:])].sum()
        rows = rows.sort_values(["metric", "config"], key=lambda c: c.map(rank) if c.name == "metric" else c,
                                kind="stable").reset_index(drop=True)
    wtl = pd.DataFrame({c: rows[c] for c in _WTL_COLUMNS}, columns=list(_WTL_COLUMNS))
    return PaperTable(table=table, wtl=wtl, reference=reference, metrics=tuple(infos), alpha=alpha)


def format_paper_table(pt: PaperTable, fmt: str = "text") -> str:
    """Render a :class:`PaperTable`: the main table, then the w/t/l table, then the legend.

    Parameters
    ----------
    pt : PaperTable
        From :func:`paper_table`.
    fmt : {"text", "markdown", "csv", "html"}
        ``csv`` gives the main table then the w/t/l table, separated by a blank line.
    """
    t = pt.table
    display = pd.DataFrame({"scenario": t["scenario"].astype(str), "planner": t["config"].astype(str),
                            "success": t["success_rate"].map(format_percent)})
    for info in pt.metrics:
        m = info.id
        med = t[f"{m}_median"].map(format_number)
        mark = t[f"{m}_mark"]  # an untestable comparison shows its number bare (one note below says why)
        display[f"{info.label} median"] = [f"{v} {k}" if k and k != NOT_TESTABLE else v for v, k in zip(med, mark)]
        display[f"{info.label} SD"] = t[f"{m}_sd"].map(format_number)
    others = sorted(pt.wtl["config"].unique())
    wtl_display = pd.DataFrame({"metric": [i.label for i in pt.metrics]})
    for cfg in others:
        cells = []
        for info in pt.metrics:
            row = pt.wtl[(pt.wtl["metric"] == info.id) & (pt.wtl["config"] == cfg)]
            if not len(row):
                cells.append("–")
                continue
            cell = f"{row.wins.iloc[0]}/{row.ties.iloc[0]}/{row.losses.iloc[0]}"
            cells.append(cell + (f" +{row.untestable.iloc[0]} n/s" if row.untestable.iloc[0] else ""))
        wtl_display[cfg] = cells
    legend = [
        f"Median and SD over successful runs; marks compare {pt.reference} with each planner "
        f"(two-sided rank tests, Holm-corrected per scenario and metric, alpha={pt.alpha:g}).",
        f"↑: {pt.reference} significantly better; ↓: {pt.reference} significantly worse; ≈: no significant difference; "
        "no mark: not testable with this many runs (no outcome could reach alpha after the correction).",
        f"w/t/l: scenarios on which {pt.reference} wins/ties/loses against the planner of the column; "
        "+k n/s: scenarios where the run count could not decide.",
    ]
    if fmt == "csv":
        return render_table(display, fmt, raw=t) + "\n" + render_table(wtl_display, fmt, raw=pt.wtl)
    main = render_table(display, fmt, title=f"Comparison with {pt.reference}", left=("scenario", "planner"))
    counts = render_table(wtl_display, fmt, title=f"w/t/l of {pt.reference}", notes=legend, left=("metric",))
    return main + "\n" + counts
