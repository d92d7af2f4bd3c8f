"""The leaderboard: configurations ranked within each scenario by one metric.

Ranking rule
------------
Within a scenario, configurations are ordered by

1. the **penalized median** of the metric: the median over *all* runs, where
   a run that did not succeed (no path, failed, invalid, crash, timeout)
   counts as worse than every successful run (``+inf`` for a metric to
   minimise, ``-inf`` for one to maximise). It is finite only when more than
   half of the runs succeeded, so a configuration that fails most of the time
   can never outrank one that mostly succeeds;
2. then the **success rate** (higher first), which separates configurations
   whose penalized medians are both infinite;
3. then the **median over successful runs**.

Configurations equal on all three keys share a rank (competition ranking:
1, 2, 2, 4). Metric values are compared to 12 significant digits
(:func:`pathzoo.analysis.frame.round_measurements`), so two planners whose
lengths differ only by floating-point summation order tie. Success rate is always reported in its own column; the median,
IQR and SD columns describe successful runs only.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from pathzoo.analysis.formatting import format_number, format_percent, render_table
from pathzoo.analysis.frame import Direction, with_config
from pathzoo.analysis.hybrid import HYBRID_MARK, HYBRID_NOTE, hybrid_planners
from pathzoo.analysis.path_models import MODEL_RATIO, REFERENCE_COLUMN, with_model_ratio
from pathzoo.analysis.summary import summarize
from pathzoo.core.budget import CLOCK_STOPS

__all__ = ["leaderboard", "format_leaderboard", "clock_stops", "power_note", "RANKING_RULE", "MODEL_RATIO_NOTE",
           "CLOCK_MARK", "CLOCK_NOTE"]

RANKING_RULE = (
    "Rank within each scenario: penalized median (failed runs count as worst), "
    "then success rate, then median of successful runs. "
    "Median, IQR and SD use successful runs only."
)

MODEL_RATIO_NOTE = (
    "model_ratio: length (on dynamic maps: arrival time) over the optimum of the planner's own path model; "
    "'optimum' names it: graph optimum (moves between neighbouring cells), any-angle optimum (straight segments "
    "in any direction), earliest arrival of SIPP (dynamic maps)."
)

CLOCK_MARK = " (clock)"
"""Appended to a configuration whose runs include some a clock limit ended."""

CLOCK_NOTE = (
    "(clock): some runs of this configuration were ended by a clock limit (cpu_s or time_s), "
    "so their results depend on the machine and its load; see docs/timing.md."
)

_VERDICT_NOTE = (
    "vs reference: this configuration is significantly better/worse than the reference "
    "(two-sided test, Holm-corrected per scenario, alpha={alpha:g}), else tie; "
    "n/s = not testable with this many runs (no outcome could reach alpha after the correction); "
    "A12 = P(this run beats a reference run), ties count half."
)


def power_note(table: pd.DataFrame) -> str:
    """One sentence when some comparisons of a leaderboard are ``n/s``: how many, and the runs they would need."""
    if "vs_reference" not in table.columns:
        return ""
    ns = table[table["vs_reference"] == "n/s"]
    if ns.empty:
        return ""
    need = int(ns["runs_needed"].max())
    have = int(ns["n_runs"].min())
    return (
        f"{len(ns)} comparison(s) marked n/s: with {have} run(s) per planner no result can be significant at "
        f"alpha={table.attrs.get('alpha', 0.05):g} after Holm's correction; run at least {need} seeds. "
        "A12 still shows the direction and size of each difference."
    )


def _rank_within(summary: pd.DataFrame, direction: Direction) -> pd.Series:
    sign = 1.0 if direction == "min" else -1.0
    keys = pd.DataFrame(
        {
            "pen": sign * summary["penalized_median"].astype(float),
            "rate": -summary["success_rate"].astype(float),
            "med": (sign * summary["median"].astype(float)).fillna(np.inf),
        },
        index=summary.index,
    )
    ranks = pd.Series(0, index=summary.index, dtype=int)
    for _, idx in summary.groupby("scenario").groups.items():
        k = keys.loc[idx].sort_values(["pen", "rate", "med"])
        tuples = list(k.itertuples(index=False, name=None))
        r = [1]
        for i in range(1, len(tuples)):
            r.append(r[-1] if tuples[i] == tuples[i - 1] else i + 1)
        ranks.loc[k.index] = np.asarray(r)
    return ranks


def leaderboard(
    runs: pd.DataFrame,
    metric: str = "length",
    *,
    direction: Direction | None = None,
    reference: str | None = None,
    alpha: float = 0.05,
    paired: bool | str = "auto",
) -> pd.DataFrame:
    """Rank configurations within each scenario by one metric.

    Parameters
    ----------
    runs : DataFrame
        One row per run (``pathzoo.harness.store.read_runs``).
    metric : str
        Metric id to rank by (see ``pathzoo list metrics``), or ``"model_ratio"``:
        the ratio to the optimum of each planner's own path model
        (:func:`pathzoo.analysis.path_models.with_model_ratio`), with an
        ``optimum`` column naming that reference.
    direction : {"min", "max"}, optional
        Override the metric's registered direction.
    reference : str, optional
        A configuration label (planner id, or ``planner@hash`` when a planner
        ran with several parameter sets). When given, every other
        configuration is tested against it (see
        :func:`pathzoo.analysis.stats.pairwise_tests`) and the columns
        ``vs_reference`` (``better``/``worse``/``tie``, or ``n/s`` when the
        number of runs cannot reach ``alpha`` after Holm's correction whatever
        the data), ``p_holm``, ``a12`` and ``runs_needed`` (runs per planner
        that would make the comparison testable) are added.
    alpha : float
        Significance level for ``vs_reference``.
    paired : bool or "auto"
        Passed to :func:`~pathzoo.analysis.stats.pairwise_tests`.

    Returns
    -------
    DataFrame
        Columns ``scenario, rank, planner, config, params_hash, n_runs,
        success_rate, median, iqr, sd, clock_stops`` (plus the reference
        columns; ``clock_stops`` counts the runs a clock limit ended, whose
        results depend on the machine: ``docs/timing.md``), sorted
        by scenario and rank. ``attrs["metric"]`` is the metric's
        :class:`~pathzoo.analysis.frame.MetricInfo`; ``attrs["reference"]``
        and ``attrs["alpha"]`` are set too. See the module docstring for the
        ranking rule.
    """
    if metric == MODEL_RATIO and MODEL_RATIO not in runs.columns:
        runs = with_model_ratio(runs)
    summary = summarize(runs, metric, direction=direction)
    info = summary.attrs["metric"]
    summary["rank"] = _rank_within(summary, info.direction)
    cols = ["scenario", "rank", "planner", "config", "params_hash", "n_runs", "success_rate", "median", "iqr", "sd"]
    table = summary[cols].merge(clock_stops(runs, metric), on=["scenario", "config"], how="left")
    if reference is not None:
        from pathzoo.analysis.stats import pairwise_tests

        tests = pairwise_tests(runs, metric, direction=info.direction, reference=reference, alpha=alpha, paired=paired)
        verdict = {"a": "worse", "b": "better", "tie": "tie"}
        other = tests[["scenario", "b", "p_holm", "a12", "winner", "testable", "runs_needed"]].rename(
            columns={"b": "config"}
        )
        other["a12"] = 1.0 - other["a12"]  # P(this beats the reference)
        other["vs_reference"] = other["winner"].map(verdict).where(other["testable"].astype(bool), "n/s")
        table = table.merge(other.drop(columns=["winner", "testable"]), on=["scenario", "config"], how="left")
        table["runs_needed"] = table["runs_needed"].astype("Int64")  # no float 8.0 in CSV/JSON
        table.loc[table["config"] == reference, "vs_reference"] = "reference"
    if REFERENCE_COLUMN in runs.columns:
        table = table.merge(_references_used(runs), on=["scenario", "config"], how="left")
    table = table.sort_values(["scenario", "rank", "config"], kind="stable").reset_index(drop=True)
    table.attrs.update(metric=info, reference=reference, alpha=alpha)
    return table


def _references_used(runs: pd.DataFrame) -> pd.DataFrame:
    """``scenario, config, optimum``: the reference(s) each configuration's ratio divides by, joined by "; "."""
    df = with_config(runs)
    names = df[REFERENCE_COLUMN].fillna("").astype(str)
    grouped = names.groupby([df["scenario"], df["config"]]).agg(lambda s: "; ".join(sorted({v for v in s if v})))
    return grouped.rename("optimum").reset_index()


def clock_stops(runs: pd.DataFrame, metric: str = "length") -> pd.DataFrame:
    """Per scenario and configuration, the number of runs a clock limit ended (``stopped_by`` cpu_time or wall_time)."""
    df = with_config(runs, metric)
    stopped = df["stopped_by"].isin(CLOCK_STOPS) if "stopped_by" in df.columns else pd.Series(False, index=df.index)
    counts = stopped.groupby([df["scenario"], df["config"]]).sum().astype(int)
    return counts.rename("clock_stops").reset_index()


def format_leaderboard(table: pd.DataFrame, fmt: str = "text") -> str:
    """Render a :func:`leaderboard` table.

    Parameters
    ----------
    table : DataFrame
        The output of :func:`leaderboard`.
    fmt : {"text", "markdown", "csv", "html"}
        ``csv`` keeps full precision; the others show 5 significant figures,
        a title naming the metric and its direction, and the ranking rule.

    Returns
    -------
    str
    """
    info = table.attrs.get("metric")
    label = info.label if info is not None else "metric"
    hybrids = hybrid_planners(table["planner"].astype(str)) if "planner" in table.columns else set()
    names = table["config"].astype(str)
    if hybrids:
        marked = table["planner"].astype(str).isin(hybrids)
        names = names.where(~marked, names + f" {HYBRID_MARK}")
    display = pd.DataFrame(
        {
            "scenario": table["scenario"].astype(str),
            "rank": table["rank"].astype(str),
            "planner": names + np.where(table["clock_stops"] > 0, CLOCK_MARK, ""),
            "runs": table["n_runs"].astype(str),
            "success": table["success_rate"].map(format_percent),
            "median": table["median"].map(format_number),
            "IQR": table["iqr"].map(format_number),
            "SD": table["sd"].map(format_number),
        }
    )
    notes = [RANKING_RULE]
    if "optimum" in table.columns:
        display["optimum"] = table["optimum"].fillna("").astype(str)
        notes.append(MODEL_RATIO_NOTE)
    if hybrids:
        notes.append(HYBRID_NOTE)
    if (table["clock_stops"] > 0).any():
        notes.append(CLOCK_NOTE)
    if "vs_reference" in table.columns:
        display["vs ref"] = table["vs_reference"].fillna("–")
        display["p (Holm)"] = table["p_holm"].map(lambda x: format_number(x, 2))
        display["A12"] = table["a12"].map(lambda x: f"{x:.2f}" if pd.notna(x) else "–")
        notes.append(_VERDICT_NOTE.format(alpha=table.attrs.get("alpha", 0.05)))
        note = power_note(table)
        if note:
            notes.append(note)
    title = f"Leaderboard: {label}" + (f", {info.better}" if info is not None else "")
    return render_table(
        display, fmt, raw=table, title=title, notes=notes, left=("scenario", "planner", "vs ref")
    )
