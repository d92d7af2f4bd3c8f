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
1, 2, 2, 4).

Path models
-----------
A grid planner's length and an any-angle planner's length are not measured
against the same optimum, so a raw metric never ranks planners of different
path models together: the ranking is made within each scenario *and path
model* (one section per model, rows sorted by model), and the table says so.
Ranked by ``model_ratio`` (each planner over the optimum of its own model)
all models share one ranking.

Work
----
Every row carries its path model, the median CPU seconds and the median
evaluations of its runs (``path_model``, ``median_cpu_s``,
``median_evaluations`` in CSV and JSON). When the median CPU of the ranked
rows of a scenario differs by more than :data:`CPU_SPREAD_LIMIT` times (CPU
below 1 ms counted as 1 ms), a one-line warning says that the rows did unequal
work. Metric values are compared to 12 significant digits
(:func:`pathzoo.analysis.frame.round_measurements`), so two planners whose
lengths differ only by floating-point summation order tie. Success rate is always reported in its own column; the median,
IQR and SD columns describe successful runs only.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence, Unpack

import numpy as np
import pandas as pd

from pathzoo.analysis.formatting import format_number, format_percent, render_table
from pathzoo.analysis.frame import Direction, with_config
from pathzoo.analysis.hybrid import HYBRID_MARK, HYBRID_NOTE, hybrid_planners
from pathzoo.analysis.path_models import (MODEL_COLUMN, MODEL_RATIO, REFERENCE_COLUMN, SOURCE_COLUMNS, path_models,
                                          with_model_ratio)
from pathzoo.analysis.significance import ALPHA, PairwiseOptions
from pathzoo.analysis.summary import summarize
from pathzoo.core.budget import CLOCK_STOPS
from pathzoo.core.errors import InvalidParameterError

__all__ = ["leaderboard", "leaderboard_from_db", "combine_leaderboards", "format_leaderboard", "clock_stops",
           "work_done", "cpu_spread_warning",
           "power_note", "RANKING_RULE", "MODEL_RATIO_NOTE", "PATH_MODEL_NOTE", "CLOCK_MARK", "CLOCK_NOTE", "CPU_SPREAD_LIMIT"]

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

PATH_MODEL_NOTE = (
    "Ranked within each path model (grid: moves between neighbouring cells; anyangle: straight segments in any "
    "direction; timed: waits among moving obstacles): their raw values do not share an optimum. "
    "Rank by model_ratio (--metric model_ratio) for one ranking."
)

CPU_SPREAD_LIMIT = 10.0
"""Ratio of the largest to the smallest median CPU among a scenario's ranked rows above which a warning appears."""

_CPU_FLOOR_S = 1e-3

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
        f"alpha={table.attrs.get('alpha', ALPHA):g} after Holm's correction; run at least {need} seeds. "
        "A12 still shows the direction and size of each difference."
    )


def _rank_within(summary: pd.DataFrame, direction: Direction, by: list[str]) -> pd.Series:
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
    for _, idx in summary.groupby(by if len(by) > 1 else by[0]).groups.items():
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
    **tests: Unpack[PairwiseOptions],
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
    **tests
        ``alpha``, the significance level for ``vs_reference``, and
        ``paired``: passed to :func:`~pathzoo.analysis.stats.pairwise_tests`
        (:class:`~pathzoo.analysis.significance.PairwiseOptions`).

    Returns
    -------
    DataFrame
        Columns ``scenario, rank, planner, config, params_hash, path_model,
        n_runs, success_rate, median, iqr, sd, median_cpu_s,
        median_evaluations, clock_stops`` (plus the reference columns;
        ``clock_stops`` counts the runs a clock limit ended, whose results
        depend on the machine: ``docs/timing.md``), sorted by scenario,
        path model (unless ranked by ``model_ratio``) and rank.
        ``attrs["sectioned"]`` is True when ranks are per path model and
        ``attrs["cpu_warning"]`` holds :func:`cpu_spread_warning`'s line. ``attrs["metric"]`` is the metric's
        :class:`~pathzoo.analysis.frame.MetricInfo`; ``attrs["reference"]``
        and ``attrs["alpha"]`` are set too. See the module docstring for the
        ranking rule.
    """
    if metric == MODEL_RATIO and MODEL_RATIO not in runs.columns:
        runs = with_model_ratio(runs)
    summary = summarize(runs, metric, direction=direction)
    info = summary.attrs["metric"]
    planners = summary["planner"].astype(str)
    summary[MODEL_COLUMN] = planners.map(path_models(planners.unique()))
    sectioned = metric != MODEL_RATIO
    summary["rank"] = _rank_within(summary, info.direction, ["scenario", MODEL_COLUMN] if sectioned else ["scenario"])
    cols = ["scenario", "rank", "planner", "config", "params_hash", MODEL_COLUMN, "n_runs", "success_rate", "median",
            "iqr", "sd"]
    table = summary[cols].merge(work_done(runs, metric), on=["scenario", "config"], how="left")
    table = table.merge(clock_stops(runs, metric), on=["scenario", "config"], how="left")
    if reference is not None:
        from pathzoo.analysis.stats import pairwise_tests

        verdicts = pairwise_tests(runs, metric, direction=info.direction, reference=reference, **tests)
        verdict = {"a": "worse", "b": "better", "tie": "tie"}
        other = verdicts[["scenario", "b", "p_holm", "a12", "winner", "testable", "runs_needed"]].rename(
            columns={"b": "config"}
        )
        other["a12"] = 1.0 - other["a12"]  # P(this beats the reference)
        other["vs_reference"] = other["winner"].map(verdict).where(other["testable"].astype(bool), "n/s")
        table = table.merge(other.drop(columns=["winner", "testable"]), on=["scenario", "config"], how="left")
        table["runs_needed"] = table["runs_needed"].astype("Int64")  # no float 8.0 in CSV/JSON
        table.loc[table["config"] == reference, "vs_reference"] = "reference"
    if REFERENCE_COLUMN in runs.columns:
        table = table.merge(_references_used(runs), on=["scenario", "config"], how="left")
    order = ["scenario", MODEL_COLUMN, "rank", "config"] if sectioned else ["scenario", "rank", "config"]
    table = table.sort_values(order, kind="stable").reset_index(drop=True)
    table.attrs.update(metric=info, reference=reference, alpha=tests.get("alpha", ALPHA), sectioned=sectioned,
                       cpu_warning=cpu_spread_warning(table))
    return table


def work_done(runs: pd.DataFrame, metric: str = "length") -> pd.DataFrame:
    """``scenario, config, median_cpu_s, median_evaluations``: the median CPU seconds and evaluations of all runs."""
    df = with_config(runs, metric)
    keys = [df["scenario"], df["config"]]
    cpu = pd.to_numeric(df["cpu_time_s"], errors="coerce") if "cpu_time_s" in df else pd.Series(np.nan, index=df.index)
    evals = pd.to_numeric(df["evaluations"], errors="coerce") if "evaluations" in df else pd.Series(np.nan, index=df.index)
    return pd.DataFrame({"median_cpu_s": cpu.groupby(keys).median(),
                         "median_evaluations": evals.groupby(keys).median()}).reset_index()


def cpu_spread_warning(table: pd.DataFrame) -> str:
    """One line when a scenario's rows differ in median CPU by more than :data:`CPU_SPREAD_LIMIT` times, else ``""``.

    The scenario with the largest spread is named; CPU below 1 ms counts as 1 ms.
    """
    if "median_cpu_s" not in table.columns or table.empty:
        return ""
    cpu = table["median_cpu_s"].astype(float).clip(lower=_CPU_FLOOR_S)
    spans = cpu.groupby(table["scenario"]).agg(["min", "max"]).dropna()
    if spans.empty:
        return ""
    ratio = (spans["max"] / spans["min"]).to_numpy(dtype=float)
    i = int(np.argmax(ratio))
    if not ratio[i] > CPU_SPREAD_LIMIT:
        return ""
    worst, low, high = str(spans.index[i]), float(spans["min"].iloc[i]), float(spans["max"].iloc[i])
    low_text = "under 1 ms" if low <= _CPU_FLOOR_S else f"{format_number(low)} s"
    return (f"Warning: the ranked rows' median CPU differs up to {ratio[i]:.0f}x (on {worst}: "
            f"{low_text} to {format_number(high)} s): they did unequal work; give every planner one count "
            "budget to compare equal work (docs/timing.md).")


def leaderboard_from_db(
    db: str | Path,
    experiment: str,
    metric: str = "length",
    *,
    direction: Direction | None = None,
    reference: str | None = None,
    chunk_runs: int = 20_000,
    **tests: Unpack[PairwiseOptions],
) -> pd.DataFrame:
    """:func:`leaderboard` of a stored experiment, in memory that does not grow with the number of runs.

    Every statistic of the leaderboard is within one scenario, so the runs
    are read a chunk of whole scenarios at a time
    (:func:`pathzoo.harness.store_scan.scenario_chunks`, only the columns
    the ranking needs) and ranked chunk by chunk. Configurations are named
    from the whole experiment first (:func:`~pathzoo.analysis.frame.config_labels`
    over its distinct configurations), so the names, and the table, equal
    ``leaderboard(read_runs(db, experiment), ...)``.

    Parameters
    ----------
    db : path
        Results database.
    experiment : str
        Experiment name.
    metric, direction, reference
        As for :func:`leaderboard`.
    chunk_runs : int
        About this many runs are in memory at once (a scenario is never split).
    **tests
        As for :func:`leaderboard`.

    Returns
    -------
    DataFrame
        The table of :func:`leaderboard`.

    Raises
    ------
    ResultsDatabaseError
        Missing or foreign file, or unknown experiment.
    InvalidParameterError
        ``reference`` is not a configuration of the experiment.
    """
    from pathzoo.analysis.chunks import config_names, named_chunks
    from pathzoo.harness.store_scan import CHUNK_COLUMNS

    name_of = config_names(db, experiment)
    names = set(name_of.values())
    if reference is not None and reference not in names:
        raise InvalidParameterError(
            f"reference '{reference}' is not among the planners: {', '.join(sorted(names))}")
    needed = [metric] if metric != MODEL_RATIO else list(SOURCE_COLUMNS)
    parts = []
    for chunk in named_chunks(db, experiment, needed, name_of, chunk_runs=chunk_runs):
        here = reference if reference in set(chunk["label"]) else None  # scenarios without it: no test, as in memory
        parts.append(leaderboard(chunk, metric, direction=direction, reference=here, **tests))
    if not parts:
        empty = pd.DataFrame(columns=[*CHUNK_COLUMNS, *needed])
        parts.append(leaderboard(empty, metric, direction=direction, **tests))
    return combine_leaderboards(parts, reference)


def combine_leaderboards(parts: Sequence[pd.DataFrame], reference: str | None) -> pd.DataFrame:
    """One :func:`leaderboard` table from the tables of disjoint sets of whole scenarios.

    Parameters
    ----------
    parts : sequence of DataFrame
        At least one :func:`leaderboard` table; their scenarios do not overlap.
    reference : str, optional
        The reference configuration (a part whose scenarios lack it was built without one).

    Returns
    -------
    DataFrame
        The table :func:`leaderboard` gives for the union of the parts' runs.
    """
    attrs = {str(k): v for k, v in parts[0].attrs.items()}
    table = pd.concat(parts, ignore_index=True)
    if "runs_needed" in table.columns:
        table["runs_needed"] = table["runs_needed"].astype("Int64")
    order = ["scenario", MODEL_COLUMN, "rank", "config"] if attrs["sectioned"] else ["scenario", "rank", "config"]
    table = table.sort_values(order, kind="stable").reset_index(drop=True)
    table.attrs.update(attrs, reference=reference, cpu_warning=cpu_spread_warning(table))
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
            "model": table[MODEL_COLUMN].astype(str),
            "runs": table["n_runs"].astype(str),
            "success": table["success_rate"].map(format_percent),
            "median": table["median"].map(format_number),
            "IQR": table["iqr"].map(format_number),
            "SD": table["sd"].map(format_number),
            "CPU s": table["median_cpu_s"].map(format_number),
            "evals": table["median_evaluations"].map(lambda x: f"{x:.0f}" if pd.notna(x) else "–"),
        }
    )
    notes = [RANKING_RULE]
    if table.attrs.get("sectioned") and table[MODEL_COLUMN].nunique() > 1:
        notes.append(PATH_MODEL_NOTE)
    notes.append("CPU s, evals: median CPU seconds and evaluations per run (all runs).")
    if table.attrs.get("cpu_warning"):
        notes.insert(0, table.attrs["cpu_warning"])
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
        notes.append(_VERDICT_NOTE.format(alpha=table.attrs.get("alpha", ALPHA)))
        note = power_note(table)
        if note:
            notes.append(note)
    title = f"Leaderboard: {label}" + (f", {info.better}" if info is not None else "")
    return render_table(
        display, fmt, raw=table, title=title, notes=notes, left=("scenario", "planner", "vs ref")
    )
