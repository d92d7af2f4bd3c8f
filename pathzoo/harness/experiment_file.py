"""An experiment file read and checked: every problem named by the file and the field.

The format is in :mod:`pathzoo.harness.experiment`. A ``[[planner]]`` table
with ``command`` or ``octave`` declares an external planner
(``docs/external-planners.md``); a ``[cluster]`` table is read by
:mod:`pathzoo.harness.executors.cluster_options`, not here.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any, Callable, Mapping, TypeVar

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidExperimentError, PathzooError
from pathzoo.harness.experiment_checks import (
    check_budget,
    check_jobs,
    check_name,
    check_seed,
    check_timeout,
    resolve_seeds,
)
from pathzoo.harness.planner_info import prefetch
from pathzoo.harness.scenario_entries import resolve_scenarios
from pathzoo.harness.specs import PlannerSpec, ScenarioSpec

__all__ = ["EXPERIMENT_KEYS", "FIELD_CHECKS", "read_toml", "experiment_from_mapping"]

EXPERIMENT_KEYS = ("name", "seed", "seeds", "budget", "timeout_s", "jobs", "db", "scenarios")
"""The keys of the ``[experiment]`` table."""

FIELD_CHECKS: dict[str, Callable[[Any], Any]] = {
    "name": check_name,
    "seed": check_seed,
    "seeds": resolve_seeds,
    "timeout_s": check_timeout,
    "jobs": check_jobs,
}
"""The check of each ``[experiment]`` value passed to the experiment as it is."""

E = TypeVar("E")


def _external_spec(table: Mapping[str, Any], base: Path) -> PlannerSpec:
    """Declare the external planner of a ``[[planner]]`` table (``command`` or ``octave``) and return its spec."""
    from pathzoo.plugins.external import ExternalPlanner, declare
    from pathzoo.plugins.manager import get_registry

    planner = ExternalPlanner.from_table(table, base)
    declare(get_registry(), planner)
    label = table.get("label")
    return PlannerSpec.of((planner.id, {}) if label is None else (planner.id, {}, label))


def read_toml(path: str | Path) -> dict[str, Any]:
    """The parsed TOML file ``path``.

    Raises
    ------
    InvalidExperimentError
        Naming the file when it cannot be read or is not valid TOML.
    """
    try:
        with Path(path).open("rb") as fh:
            return tomllib.load(fh)
    except OSError as exc:
        raise InvalidExperimentError(f"{path}: cannot read: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise InvalidExperimentError(f"{path}: not valid TOML: {exc}") from None
    except UnicodeDecodeError as exc:
        raise InvalidExperimentError(f"{path}: not UTF-8 text (byte {exc.start}), so not a TOML file") from None


def experiment_from_mapping(data: Mapping[str, Any], path: str | Path, build: Callable[..., E]) -> E:
    """Check the parsed experiment file ``path`` and build its experiment with ``build``.

    ``build`` is :meth:`Experiment.build <pathzoo.harness.experiment.Experiment.build>`
    (keyword arguments: planners, scenarios, budget, db, name and the values
    of :data:`FIELD_CHECKS`, plus ``_source``). Relative paths in ``data``
    are relative to ``path``.

    Raises
    ------
    InvalidExperimentError
        Naming ``path`` and the field for every problem, including unknown
        planners, bad parameters and missing scenarios.
    """
    path = Path(path)
    src = str(path)

    def bad(fld: str, msg: str) -> InvalidExperimentError:
        return InvalidExperimentError(f"{src}: field '{fld}': {msg}")

    def checked(fld: str, fn: Any) -> Any:
        from pathzoo.harness.sandbox import SandboxImportError

        try:
            return fn()
        except SandboxImportError:
            raise  # the sandbox's view of this Python, not the field
        except PathzooError as exc:
            raise bad(fld, str(exc)) from None

    unknown = sorted(set(data) - {"experiment", "planner", "scenarios", "cluster"})
    if unknown:
        raise InvalidExperimentError(
            f"{src}: unknown top-level key(s) {unknown}; allowed: experiment, planner, scenarios, cluster"
        )
    exp = data.get("experiment", {})
    if not isinstance(exp, dict):
        raise bad("experiment", "must be a table")
    unknown = sorted(set(exp) - set(EXPERIMENT_KEYS))
    if unknown:
        raise bad("experiment", f"unknown key(s) {unknown}; allowed: {', '.join(EXPERIMENT_KEYS)}")
    if "scenarios" in exp and "scenarios" in data:
        raise bad("scenarios", "given both at top level and in [experiment]")
    scenarios = exp.get("scenarios", data.get("scenarios"))
    sfield = "experiment.scenarios" if "scenarios" in exp else "scenarios"
    if scenarios is None:
        raise bad("experiment.scenarios", "missing; list scenario ids, glob patterns or files")
    if not isinstance(scenarios, list) or not scenarios or not all(isinstance(s, str) for s in scenarios):
        raise bad(sfield, "must be a non-empty list of strings")
    planner_tables = data.get("planner")
    if planner_tables is None:
        raise bad("planner", "missing; add at least one [[planner]] table with an id")
    if not isinstance(planner_tables, list) or not all(isinstance(p, dict) for p in planner_tables):
        raise bad("planner", "must be [[planner]] tables")
    planners: list[PlannerSpec] = []
    base = path.resolve().parent
    prefetch([(t["id"], t.get("params", {})) for t in planner_tables  # all in one child, not one child each
              if isinstance(t.get("id"), str) and isinstance(t.get("params", {}), dict)
              and "command" not in t and "octave" not in t])
    for i, table in enumerate(planner_tables):
        if "command" in table or "octave" in table:
            planners.append(checked(f"planner[{i}]", lambda: _external_spec(table, base)))
            continue
        extra = sorted(set(table) - {"id", "params", "label"})
        if extra:
            raise bad(f"planner[{i}]", f"unknown key(s) {extra}; allowed: id, params, label "
                      "(or command or octave, for an external planner)")
        pid, params = table.get("id"), table.get("params", {})
        label = table.get("label")
        if not isinstance(pid, str) or not pid:
            raise bad(f"planner[{i}].id", "must be a planner id string")
        if not isinstance(params, dict):
            raise bad(f"planner[{i}].params", "must be a table")
        planners.append(
            checked(f"planner[{i}]", lambda: PlannerSpec.of((pid, params) if label is None else (pid, params, label)))
        )
    budget: Budget | None = None  # the experiment's default
    if "budget" in exp:
        if not isinstance(exp["budget"], dict):
            raise bad("experiment.budget", "must be a table such as { time_s = 5 }")
        budget = checked("experiment.budget",
                         lambda: check_budget(Budget.from_mapping(exp["budget"], where="budget")))
    specs: list[ScenarioSpec] = []
    for i, item in enumerate(scenarios):
        specs.extend(checked(f"{sfield}[{i}]", lambda: resolve_scenarios([item], base)))
    checked(sfield, lambda: resolve_scenarios(specs, None))  # ids clashing across entries
    db = exp.get("db")
    if db is not None and (not isinstance(db, str) or not db):
        raise bad("experiment.db", f"must be a file name, got {db!r}")
    kwargs: dict[str, Any] = {"name": path.stem}
    for key, check in FIELD_CHECKS.items():
        if key in exp:
            checked(f"experiment.{key}", lambda: check(exp[key]))
            kwargs[key] = exp[key]
    return checked(
        "planner",
        lambda: build(
            planners=planners,
            scenarios=specs,
            budget=budget,
            db=None if db is None else base / db,
            _source=src,
            **kwargs,
        ),
    )
