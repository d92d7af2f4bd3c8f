"""An experiment: planners x scenarios x seeds with one budget, from Python or a TOML file.

TOML format (every key but the planners and scenarios is optional)::

    [experiment]
    name = "arena"              # default: the file's stem
    seed = 0                    # experiment seed; each run's seed derives from it
    seeds = 10                  # seed indices 0..9, or an explicit list [0, 4, 7]
    budget = { cpu_s = 2.0 }    # iterations, evaluations, cpu_s, time_s (default: none, each planner's own count)
    timeout_s = 60              # hard wall limit per run, never a budget (default time_s + 30 s, else 300 s)
    jobs = 4                    # worker processes (default: number of CPUs)
    db = "results.sqlite"       # result database, relative to this file
    scenarios = ["movingai.arena.*", "maps/my_scenario.toml"]

    [[planner]]
    id = "exact.astar"

    [[planner]]
    id = "aco.gant"
    params = { n_ants = 40 }
    label = "gant-40"           # optional name in tables and plots

    [[planner]]                 # an external planner (docs/external-planners.md)
    command = ["./my_planner", "--fast"]   # or: octave = "planners/aco_variant.m"
    label = "my-planner"        # its id is external.my-planner
    kinds = ["grid2d"]          # default ["grid2d"]
    params = { n_ants = 20 }    # sent to the program

Without a ``label`` a configuration is named ``id(param=value, ...)`` for the
parameters that differ from the defaults (docs/configurations.md).

Scenario entries are registered ids, glob patterns of registered ids
(``"movingai.arena.*"``) or file paths (anything with a ``/`` or a scenario
file suffix; relative paths are relative to the TOML file). A ``.scen`` file
gives all its problems; ``"maps/den312d.scen#12"`` gives the problem at the
0-based index 12 only, and ``"maps/den312d.scen#den312d.1?"`` those whose id
(or index) matches the glob. ``scenarios`` may also be written as a top-level
key before ``[experiment]``. A ``[cluster]`` table says where ``pathzoo run
--executor slurm`` (``pbs``, ``sge``) runs; it is not part of the experiment
(:mod:`pathzoo.harness.executors.cluster_options`).
"""

from __future__ import annotations

import fnmatch
import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Mapping, Sequence

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidExperimentError, PathzooError
from pathzoo.core.scenario import Scenario
from pathzoo.io.paths import looks_like_path
from pathzoo.harness.planner_info import prefetch
from pathzoo.harness.specs import PlannerSpec, RunTask, ScenarioSpec, run_key, run_seed

if TYPE_CHECKING:
    from pathzoo.core.planner import Planner

__all__ = ["Experiment", "read_toml", "DEFAULT_BUDGET", "TIMEOUT_MARGIN_S", "DEFAULT_TIMEOUT_NO_TIME_S"]

DEFAULT_BUDGET = Budget()
"""Budget when none is given: no limit, so every planner runs its own default count and every result repeats on
any machine and load (``docs/timing.md``). A clock here would be a budget for the anytime planners (they search
until it) and not for the others; the hard limit ``timeout_s`` is the only safety stop, and no planner sees it."""
TIMEOUT_MARGIN_S = 30.0
"""Default hard limit = ``budget.time_s`` + this margin."""
DEFAULT_TIMEOUT_NO_TIME_S = 300.0
"""Default hard limit when the budget has no time limit."""

_EXPERIMENT_KEYS = ("name", "seed", "seeds", "budget", "timeout_s", "jobs", "db", "scenarios")


def _resolve_scenarios(
    items: Sequence["str | Path | Scenario | ScenarioSpec"], base: Path | None
) -> tuple[ScenarioSpec, ...]:
    from pathzoo.plugins.lookup import load_scenarios
    from pathzoo.plugins.manager import get_registry

    specs: dict[str, ScenarioSpec] = {}

    def add(spec: ScenarioSpec) -> None:
        prev = specs.get(spec.id)
        if prev is not None and prev.cache_key != spec.cache_key:
            raise InvalidExperimentError(f"two different scenarios share the id '{spec.id}'")
        specs.setdefault(spec.id, spec)

    if isinstance(items, (str, Path, Scenario, ScenarioSpec)):
        items = [items]
    for item in items:
        if isinstance(item, ScenarioSpec):
            add(item)
        elif isinstance(item, Scenario):
            add(ScenarioSpec.of_object(item))
        elif isinstance(item, Path) or (isinstance(item, str) and looks_like_path(item)):
            name, selector = _split_selector(item, base)
            path = Path(name).expanduser()
            if base is not None and not path.is_absolute():
                path = base / path
            location = str(path.resolve())
            if selector is not None and path.suffix.lower() != ".scen":
                raise InvalidExperimentError(f"{item}: '#' selects problems of a .scen file, and {path.name} is not one")
            found = load_scenarios(Path(location))
            for sc in found if selector is None else _select_problems(found, selector, str(item)):
                add(ScenarioSpec(sc.id, sc.kind, "file", location))
        elif isinstance(item, str):
            registry = get_registry()
            for sid in registry.match("scenarios", item):
                entry = registry.get("scenarios", sid)
                kind = getattr(entry.obj, "kind", "") or entry.obj.load().kind
                add(ScenarioSpec(sid, kind, "registry", sid))
        else:
            raise InvalidExperimentError(
                f"a scenario must be an id, a glob pattern, a path or a Scenario, got {item!r}"
            )
    if not specs:
        raise InvalidExperimentError("no scenarios given")
    return tuple(specs.values())


def _split_selector(item: "str | Path", base: Path | None) -> tuple["str | Path", str | None]:
    """``("maps/x.scen", "12")`` for ``"maps/x.scen#12"``; the item and None without a ``#`` selector.

    A ``#`` belongs to the file name when a file of the whole name exists.
    """
    if not isinstance(item, str) or "#" not in item:
        return item, None
    whole = Path(item).expanduser()
    if (whole if base is None or whole.is_absolute() else base / whole).exists():
        return item, None
    name, _, selector = item.rpartition("#")
    return name, selector


def _select_problems(scenarios: "list[Scenario]", selector: str, item: str) -> "list[Scenario]":
    """The problems of a ``.scen`` file that ``file.scen#<selector>`` names.

    ``selector`` is a 0-based problem index (``#12``: the 13th problem line
    after the ``version`` line) or a glob pattern matched against the
    scenario ids (``#den312d.1?``) and the indices (``#1?``).

    Raises
    ------
    InvalidExperimentError
        An index past the last problem, or a pattern that matches nothing.
    """
    if selector.isdigit():
        index = int(selector)
        if index >= len(scenarios):
            raise InvalidExperimentError(
                f"{item}: problem index {index} is past the last problem, {len(scenarios) - 1} (indices start at 0)"
            )
        return [scenarios[index]]
    chosen = [s for i, s in enumerate(scenarios)
              if fnmatch.fnmatchcase(s.id, selector) or fnmatch.fnmatchcase(str(i), selector)]
    if not chosen:
        raise InvalidExperimentError(
            f"{item}: no problem id or index matches '{selector}' (ids {scenarios[0].id} .. {scenarios[-1].id})"
        )
    return chosen


MAX_RUNS = 2_000_000
"""Most runs per experiment (planner x scenario pairs x seeds)."""

MAX_SEEDS = 100_000
"""Most seeds per experiment (a larger count is almost surely a typo, and would exhaust memory)."""

MAX_INT = 2**63 - 1
"""Largest seed, seed index or budget count: the database stores them as signed 64-bit integers."""


def resolve_seeds(seeds: int | Iterable[int]) -> tuple[int, ...]:
    if isinstance(seeds, bool):
        raise InvalidExperimentError(f"seeds must be a count or a list of seed indices, got {seeds!r}")
    if isinstance(seeds, int):
        if not 1 <= seeds <= MAX_SEEDS:
            raise InvalidExperimentError(f"seeds must be between 1 and {MAX_SEEDS}, got {seeds}")
        return tuple(range(seeds))
    if isinstance(seeds, (str, bytes)):
        raise InvalidExperimentError(f"seeds must be a count or a list of seed indices, got {seeds!r}")
    try:
        out = tuple(seeds)
    except TypeError:
        raise InvalidExperimentError(f"seeds must be a count or a list of seed indices, got {seeds!r}") from None
    if not out or any(isinstance(s, bool) or not isinstance(s, int) or not 0 <= s <= MAX_INT for s in out):
        raise InvalidExperimentError(
            f"seed indices must be a non-empty list of integers in [0, 2**63-1], got {_short(list(out))}"
        )
    if len(out) > MAX_SEEDS:
        raise InvalidExperimentError(f"at most {MAX_SEEDS} seed indices, got {len(out)}")
    if len(set(out)) != len(out):
        raise InvalidExperimentError(f"seed indices must be distinct, got {list(out)!r}")
    return out


def _short(value: Any, limit: int = 80) -> str:
    """``repr(value)`` cut to ``limit`` characters, so an error message stays one short line."""
    text = repr(value)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def check_budget(budget: Budget) -> Budget:
    """``budget`` if its counts fit the database's 64-bit integers.

    Raises
    ------
    InvalidExperimentError
        Naming the count that is too large.
    """
    for name in ("iterations", "evaluations"):
        value = getattr(budget, name)
        if value is not None and value > MAX_INT:
            raise InvalidExperimentError(f"budget.{name} must be at most 2**63-1, got {_short(value)}")
    return budget


def _check_timeout(value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise InvalidExperimentError(f"timeout_s must be a positive number of seconds, got {value!r}")
    return float(value)


def _check_name(value: Any) -> str:
    if not isinstance(value, str) or not value.strip():
        raise InvalidExperimentError(f"name must be a non-empty string, got {value!r}")
    return value


def _check_seed(value: Any) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not -MAX_INT - 1 <= value <= MAX_INT:
        raise InvalidExperimentError(f"seed must be a 64-bit integer, got {_short(value)}")
    return value


def _check_jobs(value: Any) -> int | None:
    if value is not None and (isinstance(value, bool) or not isinstance(value, int) or value < 1):
        raise InvalidExperimentError(f"jobs must be a positive integer, got {value!r}")
    return value


_FIELD_CHECKS = {
    "name": _check_name,
    "seed": _check_seed,
    "seeds": lambda v: resolve_seeds(v),
    "timeout_s": _check_timeout,
    "jobs": _check_jobs,
}


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


@dataclass(frozen=True)
class Experiment:
    """Planners x scenarios x seeds, run under one budget.

    Build it with :meth:`build` (Python) or :meth:`from_toml` (file), then
    run it with :func:`pathzoo.harness.runner.run_experiment`.

    Attributes
    ----------
    name : str
        Names the experiment in the result database.
    seed : int
        Experiment seed; each run's seed is derived from it and the run key.
    planners : tuple of PlannerSpec
        Planner ids with complete validated parameters.
    scenarios : tuple of ScenarioSpec
        Resolved scenarios (globs expanded, files read).
    seeds : tuple of int
        Seed indices.
    budget : Budget
        Per-run planning budget.
    timeout_s : float
        Hard per-run wall-clock limit.
    jobs : int, optional
        Default number of workers for this experiment (from the TOML file).
    db : Path, optional
        Default result database (from the TOML file).
    source : str, optional
        The TOML file it was read from.
    """

    name: str
    seed: int
    planners: tuple[PlannerSpec, ...]
    scenarios: tuple[ScenarioSpec, ...]
    seeds: tuple[int, ...]
    budget: Budget = DEFAULT_BUDGET
    timeout_s: float = DEFAULT_TIMEOUT_NO_TIME_S
    jobs: int | None = None
    db: Path | None = None
    source: str | None = field(default=None, compare=False)

    @classmethod
    def build(
        cls,
        *,
        planners: Sequence[
            "str | Planner | tuple[str, Mapping[str, Any]] | tuple[str, Mapping[str, Any], str] | PlannerSpec"
        ],
        scenarios: Sequence["str | Path | Scenario | ScenarioSpec"],
        seeds: int | Iterable[int] = 5,
        budget: Budget | None = None,
        timeout_s: float | None = None,
        name: str = "default",
        seed: int = 0,
        jobs: int | None = None,
        db: str | Path | None = None,
        _source: str | None = None,
    ) -> "Experiment":
        """Validate and resolve an experiment given in Python.

        Parameters
        ----------
        planners : sequence
            Planner ids, ``(id, params)`` pairs, ``(id, params, label)``
            triples, :class:`PlannerSpec` objects or planner instances (kept
            as id + parameters; workers rebuild them). Labels name the
            configurations in tables and plots and must be distinct.
        scenarios : sequence
            Registered ids, glob patterns of ids, file paths or Scenario objects.
        seeds : int or iterable of int
            Count (indices ``0..n-1``) or explicit seed indices.
        budget : Budget, optional
            Default :data:`DEFAULT_BUDGET`, ``Budget()``: each planner's own count.
        timeout_s : float, optional
            Hard wall limit of a run, never a budget: a run past it is killed and stored as a timeout.
            Default ``budget.time_s + 30`` s (300 s without a time budget).
        name, seed : str, int
            Experiment name and seed.
        jobs : int, optional
            Default worker count for :func:`run_experiment`.
        db : path, optional
            Default result database for :func:`run_experiment`.

        Raises
        ------
        InvalidExperimentError
            Bad experiment-level values, duplicate planners or names, or conflicting scenario ids.
        UnknownPluginError, InvalidParameterError, InvalidScenarioError
            From resolving planners and scenarios.
        """
        _check_name(name)
        _check_seed(seed)
        _check_jobs(jobs)
        if isinstance(planners, str):
            planners = [planners]
        prefetch([(p, {}) if isinstance(p, str) else (p.id, p.params) if isinstance(p, PlannerSpec) else (p[0], p[1])
                  for p in planners if isinstance(p, (str, PlannerSpec)) or (isinstance(p, tuple) and len(p) >= 2
                                                                             and isinstance(p[0], str)
                                                                             and isinstance(p[1], Mapping))])
        specs = [PlannerSpec.of(p) for p in planners]
        if not specs:
            raise InvalidExperimentError("no planners given")
        seen: dict[tuple[str, str], int] = {}
        for i, spec in enumerate(specs):
            key = (spec.id, spec.params_hash)
            if key in seen:
                raise InvalidExperimentError(
                    f"planner {i} ({spec.id}) repeats planner {seen[key]} with the same parameters"
                )
            seen[key] = i
        names: dict[str, int] = {}
        for i, spec in enumerate(specs):
            if spec.name in names:
                raise InvalidExperimentError(
                    f"planner {i} ({spec.id}) has the same name '{spec.name}' as planner {names[spec.name]}; "
                    "give them distinct labels"
                )
            names[spec.name] = i
        budget = DEFAULT_BUDGET if budget is None else budget
        if not isinstance(budget, Budget):
            raise InvalidExperimentError(f"budget must be a pathzoo.Budget, got {budget!r}")
        check_budget(budget)
        if timeout_s is None:
            timeout_s = DEFAULT_TIMEOUT_NO_TIME_S if budget.time_s is None else budget.time_s + TIMEOUT_MARGIN_S
        timeout_s = _check_timeout(timeout_s)
        experiment = cls(
            name=name,
            seed=seed,
            planners=tuple(specs),
            scenarios=_resolve_scenarios(scenarios, None),
            seeds=resolve_seeds(seeds),
            budget=budget,
            timeout_s=timeout_s,
            jobs=jobs,
            db=None if db is None else Path(db),
            source=_source,
        )
        if not experiment.pairs():
            supported = sorted({k for p in experiment.planners for k in p.kinds})
            given = sorted({s.kind for s in experiment.scenarios})
            raise InvalidExperimentError(
                f"nothing to run: no planner supports any of the scenarios (the planners support "
                f"{', '.join(supported) or 'no kind'}; the scenarios are {', '.join(given)})"
            )
        return experiment

    @classmethod
    def from_toml(cls, path: str | Path) -> "Experiment":
        """Read an experiment file (format in the module docstring).

        Raises
        ------
        InvalidExperimentError
            Naming the file and the field for every problem, including unknown
            planners, bad parameters and missing scenarios.
        """
        return cls.from_mapping(read_toml(path), path)

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], path: str | Path) -> "Experiment":
        """Build an experiment from the parsed contents of the experiment file ``path``.

        :meth:`from_toml` without the reading, for readers of extended files
        (``pathzoo tune`` takes its own keys out and passes the rest here).
        Errors name ``path``; relative paths in ``data`` are relative to it.
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
        unknown = sorted(set(exp) - set(_EXPERIMENT_KEYS))
        if unknown:
            raise bad("experiment", f"unknown key(s) {unknown}; allowed: {', '.join(_EXPERIMENT_KEYS)}")
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
        budget = DEFAULT_BUDGET
        if "budget" in exp:
            if not isinstance(exp["budget"], dict):
                raise bad("experiment.budget", "must be a table such as { time_s = 5 }")
            budget = checked("experiment.budget",
                             lambda: check_budget(Budget.from_mapping(exp["budget"], where="budget")))
        specs: list[ScenarioSpec] = []
        for i, item in enumerate(scenarios):
            specs.extend(checked(f"{sfield}[{i}]", lambda: _resolve_scenarios([item], base)))
        checked(sfield, lambda: _resolve_scenarios(specs, None))  # ids clashing across entries
        db = exp.get("db")
        if db is not None and (not isinstance(db, str) or not db):
            raise bad("experiment.db", f"must be a file name, got {db!r}")
        kwargs: dict[str, Any] = {"name": path.stem}
        for key, check in _FIELD_CHECKS.items():
            if key in exp:
                checked(f"experiment.{key}", lambda: check(exp[key]))
                kwargs[key] = exp[key]
        return checked(
            "planner",
            lambda: cls.build(
                planners=planners,
                scenarios=specs,
                budget=budget,
                db=None if db is None else base / db,
                _source=src,
                **kwargs,
            ),
        )

    # ------------------------------------------------------------------ runs
    def pairs(self) -> list[tuple[PlannerSpec, ScenarioSpec]]:
        """Supported (planner, scenario) pairs, scenario-major so workers reuse loaded scenarios."""
        return [(p, s) for s in self.scenarios for p in self.planners if s.kind in p.kinds]

    def skipped(self) -> list[tuple[str, str, str]]:
        """``(planner id, scenario id, scenario kind)`` of every unsupported pair (not run)."""
        return [
            (p.id, s.id, s.kind) for s in self.scenarios for p in self.planners if s.kind not in p.kinds
        ]

    def tasks(self, plugin_modules: tuple[tuple[str, str], ...] = ()) -> list[RunTask]:
        """Every run of the experiment, in a deterministic order.

        Raises
        ------
        InvalidExperimentError
            More than :data:`MAX_RUNS` runs (checked before any is built).
        """
        pairs = self.pairs()
        if len(pairs) * len(self.seeds) > MAX_RUNS:
            raise InvalidExperimentError(
                f"experiment '{self.name}' has {len(pairs)} planner x scenario pairs x {len(self.seeds)} seeds = "
                f"{len(pairs) * len(self.seeds)} runs, more than the limit of {MAX_RUNS}; split it"
            )
        out = []
        for planner, scenario in pairs:
            version, phash = planner.version, planner.params_hash
            by_value = planner.by_value
            for index in self.seeds:
                key = run_key(planner.id, phash, scenario.id, index)
                out.append(
                    RunTask(
                        run_key=key,
                        experiment=self.name,
                        planner=planner,
                        planner_version=version,
                        params_hash=phash,
                        scenario=scenario,
                        seed_index=index,
                        seed=run_seed(self.seed, key),
                        budget=self.budget,
                        timeout_s=self.timeout_s,
                        plugin_modules=plugin_modules,
                        planner_class=by_value,
                    )
                )
        return out

    def config(self) -> dict[str, Any]:
        """The experiment as JSON-friendly data (stored with the results)."""
        return {
            "name": self.name,
            "seed": self.seed,
            "seeds": list(self.seeds),
            "budget": self.budget.to_dict(),
            "timeout_s": self.timeout_s,
            "planners": [
                {"id": p.id, "version": p.version, "params": dict(p.params), **({"label": p.label} if p.label else {})}
                for p in self.planners
            ],
            "scenarios": [s.describe() for s in self.scenarios],
            "source": self.source,
        }
