"""What a report shows, gathered a chunk of whole scenarios at a time, so its memory does not grow with the runs.

Every statistic of the report is taken within one scenario (leaderboards,
tests, the paper-style table, per-scenario summaries, time to target) or
adds up over scenarios (run outcomes, counts, the list of unsuccessful
runs). :class:`ReportGatherer` therefore reads the runs as frames of whole
scenarios (one frame of every run, or
:func:`pathzoo.analysis.chunks.named_chunks` of a database) and keeps, from
each, only its share of the tables: one row per scenario and configuration,
not one per run. Only the scenarios drawn on figures of their own keep
their runs (the columns their box plots and convergence curves need), and
the time-to-target view keeps three small fields per run.
"""

from __future__ import annotations

import json
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator, Sequence

import pandas as pd

from pathzoo.analysis.comparison_table import PaperPart, PaperTable, combine_paper_tables, paper_part
from pathzoo.analysis.frame import MetricInfo, metric_info, with_config
from pathzoo.analysis.leaderboard import combine_leaderboards, leaderboard
from pathzoo.analysis.path_models import MODEL_RATIO, SOURCE_COLUMNS, with_model_ratio
from pathzoo.core.budget import CLOCK_STOPS
from pathzoo.core.errors import InvalidParameterError
from pathzoo.core.status import RunStatus

__all__ = ["ReportData", "ReportGatherer", "GatheredReport", "gather_from_db", "shown_scenarios", "summarised_metrics",
           "BOX_METRICS", "TABLE_METRICS", "PAPER_METRICS", "FAILURES_SHOWN", "SHOWN_COLUMNS"]

BOX_METRICS: tuple[str, ...] = ("length_ratio", "planning_time", "energy", "turns")
"""Metrics shown as box plots besides the ranked metric (when present and not all NaN)."""

TABLE_METRICS: tuple[str, ...] = (
    "length", "length_ratio", "length_ratio_anyangle", "planning_time", "cpu_time", "travel_time", "energy", "turns",
    "turning_angle", "smoothness", "clearance_min", "clearance_mean",
)  # fmt: skip
"""Metrics summarised (median and IQR) in the report's metric tables."""

PAPER_METRICS: tuple[str, ...] = ("planning_time", "energy")
"""Metrics of the paper-style table besides the ranked one (when present)."""

FAILURES_SHOWN = 60
"""Unsuccessful runs listed in the report (the others are counted)."""

SHOWN_COLUMNS: tuple[str, ...] = ("run_key", "planner", "params_hash", "label", "scenario", "seed_index", "status",
                                  "valid")
"""The columns kept of a run of a scenario drawn on figures of its own (with the metrics drawn)."""


@dataclass
class ReportData:
    """The tables and counts a report shows (see :class:`ReportGatherer`).

    Attributes
    ----------
    n_runs : int
        Runs in the experiment.
    configs, scenario_ids : list of str
        The configurations and scenarios, sorted.
    not_isolated, not_sandboxed : int or None
        Runs that ran inline / outside the OS sandbox (None: the runs do not say).
    clocked : int
        Runs a clock limit ended; ``clocked_configs`` names their configurations, sorted.
    outcomes : DataFrame
        Per configuration: runs per status, ``runs`` and ``success``.
    planners : DataFrame
        ``config, planner, planner_version, params`` of each configuration's first run.
    leaderboard, own_leaderboard : DataFrame
        The leaderboard of the metric, and by ``model_ratio`` (None when no run has one).
    paper : PaperTable or None
        The paper-style table (with a reference).
    summaries : dict
        :func:`~pathzoo.analysis.summary.summarize` of the ranked metric and of
        every other metric summarised that has a value.
    shown_runs : DataFrame
        The runs of the scenarios drawn on figures of their own.
    typical : DataFrame or None
        :func:`~pathzoo.analysis.summary.median_runs` of those scenarios (when paths are drawn).
    shown_history : DataFrame or None
        The history of those runs (None without history).
    hits : DataFrame or None
        ``config, comparable, hit`` of :func:`~pathzoo.analysis.anytime.time_to_target` (history and length only).
    failures : DataFrame
        The first :data:`FAILURES_SHOWN` unsuccessful runs; ``n_failures`` counts them all.
    valued : set of str
        The metrics summarised that some run has a value of.
    """

    n_runs: int
    configs: list[str]
    scenario_ids: list[str]
    not_isolated: int | None
    not_sandboxed: int | None
    clocked: int
    clocked_configs: list[str]
    outcomes: pd.DataFrame
    planners: pd.DataFrame
    leaderboard: pd.DataFrame
    own_leaderboard: pd.DataFrame | None
    paper: PaperTable | None
    summaries: dict[str, pd.DataFrame]
    shown_runs: pd.DataFrame
    typical: pd.DataFrame | None
    shown_history: pd.DataFrame | None
    hits: pd.DataFrame | None
    failures: pd.DataFrame
    n_failures: int

    valued: set[str]

    def present(self, metric: str) -> bool:
        """Whether some run has a value of ``metric`` (one of the metrics summarised)."""
        return metric in self.valued


@dataclass
class ReportGatherer:
    """Gathers :class:`ReportData` from frames of whole scenarios (:meth:`add`, then :meth:`result`).

    Parameters
    ----------
    metric : str
        The ranked metric.
    summarised : sequence of str
        Metrics to summarise besides it (kept when some run has a value).
    reference : str, optional
        The reference configuration (leaderboard tests, paper-style table).
    paper_metrics : sequence of str
        The paper-style table's metrics (with a reference).
    alpha : float
        Significance level.
    shown : sequence of str
        Scenarios drawn on figures of their own.
    drawn : sequence of str
        Metrics drawn for them (box plots).
    typical : bool
        Pick each planner's most typical run of those scenarios (to draw its path).
    ecdf : bool
        Gather the time-to-target view (needs the history of every run).
    planners : DataFrame, optional
        ``config, planner, planner_version, params`` of each configuration's
        first run; by default the first run of each in the frames.
    """

    metric: str
    summarised: Sequence[str]
    reference: str | None = None
    paper_metrics: Sequence[str] = ()
    alpha: float = 0.05
    shown: Sequence[str] = ()
    drawn: Sequence[str] = ()
    typical: bool = False
    ecdf: bool = False
    planners: pd.DataFrame | None = None
    _n: int = field(default=0, init=False)
    _configs: set[str] = field(default_factory=set, init=False)
    _scenarios: list[str] = field(default_factory=list, init=False)
    _not_isolated: int | None = field(default=None, init=False)
    _not_sandboxed: int | None = field(default=None, init=False)
    _clocked: int = field(default=0, init=False)
    _clocked_configs: set[str] = field(default_factory=set, init=False)
    _status: Counter[tuple[str, str]] = field(default_factory=Counter, init=False)
    _success: Counter[str] = field(default_factory=Counter, init=False)
    _runs: Counter[str] = field(default_factory=Counter, init=False)
    _first: list[pd.DataFrame] = field(default_factory=list, init=False)
    _boards: list[pd.DataFrame] = field(default_factory=list, init=False)
    _own: list[pd.DataFrame] = field(default_factory=list, init=False)
    _own_any: bool = field(default=False, init=False)
    _paper: list[PaperPart] = field(default_factory=list, init=False)
    _summaries: dict[str, list[pd.DataFrame]] = field(default_factory=dict, init=False)
    _valued: set[str] = field(default_factory=set, init=False)
    _shown: list[pd.DataFrame] = field(default_factory=list, init=False)
    _typical: list[pd.DataFrame] = field(default_factory=list, init=False)
    _history: list[pd.DataFrame] = field(default_factory=list, init=False)
    _hits: list[pd.DataFrame] = field(default_factory=list, init=False)
    _failures: list[pd.DataFrame] = field(default_factory=list, init=False)
    _n_failures: int = field(default=0, init=False)

    def add(self, runs: pd.DataFrame, history: pd.DataFrame | None = None) -> None:
        """Take the share of one frame of whole scenarios (and of its runs' history, if any).

        Parameters
        ----------
        runs : DataFrame
            Runs of scenarios no earlier frame held, named as in the whole
            experiment; frames come in scenario order.
        history : DataFrame, optional
            Their history rows (for the convergence curves and the time-to-target view).
        """
        from pathzoo.analysis.anytime import time_to_target
        from pathzoo.analysis.summary import median_runs, summarize

        df = with_config(runs, self.metric)
        self._n += len(df)
        self._configs.update(df["config"])
        self._scenarios += sorted(df["scenario"].unique())
        if "isolated" in df.columns:
            self._not_isolated = (self._not_isolated or 0) + int((~df["isolated"].astype(bool)).sum())
        if "sandboxed" in df.columns:
            self._not_sandboxed = (self._not_sandboxed or 0) + int((~df["sandboxed"].astype(bool)).sum())
        if "stopped_by" in df.columns:
            clocked = df["stopped_by"].isin(CLOCK_STOPS)
            self._clocked += int(clocked.sum())
            self._clocked_configs.update(df.loc[clocked, "config"].astype(str))
        self._status.update(dict(df.groupby(["config", "status"]).size()))
        self._success.update(dict(df.groupby("config")["success"].sum()))
        self._runs.update(dict(df.groupby("config").size()))
        if self.planners is None:
            self._first.append(df.drop_duplicates("config")[["config", "planner", "planner_version", "params"]])
        here = self.reference if self.reference in set(df["config"]) else None
        self._boards.append(leaderboard(runs, self.metric, reference=here, alpha=self.alpha))
        if self.metric != MODEL_RATIO:
            own = with_model_ratio(runs)
            self._own_any = self._own_any or bool(own[MODEL_RATIO].notna().any())
            self._own.append(leaderboard(own, MODEL_RATIO))
        if self.reference is not None and self.paper_metrics:  # (else result() raises)
            self._paper.append(paper_part(runs, here, self._paper_infos(), alpha=self.alpha))
        for m in dict.fromkeys((self.metric, *self.summarised)):
            if m in runs.columns:
                if pd.to_numeric(runs[m], errors="coerce").notna().any():
                    self._valued.add(m)
                self._summaries.setdefault(m, []).append(summarize(runs, m))
        mine = df["scenario"].isin(set(self.shown)).to_numpy()
        if mine.any():
            drawn = [m for m in dict.fromkeys((self.metric, *self.drawn)) if m in runs.columns]
            kept = [c for c in SHOWN_COLUMNS if c in runs.columns and c != "label"]
            # named as in the whole frame: a frame of some scenarios may not hold every parameter set of a planner
            sub = runs.loc[mine, [*kept, *drawn]].assign(label=df.loc[mine, "config"].to_numpy())
            self._shown.append(sub.reset_index(drop=True))
            if self.typical:
                self._typical.append(median_runs(sub, self.metric))
            if history is not None:
                self._history.append(history[history["run_key"].isin(set(df.loc[mine, "run_key"]))])
        if self.ecdf and history is not None:
            hits = time_to_target(history, runs, eps=0.05)
            self._hits.append(hits[["config", "comparable", "hit"]])
        self._add_failures(df)

    def _paper_infos(self) -> tuple[MetricInfo, ...]:
        return tuple(metric_info(m) for m in self.paper_metrics)

    def _add_failures(self, df: pd.DataFrame) -> None:
        bad = df[~df["success"]]
        self._n_failures += len(bad)
        room = FAILURES_SHOWN - sum(len(f) for f in self._failures)
        if room <= 0 or bad.empty:
            return
        bad = bad.sort_values(["scenario", "config", "seed_index"])
        reason = [r if isinstance(r, str) and r else m for r, m in zip(bad["invalid_reason"], bad["message"])]
        self._failures.append(pd.DataFrame({
            "scenario": bad["scenario"].astype(str), "planner": bad["config"].astype(str),
            "seed": bad["seed_index"].astype(str), "status": bad["status"].astype(str),
            "reason": [str(r)[:140] for r in reason],
        }).head(room))

    def result(self) -> ReportData:
        """The gathered :class:`ReportData` (at least one run must have been added).

        Raises
        ------
        InvalidParameterError
            ``reference`` is not among the configurations.
        """
        configs = sorted(self._configs)
        if self.reference is not None and not self.paper_metrics:
            raise InvalidParameterError("metrics must name at least one metric")  # as paper_table says it
        if self.reference is not None and self.reference not in self._configs:
            raise InvalidParameterError(
                f"reference '{self.reference}' is not among the planners: {', '.join(configs)}")
        summaries = {m: _stack(parts) for m, parts in self._summaries.items()}
        if self.planners is None:
            planners = pd.concat(self._first, ignore_index=True).drop_duplicates("config")
        else:
            planners = self.planners
        paper = None
        if self._paper:
            paper = combine_paper_tables(self._paper, str(self.reference), self._paper_infos(), alpha=self.alpha)
        failures = (pd.concat(self._failures, ignore_index=True) if self._failures
                    else pd.DataFrame(columns=["scenario", "planner", "seed", "status", "reason"]))
        return ReportData(
            n_runs=self._n, configs=configs, scenario_ids=self._scenarios, not_isolated=self._not_isolated,
            not_sandboxed=self._not_sandboxed, clocked=self._clocked, clocked_configs=sorted(self._clocked_configs),
            outcomes=self._outcomes(configs), planners=planners.sort_values("config"),
            leaderboard=combine_leaderboards(self._boards, self.reference),
            own_leaderboard=combine_leaderboards(self._own, None) if self._own_any else None, paper=paper,
            summaries=summaries, shown_runs=_concat(self._shown),
            typical=_concat(self._typical) if self.typical else None,
            shown_history=_concat(self._history) if self._history else None,
            hits=_concat(self._hits) if self._hits else None, failures=failures, n_failures=self._n_failures,
            valued=set(self._valued),
        )

    def _outcomes(self, configs: list[str]) -> pd.DataFrame:
        """Runs per status (in :class:`RunStatus` order), runs and success rate of each configuration."""
        statuses = {s for _, s in self._status}
        order = [s.value for s in RunStatus]
        columns = sorted(statuses, key=lambda c: order.index(c) if c in order else len(order))
        counts = pd.DataFrame([[self._status.get((c, s), 0) for s in columns] for c in configs],
                              index=pd.Index(configs, name="config"), columns=columns).astype(int)
        counts["runs"] = counts.sum(axis=1)
        rate = pd.Series([self._success[c] / self._runs[c] for c in configs], index=counts.index)
        counts["success"] = rate.map(lambda x: f"{100 * x:.0f}%")
        return counts.reset_index().rename(columns={"config": "planner"})


def _concat(parts: Sequence[pd.DataFrame]) -> pd.DataFrame:
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame()


def _stack(parts: Sequence[pd.DataFrame]) -> pd.DataFrame:
    """Summaries of disjoint scenarios as one (their metric facts kept)."""
    out = pd.concat(parts, ignore_index=True) if len(parts) > 1 else parts[0]
    out.attrs = dict(parts[0].attrs)
    return out


def summarised_metrics(metric: str) -> list[str]:
    """Every metric a report ranked by ``metric`` may summarise or draw (model_ratio reads SOURCE_COLUMNS)."""
    return list(dict.fromkeys((metric, *PAPER_METRICS, *BOX_METRICS, *TABLE_METRICS, "length")))


def shown_scenarios(scenario_ids: Sequence[str], detail: Sequence[str], max_scenarios: int) -> list[str]:
    """The scenarios drawn on figures of their own: all up to ``max_scenarios``, else those of ``detail``.

    Raises
    ------
    InvalidParameterError
        A scenario of ``detail`` has no runs.
    """
    unknown = [s for s in detail if s not in set(scenario_ids)]
    if unknown:
        raise InvalidParameterError(f"scenario '{unknown[0]}' has no runs in this experiment")
    return list(scenario_ids) if len(scenario_ids) <= max_scenarios else sorted(set(detail))


@dataclass(frozen=True)
class GatheredReport:
    """:func:`gather_from_db`'s result: the :class:`ReportData` and how it was read.

    Attributes
    ----------
    data : ReportData
        The tables.
    shown_ids : list of str
        The scenarios drawn on figures of their own.
    has_history : bool
        Whether the experiment's runs stored convergence points.
    db : Path
        The database.
    experiment : str
        The experiment.
    names : dict
        Its configurations' names (:func:`pathzoo.analysis.chunks.config_names`).
    chunk_runs : int
        Runs per chunk.
    """

    data: ReportData
    shown_ids: list[str]
    has_history: bool
    db: Path
    experiment: str
    names: dict[tuple[str, str, str], str]
    chunk_runs: int

    def chunks(self, metrics: Sequence[str]) -> Iterator[pd.DataFrame]:
        """The runs again, a chunk of whole scenarios at a time (with ``metrics``), named as in ``data``."""
        from pathzoo.analysis.chunks import named_chunks

        return named_chunks(self.db, self.experiment, metrics, self.names, chunk_runs=self.chunk_runs)


def gather_from_db(db: str | Path, experiment: str, metric: str = "length", *, reference: str | None = None,
                   alpha: float = 0.05, detail: Sequence[str] = (), max_scenarios: int = 12,
                   chunk_runs: int = 20_000) -> GatheredReport:
    """The :class:`ReportData` of a stored experiment, read a chunk of whole scenarios at a time.

    What is known of the whole experiment before the chunks are read (its
    scenarios, configurations and their first runs, which metrics have a
    value, whether there is history) is asked of SQLite. Each chunk's
    history is read with it, only where it is used (the scenarios drawn, and
    every run for the time-to-target view). Equal to gathering from
    ``read_runs`` and ``read_history`` of the whole experiment.

    Parameters
    ----------
    db : path
        Results database.
    experiment : str
        Experiment name.
    metric, reference, alpha, detail, max_scenarios
        As for :func:`pathzoo.analysis.report.render_report`.
    chunk_runs : int
        About this many runs are in memory at once (a scenario is never split).

    Raises
    ------
    InvalidParameterError
        No runs, no such metric, an unknown reference or scenario of ``detail``.
    ResultsDatabaseError
        Missing or foreign file, or unknown experiment.
    """
    from pathzoo.analysis.chunks import config_names, named_chunks
    from pathzoo.harness.store import RUN_COLUMNS, read_history
    from pathzoo.harness.store_scan import first_runs, has_history, has_metric, metrics_with_values, scenario_ids

    ids = scenario_ids(db, experiment)
    if metric not in RUN_COLUMNS and not has_metric(db, experiment, metric):
        raise InvalidParameterError(f"runs: missing column '{metric}'")
    if not ids:
        raise InvalidParameterError("runs is empty: nothing to report")
    names = config_names(db, experiment)
    known = sorted(set(names.values()))
    if reference is not None and reference not in known:
        raise InvalidParameterError(f"reference '{reference}' is not among the planners: {', '.join(known)}")
    shown = shown_scenarios(ids, detail, max_scenarios)
    history = has_history(db, experiment)
    summarised = summarised_metrics(metric)
    valued = metrics_with_values(db, experiment, [*summarised, *SOURCE_COLUMNS])
    first = first_runs(db, experiment)
    planners = pd.DataFrame({
        "config": [names[k] for k in zip(first["planner"], first["params_hash"], first["label"])],
        "planner": first["planner"], "planner_version": first["planner_version"],
        "params": [json.loads(p) for p in first["params"]],
    }).drop_duplicates("config")
    gatherer = ReportGatherer(
        metric, summarised, reference=reference, alpha=alpha, shown=shown, drawn=BOX_METRICS, typical=True,
        paper_metrics=[m for m in dict.fromkeys((metric, *PAPER_METRICS)) if m in valued],
        ecdf=history and "length" in valued, planners=planners)
    wanted = [m for m in dict.fromkeys((*summarised, *SOURCE_COLUMNS)) if m in valued or m == metric]
    for chunk in named_chunks(db, experiment, wanted, names, chunk_runs=chunk_runs,
                              columns=("invalid_reason", "message")):
        hist = None
        if history:
            keys = chunk["run_key"] if gatherer.ecdf else chunk.loc[chunk["scenario"].isin(set(shown)), "run_key"]
            hist = read_history(db, experiment, run_keys=list(keys)) if len(keys) else None
        gatherer.add(chunk, hist)
    return GatheredReport(data=gatherer.result(), shown_ids=shown, has_history=history, db=Path(db),
                          experiment=experiment, names=names, chunk_runs=chunk_runs)
