"""A self-contained HTML report of one experiment: tables, statistics and figures in one offline page.

``index.html`` uses no external CSS, JavaScript, fonts or images. Figures
are PNGs embedded as base64 data URIs, or, with ``embed=False``, written to
``figures/`` next to it and linked relatively. Every figure is also written
to ``figures/`` as SVG and PDF, linked from its caption, for papers. The page
opens offline in any browser. Sections:

1. the experiment: budget, seeds, planners with their parameters, run outcomes;
2. the leaderboard of the chosen metric (with tests against ``reference``);
3. the paper-style table against ``reference`` (when one is given);
4. across scenarios: Friedman test and critical-difference diagram;
5. box plots of the main metrics;
6. per scenario: the map with each planner's most typical path (when the
   scenario can be loaded), and convergence curves;
7. time to reach within 5 % of the best known length (ECDF);
8. every metric's median and IQR, and the list of unsuccessful runs.
"""

from __future__ import annotations

import datetime as _dt
from pathlib import Path
from typing import Any, Callable, Mapping, Sequence

import numpy as np
import pandas as pd

from pathzoo.analysis.formatting import format_number, render_table
from pathzoo.analysis.frame import metric_info, with_config
from pathzoo.analysis.leaderboard import format_leaderboard
from pathzoo.analysis.path_models import MODEL_RATIO
from pathzoo.analysis.report_data import (BOX_METRICS, PAPER_METRICS, TABLE_METRICS, ReportData, ReportGatherer,
                                          gather_from_db, shown_scenarios, summarised_metrics)
from pathzoo.analysis.report_page import VECTOR_FORMATS, ReportPage
from pathzoo.core.errors import InvalidParameterError, PathzooError
from pathzoo.core.scenario import Scenario

__all__ = ["write_report", "render_report", "ReportPage", "BOX_METRICS", "TABLE_METRICS", "VECTOR_FORMATS"]

def _present(runs: pd.DataFrame, metric: str) -> bool:
    return metric in runs.columns and bool(pd.to_numeric(runs[metric], errors="coerce").notna().any())


def _metric_tables(page: ReportPage, data: ReportData, metrics: Sequence[str]) -> None:
    """Add one median [IQR] table per metric, with planners or scenarios as columns, whichever are fewer."""
    for m in metrics:
        s = data.summaries[m].copy()
        info = s.attrs["metric"]
        s["cell"] = [f"{format_number(a)} [{format_number(b)}]" for a, b in zip(s["median"], s["iqr"])]
        rows, cols = ("scenario", "config")
        if s["config"].nunique() > s["scenario"].nunique():
            rows, cols = cols, rows
        wide = s.pivot(index=rows, columns=cols, values="cell").fillna("–").reset_index()
        wide.columns.name = None
        wide = wide.rename(columns={"config": "planner"})
        page.table(render_table(wide, "html", title=f"{info.label}: median [IQR] over successful runs, "
                                f"{info.better}"))


def render_report(
    runs: pd.DataFrame,
    history: pd.DataFrame | None = None,
    *,
    metric: str = "length",
    reference: str | None = None,
    alpha: float = 0.05,
    scenarios: Mapping[str, Scenario] | None = None,
    path_of: Callable[[str], np.ndarray | None] | None = None,
    title: str = "pathzoo report",
    meta: Mapping[str, str] | None = None,
    embed: bool = True,
    max_scenarios: int = 12,
    detail: Sequence[str] = (),
) -> ReportPage:
    """Assemble the report of a runs frame (no database needed).

    Parameters
    ----------
    runs : DataFrame
        One row per run.
    history : DataFrame, optional
        Convergence points (``read_history``); without it the anytime
        sections are left out.
    metric : str
        Metric of the leaderboard and the Friedman ranks.
    reference : str, optional
        Configuration the others are tested against (leaderboard columns
        and the paper-style table).
    alpha : float
        Significance level.
    scenarios : mapping, optional
        Scenario objects by id, for the path figures.
    path_of : callable, optional
        ``run_key -> path`` (e.g. from ``read_path``), for the path figures.
    title : str
        Page title.
    meta : mapping, optional
        Extra lines for the header (label to value).
    embed : bool
        Embed figures as data URIs (else they go to ``ReportPage.files``).
    max_scenarios : int
        Up to this many scenarios, every scenario gets its own figures (box
        plot panels, map, convergence); with more, the box plots summarise
        across scenarios (:func:`~pathzoo.plotting.boxplots.plot_relative_medians`)
        and only the scenarios of ``detail`` get their own.
    detail : sequence of str
        Scenarios to draw on their own figures whatever their number.

    Returns
    -------
    ReportPage
        Call ``.html(title)`` for the document.
    """
    with_config(runs.iloc[:0], metric)  # the columns, checked first
    if runs.empty:
        raise InvalidParameterError("runs is empty: nothing to report")
    scenario_ids = sorted(runs["scenario"].unique())
    shown_ids = shown_scenarios(scenario_ids, detail, max_scenarios)
    has_history = history is not None and len(history) > 0
    gatherer = ReportGatherer(
        metric, summarised_metrics(metric), reference=reference, alpha=alpha, shown=shown_ids, drawn=BOX_METRICS,
        paper_metrics=[m for m in dict.fromkeys((metric, *PAPER_METRICS)) if _present(runs, m)],
        typical=path_of is not None,
        ecdf=has_history and _present(runs, "length"))
    gatherer.add(runs, history if has_history else None)
    return _render(gatherer.result(), metric=metric, reference=reference, alpha=alpha, scenarios=scenarios,
                   path_of=path_of, title=title, meta=meta, embed=embed, max_scenarios=max_scenarios,
                   shown_ids=shown_ids, has_history=has_history)


def _render(data: ReportData, *, metric: str, reference: str | None, alpha: float,
            scenarios: Mapping[str, Scenario] | None, path_of: Callable[[str], np.ndarray | None] | None, title: str,
            meta: Mapping[str, str] | None, embed: bool, max_scenarios: int, shown_ids: Sequence[str],
            has_history: bool) -> ReportPage:
    """The page of :func:`render_report` from the gathered tables."""
    from pathzoo.analysis.comparison_table import format_paper_table
    from pathzoo.analysis.ranks import friedman_of_summary
    from pathzoo.plotting.boxplots import plot_metric_panels, plot_relative_medians
    from pathzoo.plotting.cd_diagram import plot_cd_diagram
    from pathzoo.plotting.convergence import plot_convergence
    from pathzoo.plotting.ecdf import plot_time_to_target_ecdf
    from pathzoo.plotting.figure import new_figure, planner_colors
    from pathzoo.plotting.paths import plot_paths

    info = metric_info(metric)
    scenario_ids, configs, n_runs = data.scenario_ids, data.configs, data.n_runs
    palette = planner_colors(configs)
    page = ReportPage(embed=embed)

    page.heading(1, title)
    lines = dict(meta or {})
    lines.update({"planners": str(len(configs)), "scenarios": str(len(scenario_ids)), "runs": str(n_runs),
                  "ranked by": f"{info.label}, {info.better}"})
    if reference:
        lines["reference"] = reference
    lines["generated"] = _dt.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    page.meta(lines)
    sections = [("outcomes", "Runs"), ("leaderboard", "Leaderboard")]
    if reference:
        sections.append(("comparison", f"Comparison with {reference}"))
    sections += [("ranks", "Across scenarios"), ("boxes", "Distributions"), ("scenarios", "Per scenario")]
    if has_history:
        sections.append(("anytime", "Time to target"))
    sections += [("metrics", "All metrics"), ("failures", "Unsuccessful runs")]
    page.nav(sections)

    page.heading(2, "Runs", "outcomes")
    if data.not_isolated:
        page.note(f"{data.not_isolated} of {n_runs} runs ran inline, in the harness's own process: not isolated from "
                  "each other or from the harness (for debugging only); rerun with the process or Dask executor for "
                  "results.", "warn")
    if data.not_sandboxed is not None:
        n = data.not_sandboxed
        page.note(f"{n_runs - n} of {n_runs} runs ran in the OS sandbox" + (
            f"; {n} did not, so those planners could have reached other runs' results (see docs/sandbox.md)."
            if n else "."), "warn" if n else "pz-note")
    if data.clocked:
        names = ", ".join(data.clocked_configs)
        page.note(f"{data.clocked} of {n_runs} runs were ended by a clock limit (cpu_s or time_s), so their "
                  f"results depend on the machine and its load ({names}; marked '(clock)' in the leaderboards; "
                  "see docs/timing.md).", "warn")
    page.table(render_table(data.outcomes, "html", title="Run outcomes per planner"))
    planners = data.planners
    page.begin("details", "Planner parameters")
    page.table(render_table(pd.DataFrame({
        "planner": planners["config"], "id": planners["planner"], "version": planners["planner_version"].astype(str),
        "parameters": [str(p) for p in planners["params"]]}), "html"))
    page.end()

    page.heading(2, "Leaderboard", "leaderboard")
    page.table(format_leaderboard(data.leaderboard, "html"))
    if metric != MODEL_RATIO and data.own_leaderboard is not None:
        page.heading(3, "Against each planner's own optimum", "optimum")
        page.table(format_leaderboard(data.own_leaderboard, "html"))

    if reference and data.paper is not None:
        page.heading(2, f"Comparison with {reference}", "comparison")
        page.table(format_paper_table(data.paper, "html"))

    page.heading(2, "Across scenarios", "ranks")
    try:
        fr = friedman_of_summary(data.summaries[metric], alpha=alpha)
    except PathzooError as exc:
        page.note(f"No Friedman test: {exc}.")
    else:
        if fr.n_scenarios < 2:
            page.note("The Friedman test needs at least two scenarios on which every planner ran.")
        else:
            page.note(
                f"Friedman χ² = {fr.statistic:.3f} (p = {fr.pvalue:.3g}); Iman–Davenport F = "
                f"{fr.iman_davenport:.3f} (p = {fr.iman_davenport_pvalue:.3g}); N = {fr.n_scenarios} scenarios, "
                f"k = {fr.n_configs} planners; Nemenyi CD = {fr.cd:.3f} at α = {alpha:g}."
            )
            if fr.dropped:
                page.note(f"Left out (not every planner ran there): {', '.join(fr.dropped)}.")
            page.figure(plot_cd_diagram(fr, palette=palette), "cd",
                        "Mean ranks of the penalized median per scenario (1 = best). Planners joined by a bar do "
                        "not differ significantly (Nemenyi).")

    page.heading(2, "Distributions", "boxes")
    box_metrics = [m for m in dict.fromkeys((metric, *BOX_METRICS)) if data.present(m)]
    summarised = len(scenario_ids) > max_scenarios
    runs = data.shown_runs
    for m in box_metrics:
        mi = metric_info(m)
        if summarised:
            page.figure(plot_relative_medians(None, m, palette=palette, summary=data.summaries[m]), f"box-{m}",
                        f"Across {len(scenario_ids)} scenarios: each planner's median {mi.label} on a scenario over "
                        "the best planner's median there (one value per scenario); red numbers are the share of "
                        "scenarios with a successful run, when below 100%.")
        if shown_ids:
            page.figure(plot_metric_panels(runs, m, scenarios=shown_ids, palette=palette, configs=configs),
                        f"box-{m}" + ("-named" if summarised else ""),
                        f"{mi.label} over successful runs, one panel (and axis) per scenario; red numbers are "
                        "success rates below 100%.")

    page.heading(2, "Per scenario", "scenarios")
    if len(scenario_ids) > max_scenarios:
        page.note(f"{len(scenario_ids)} scenarios: figures of their own for "
                  + (", ".join(shown_ids) if shown_ids else "none")
                  + " (name scenarios with --scenario on the command line, detail= in Python).")
    typical = data.typical
    missing = [s for s in shown_ids if not scenarios or s not in scenarios]
    if path_of is not None and missing:
        page.note("No map for " + ", ".join(missing) + ": the scenario could not be rebuilt from the "
                  "experiment (Scenario objects passed to pathzoo.run are not stored); pass scenarios=.")
    history = data.shown_history
    df = with_config(runs) if len(runs) else runs
    for sid in shown_ids:
        page.heading(3, sid)
        page.begin("grid")
        if scenarios and sid in scenarios and typical is not None and path_of is not None:
            picks = typical[typical["scenario"] == sid]
            paths, colors = {}, {}
            row: Any  # a DataFrame row: its fields are whatever the columns hold
            for row in picks.itertuples(index=False):
                p = path_of(row.run_key)
                if p is not None and len(p):
                    label = f"{row.config} (seed {row.seed_index})"
                    paths[label], colors[label] = p, palette[row.config]
            caption = (f"Each planner's successful run whose {metric} is closest to its median." if paths
                       else "No successful run to draw on this map.")
            page.figure(plot_paths(scenarios[sid], paths, colors=colors), f"paths-{sid}", caption)
        if has_history and history is not None:
            sub_keys = set(df.loc[df["scenario"] == sid, "run_key"])
            sub_hist = history[history["run_key"].isin(sub_keys)]
            if len(sub_hist) and df.loc[df["scenario"] == sid, "success"].any():
                fig = new_figure((5.6, 7.0))
                ax1, ax2 = fig.subplots(2, 1)
                plot_convergence(sub_hist, runs, sid, x="iteration", ax=ax1, log=None, palette=palette)
                plot_convergence(sub_hist, runs, sid, x="time_s", ax=ax2, log=None, palette=palette)
                ax1.set_title(f"{sid}: best cost against iterations", fontsize="medium")
                ax2.set_title("and against time", fontsize="medium")
                ax2.get_legend().remove()
                page.figure(fig, f"conv-{sid}",
                            "Median best cost (planner's own objective) with interquartile band; a curve starts "
                            "once at least half of the runs hold a solution.")
        page.end()

    if has_history:
        page.heading(2, "Time to target", "anytime")
        if data.hits is not None:
            page.figure(plot_time_to_target_ecdf(None, None, eps=0.05, palette=palette, hits=data.hits), "ecdf",
                        "Share of runs whose best cost came within 5% of the best known length, against time. "
                        "Only runs whose reported best cost equals their measured length count (planners "
                        "optimising other objectives are 'not comparable'); unsuccessful runs never arrive.")
        else:
            page.note("No length metric stored; no time-to-target view.")

    page.heading(2, "All metrics", "metrics")
    page.begin("details", "Median [IQR] of every metric")
    _metric_tables(page, data, [m for m in TABLE_METRICS if data.present(m)])
    page.end()

    page.heading(2, "Unsuccessful runs", "failures")
    if data.n_failures == 0:
        page.note("Every run succeeded.")
    else:
        if data.n_failures > len(data.failures):
            page.note(f"First {len(data.failures)} of {data.n_failures}.")
        page.table(render_table(data.failures, "html"))
    page.note("Statistics: docs/statistics.md in the pathzoo sources (ranking rule, tests, pairing, Holm, A12, "
              "Friedman/Nemenyi).")
    return page


def _load_experiment_scenarios(config: Mapping[str, Any], wanted: set[str]) -> dict[str, Scenario]:
    from pathzoo.harness.specs import ScenarioSpec

    out: dict[str, Scenario] = {}
    for desc in config.get("scenarios", []):
        if desc.get("source") not in ("registry", "file") or desc["id"] not in wanted:
            continue
        try:
            out[desc["id"]] = ScenarioSpec(desc["id"], desc.get("kind", ""), desc["source"], desc["location"]).load()
        except (PathzooError, OSError):
            continue
    return out


def write_report(
    db: str | Path,
    out_dir: str | Path,
    experiment: str | None = None,
    metric: str = "length",
    reference: str | None = None,
    *,
    alpha: float = 0.05,
    scenarios: Sequence[Scenario] | Mapping[str, Scenario] | None = None,
    embed: bool = True,
    max_scenarios: int = 12,
    detail: Sequence[str] = (),
) -> Path:
    """Write ``out_dir/index.html``, the report of one stored experiment.

    Parameters
    ----------
    db : path
        Results database written by the harness.
    out_dir : path
        Directory to write (created); ``index.html`` is replaced, other
        files are left alone.
    experiment : str, optional
        Experiment to report; required when ``db`` holds several.
    metric : str
        Metric to rank by.
    reference : str, optional
        Planner (configuration label) to test the others against.
    alpha : float
        Significance level.
    scenarios : sequence or mapping of Scenario, optional
        Scenario objects for the maps, when the experiment's scenarios cannot
        be rebuilt from the database (objects passed to :func:`pathzoo.run`).
        Scenarios from the registry or from files are rebuilt automatically.
    embed : bool
        Embed the PNG figures in the HTML (default) or write them to
        ``out_dir/figures``; the SVG and PDF copies always go there.
    max_scenarios, detail
        As for :func:`render_report`: which scenarios get figures of their own.

    Returns
    -------
    Path
        The written ``index.html``.

    Raises
    ------
    InvalidParameterError
        ``db`` holds several experiments and none was chosen, or none at all.
    """
    from pathzoo.analysis.database import experiment_info
    from pathzoo.analysis.tuning_report import add_tuning_section
    from pathzoo.harness.store import read_path

    exp = experiment_info(db, experiment)
    gathered = gather_from_db(db, exp.name, metric, reference=reference, alpha=alpha, detail=detail,
                              max_scenarios=max_scenarios)
    known = _load_experiment_scenarios(exp.config, set(gathered.shown_ids))
    if scenarios is not None:
        known.update(scenarios if isinstance(scenarios, Mapping) else {s.id: s for s in scenarios})
    meta = {"database": str(Path(db).resolve()), "experiment": exp.name, "budget per run": exp.budget_text,
            "seeds": str(len(exp.config.get("seeds", []))), "created": exp.created}
    page = _render(
        gathered.data, metric=metric, reference=reference, alpha=alpha, scenarios=known,
        path_of=lambda key: read_path(db, exp.name, key)[0], title=f"pathzoo report: {exp.name}", meta=meta,
        embed=embed, max_scenarios=max_scenarios, shown_ids=gathered.shown_ids, has_history=gathered.has_history,
    )
    add_tuning_section(page, db, exp.name, gathered.chunks([metric]), metric=metric,  # only 'pathzoo tune' results
                       alpha=alpha)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    if page.files:
        (out / "figures").mkdir(exist_ok=True)
        for name, data in page.files.items():
            (out / "figures" / name).write_bytes(data)
    index = out / "index.html"
    index.write_text(page.html(f"pathzoo report: {exp.name}"), encoding="utf-8")
    return index
