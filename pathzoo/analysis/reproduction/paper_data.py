"""A paper's comparison table as data: the schema of a paper's TOML file, where plugins provide it, and its reader.

Each paper's data file (a TOML file that a plugin provides through the
:func:`~pathzoo.plugins.hookspecs.pathzoo_paper_tables` hook; the bundled
scenario plugin ships ``pathzoo_scenarios/papers/<paper>.toml`` for the five
papers of :data:`PAPERS`) names the table its numbers
come from, the statistic they are (median, mean or a single value), the run
count, the planners (pathzoo ids and parameters), the metrics (with the
factor from our SI unit to the paper's unit) and, per scenario and planner,
the paper's value and SD (and its ↑/↓/≈ mark where the paper prints one).
A ``[paper]`` table may also set ``sandbox_memory_gib``, the memory each
sandboxed worker needs for the paper's largest scenarios (default: the
sandbox's own limit).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

import pandas as pd

from pathzoo.core.errors import InvalidExperimentError, InvalidParameterError

__all__ = [
    "PAPERS",
    "PAPER_MARKS",
    "PaperDataError",
    "PaperPlanner",
    "PaperMetric",
    "PaperData",
    "paper_file",
    "paper_tables",
    "load_paper",
]

PAPERS: tuple[str, ...] = ("ggaco", "dsaco", "gant", "iaca", "fgdaco")
"""The papers ``pathzoo reproduce`` knows, by the name of their data file."""

PAPER_MARKS = ("↑", "↓", "≈")
"""The marks a paper prints beside a rival's number, read from the proposed method's side: better, worse, equal."""

_STATISTICS = ("median", "mean", "value")


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
    sandbox_memory_gib: float | None = None

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
            if mark not in PAPER_MARKS or metric not in metric_ids:
                raise PaperDataError(f"{w}: bad mark {metric} = {mark!r}")
        for metric, pair in _field(r, "values", dict, w).items():
            if metric not in metric_ids:
                raise PaperDataError(f"{w}: unknown metric '{metric}'")
            if not isinstance(pair, list) or not 1 <= len(pair) <= 2:
                raise PaperDataError(f"{w}: values.{metric} must be [value] or [value, SD]")
            rows.append(dict(scenario=scen, planner=planner, metric=metric, value=float(pair[0]),
                             sd=float(pair[1]) if len(pair) == 2 else math.nan, mark=marks.get(metric, "")))
    budget = dict(_field(head, "budget", dict, f"{where} [paper]"))
    memory = head.get("sandbox_memory_gib")
    if memory is not None and (isinstance(memory, bool) or not isinstance(memory, (int, float)) or not memory > 0):
        raise PaperDataError(f"{where} [paper]: sandbox_memory_gib must be a positive number of GiB, got {memory!r}")
    return PaperData(
        name=name, title=_field(head, "title", str, f"{where} [paper]"), file=str(head.get("file", "")),
        table=_field(head, "table", str, f"{where} [paper]"), statistic=statistic, runs=runs, reference=reference,
        budget=budget, claim=str(head.get("claim", "")), notes=tuple(head.get("notes", ())),
        planners=tuple(planners), metrics=tuple(metrics), scenarios=scenarios,
        values=pd.DataFrame(rows, columns=["scenario", "planner", "metric", "value", "sd", "mark"]), source=where,
        sandbox_memory_gib=None if memory is None else float(memory),
    )

