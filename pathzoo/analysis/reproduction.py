"""A paper's comparison table rerun: the paper's numbers as data, our runs beside them, a verdict per claim.

Each paper's data file (a TOML file that a plugin provides through the
:func:`~pathzoo.plugins.hookspecs.pathzoo_paper_tables` hook; the bundled
scenario plugin ships ``pathzoo_scenarios/papers/<paper>.toml`` for the five
papers of :data:`PAPERS`) names the table its numbers
come from, the statistic they are (median, mean or a single value), the run
count, the planners (pathzoo ids and parameters), the metrics (with the
factor from our SI unit to the paper's unit) and, per scenario and planner,
the paper's value and SD (and its ↑/↓/≈ mark where the paper prints one).

:func:`run_paper` runs the comparison through the harness;
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
reconstructed)" with the paper's numbers; it is never dropped. Runs are
labelled by the paper's planner keys, so two configurations of one planner
(or one paper's parameters against another's) stay apart without help from
the harness.
"""

from __future__ import annotations

import fnmatch
import importlib
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np
import pandas as pd

from pathzoo.analysis.comparison_table import NOT_TESTABLE, paper_table
from pathzoo.analysis.formatting import format_number, format_percent, render_table
from pathzoo.analysis.frame import MetricInfo, success_mask
from pathzoo.core.errors import InvalidExperimentError, InvalidParameterError, PathzooError

__all__ = [
    "PAPERS",
    "NOT_AVAILABLE",
    "RIVAL_FAILED",
    "PaperDataError",
    "PaperPlanner",
    "PaperMetric",
    "PaperData",
    "Reproduction",
    "paper_file",
    "paper_tables",
    "load_paper",
    "planner_status",
    "selected_scenarios",
    "build_experiments",
    "planner_groups",
    "paper_budget",
    "experiment_name",
    "label_runs",
    "add_derived",
    "run_paper",
    "compare_paper",
    "format_reproduction",
    "replace_section",
]

PAPERS: tuple[str, ...] = ("ggaco", "dsaco", "gant", "iaca", "fgdaco")
"""The papers ``pathzoo reproduce`` knows, by the name of their data file."""

NOT_AVAILABLE = "not available (not reconstructed)"
"""What the table shows for a planner id that is not registered."""

_STATISTICS = ("median", "mean", "value")
_VERDICTS = ("holds", "not shown", "reversed", "differs", "not testable")
_PAPER_MARKS = ("↑", "↓", "≈")


class PaperDataError(InvalidExperimentError):
    """A paper data file is malformed (the message names the file and the field)."""


@dataclass(frozen=True)
class PaperPlanner:
    """One method of the paper's table: its key in the data, its label in the paper, a pathzoo id and parameters.

    A planner that cannot run the paper's scenarios (e.g. no moving
    obstacles) may run a variant of them, named by ``variant``; its rows say so.
    """

    key: str
    label: str
    id: str
    params: Mapping[str, Any] = field(default_factory=dict)
    variant: str = ""
    """Suffix of the scenario ids this planner runs on instead (``"_static"``: without moving obstacles)."""
    in_table: bool = True
    """False for a planner the paper's table does not have (e.g. the proposed method's parent): its rows carry
    no paper numbers and no claim (``in_table = false`` in the TOML file)."""


@dataclass(frozen=True)
class PaperMetric:
    """One metric column: pathzoo metric id, the paper's label, and ``paper unit = ours * scale``.

    ``derived`` names a function ``module:function(scenario, path) -> float``
    that computes the value from a stored path, for a paper measure that is
    not a registered metric.
    """

    id: str
    label: str
    scale: float = 1.0
    derived: str | None = None


@dataclass(frozen=True)
class PaperData:
    """A paper's comparison table as data (see the module docstring)."""

    name: str
    title: str
    file: str
    table: str
    statistic: str
    runs: int
    reference: str
    budget: Mapping[str, Any]
    claim: str
    notes: tuple[str, ...]
    planners: tuple[PaperPlanner, ...]
    metrics: tuple[PaperMetric, ...]
    scenarios: Mapping[str, str]
    values: pd.DataFrame
    source: str = ""

    def planner(self, key: str) -> PaperPlanner:
        """The planner with data key ``key``."""
        return next(p for p in self.planners if p.key == key)


def paper_tables() -> dict[str, Path]:
    """Every paper table the installed plugins provide (hook ``pathzoo_paper_tables``): name to data file.

    The first plugin registered that names a paper provides it, as with
    planner ids (pluggy calls the last registered first).
    """
    from pathzoo.plugins.manager import get_registry

    tables: dict[str, Path] = {}
    for provided in reversed(get_registry().pm.hook.pathzoo_paper_tables()):
        for name, file in dict(provided).items():
            tables.setdefault(str(name), Path(file))
    return tables


def paper_file(name: str) -> Path:
    """The data file of paper ``name``, as a plugin provides it (:func:`paper_tables`).

    Raises
    ------
    InvalidParameterError
        No installed plugin provides a table for ``name``.
    """
    tables = paper_tables()
    if name not in tables:
        known = ", ".join(tables) or "none (is the pathzoo scenarios plugin installed?)"
        raise InvalidParameterError(f"unknown paper '{name}'; choose one of {known}")
    return tables[name]


def _field(data: Mapping[str, Any], key: str, kind: type | tuple[type, ...], where: str) -> Any:
    if key not in data:
        raise PaperDataError(f"{where}: missing field '{key}'")
    value = data[key]
    if not isinstance(value, kind) or isinstance(value, bool) and kind is not bool:
        raise PaperDataError(f"{where}: field '{key}' has the wrong type ({type(value).__name__})")
    return value


def load_paper(name: str, path: str | Path | None = None) -> PaperData:
    """Read and check a paper's data file.

    Parameters
    ----------
    name : str
        The paper (one of :data:`PAPERS`).
    path : path, optional
        Read this file instead of the bundled one.

    Raises
    ------
    PaperDataError
        A field is missing, of the wrong type or inconsistent (unknown
        planner key, scenario key, metric or mark), naming the file.
    """
    file = Path(path) if path is not None else paper_file(name)
    with open(file, "rb") as fh:
        try:
            doc = tomllib.load(fh)
        except tomllib.TOMLDecodeError as exc:
            raise PaperDataError(f"{file}: {exc}") from None
    where = str(file)
    head = _field(doc, "paper", dict, where)
    statistic = _field(head, "statistic", str, f"{where} [paper]")
    if statistic not in _STATISTICS:
        raise PaperDataError(f"{where} [paper]: statistic must be one of {', '.join(_STATISTICS)}")
    runs = _field(head, "runs", int, f"{where} [paper]")
    if runs < 1:
        raise PaperDataError(f"{where} [paper]: runs must be >= 1")
    planners = []
    for i, p in enumerate(_field(doc, "planner", list, where)):
        w = f"{where} [[planner]] {i}"
        planners.append(PaperPlanner(_field(p, "key", str, w), _field(p, "label", str, w), _field(p, "id", str, w),
                                     dict(p.get("params", {})), str(p.get("variant", "")),
                                     bool(p.get("in_table", True))))
    keys = [p.key for p in planners]
    if len(set(keys)) != len(keys):
        raise PaperDataError(f"{where}: planner keys repeat")
    reference = _field(head, "reference", str, f"{where} [paper]")
    if reference not in keys:
        raise PaperDataError(f"{where} [paper]: reference '{reference}' is not a planner key")
    metrics = []
    for i, m in enumerate(_field(doc, "metric", list, where)):
        w = f"{where} [[metric]] {i}"
        scale = float(_field(m, "scale", (int, float), w))
        metrics.append(PaperMetric(_field(m, "id", str, w), _field(m, "label", str, w), scale, m.get("derived")))
    scenarios: dict[str, str] = {}
    for i, s in enumerate(_field(doc, "scenario", list, where)):
        w = f"{where} [[scenario]] {i}"
        scenarios[_field(s, "key", str, w)] = _field(s, "id", str, w)
    metric_ids = {m.id for m in metrics}
    rows = []
    for i, r in enumerate(_field(doc, "row", list, where)):
        w = f"{where} [[row]] {i}"
        scen, planner = _field(r, "scenario", str, w), _field(r, "planner", str, w)
        if scen not in scenarios:
            raise PaperDataError(f"{w}: unknown scenario key '{scen}'")
        if planner not in keys:
            raise PaperDataError(f"{w}: unknown planner key '{planner}'")
        if not next(p for p in planners if p.key == planner).in_table:
            raise PaperDataError(f"{w}: planner '{planner}' is marked in_table = false but has a row")
        marks = r.get("marks", {})
        for metric, mark in marks.items():
            if mark not in _PAPER_MARKS or metric not in metric_ids:
                raise PaperDataError(f"{w}: bad mark {metric} = {mark!r}")
        for metric, pair in _field(r, "values", dict, w).items():
            if metric not in metric_ids:
                raise PaperDataError(f"{w}: unknown metric '{metric}'")
            if not isinstance(pair, list) or not 1 <= len(pair) <= 2:
                raise PaperDataError(f"{w}: values.{metric} must be [value] or [value, SD]")
            rows.append(dict(scenario=scen, planner=planner, metric=metric, value=float(pair[0]),
                             sd=float(pair[1]) if len(pair) == 2 else math.nan, mark=marks.get(metric, "")))
    budget = dict(_field(head, "budget", dict, f"{where} [paper]"))
    return PaperData(
        name=name, title=_field(head, "title", str, f"{where} [paper]"), file=str(head.get("file", "")),
        table=_field(head, "table", str, f"{where} [paper]"), statistic=statistic, runs=runs, reference=reference,
        budget=budget, claim=str(head.get("claim", "")), notes=tuple(head.get("notes", ())),
        planners=tuple(planners), metrics=tuple(metrics), scenarios=scenarios,
        values=pd.DataFrame(rows, columns=["scenario", "planner", "metric", "value", "sd", "mark"]), source=where,
    )


def planner_status(planner: PaperPlanner) -> str:
    """``""`` when the planner can run with the paper's parameters, else why not (shown in the table)."""
    from pathzoo.harness.specs import PlannerSpec
    from pathzoo.plugins.manager import get_registry

    if planner.id not in get_registry().planners:
        return NOT_AVAILABLE
    try:
        PlannerSpec.of((planner.id, dict(planner.params)))
    except PathzooError as exc:
        return f"not run: parameters rejected ({exc})"
    return ""


def selected_scenarios(paper: PaperData, pattern: str | None) -> dict[str, str]:
    """The paper's scenarios (key -> scenario id) whose id matches the glob ``pattern`` (all if ``None``)."""
    chosen = {k: v for k, v in paper.scenarios.items() if pattern is None or fnmatch.fnmatchcase(v, pattern)}
    if not chosen:
        raise InvalidParameterError(f"no scenario of paper '{paper.name}' matches '{pattern}'")
    return chosen


def build_experiments(
    paper: PaperData,
    *,
    seeds: int | None = None,
    iterations: int | None = None,
    scenarios: str | None = None,
    db: str | Path | None = None,
) -> list["Any"]:
    """The :class:`~pathzoo.harness.experiment.Experiment` (s) that rerun the paper's table.

    Only available planners take part; planners that run a scenario variant
    (:attr:`PaperPlanner.variant`) form their own experiment, so nobody runs
    scenarios it does not need. ``seeds`` defaults to the paper's run count;
    ``iterations`` replaces the budget's iteration limit and caps every
    planner's ``iterations`` parameter (for quick checks); ``scenarios`` is a
    glob on the paper's scenario ids. The experiment names record the seed
    count and any iteration override, so runs with other settings are kept
    apart in one database.
    """
    from pathzoo.core.budget import Budget
    from pathzoo.harness.experiment import Experiment

    groups = planner_groups(paper, iterations)
    n = seeds if seeds is not None else paper.runs
    name = experiment_name(paper, n, iterations)
    ids = list(selected_scenarios(paper, scenarios).values())
    return [
        Experiment.build(planners=specs, scenarios=[sid + variant for sid in ids], seeds=n,
                         budget=Budget(**paper_budget(paper, iterations)), name=name + variant.replace("_", "."), db=db)
        for variant, specs in sorted(groups.items())
    ]


def planner_groups(paper: PaperData, iterations: int | None = None,
                   keys: Callable[[PaperPlanner], bool] = lambda p: True) -> dict[str, list[tuple[str, dict[str, Any]]]]:
    """The available planners (of those ``keys`` accepts) as ``(id, params)`` per scenario variant.

    ``iterations`` caps every planner's ``iterations`` parameter (see :func:`build_experiments`).

    Raises
    ------
    InvalidExperimentError
        When none of the paper's planners is available.
    """
    groups: dict[str, list[tuple[str, dict[str, Any]]]] = {}
    for p in paper.planners:
        if planner_status(p) or not keys(p):
            continue
        params = dict(p.params)
        if iterations is not None and "iterations" in _param_names(p.id):
            params["iterations"] = min(int(params.get("iterations", iterations)), iterations)
        groups.setdefault(p.variant, []).append((p.id, params))
    if not groups:
        raise InvalidExperimentError(f"paper '{paper.name}': none of its planners is available")
    return groups


def paper_budget(paper: PaperData, iterations: int | None = None) -> dict[str, Any]:
    """The paper's budget as keyword arguments of :class:`~pathzoo.core.budget.Budget`, ``iterations`` replacing its count."""
    budget = dict(paper.budget)
    if iterations is not None:
        budget["iterations"] = iterations
    return budget


def experiment_name(paper: PaperData, seeds: int, iterations: int | None = None) -> str:
    """The name of a rerun's experiment: the paper, the seed count and any iteration override."""
    return f"reproduce.{paper.name}.s{seeds}" + (f".i{iterations}" if iterations is not None else "")


def _param_names(planner_id: str) -> set[str]:
    from pathzoo.harness.planner_info import info_of

    return set(info_of(planner_id, {}).declared)


def label_runs(paper: PaperData, runs: pd.DataFrame, experiment: Any) -> pd.DataFrame:
    """Runs labelled by the paper's planner key (one configuration per key), variants under the paper's scenario id."""
    by_spec = {}
    for spec in experiment.planners:
        for p in paper.planners:
            if p.id == spec.id and not planner_status(p):
                by_spec[(spec.id, spec.params_hash)] = p
    out = runs.copy()
    chosen = [by_spec.get((pid, h)) for pid, h in zip(runs["planner"], runs["params_hash"])]
    out["planner"] = [p.key if p else pid for p, pid in zip(chosen, runs["planner"])]
    out["scenario"] = [sid[: len(sid) - len(p.variant)] if p and p.variant and sid.endswith(p.variant) else sid
                       for p, sid in zip(chosen, runs["scenario"])]
    out["params_hash"] = "paper"
    out["label"] = out["planner"]  # the configuration name the analysis shows (pathzoo.analysis.frame.config_labels)
    return out


def add_derived(paper: PaperData, runs: pd.DataFrame, db: str | Path, experiment: str) -> pd.DataFrame:
    """Columns for the paper's derived metrics, computed from each stored path."""
    from pathzoo.plugins.lookup import load_scenario
    from pathzoo.harness.store import read_path

    derived = [m for m in paper.metrics if m.derived]
    if not derived:
        return runs
    out = runs.copy()
    scenarios = {sid: load_scenario(sid) for sid in out["scenario"].unique()}
    for m in derived:
        module, _, func = str(m.derived).partition(":")
        fn: Callable[[Any, np.ndarray], float] = getattr(importlib.import_module(module), func)
        values = []
        for key, sid in zip(out["run_key"], out["scenario"]):
            path = read_path(db, experiment, key)[0]
            values.append(float(fn(scenarios[sid], path)) if path is not None and len(path) else math.nan)
        out[m.id] = values
    return out


def run_paper(
    paper: PaperData,
    *,
    db: str | Path,
    seeds: int | None = None,
    iterations: int | None = None,
    scenarios: str | None = None,
    jobs: int | None = None,
    executor: str = "process",
    progress: bool = True,
) -> tuple[pd.DataFrame, list[str]]:
    """Run (or resume) the paper's comparison; return the labelled runs and the experiments' names.

    See :func:`build_experiments` for ``seeds``, ``iterations`` and ``scenarios``.
    """
    from pathzoo.harness.runner import run_experiment

    frames, names = [], []
    for exp in build_experiments(paper, seeds=seeds, iterations=iterations, scenarios=scenarios, db=db):
        runs = run_experiment(exp, db=db, jobs=jobs, executor=executor, progress=progress)
        frames.append(label_runs(paper, add_derived(paper, runs, db, exp.name), exp))
        names.append(exp.name)
    return pd.concat(frames, ignore_index=True), names


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
        count = {k: (g["paper_mark"] == k).sum() for k in _PAPER_MARKS}
        ours_count = {k: (g["mark"] == k).sum() for k in _PAPER_MARKS}
        tested = bool(g["status"].eq("").all())
        wtl_rows.append(dict(metric=metric, planner=planner,
                             paper=f"{count['↑']}/{count['≈']}/{count['↓']}",
                             ours=f"{ours_count['↑']}/{ours_count['≈']}/{ours_count['↓']}" if tested else "–"))
    seeds = int(runs.groupby(["planner", "scenario"]).size().max()) if len(runs) else 0
    wtl = pd.DataFrame(wtl_rows, columns=["metric", "planner", "paper", "ours"])
    return Reproduction(paper=paper, table=table, wtl=wtl,
                        seeds=seeds, alpha=alpha)


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
        f"Claims: {len(claims)}; " + ", ".join(f"{k} {int(counts.get(k, 0))}" for k in _VERDICTS) + ".",
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


def replace_section(path: str | Path, name: str, text: str) -> None:
    """Put ``text`` between the markers ``<!-- reproduce:NAME:begin/end -->`` of the page ``path``.

    The block is replaced where the markers exist and appended otherwise,
    so a generated section can be rewritten any number of times while the
    hand-written text around it stays.
    """
    page = Path(path)
    begin, end = f"<!-- reproduce:{name}:begin -->", f"<!-- reproduce:{name}:end -->"
    old = page.read_text(encoding="utf-8") if page.exists() else ""
    block = f"{begin}\n{text}{end}"
    if begin in old and end in old:
        new = old[: old.index(begin)] + block + old[old.index(end) + len(end):]
    else:
        new = old + ("\n" if old and not old.endswith("\n") else "") + block + "\n"
    page.write_text(new, encoding="utf-8")
